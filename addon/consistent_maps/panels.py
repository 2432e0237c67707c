"""Sidebar UI (View3D > Sidebar > Consistent Maps): the set, its features, Compute, results, morphs and
transfers."""
import bpy

from . import features, job, operators_transfer, results, status, topology
from .properties import set_objects

CATEGORY = "Consistent Maps"
RESULT_ICONS = {"NONE": 'BLANK1', "CURRENT": 'CHECKMARK', "STALE": 'ERROR'}
RESULT_TEXT = {"NONE": "not computed", "CURRENT": "up to date", "STALE": "stale (mesh edited)"}
MAX_PROBLEM_LINES = 6


class CM_UL_members(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_property, index=0, flt_flag=0):
        obj = item.object
        if obj is None:
            layout.label(text="(deleted object)", icon='ERROR')
            return
        result = status.of(obj).result
        layout.label(text=obj.name, icon='MESH_DATA')
        layout.label(text="", icon=RESULT_ICONS[result])


class CM_UL_features(bpy.types.UIList):
    """The CM: vertex groups of an object, shown by feature name with their state."""

    def draw_item(self, context, layout, data, item, icon, active_data, active_property, index=0, flt_flag=0):
        verts = features.memberships(data).get(features.feature_name(item.name), [])
        row = layout.row()
        row.label(text=features.feature_name(item.name), icon='DOT')
        if len(verts) == 1:
            row.label(text=f"vertex {verts[0]}")
        else:
            row.label(text="not placed" if not verts else f"{len(verts)} vertices!", icon='ERROR')

    def filter_items(self, context, data, propname):
        groups = getattr(data, propname)
        flags = [self.bitflag_filter_item if features.is_feature_group(g.name) else 0 for g in groups]
        return flags, []


class _Panel:
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = CATEGORY


class CM_PT_main(_Panel, bpy.types.Panel):
    bl_label = "Consistent Maps"

    def draw(self, context):
        settings = context.scene.consistent_maps
        row = self.layout.row()
        row.template_list("CM_UL_members", "", settings, "members", settings, "active_member", rows=3)
        column = row.column(align=True)
        column.operator("consistent_maps.add_selected", text="", icon='ADD')
        column.operator("consistent_maps.remove_member", text="", icon='REMOVE')
        column.separator()
        column.operator("consistent_maps.move_member", text="", icon='TRIA_UP').direction = 'UP'
        column.operator("consistent_maps.move_member", text="", icon='TRIA_DOWN').direction = 'DOWN'
        if 0 <= settings.active_member < len(settings.members) and settings.members[settings.active_member].object:
            _draw_status(self.layout.box(), settings.members[settings.active_member].object,
                         set_objects(context.scene))
        _draw_problems(self.layout, set_objects(context.scene), settings.pair_map)


def _draw_status(layout, obj, objects):
    s = status.of(obj)
    column = layout.column(align=True)
    column.label(text=obj.name, icon='OBJECT_DATA')
    column.label(text=f"{s.triangles} triangles, genus {s.genus}")
    column.label(text="Manifold" if s.manifold else "Not manifold", icon='CHECKMARK' if s.manifold else 'ERROR')
    column.label(text=f"{len(s.placed)} features placed")
    names = features.shared_names(objects) if len(objects) > 1 else []
    lacking = [name for name in names if name not in s.placed]
    if lacking:  # allowed: the map is left free there
        column.label(text=f"{len(names) - len(lacking)} of the set's {len(names)} (without {', '.join(lacking[:3])}"
                          f"{'...' if len(lacking) > 3 else ''})", icon='INFO')
    if s.unplaced or s.ambiguous:
        column.label(text=f"{len(s.unplaced)} to place, {len(s.ambiguous)} invalid", icon='ERROR')
    column.label(text=RESULT_TEXT[s.result].capitalize(), icon=RESULT_ICONS[s.result])


def _draw_problems(layout, objects, pair_map):
    """What Compute would refuse, as it would say it."""
    reports = [status.of(obj).report for obj in objects]
    lines = topology.problems([obj.name for obj in objects], reports, pair_map)
    lines += features.problems(objects, minimum=0 if topology.is_pair(reports, pair_map) else features.MIN_SHARED)
    if not lines:
        return
    box = layout.box()
    for line in lines[:MAX_PROBLEM_LINES]:
        box.label(text=line, icon='ERROR')
    if len(lines) > MAX_PROBLEM_LINES:
        box.label(text=f"... and {len(lines) - MAX_PROBLEM_LINES} more")


class CM_PT_features(_Panel, bpy.types.Panel):
    bl_label = "Features"
    bl_parent_id = "CM_PT_main"

    def draw_header(self, context):
        self.layout.prop(context.scene.consistent_maps, "show_features", text="")

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        if obj is None or obj.type != 'MESH':
            layout.label(text="Select a mesh object to see its features")
            return
        layout.label(text=f"Features of '{obj.name}'")
        row = layout.row()
        row.template_list("CM_UL_features", "", obj, "vertex_groups", obj.vertex_groups, "active_index", rows=3)
        column = row.column(align=True)
        column.operator("consistent_maps.add_feature", text="", icon='ADD')
        column.operator("consistent_maps.delete_feature", text="", icon='REMOVE')
        column.separator()
        column.operator("consistent_maps.select_feature", text="", icon='RESTRICT_SELECT_OFF')
        column.operator("consistent_maps.rename_feature", text="", icon='GREASEPENCIL')
        layout.operator("consistent_maps.copy_feature_names", icon='COPYDOWN')
        if obj.mode != 'EDIT':
            layout.label(text="Edit Mode: pick a vertex, press +", icon='INFO')
        _draw_missing(layout, obj, set_objects(context.scene))


def _draw_missing(layout, obj, objects):
    """Features of obj still to place (empty groups) and features of other objects of the set obj does not
    have (optional: its map is left free there), each with a Place button in Edit Mode."""
    names = []
    for other in objects:
        names += [n for n in features.features(other) if n not in names]
    own = features.memberships(obj)
    for title, listed in (("To place on this object:", [n for n, verts in own.items() if not verts]),
                          ("Optional here (left free without):", [n for n in names if n not in own])):
        if not listed:
            continue
        box = layout.box()
        box.label(text=title)
        for name in listed:
            row = box.row()
            row.label(text=name, icon='ERROR' if title.startswith("To place") else 'DOT')
            if obj.mode == 'EDIT':
                row.operator("consistent_maps.add_feature", text="Place at Selected").name = name


class CM_PT_compute(_Panel, bpy.types.Panel):
    bl_label = "Compute"
    bl_parent_id = "CM_PT_main"

    def draw(self, context):
        layout = self.layout
        settings = context.scene.consistent_maps
        running = job.current()
        if running is None:
            layout.prop(settings, "effort")
            layout.prop(settings, "restarts")
            layout.prop(settings, "align")
            if len(settings.members) == 2:
                layout.prop(settings, "pair_map")
            layout.operator("consistent_maps.compute", icon='PLAY')
        else:
            row = layout.row()
            row.enabled = False
            row.prop(context.window_manager, "consistent_maps_progress", slider=True)
            layout.label(text=running.stage)
            layout.operator("consistent_maps.cancel", icon='CANCEL')


class CM_PT_results(_Panel, bpy.types.Panel):
    bl_label = "Results"
    bl_parent_id = "CM_PT_main"

    def draw(self, context):
        layout = self.layout
        objects = set_objects(context.scene)
        column = layout.column(align=True)
        for obj in objects:
            s = status.of(obj)
            stats = results.stats(obj.data)
            row = column.row()
            row.label(text=obj.name, icon=RESULT_ICONS[s.result])
            if s.result == results.NONE or not stats:
                row.label(text="not computed")
                continue
            quality = (f"{stats['efficiency']:.3f}" if "efficiency" in stats
                       else f"genus {stats.get('genus')}, {stats.get('median_symmetric_dirichlet', 0):.1f}")
            row.label(text=f"{quality}, {stats['seconds']:.1f} s" + ("" if stats.get("bijective") else ", FLIPS"))
        if objects:
            column.label(text="Efficiency (best 1) or genus, median distortion (best 4); time")
        row = layout.row(align=True)
        row.operator("consistent_maps.sphere_preview", text="Sphere", icon='SPHERE').show = True
        row.operator("consistent_maps.sphere_preview", text="Shape", icon='MESH_DATA').show = False
        row = layout.row(align=True)
        row.prop(context.scene.consistent_maps, "resolution")
        row.operator("consistent_maps.remesh", text="Remesh", icon='MOD_REMESH')
        row = layout.row(align=True)
        row.prop(context.scene.consistent_maps, "components")
        row.operator("consistent_maps.pca", text="Mean + PCA", icon='SHAPEKEY_DATA')
        layout.operator("consistent_maps.blend", text="Blend Selected Remeshes", icon='MOD_REMESH')


class CM_PT_morph(_Panel, bpy.types.Panel):
    """The active object takes a target's shape (shape key), animated over a frame range."""
    bl_label = "Morph"
    bl_parent_id = "CM_PT_main"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = self.layout
        settings = context.scene.consistent_maps
        obj = context.active_object
        layout.label(text=f"Morph: {obj.name if obj else '(no active object)'}", icon='SHAPEKEY_DATA')
        layout.prop(settings, "morph_target")
        layout.prop(settings, "morph_align")
        layout.operator("consistent_maps.morph", icon='SHAPEKEY_DATA')
        row = layout.row(align=True)
        row.prop(settings, "frame_start")
        row.prop(settings, "frame_end")
        row = layout.row(align=True)
        row.prop(settings, "ping_pong")
        row.operator("consistent_maps.animate_morph", icon='KEYFRAME')


class CM_PT_transfer(_Panel, bpy.types.Panel):
    """Layers of a source copied onto the active object."""
    bl_label = "Transfer"
    bl_parent_id = "CM_PT_main"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        layout.prop(context.scene.consistent_maps, "transfer_source")
        layout.label(text=f"Onto: {obj.name if obj else '(no active object)'}", icon='FORWARD')
        column = layout.column(align=True)
        for kind, label, _ in operators_transfer.KINDS:
            column.operator("consistent_maps.transfer", text=label).kind = kind
        settings = context.scene.consistent_maps
        layout.prop(settings, "bake_size")
        layout.operator("consistent_maps.bake_texture", icon='TEXTURE')
        row = layout.row(align=True)
        row.prop(settings, "normal_align", text="")
        row.operator("consistent_maps.bake_normal_map", icon='NORMALS_FACE')
        layout.operator("consistent_maps.show_distortion", icon='VPAINT_HLT')


CLASSES = (CM_UL_members, CM_UL_features, CM_PT_main, CM_PT_features, CM_PT_compute, CM_PT_results, CM_PT_morph,
           CM_PT_transfer)
