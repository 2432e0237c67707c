"""The active object coloured by how the common map onto the panel's source distorts it."""
import bpy

from . import api


class CM_OT_show_distortion(bpy.types.Operator):
    """Colour the active object by how the common map onto the source stretches it (colour attribute "Map
    distortion": white where it keeps shape, yellow at 4 times the optimal energy, red beyond, magenta where a
    face's image folds): add features where it is red"""
    bl_idname = "consistent_maps.show_distortion"
    bl_label = "Show Distortion"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        other, obj = context.scene.consistent_maps.transfer_source, context.active_object
        if other is None or obj is None:
            self.report({'ERROR'}, "Choose the source, and make the object to colour the active object")
            return {'CANCELLED'}
        try:
            summary = api.show_distortion(obj, other)
        except api.MapError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        for area in context.screen.areas if context.screen else ():
            for space in area.spaces:
                if space.type == 'VIEW_3D':
                    space.shading.color_type = 'VERTEX'  # the active colour attribute, in Solid mode
        self.report({'INFO'}, f"'{obj.name}' onto '{other.name}': median {summary['median']:.2f}, mean "
                              f"{summary['mean']:.1f} (optimum 4); {summary['high_area']:.1%} of the area at 16 "
                              f"or more; {summary['folded']} folded triangles")
        return {'FINISHED'}


CLASSES = (CM_OT_show_distortion,)
