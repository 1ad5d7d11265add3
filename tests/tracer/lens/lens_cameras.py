"""Shared helpers for the real-lens camera tests: cameras with a given film distance and
deterministic lens samples."""

import numpy as np

from engine.tracer.lens.camera import RealLensCamera
from engine.tracer.lens.catalogue import LENS_DIRECTORY
from engine.tracer.scene import Camera
from engine.tracer.settings import RenderSettings

D_LINE_NM = 587.5618


def lens_path(name):
    return str(LENS_DIRECTORY / f"{name}.lens")


def real_lens_camera(lens_file, fstop, sensor_distance_mm=None, focus_distance_m=3.0, film_mm=36.0, **settings):
    """A square-film ``RealLensCamera`` at the world origin (camera space = world space)."""
    camera = Camera("cam", np.eye(4), (64, 64), film_width_mm=film_mm, film_height_mm=film_mm, model="real_lens",
                    lens_file=lens_file, fstop=fstop, focus_distance_m=focus_distance_m,
                    sensor_distance_mm=sensor_distance_mm)
    return RealLensCamera(camera, RenderSettings(**settings))


def lattice_uv(count=10946, generator=6765):
    """A Fibonacci lattice of ``count`` lens samples in [0, 1)^2 (F_21 points, generator F_20)."""
    i = np.arange(count)
    return np.column_stack([(i + 0.5) / count, ((i * generator) % count + 0.5) / count])


def ring_uv(fraction, per_side=4):
    """Lens samples that the concentric disk map sends to the circle of radius ``fraction``
    of the sampled shape (the square ring max(|2u - 1|, |2v - 1|) = fraction)."""
    s = (np.arange(per_side) + 0.5) / per_side * 2.0 - 1.0
    sides = np.concatenate([np.column_stack([np.ones_like(s), s]), np.column_stack([-np.ones_like(s), s]),
                            np.column_stack([s, np.ones_like(s)]), np.column_stack([s, -np.ones_like(s)])])
    return 0.5 + 0.5 * fraction * sides
