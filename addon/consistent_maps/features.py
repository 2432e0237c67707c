"""Feature points: a vertex group named `CM:<name>` holding exactly one vertex.

The same name on two objects means "these points correspond". A group with no
vertex is a feature still to be placed (what "copy names" creates); a group with
several vertices is invalid. Works in Object Mode and in Edit Mode (through
bmesh). While the add-on is registered, group memberships are read once per
change (the panels redraw often): `invalidate()` is called by the add-on's
depsgraph, load and undo handlers and by every function here that edits groups.
Without those handlers (the api used from a script, the add-on not registered)
nothing would say when a cache went stale, so every call reads the groups.
"""
import re

PREFIX = "CM:"
MIN_SHARED = 3

# {(object, mesh, mode, group names): memberships} while registered (use_cache), else None. Freed
# objects' addresses are reused: the group names keep a new object from taking an old one's entry
# before the next handler call.
_memberships_cache = None


class FeatureError(ValueError):
    """A feature operation cannot be done; the message says why."""


def use_cache(enabled):
    """Caches memberships (enabled by register(), whose handlers invalidate them) or reads them each time."""
    global _memberships_cache
    _memberships_cache = {} if enabled else None


def invalidate():
    if _memberships_cache is not None:
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
    if _memberships_cache is None:
        return _read_memberships(obj)
    key = (obj.as_pointer(), obj.data.as_pointer(), obj.mode, tuple(g.name for g in obj.vertex_groups))
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
    """The set's features, in order of first appearance: for one object its placed features; for several,
    the names placed on at least two of them (a name on one object corresponds to nothing). An object
    may lack some of them: it is left free there (see problems() for what is still required)."""
    placed = [features(obj) for obj in objects]
    names = []
    for p in placed:
        names += [name for name in p if name not in names]
    if len(objects) > 1:
        names = [name for name in names if sum(name in p for p in placed) >= 2]
    return names


def _listed(names, limit=4):
    shown = ", ".join(f"'{n}'" for n in names[:limit])
    return shown + (f" and {len(names) - limit} more" if len(names) > limit else "")


def problems(objects, minimum=MIN_SHARED):
    """Plain-language problems with the features of a set, each telling what to fix.

    A set of several objects needs: every CM: group placed (one vertex; an empty group is a feature
    still to place), every feature on at least two objects, at least `minimum` of the set's features on
    each object, and one object carrying all of them (it fixes where they lie on the common sphere).
    An object may lack a feature (no group at all): its map is left free there.
    """
    found = []
    for obj in objects:
        for name, verts in memberships(obj).items():
            if not verts:
                found.append(f"Feature '{name}' is not placed on '{obj.name}': select a vertex in Edit Mode and "
                             f"press Add Feature with this name, or delete the empty group from '{obj.name}' "
                             f"to leave it out there")
            elif len(verts) > 1:
                found.append(f"Feature '{name}' on '{obj.name}' has {len(verts)} vertices: a feature is one vertex, "
                             f"place it again with Add Feature")
    if len(objects) < 2:
        return found
    placed = [features(obj) for obj in objects]
    names = shared_names(objects)
    for obj, p in zip(objects, placed):
        alone = [name for name in p if name not in names]
        if alone:
            found.append(f"Feature(s) {_listed(alone)} placed only on '{obj.name}': a feature marks corresponding "
                         f"points, so place it on at least one other object (Copy Names) or delete it")
    for obj, p in zip(objects, placed):
        own = [name for name in names if name in p]
        if len(own) < minimum:
            found.append(f"'{obj.name}' has {len(own)} of the set's features ({_listed(own) or 'none'}); each "
                         f"object needs at least {minimum}: place more on it (Copy Names, then place them)")
    if names and not any(all(name in p for name in names) for p in placed):
        lacking = [[name for name in names if name not in p] for p in placed]
        best = min(range(len(objects)), key=lambda i: len(lacking[i]))
        found.append(f"No object has all {len(names)} features of the set; one must, to fix where they lie on the "
                     f"common sphere: e.g. place {_listed(lacking[best])} on '{objects[best].name}'")
    return found
