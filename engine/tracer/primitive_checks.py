"""Checks of a scene's point clouds and hair curves before they render (``Scene.validate``): materials that
exist, control points that exist, positions within the range the tracer's float32 arithmetic can hold."""

from __future__ import annotations

import numpy as np

from .errors import PrismInputError
from .spheres import rendered_rows

#: Positions beyond this (m, about 6700 astronomical units) leave too little float32 range for the
#: products of distances the tracer forms (areas, squared lengths): such a scene cannot render reliably.
MAX_DISTANCE_M = 1.0e15


def _check_materials(what: str, materials, material_count: int) -> None:
    materials = np.asarray(materials)
    if materials.min() < 0 or materials.max() >= material_count:
        raise PrismInputError(
            f"Scene {what} refer to material {int(materials.max())} but there are only {material_count} "
            "materials: the exported materials are inconsistent.")


def _reach(positions) -> np.ndarray:
    with np.errstate(invalid="ignore"):
        return np.abs(np.asarray(positions, np.float64)).max(axis=1)


def _check_steps(kind: str, what: str, motion, count: int, rows) -> None:
    """``motion`` [S >= 2, ``count``, 4] (position and radius at the shutter's time steps), finite with radii >= 0 at
    ``rows``."""
    steps = np.asarray(motion)
    if steps.ndim != 3 or steps.shape[0] < 2 or steps.shape[1:] != (count, 4):
        raise PrismInputError(f"Scene {kind} motion has shape {steps.shape}, not (steps >= 2, {count}, 4) (time steps, "
                              f"{what}, position and radius): re-export the scene.")
    steps = steps[:, rows]
    if not (np.isfinite(steps).all() and (steps[..., 3] >= 0).all()):
        raise PrismInputError(f"Scene {kind} motion has {what} that are not finite or radii below 0: re-export the "
                              "scene.")


def check_points(points, material_count: int, object_names, color_slots: int = 0, motion=None) -> None:
    """``points`` (a ``spheres.SpherePoints``): materials, finite and reachable centres, colour attributes (one row
    per point in each of the scene's ``color_slots`` slots), and the points at the shutter's time steps ``motion``
    (``motion.Motion.points``: [S, N, 4], finite with radii >= 0 where the point renders)."""
    _check_materials("points", points.material, material_count)
    if motion is not None:
        _check_steps("point", "points", motion, len(points), rendered_rows(points))
    if points.colors is not None and np.shape(points.colors) != (color_slots, len(points), 4):
        raise PrismInputError(f"Scene point colour attributes have shape {np.shape(points.colors)}, not "
                              f"{(color_slots, len(points), 4)} (slots, points, RGBA): re-export the scene.")
    reach = _reach(points.centres)
    for bad, problem in ((~np.isfinite(reach), "has points whose position is NaN or infinite: fix or delete them"),
                         (reach > MAX_DISTANCE_M, f"has points more than {MAX_DISTANCE_M:.0e} m from the world "
                          "origin, beyond what Prism renders: check the object's scale and location")):
        if bad.any():
            first = int(np.flatnonzero(bad)[0])
            name = object_names[int(points.object[first])] if object_names else f"point {first}"
            raise PrismInputError(f"Point cloud '{name}' {problem} before rendering.")


def check_curves(curves, material_count: int, object_names, color_slots: int = 0, uv_slots: int = 0,
                 motion=None) -> None:
    """``curves`` (a ``curves.CurveSegments``): materials, control points, reachable points, colour attributes and
    UV maps (one row per segment, in each of the scene's ``color_slots`` and ``uv_slots`` slots), and the control
    points at the shutter's time steps ``motion`` (``motion.Motion.curves``: [S, P, 4], finite, radii >= 0)."""
    _check_materials("curves", curves.material, material_count)
    segments = np.asarray(curves.segments)
    if segments.min() < 0 or segments.max() + 3 >= len(curves.radii):
        raise PrismInputError("Scene curve segments refer to control points that do not exist: re-export the scene.")
    if motion is not None:
        _check_steps("curve", "control points", motion, len(curves.radii), slice(None))
    for what, ends, shape in (("colour attributes", curves.colors, (color_slots, len(segments), 2, 4)),
                              ("UV maps", curves.uvs, (uv_slots, len(segments), 2, 2))):
        if ends is not None and np.shape(ends) != shape:
            raise PrismInputError(f"Scene curve {what} have shape {np.shape(ends)}, not {shape} (slots, segments, "
                                  "ends, values): re-export the scene.")
    far = _reach(curves.points) > MAX_DISTANCE_M
    if far.any():
        first = int(np.searchsorted(segments, int(np.flatnonzero(far)[0]), "right")) - 1
        name = object_names[int(curves.object[max(first, 0)])] if object_names else "hair"
        raise PrismInputError(f"Hair curves '{name}' have points more than {MAX_DISTANCE_M:.0e} m from the world "
                              "origin, beyond what Prism renders: check the object's scale and location.")
