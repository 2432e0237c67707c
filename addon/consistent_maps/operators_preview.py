"""Sphere preview on and off for the objects of the set."""
import bpy
from bpy.props import BoolProperty

from . import api, preview
from .properties import set_objects


class CM_OT_sphere_preview(bpy.types.Operator):
    """Show or hide each object of the set wrapped onto its sphere (shape key 'CM Sphere')"""
    bl_idname = "consistent_maps.sphere_preview"
    bl_label = "Sphere Preview"
    bl_options = {'REGISTER', 'UNDO'}

    show: BoolProperty(name="Show", default=True)

    def execute(self, context):
        objects = set_objects(context.scene)
        if not objects:
            self.report({'ERROR'}, "The set is empty: select mesh objects and press Add Selected")
            return {'CANCELLED'}
        problems = [p for p in map(preview.problem, objects) if p] if self.show else []
        if problems:
            self.report({'ERROR'}, "\n".join(problems))
            return {'CANCELLED'}
        for obj in objects:
            api.show_sphere(obj, self.show)
        return {'FINISHED'}


CLASSES = (CM_OT_sphere_preview,)
