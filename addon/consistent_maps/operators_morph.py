"""Morph the active object into another member's shape (shape key) and animate it."""
import bpy

from . import api


class CM_OT_morph(bpy.types.Operator):
    """Add the shape key "→ <target>": the active object in the target's shape, with its own mesh"""
    bl_idname = "consistent_maps.morph"
    bl_label = "Morph"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        settings = context.scene.consistent_maps
        source, target = context.active_object, settings.morph_target
        if source is None or target is None:
            self.report({'ERROR'}, "Choose the target, and make the object to morph the active object")
            return {'CANCELLED'}
        try:
            key = api.morph(source, target, settings.morph_align)
        except api.MapError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, f"Shape key '{key.name}' on '{source.name}'")
        return {'FINISHED'}


class CM_OT_animate_morph(bpy.types.Operator):
    """Keyframe the active object's morph key from 0 to 1 over the frame range (there and back with
    Ping-Pong), so Play shows the morph"""
    bl_idname = "consistent_maps.animate_morph"
    bl_label = "Animate"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        settings = context.scene.consistent_maps
        obj = context.active_object
        if obj is None:
            self.report({'ERROR'}, "Make the morphed object the active object")
            return {'CANCELLED'}
        try:
            key = api.animate_morph(obj, settings.frame_start, settings.frame_end, settings.ping_pong)
        except api.MapError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, f"'{key.name}' animated over frames {settings.frame_start}-{settings.frame_end}")
        return {'FINISHED'}


CLASSES = (CM_OT_morph, CM_OT_animate_morph)
