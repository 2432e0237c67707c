"""Operators on feature points: add/place at the selected vertex, rename across the set,
delete, select and frame, copy the names to the other objects of the set."""
import bpy
from bpy.props import BoolProperty, StringProperty

from . import api, features
from .properties import set_objects


def _active_feature(obj):
    group = obj.vertex_groups.active if obj is not None and obj.type == 'MESH' else None
    return features.feature_name(group.name) if group and features.is_feature_group(group.name) else ""


def _set_and(context, obj):
    """The set's objects, plus obj if it is not one of them."""
    objects = set_objects(context.scene)
    return objects if obj in objects else objects + [obj]


def _has_mesh(context):
    obj = context.active_object
    return obj is not None and obj.type == 'MESH'


class CM_OT_add_feature(bpy.types.Operator):
    """Make the selected vertex a feature (in Edit Mode); an existing name moves that feature here"""
    bl_idname = "consistent_maps.add_feature"
    bl_label = "Add Feature"
    bl_options = {'REGISTER', 'UNDO'}

    name: StringProperty(name="Name", description="Feature name; the same name on other objects corresponds",
                         options={'SKIP_SAVE'})  # each use proposes the next free name, not the last one

    @classmethod
    def poll(cls, context):
        obj = context.edit_object
        return obj is not None and obj.type == 'MESH'

    def invoke(self, context, event):
        if not self.name:
            self.name = features.next_free_name(_set_and(context, context.edit_object))
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        import bmesh
        obj = context.edit_object
        selected = [v.index for v in bmesh.from_edit_mesh(obj.data).verts if v.select]
        if len(selected) != 1:
            self.report({'ERROR'}, f"Select exactly one vertex ({len(selected)} selected)")
            return {'CANCELLED'}
        name = self.name or features.next_free_name(_set_and(context, obj))
        try:
            name = api.add_feature(obj, name, selected[0])
        except api.FeatureError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, f"Feature '{name}' at vertex {selected[0]} of '{obj.name}'")
        return {'FINISHED'}


class CM_OT_rename_feature(bpy.types.Operator):
    """Rename a feature on every object of the set that has it"""
    bl_idname = "consistent_maps.rename_feature"
    bl_label = "Rename Feature"
    bl_options = {'REGISTER', 'UNDO'}

    name: StringProperty(name="Feature", description="Current name (default: the active feature)",
                         options={'SKIP_SAVE'})
    new_name: StringProperty(name="New Name", options={'SKIP_SAVE'})

    poll = classmethod(lambda cls, context: _has_mesh(context))

    def invoke(self, context, event):
        self.name = self.name or _active_feature(context.active_object)
        self.new_name = self.new_name or self.name
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        old = self.name or _active_feature(context.active_object)
        try:
            new = api.rename_feature(_set_and(context, context.active_object), old, self.new_name)
        except api.FeatureError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, f"Renamed '{old}' to '{new}'")
        return {'FINISHED'}


class CM_OT_delete_feature(bpy.types.Operator):
    """Delete a feature from the active object, or from every object of the set"""
    bl_idname = "consistent_maps.delete_feature"
    bl_label = "Delete Feature"
    bl_options = {'REGISTER', 'UNDO'}

    name: StringProperty(name="Feature", description="Name (default: the active feature)", options={'SKIP_SAVE'})
    everywhere: BoolProperty(name="Whole Set", description="Delete it from every object of the set",
                             options={'SKIP_SAVE'})

    poll = classmethod(lambda cls, context: _has_mesh(context))

    def execute(self, context):
        obj = context.active_object
        name = self.name or _active_feature(obj)
        objects = _set_and(context, obj) if self.everywhere else [obj]
        if not name or api.delete_feature(objects, name) == 0:
            self.report({'ERROR'}, f"No feature '{name}' to delete" if name else "No feature is active")
            return {'CANCELLED'}
        return {'FINISHED'}


class CM_OT_select_feature(bpy.types.Operator):
    """Select the feature's vertex in Edit Mode and frame it in the view"""
    bl_idname = "consistent_maps.select_feature"
    bl_label = "Select Feature"
    bl_options = {'REGISTER', 'UNDO'}

    name: StringProperty(name="Feature", description="Name (default: the active feature)", options={'SKIP_SAVE'})

    poll = classmethod(lambda cls, context: _has_mesh(context))

    def execute(self, context):
        import bmesh
        obj = context.active_object
        name = self.name or _active_feature(obj)
        index = api.features(obj).get(name)
        if index is None:
            self.report({'ERROR'}, f"'{obj.name}' has no placed feature '{name}'")
            return {'CANCELLED'}
        if obj.mode != 'EDIT':
            bpy.ops.object.mode_set(mode='EDIT')
        context.tool_settings.mesh_select_mode = (True, False, False)
        bm = bmesh.from_edit_mesh(obj.data)
        for element in (*bm.verts, *bm.edges, *bm.faces):
            element.select = False
        bm.verts.ensure_lookup_table()
        bm.verts[index].select = True
        bm.select_history.clear()
        bm.select_history.add(bm.verts[index])
        bmesh.update_edit_mesh(obj.data)
        obj.vertex_groups.active_index = obj.vertex_groups[features.group_name(name)].index
        if context.area is not None and context.area.type == 'VIEW_3D':
            bpy.ops.view3d.view_selected()
        return {'FINISHED'}


class CM_OT_copy_feature_names(bpy.types.Operator):
    """Give the other objects of the set the active object's feature names, to be placed"""
    bl_idname = "consistent_maps.copy_feature_names"
    bl_label = "Copy Names to Set"
    bl_options = {'REGISTER', 'UNDO'}

    poll = classmethod(lambda cls, context: _has_mesh(context))

    def execute(self, context):
        source = context.active_object
        targets = [obj for obj in set_objects(context.scene) if obj is not source]
        if not targets:
            self.report({'ERROR'}, "The set has no other object to copy feature names to")
            return {'CANCELLED'}
        if not features.memberships(source):
            self.report({'ERROR'}, f"'{source.name}' has no features to copy")
            return {'CANCELLED'}
        added = api.copy_feature_names(source, targets)
        self.report({'INFO'}, f"{added} feature(s) to place on the other objects")
        return {'FINISHED'}


CLASSES = (CM_OT_add_feature, CM_OT_rename_feature, CM_OT_delete_feature, CM_OT_select_feature,
           CM_OT_copy_feature_names)
