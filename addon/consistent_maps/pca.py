"""Database of consistent remeshes (thesis 4.2): the mean shape and its principal variations.

Remeshes share one connectivity, so each is a vector of V positions; the mean of
those vectors becomes a new object whose shape keys are the first principal
components at +3 standard deviations (sliders from -1 to 1: -3 to +3 sd).
"""
import numpy as np

from . import connectivity, features, maps

VARIANCE = "cm_explained_variance"
SPREAD = 3.0  # standard deviations at a key's full strength


def analyse(positions, k):
    """(mean (V, 3), components (k, V, 3) at one standard deviation, fraction of variance each explains)."""
    samples = positions.reshape(len(positions), -1)
    mean = samples.mean(axis=0)
    _, singular, directions = np.linalg.svd(samples - mean, full_matrices=False)
    variance = singular ** 2
    total = variance.sum()
    fraction = variance[:k] / total if total > 0 else np.zeros(k)
    deviation = singular[:k] / np.sqrt(len(samples) - 1)
    return mean.reshape(-1, 3), (directions[:k] * deviation[:, None]).reshape(k, -1, 3), fraction


def create(objects, k):
    """The mean object ("Mean shape", in the collection "Consistent Maps") with k component keys."""
    import bpy

    from . import remeshes  # Blender-only, like everything that creates data
    objects = list(objects)
    connectivity.check(objects, "Principal components")
    if not 1 <= k <= len(objects) - 1:
        raise connectivity.RemeshSetError(
            f"{len(objects)} remeshes have at most {len(objects) - 1} principal component(s), not {k}")
    mean, components, fraction = analyse(np.stack([maps.positions(obj.data) for obj in objects]), k)
    mesh = objects[0].data.copy()  # the connectivity, and the features: vertex groups live on the mesh
    mesh.name = "Mean shape"
    obj = bpy.data.objects.new("Mean shape", mesh)
    obj.shape_key_clear()
    mesh.vertices.foreach_set("co", mean.astype(np.float32).ravel())
    obj.shape_key_add(name="Basis", from_mix=False)
    for index, (component, share) in enumerate(zip(components, fraction), start=1):
        key = obj.shape_key_add(name=f"PC{index} ({100 * share:.1f} %)", from_mix=False)
        key.data.foreach_set("co", (mean + SPREAD * component).astype(np.float32).ravel())
        key.slider_min = -1.0
    obj[VARIANCE] = [float(x) for x in fraction]
    obj.matrix_world = objects[0].matrix_world.copy()
    remeshes.collection(bpy.context.scene).objects.link(obj)
    mesh.update()
    features.invalidate()
    return obj
