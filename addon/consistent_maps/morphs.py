"""Shape-key morphs: one object taking another's shape with its own mesh, and their animation.

The key "→ <target>" on the source holds each source vertex mapped onto the target
through the common sphere, optionally aligned onto the source first (alignment).
"""
import numpy as np

from . import alignment, features, mapping, maps, meshdata

PREFIX = "→ "


def key_name(target):
    return f"{PREFIX}{target.name}"


def shared_features(source, target):
    """(source vertices, target vertices) of the placed features both objects have, for aligning them;
    raises maps.MapError below 3."""
    source_features, target_features = features.features(source), features.features(target)
    shared = [name for name in source_features if name in target_features]
    if len(shared) < 3:
        raise maps.MapError(f"'{source.name}' and '{target.name}' share {len(shared)} placed feature(s); aligning "
                            f"by features needs 3: place more or choose another alignment")
    return [source_features[n] for n in shared], [target_features[n] for n in shared]


def _transform(source, target, align, mapped):
    if align == 'none':
        return alignment.identity()
    if align == 'bounds':
        return alignment.bounds(mapped, maps.positions(source.data))
    source_vertices, target_vertices = shared_features(source, target)
    return alignment.similarity(maps.positions(target.data)[target_vertices],
                                maps.positions(source.data)[source_vertices])


def positions(source, target, align='features'):
    """(n, 3) the source's vertices mapped onto the target, in the source's object space after alignment."""
    if align not in alignment.MODES:
        raise maps.MapError(f"Unknown alignment '{align}': use one of {', '.join(alignment.MODES)}")
    maps.check([source, target])
    target_triangles, _ = meshdata.loop_triangles(target.data)
    mapped = mapping.at_vertices(maps.vertex_landing(source, target), target_triangles,
                                 maps.positions(target.data))
    return _transform(source, target, align, mapped)(mapped)


def add(source, target, align='features'):
    """Adds (or refreshes) the key "→ <target>" on source; returns the key block. Nothing is modified
    when the objects cannot be mapped (MapError)."""
    co = positions(source, target, align)
    mesh = source.data
    if mesh.shape_keys is None:
        source.shape_key_add(name="Basis", from_mix=False)
    name = key_name(target)
    key = mesh.shape_keys.key_blocks.get(name) or source.shape_key_add(name=name, from_mix=False)
    key.data.foreach_set("co", co.astype(np.float32).ravel())
    mesh.update()
    return key


def morph_keys(obj):
    keys = obj.data.shape_keys if obj.type == 'MESH' else None
    return [key for key in keys.key_blocks if key.name.startswith(PREFIX)] if keys else []


def animate(obj, frame_start, frame_end, ping_pong=False, key=None):
    """Keyframes a morph key's value from 0 at frame_start to 1 at frame_end (ping_pong: 1 half way,
    back to 0 at frame_end), replacing its earlier keyframes. key: its name; by default the object's
    last morph key. Returns the key block."""
    candidates = morph_keys(obj)
    chosen = candidates[-1] if candidates and key is None else next((k for k in candidates if k.name == key), None)
    if chosen is None:
        raise maps.MapError(f"'{obj.name}' has no morph key{'' if key is None else f' {key!r}'}: "
                            f"create one with Morph first")
    if frame_end <= frame_start:
        raise maps.MapError(f"The animation must end after it starts (frames {frame_start} to {frame_end})")
    keys = obj.data.shape_keys
    path = chosen.path_from_id("value")
    action = keys.animation_data.action if keys.animation_data else None
    curve = action.fcurves.find(path) if action else None
    if curve is not None:
        action.fcurves.remove(curve)
    frames = [(frame_start, 0.0), (frame_end, 1.0)]
    if ping_pong:
        frames = [(frame_start, 0.0), ((frame_start + frame_end) / 2, 1.0), (frame_end, 0.0)]
    for frame, value in frames:
        chosen.value = value
        chosen.keyframe_insert("value", frame=frame)
    return chosen
