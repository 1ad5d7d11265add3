"""Which rays see an object (Cycles' Object ▸ Visibility ▸ Ray Visibility) and holdouts, per triangle.

Bits of ``Geometry.flags``: ``RAY_CAMERA``, ``RAY_SHADOW``, ``RAY_DIFFUSE``, ``RAY_GLOSSY``,
``RAY_TRANSMISSION`` (the object is seen by such rays), ``HOLDOUT`` (Object ▸ Visibility ▸ Holdout,
or a Holdout material: camera paths find a transparent hole there) and ``SHADOW_CATCHER`` (Object ▸
Visibility ▸ Mask ▸ Shadow Catcher: ``stages.shadow_catcher``).
"""

from __future__ import annotations

import numpy as np

RAY_CAMERA = 1
RAY_SHADOW = 2
RAY_DIFFUSE = 4
RAY_GLOSSY = 8
RAY_TRANSMISSION = 16
HOLDOUT = 32
SHADOW_CATCHER = 64
ALL_RAYS = RAY_CAMERA | RAY_SHADOW | RAY_DIFFUSE | RAY_GLOSSY | RAY_TRANSMISSION


def triangle_flags(scene, original) -> np.ndarray:
    """uint8 [T] of the render's triangles (``original``: their indices in ``scene.triangles``)."""
    count = len(original)
    flags = np.full(count, ALL_RAYS, np.uint8)
    if scene.object_flags is not None and scene.triangle_object is not None and count:
        objects = np.asarray(scene.triangle_object)[original]
        flags = np.asarray(scene.object_flags, np.uint8)[objects].copy()
    holdout_materials = np.array([bool(getattr(m, "holdout", False)) for m in scene.materials], bool)
    if holdout_materials.any() and count:
        flags[holdout_materials[np.asarray(scene.triangle_material)[original]]] |= HOLDOUT
    return np.ascontiguousarray(flags)


def sphere_flags(scene, rows) -> np.ndarray:
    """uint8 [S] of the spheres ``rows`` of ``scene.points`` (as ``triangle_flags``: their object's rays and
    holdout)."""
    return _primitive_flags(scene, np.asarray(scene.points.object)[rows], np.asarray(scene.points.material)[rows])


def curve_flags(scene) -> np.ndarray:
    """uint8 [C] of the curve segments of ``scene.curves`` (as ``triangle_flags``)."""
    return _primitive_flags(scene, np.asarray(scene.curves.object), np.asarray(scene.curves.material))


def _primitive_flags(scene, objects, materials) -> np.ndarray:
    """uint8 flags of primitives of ``objects`` with ``materials`` (rows of the scene's tables)."""
    flags = np.full(len(objects), ALL_RAYS, np.uint8)
    if scene.object_flags is not None and len(objects):
        flags = np.asarray(scene.object_flags, np.uint8)[objects].copy()
    holdout_materials = np.array([bool(getattr(m, "holdout", False)) for m in scene.materials], bool)
    if holdout_materials.any() and len(objects):
        flags[holdout_materials[materials]] |= HOLDOUT
    return np.ascontiguousarray(flags)
