"""Attribute transfer from one computed object to another through their maps.

Per-vertex layers are read at the source point each target vertex maps to; per-corner
layers (UV maps, corner colours, custom normals, corner attributes) at the point of
each target corner moved slightly into its own triangle, so seams stay seams; a UV map's
coordinates of one target face are continued across the source's seams into one chart
(so a face whose image straddles a seam does not span the whole texture). Every
requested layer is checked and computed before the target is modified.
"""
import bpy
import numpy as np

from . import features, mapping, maps, meshdata

FLOAT_FIELDS = {'FLOAT': ("value", 1), 'FLOAT2': ("vector", 2), 'FLOAT_VECTOR': ("vector", 3)}
DOMAINS = ('POINT', 'CORNER')
COLOR_WIDTH = 4


def _read(collection, field, width):
    values = np.empty(len(collection) * width, dtype=np.float32)
    collection.foreach_get(field, values)
    return values.reshape(-1, width) if width > 1 else values


def corner_normals(mesh):
    """(loops, 3) the shading normal of every face corner (smooth, flat or custom), object space."""
    if bpy.app.version >= (4, 1, 0):
        return _read(mesh.corner_normals, "vector", 3)
    mesh.calc_normals_split()
    return _read(mesh.loops, "normal", 3)


def _vertex_weights(obj, group):
    """Weights of a vertex group per vertex (0 outside it); bpy has no bulk access to group weights."""
    weights = np.zeros(len(obj.data.vertices))
    for vertex in obj.data.vertices:
        for element in vertex.groups:
            if element.group == group.index:
                weights[vertex.index] = element.weight
    return weights


def _user_attributes(mesh):
    """Float attributes on points or corners a user made (no UV maps, internals or results)."""
    uv_maps = {layer.name for layer in mesh.uv_layers}
    return [a.name for a in mesh.attributes
            if a.data_type in FLOAT_FIELDS and a.domain in DOMAINS and a.name not in uv_maps
            and a.name != "position" and not a.name.startswith((".", "cm_"))]


def layers(obj):
    """{kind: [names]} the object offers for transfer (feature groups CM:* excluded)."""
    mesh = obj.data
    return {"uv_maps": [layer.name for layer in mesh.uv_layers],
            "color_attributes": [a.name for a in mesh.color_attributes],
            "vertex_groups": [g.name for g in obj.vertex_groups if not features.is_feature_group(g.name)],
            "attributes": _user_attributes(mesh)}


def _missing(source, uv_maps, color_attributes, vertex_groups, attributes):
    offered = layers(source)
    found = []
    for kind, names, what in (("uv_maps", uv_maps, "UV map"), ("color_attributes", color_attributes, "colour attribute"),
                              ("vertex_groups", vertex_groups, "vertex group")):
        found += [f"'{source.name}' has no {what} '{n}'" for n in names if n not in offered[kind]]
    for name in attributes:
        attribute = source.data.attributes.get(name)
        if attribute is None:
            found.append(f"'{source.name}' has no attribute '{name}'")
        elif name not in offered["attributes"]:
            found.append(f"'{source.name}': attribute '{name}' is not a float attribute on points or face "
                         f"corners ({attribute.data_type} on {attribute.domain}) or is internal")
    return found


class _Values:
    """Source values interpolated for the target, on demand: per point or per corner."""

    def __init__(self, source, target):
        self.source, self.target = source, target
        self._vertex = self._corner = None
        self._source_triangles = meshdata.loop_triangles(source.data)

    def uvs(self, uv):
        """Source's per-corner texture coordinates at the target's corners, each face in one chart."""
        if self._corner is None:
            self._corner = maps.corner_landing(self.source, self.target)
        return maps.uvs_at_corners(self.source, self.target, self._corner, uv)

    def at(self, domain, values):
        if domain == 'POINT':
            if self._vertex is None:
                self._vertex = maps.vertex_landing(self.target, self.source)
            return mapping.at_vertices(self._vertex, self._source_triangles[0], values)
        if self._corner is None:
            self._corner = maps.corner_landing(self.source, self.target)
        return mapping.at_corners(self._corner, self._source_triangles[1], values)


def _replace_attribute(mesh, name, data_type, domain):
    old = mesh.attributes.get(name)
    if old is not None and (old.data_type != data_type or old.domain != domain):
        mesh.attributes.remove(old)
        old = None
    return old or mesh.attributes.new(name, data_type, domain)


def transfer(source, target, uv_maps=(), color_attributes=(), normals=False, vertex_groups=(), attributes=()):
    """Copies the named layers of source onto target (created or overwritten there); returns the names of
    what was transferred. Raises maps.MapError (nothing modified) when the objects have no common map or
    a layer is missing."""
    found = maps.problems([source, target])
    if not found:
        found = _missing(source, uv_maps, color_attributes, vertex_groups, attributes)
    if found:
        raise maps.MapError("\n".join(found))
    values = _Values(source, target)
    smesh, tmesh = source.data, target.data
    writes = []  # (write function, name); applied only once everything is computed
    for name in uv_maps:
        uv = values.uvs(_read(smesh.uv_layers[name].data, "uv", 2))
        writes.append((lambda name=name, uv=uv: (tmesh.uv_layers.get(name) or tmesh.uv_layers.new(name=name))
                       .data.foreach_set("uv", uv.astype(np.float32).ravel()), f"UV map {name}"))
    for name in color_attributes:
        layer = smesh.color_attributes[name]
        rgba = values.at(layer.domain, _read(layer.data, "color", COLOR_WIDTH))
        writes.append((lambda layer=layer, rgba=rgba: _replace_attribute(tmesh, layer.name, layer.data_type, layer.domain)
                       .data.foreach_set("color", np.clip(rgba, 0, None).astype(np.float32).ravel()),
                       f"colour {name}"))
    for name in attributes:
        layer = smesh.attributes[name]
        field, width = FLOAT_FIELDS[layer.data_type]
        data = values.at(layer.domain, _read(layer.data, field, width))
        writes.append((lambda layer=layer, field=field, data=data: _replace_attribute(
            tmesh, layer.name, layer.data_type, layer.domain).data.foreach_set(field, data.astype(np.float32).ravel()),
            f"attribute {name}"))
    for name in vertex_groups:
        weights = values.at('POINT', _vertex_weights(source, source.vertex_groups[name]))
        writes.append((lambda name=name, weights=weights: _write_weights(target, name, weights),
                       f"vertex group {name}"))
    if normals:
        corner = values.at('CORNER', corner_normals(smesh))
        corner /= np.maximum(np.linalg.norm(corner, axis=1, keepdims=True), 1e-12)
        writes.append((lambda corner=corner: _write_normals(tmesh, corner), "normals"))
    for write, _ in writes:
        write()
    tmesh.update()
    return [what for _, what in writes]


def _write_weights(obj, name, weights):
    group = obj.vertex_groups.get(name) or obj.vertex_groups.new(name=name)
    group.remove(range(len(obj.data.vertices)))
    for index in np.flatnonzero(weights > 0):  # bpy adds weights one value at a time
        group.add([int(index)], float(weights[index]), 'REPLACE')


def _write_normals(mesh, normals):
    if bpy.app.version < (4, 1, 0):
        mesh.use_auto_smooth = True  # custom normals need it before 4.1
    mesh.normals_split_custom_set(normals.tolist())

