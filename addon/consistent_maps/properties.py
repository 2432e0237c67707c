"""Data the add-on keeps in the .blend: the set of objects and the compute and remesh options.

`bpy.types.Scene.consistent_maps` holds them; the progress of a running
computation lives on the window manager (shown in the panel, not worth saving).
"""
import bpy
from bpy.props import BoolProperty, CollectionProperty, EnumProperty, FloatProperty, IntProperty, PointerProperty

EFFORT_ITEMS = [
    ('0', "Fast", "Quickest map, more stretch"),
    ('1', "Balanced", "Good map in reasonable time"),
    ('2', "Best", "Least stretch, slowest"),
]

NORMAL_ALIGN_ITEMS = [
    ('features', "Features", "Turn the source's normals by the least-squares rotation taking its features onto "
                             "the active object's"),
    ('none', "None", "The source's normals as they are (object space)"),
]
ALIGN_ITEMS = [
    ('features', "Features", "Least-squares rotation, scale and offset taking the target's features onto the own"),
    ('bounds', "Bounds", "The target's bounding box onto the own"),
    ('none', "None", "The target's coordinates as they are"),
]


def _is_mesh(_self, obj):
    return obj.type == 'MESH'


def _redraw_views(_self, context):
    for area in context.screen.areas if context.screen else ():
        if area.type == 'VIEW_3D':
            area.tag_redraw()


class CM_Member(bpy.types.PropertyGroup):
    object: PointerProperty(type=bpy.types.Object, poll=_is_mesh, name="Object")


class CM_Settings(bpy.types.PropertyGroup):
    members: CollectionProperty(type=CM_Member)
    active_member: IntProperty(name="Active Member")
    effort: EnumProperty(name="Effort", items=EFFORT_ITEMS, default='1',
                         description="How hard the optimizer works on reducing stretch")
    restarts: IntProperty(name="Restarts", default=1, min=1, max=16,
                          description="Compute several objects this many times (other random seeds) and keep the "
                                      "best: with few features a run can twist one object's map around them. A "
                                      "pair mapped onto each other without features optimizes this many of its "
                                      "best first pairs, which pair the shapes' parts differently")
    align: BoolProperty(name="Align to First", default=False,
                        description="Refit every object's map towards the first complete object's where that "
                                    "distorts the map between them less: poses of one shape slide less between "
                                    "the features (takes longer, costs some stretch efficiency; objects with "
                                    "holes keep their maps)")
    pair_map: BoolProperty(name="Map the Pair Directly", default=False,
                           description="Two objects of genus 0: map them onto each other (through the sphere "
                                       "and directly through a consistent partition, the less distorted kept) "
                                       "instead of onto the common sphere: poses of one shape correspond far "
                                       "better; no sphere preview then. Objects with handles are "
                                       "always mapped in pairs")
    resolution: IntProperty(name="Resolution", default=64, min=2, max=1024,
                            description="Resolution n of the remeshes (even): n² + 2 vertices, on the octahedral grid "
                                        "(a pair mapped directly: simplified to that many)")
    morph_target: PointerProperty(type=bpy.types.Object, poll=_is_mesh, name="Target",
                                  description="The object whose shape the active object takes")
    morph_align: EnumProperty(name="Align", items=ALIGN_ITEMS, default='features',
                              description="How the target's shape is placed onto the active object")
    frame_start: IntProperty(name="Start", default=1, description="First frame of the morph animation")
    frame_end: IntProperty(name="End", default=24, description="Last frame of the morph animation")
    ping_pong: BoolProperty(name="Ping-Pong", default=False,
                            description="Morph there and back: the target's shape half way, the own at the end")
    transfer_source: PointerProperty(type=bpy.types.Object, poll=_is_mesh, name="Source",
                                     description="The object whose layers are copied onto the active object")
    bake_size: IntProperty(name="Size", default=1024, min=16, max=16384, subtype='PIXEL',
                           description="Width and height of the baked image")
    normal_align: EnumProperty(name="Align", items=NORMAL_ALIGN_ITEMS, default='features',
                               description="How the source's normals are turned onto the active object")
    components: IntProperty(name="Components", default=3, min=1, max=64,
                            description="How many principal components the mean shape gets as shape keys")
    show_features: BoolProperty(name="Show Features", default=True, update=_redraw_views,
                                description="Draw the features of the set in the viewport, with their names")



def set_objects(scene):
    """The objects of the set, in order (members whose object was deleted are skipped)."""
    return [m.object for m in scene.consistent_maps.members if m.object is not None]


CLASSES = (CM_Member, CM_Settings)


def attach():
    bpy.types.Scene.consistent_maps = PointerProperty(type=CM_Settings)
    bpy.types.WindowManager.consistent_maps_progress = FloatProperty(
        name="Progress", subtype='PERCENTAGE', min=0, max=100, precision=0)


def detach():
    del bpy.types.WindowManager.consistent_maps_progress
    del bpy.types.Scene.consistent_maps
