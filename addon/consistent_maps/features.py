"""Feature points: a vertex group named `CM:<name>` holding exactly one vertex.

The same name on two objects means "these points correspond". A group with no
vertex is a feature still to be placed (what "copy names" creates); a group with
several vertices is invalid. Works in Object Mode and in Edit Mode (through
bmesh), reading group memberships once per change: `invalidate()` is called by
the add-on's depsgraph handler and by every function here that edits groups.
"""
import re

PREFIX = "CM:"
MIN_SHARED = 3

_memberships_cache = {}


class FeatureError(ValueError):
    """A feature operation cannot be done; the message says why."""


def invalidate():
    _memberships_cache.clear()


def group_name(name):
    return PREFIX + name


def is_feature_group(group_name_):
    return group_name_.startswith(PREFIX)


def feature_name(group_name_):
    return group_name_[len(PREFIX):]


def _edit_bmesh(obj):
    import bmesh
    return bmesh.from_edit_mesh(obj.data)


def _read_memberships(obj):
    groups = {g.index: feature_name(g.name) for g in obj.vertex_groups if is_feature_group(g.name)}
    members = {name: [] for name in groups.values()}
    if not groups:
        return members
    if obj.mode == 'EDIT':
        bm = _edit_bmesh(obj)
        deform = bm.verts.layers.deform.active
        if deform is not None:
            for v in bm.verts:
                for index, weight in v[deform].items():
                    if index in groups and weight > 0:
                        members[groups[index]].append(v.index)
    else:
        for v in obj.data.vertices:
            for g in v.groups:
                if g.group in groups and g.weight > 0:
                    members[groups[g.group]].append(v.index)
    return members


def memberships(obj):
    """{feature name: [vertex indices]} for every CM: group of obj, valid or not."""
    key = (obj.as_pointer(), obj.data.as_pointer(), obj.mode)
    if key not in _memberships_cache:
        _memberships_cache[key] = _read_memberships(obj)
    return _memberships_cache[key]


def features(obj):
    """{feature name: vertex index} of the features placed on obj (groups with exactly one vertex)."""
    return {name: verts[0] for name, verts in memberships(obj).items() if len(verts) == 1}


def _check_name(name):
    name = name.strip()
    if not name:
        raise FeatureError("A feature name cannot be empty")
    if len(group_name(name)) > 63:
        raise FeatureError(f"Feature name '{name}' is too long (vertex group names hold 63 characters)")
    return name


def next_free_name(objects):
    """'F<k>' with the smallest k not used by a feature on any of the objects."""
    used = {name for obj in objects for name in memberships(obj)}
    numbers = {int(m.group(1)) for name in used if (m := re.fullmatch(r"F(\d+)", name))}
    k = 1
    while k in numbers:
        k += 1
    return f"F{k}"


def _assign(obj, group, vertex_index):
    """Makes vertex_index the only member of group."""
    if obj.mode == 'EDIT':
        import bmesh
        bm = _edit_bmesh(obj)
        deform = bm.verts.layers.deform.verify()
        for v in bm.verts:
            if group.index in v[deform]:
                del v[deform][group.index]
        bm.verts.ensure_lookup_table()
        bm.verts[vertex_index][deform][group.index] = 1.0
        bmesh.update_edit_mesh(obj.data)
    else:
        group.remove(list(range(len(obj.data.vertices))))
        group.add([vertex_index], 1.0, 'REPLACE')


def _vertex_count(obj):
    return len(_edit_bmesh(obj).verts) if obj.mode == 'EDIT' else len(obj.data.vertices)


def add(obj, name, vertex_index):
    """Places feature `name` at vertex_index, creating its group or moving an existing one."""
    name = _check_name(name)
    if obj.type != 'MESH':
        raise FeatureError(f"'{obj.name}' is not a mesh")
    count = _vertex_count(obj)
    if not 0 <= vertex_index < count:
        raise FeatureError(f"'{obj.name}' has no vertex {vertex_index} (it has {count} vertices)")
    taken = [other for other, verts in memberships(obj).items() if verts == [vertex_index] and other != name]
    if taken:
        raise FeatureError(f"Vertex {vertex_index} of '{obj.name}' is already feature '{taken[0]}'")
    group = obj.vertex_groups.get(group_name(name)) or obj.vertex_groups.new(name=group_name(name))
    _assign(obj, group, vertex_index)
    obj.vertex_groups.active_index = group.index
    invalidate()
    return name


def rename(objects, old, new):
    """Renames feature `old` to `new` on every object that has it."""
    new = _check_name(new)
    holders = [obj for obj in objects if obj.vertex_groups.get(group_name(old))]
    if not holders:
        raise FeatureError(f"No object has a feature named '{old}'")
    clashes = [obj.name for obj in holders if new != old and obj.vertex_groups.get(group_name(new))]
    if clashes:
        raise FeatureError(f"'{clashes[0]}' already has a feature named '{new}'")
    for obj in holders:
        obj.vertex_groups[group_name(old)].name = group_name(new)
    invalidate()
    return new


def delete(objects, name):
    """Removes feature `name` from the objects; returns how many had it."""
    holders = [obj for obj in objects if obj.vertex_groups.get(group_name(name))]
    for obj in holders:
        obj.vertex_groups.remove(obj.vertex_groups[group_name(name)])
    invalidate()
    return len(holders)


def copy_names(source, targets):
    """Adds the source's feature names to the targets as empty groups (to be placed); returns how many."""
    added = 0
    for obj in targets:
        for name in memberships(source):
            if obj is not source and not obj.vertex_groups.get(group_name(name)):
                obj.vertex_groups.new(name=group_name(name))
                added += 1
    invalidate()
    return added


def shared_names(objects):
    """Names placed on every object, in the order of the first object's groups."""
    if not objects:
        return []
    placed = [features(obj) for obj in objects]
    return [name for name in placed[0] if all(name in p for p in placed[1:])]


def problems(objects):
    """Plain-language problems with the features of a set, each telling what to fix."""
    found = []
    all_names = []
    for obj in objects:
        for name, verts in memberships(obj).items():
            if name not in all_names:
                all_names.append(name)
            if not verts:
                found.append(f"Feature '{name}' is not placed on '{obj.name}': select a vertex in Edit Mode "
                             f"and press Add Feature with this name")
            elif len(verts) > 1:
                found.append(f"Feature '{name}' on '{obj.name}' has {len(verts)} vertices: a feature is one vertex, "
                             f"place it again with Add Feature")
    if len(objects) > 1:
        for name in all_names:
            missing = [obj.name for obj in objects if name not in memberships(obj)]
            if missing:
                found.append(f"Feature '{name}' is missing on {', '.join(repr(m) for m in missing)}: "
                             f"use Copy Names, then place it")
        shared = shared_names(objects)
        if len(shared) < MIN_SHARED:
            found.append(f"The set shares {len(shared)} feature(s); at least {MIN_SHARED} are needed to put "
                         f"{len(objects)} objects into correspondence")
    return found
