"""The mean shape and principal variations of the selected consistent remeshes."""
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
        except api.PCAError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        shares = ", ".join(f"{100 * x:.1f} %" for x in mean[api.EXPLAINED_VARIANCE])
        self.report({'INFO'}, f"'{mean.name}' from {len(objects)} remeshes; components explain {shares}")
        return {'FINISHED'}


CLASSES = (CM_OT_pca,)
