"""Copy layers of the chosen source onto the active object through their common map, or bake its texture or
normals."""
import contextlib

import bpy
from bpy.props import EnumProperty, StringProperty

from . import api, transfer

KINDS = [
    ('uv_maps', "UV Maps", "UV maps, per face corner; seams stay seams"),
    ('color_attributes', "Colours", "Colour attributes on points or face corners"),
    ('normals', "Normals", "Custom split normals"),
    ('vertex_groups', "Vertex Groups", "Vertex groups and their weights (not the features)"),
    ('attributes', "Attributes", "Float attributes on points or face corners"),
]


class CM_OT_transfer(bpy.types.Operator):
    """Copy layers of the source onto the active object through the common map (same-named layers of the
    active object are overwritten)"""
    bl_idname = "consistent_maps.transfer"
    bl_label = "Transfer"
    bl_options = {'REGISTER', 'UNDO'}

    kind: EnumProperty(name="Kind", items=KINDS, default='uv_maps', options={'SKIP_SAVE'})
    layer: StringProperty(name="Layer", default="", options={'SKIP_SAVE'},
                          description="The layer to copy; empty: every layer of the kind the source has")

    def execute(self, context):
        source, target = context.scene.consistent_maps.transfer_source, context.active_object
        if source is None or target is None:
            self.report({'ERROR'}, "Choose the source, and make the object to receive the layers the active object")
            return {'CANCELLED'}
        if self.kind == 'normals':
            request = {"normals": True}
        else:
            names = [self.layer] if self.layer else transfer.layers(source)[self.kind] if source.type == 'MESH' else []
            if not names:
                self.report({'ERROR'}, f"'{source.name}' has no {self.kind.replace('_', ' ')} to transfer")
                return {'CANCELLED'}
            request = {self.kind: names}
        try:
            done = api.transfer(source, target, **request)
        except api.MapError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, f"From '{source.name}' to '{target.name}': {', '.join(done)}")
        return {'FINISHED'}


@contextlib.contextmanager
def _progress_indicator(window_manager):
    """Blender's progress indicator (the cursor shows the percentage), fed by the yielded progress(fraction):
    a bake runs Cycles on the main thread, so the interface cannot redraw a status line meanwhile."""
    window_manager.progress_begin(0, 100)
    try:
        yield lambda fraction: window_manager.progress_update(100 * fraction)
    finally:
        window_manager.progress_end()


class BakeOperator:
    """The bake operators' shared steps: the panel's source, the active object as target, one report."""
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        settings = context.scene.consistent_maps
        source, target = settings.transfer_source, context.active_object
        if source is None or target is None:
            self.report({'ERROR'}, "Choose the source, and make the object to bake for the active object")
            return {'CANCELLED'}
        try:
            with _progress_indicator(context.window_manager) as progress:
                image = self.bake(settings, source, target, progress)
        except api.MapError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, self.baked(image, target))
        return {'FINISHED'}


class CM_OT_bake_texture(BakeOperator, bpy.types.Operator):
    """Bake the source's image texture into a new image in the active object's UV layout, through the
    common map (Cycles); the objects are not modified"""
    bl_idname = "consistent_maps.bake_texture"
    bl_label = "Bake Texture"

    def bake(self, settings, source, target, progress):
        return api.bake_texture(source, target, settings.bake_size, progress=progress)

    def baked(self, image, target):
        return f"Image '{image.name}' ({image.size[0]} px): save or pack it to keep it"


class CM_OT_bake_normal_map(BakeOperator, bpy.types.Operator):
    """Bake the source's surface normals into a new tangent-space normal map in the active object's UV
    layout, through the common map (Cycles); the objects are not modified"""
    bl_idname = "consistent_maps.bake_normal_map"
    bl_label = "Bake Normal Map"

    def bake(self, settings, source, target, progress):
        return api.bake_normal_map(source, target, settings.bake_size, align=settings.normal_align,
                                   progress=progress)

    def baked(self, image, target):
        return (f"Normal map '{image.name}' ({image.size[0]} px, tangent space of UV map "
                f"'{target.data.uv_layers.active.name}'): save or pack it to keep it")


CLASSES = (CM_OT_transfer, CM_OT_bake_texture, CM_OT_bake_normal_map)
