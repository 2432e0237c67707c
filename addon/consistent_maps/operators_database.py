"""Selected consistent remeshes as a database: their mean shape and principal variations, n-way blends."""
import bpy

from . import api


class CM_OT_pca(bpy.types.Operator):
    """Create the mean shape of the selected consistent remeshes, with a shape key per principal component
    (-3 to +3 standard deviations), in the collection "Consistent Maps\""""
    bl_idname = "consistent_maps.pca"
    bl_label = "Mean and Principal Components"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        objects = sorted(context.selected_objects, key=lambda obj: obj.name)
        try:
            mean = api.pca(objects, context.scene.consistent_maps.components)
        except api.RemeshSetError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        shares = ", ".join(f"{100 * x:.1f} %" for x in mean[api.EXPLAINED_VARIANCE])
        self.report({'INFO'}, f"'{mean.name}' from {len(objects)} remeshes; components explain {shares}")
        return {'FINISHED'}


class CM_OT_blend(bpy.types.Operator):
    """Create the object "Blend": the active remesh with a shape key per other selected remesh, to mix
    their shapes (in the collection "Consistent Maps")"""
    bl_idname = "consistent_maps.blend"
    bl_label = "Blend Shapes"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        active = context.active_object
        objects = [active] + [obj for obj in context.selected_objects if obj != active] if active else []
        try:
            blend = api.blend(objects)
        except api.RemeshSetError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, f"'{blend.name}' with {len(objects) - 1} shape key(s)")
        return {'FINISHED'}


CLASSES = (CM_OT_pca, CM_OT_blend)
