"""How the common map distorts an object, shown as a colour of its faces (Blender-only)."""
import numpy as np

from . import maps, meshdata, native

NAME = "Map distortion"
OPTIMUM = 4.0  # the symmetric Dirichlet energy of an isometry
HIGH = 16.0    # yellow; red from 64 (4 * HIGH) on
FOLDED = (1.0, 0.0, 1.0, 1.0)
ZERO_AREA = (0.5, 0.5, 0.5, 1.0)


def colours(energy, folded):
    """RGBA per face: white at the optimum, yellow at HIGH, red from 4 * HIGH (logarithmic in between), magenta
    where the image folds, grey for faces of zero area (nan)."""
    t = np.clip(np.log2(np.maximum(np.nan_to_num(energy, nan=OPTIMUM), OPTIMUM) / OPTIMUM)
                / (2 * np.log2(HIGH / OPTIMUM)), 0, 1)
    rgba = np.column_stack([np.ones_like(t), np.clip(2 - 2 * t, 0, 1), np.clip(1 - 2 * t, 0, 1), np.ones_like(t)])
    rgba[np.isnan(energy)] = ZERO_AREA
    rgba[folded] = FOLDED
    return rgba


def show(obj, other):
    """Writes the face-corner colour attribute NAME of obj (replacing one of that name) and makes it the active
    colour; returns the summary (see api.show_distortion). Raises maps.MapError (nothing modified)."""
    maps.check([obj, other])
    landing = maps.vertex_landing(obj, other)
    mesh = obj.data
    triangles, corners = meshdata.loop_triangles(mesh)
    measured = native.map_distortion((maps.positions(mesh), triangles),
                                     (maps.positions(other.data), meshdata.loop_triangles(other.data)[0]),
                                     (landing.triangle, landing.barycentric))
    energy, folded, area = measured["symmetric_dirichlet"], measured["flipped"], measured["area"]
    polygon = np.empty(len(triangles), dtype=np.int64)
    mesh.loop_triangles.foreach_get("polygon_index", polygon)
    # Per face: the area-weighted mean of its triangles (inf if one degenerates), folded if one folds.
    finite = np.isfinite(energy)
    face_area = np.bincount(polygon, weights=np.where(finite, area, 0), minlength=len(mesh.polygons))
    face_energy = np.bincount(polygon, weights=np.where(finite, area * energy, 0), minlength=len(mesh.polygons))
    with np.errstate(invalid="ignore", divide="ignore"):
        face_energy = np.where(face_area > 0, face_energy / face_area, np.nan)
    face_energy[polygon[np.isinf(energy)]] = np.inf
    face_folded = np.bincount(polygon, weights=folded, minlength=len(mesh.polygons)) > 0
    rgba = np.empty((len(mesh.loops), 4), dtype=np.float32)
    rgba[corners.ravel()] = colours(face_energy, face_folded)[np.repeat(polygon, 3)]

    old = mesh.color_attributes.get(NAME)
    if old is not None:
        mesh.color_attributes.remove(old)
    layer = mesh.color_attributes.new(NAME, 'FLOAT_COLOR', 'CORNER')
    layer.data.foreach_set("color", rgba.ravel())
    mesh.color_attributes.active_color = layer
    mesh.update()
    high = area[~np.isnan(energy) & (energy >= HIGH)].sum()
    return {"median": measured["median"], "mean": measured["mean"], "folded": measured["folded"],
            "high_area": float(high / area.sum()) if area.sum() > 0 else 0.0}
