"""Placing one shape onto another before morphing: none, by bounding boxes, or by the features.

Each function returns a transform, a function of (n, 3) points, that brings `moving`
onto `fixed`.
"""
import numpy as np

MODES = ('none', 'bounds', 'features')


def identity():
    return lambda points: points


def bounds(moving, fixed):
    """The bounding box centre of moving onto that of fixed, scaled by the ratio of their diagonals."""
    def box(points):
        low, high = points.min(axis=0), points.max(axis=0)
        return (low + high) / 2, np.linalg.norm(high - low)
    (moving_centre, moving_size), (fixed_centre, fixed_size) = box(moving), box(fixed)
    scale = fixed_size / moving_size if moving_size > 0 else 1.0
    return lambda points: (points - moving_centre) * scale + fixed_centre


def _fit(moving, fixed):
    """(scale, rotation, moving mean, fixed mean) of the least-squares similarity (Umeyama 1991)."""
    moving_mean, fixed_mean = moving.mean(axis=0), fixed.mean(axis=0)
    a, b = moving - moving_mean, fixed - fixed_mean
    u, s, vt = np.linalg.svd(b.T @ a)
    d = np.diag([1.0, 1.0, np.sign(np.linalg.det(u @ vt)) or 1.0])
    rotation = u @ d @ vt
    spread = (a ** 2).sum()
    scale = float((s * np.diag(d)).sum() / spread) if spread > 0 else 1.0
    return scale, rotation, moving_mean, fixed_mean


def similarity(moving, fixed):
    """The least-squares similarity (rotation, uniform scale, translation) taking the points moving[i]
    onto fixed[i] (Umeyama 1991); needs at least 3 points not all on a line for a unique rotation."""
    scale, rotation, moving_mean, fixed_mean = _fit(moving, fixed)
    return lambda points: scale * (points - moving_mean) @ rotation.T + fixed_mean


def rotation(moving, fixed):
    """(3, 3) the rotation of similarity(moving, fixed): how directions (normals) turn with it."""
    return _fit(moving, fixed)[1]
