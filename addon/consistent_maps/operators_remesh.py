"""Consistent remeshes of the computed set, as new objects."""
import bpy

from . import api, remeshes
from .properties import set_objects


class CM_OT_remesh(bpy.types.Operator):
    """Create, for each object of the set, a new object with the common connectivity (the octahedral grid; a pair
    mapped directly: one of them simplified), features at identical vertex indices, in the collection
    "Consistent Maps"; the originals stay as they are"""
    bl_idname = "consistent_maps.remesh"
    bl_label = "Consistent Remeshes"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        resolution = context.scene.consistent_maps.resolution
        try:
            created = api.remesh(set_objects(context.scene), resolution)
        except api.ComputeError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        pair = created[0].get(remeshes.PAIR_REMESH)
        through = (f" through the pair's map ({pair['carrier']}'s own vertices, {pair['folded_triangles']} "
                   f"folded triangle(s))" if pair else "")
        self.report({'INFO'}, f"{len(created)} remesh(es) of {len(created[0].data.vertices)} vertices "
                              f"in the collection '{created[0].users_collection[0].name}'{through}")
        return {'FINISHED'}


CLASSES = (CM_OT_remesh,)
