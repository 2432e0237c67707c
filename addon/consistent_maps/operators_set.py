"""Operators that edit the set of objects: add the selected meshes, remove one, reorder."""
import bpy
from bpy.props import EnumProperty


class CM_OT_add_selected(bpy.types.Operator):
    """Add the selected mesh objects to the set"""
    bl_idname = "consistent_maps.add_selected"
    bl_label = "Add Selected"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        settings = context.scene.consistent_maps
        present = {m.object for m in settings.members}
        selected = [obj for obj in context.selected_objects if obj.type == 'MESH']
        if not selected:
            self.report({'ERROR'}, "Select one or more mesh objects first")
            return {'CANCELLED'}
        added = [obj for obj in selected if obj not in present]
        for obj in sorted(added, key=lambda o: o.name):
            settings.members.add().object = obj
        settings.active_member = len(settings.members) - 1
        self.report({'INFO'}, f"Added {len(added)} object(s) to the set")
        return {'FINISHED'}


class CM_OT_remove_member(bpy.types.Operator):
    """Remove the active object from the set (the object itself is kept)"""
    bl_idname = "consistent_maps.remove_member"
    bl_label = "Remove from Set"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        settings = context.scene.consistent_maps
        if not 0 <= settings.active_member < len(settings.members):
            self.report({'ERROR'}, "No object of the set is selected in the list")
            return {'CANCELLED'}
        settings.members.remove(settings.active_member)
        settings.active_member = min(settings.active_member, len(settings.members) - 1)
        return {'FINISHED'}


class CM_OT_move_member(bpy.types.Operator):
    """Move the active object up or down in the set"""
    bl_idname = "consistent_maps.move_member"
    bl_label = "Move in Set"
    bl_options = {'REGISTER', 'UNDO'}

    direction: EnumProperty(items=[('UP', "Up", ""), ('DOWN', "Down", "")])

    def execute(self, context):
        settings = context.scene.consistent_maps
        index = settings.active_member
        target = index - 1 if self.direction == 'UP' else index + 1
        if not (0 <= index < len(settings.members) and 0 <= target < len(settings.members)):
            return {'CANCELLED'}
        settings.members.move(index, target)
        settings.active_member = target
        return {'FINISHED'}


CLASSES = (CM_OT_add_selected, CM_OT_remove_member, CM_OT_move_member)
