"""The 24 ColorChecker patches inside a closed sphere that emits a standard illuminant (not a test
module): every patch receives the irradiance π L(λ) of the sphere, so its radiance is ρ(λ) L(λ)."""

from __future__ import annotations

import numpy as np

from engine.tracer.scene import Camera, Material, ReflectanceSpec, SpectrumSpec
from engine.tracer.spectra.measured_reflectance import checker_patches

from .tracer_scenes import look_at, make_scene, quad, uv_sphere

CHECKER = "ColorChecker N Ohta"
COLUMNS, ROWS = 6, 4
PATCH_M, GAP_M = 0.25, 0.05
PIXELS_PER_M = 64.0


def patch_centres():
    """(x, y) of patch i (chart order, row by row from the top-left), metres."""
    pitch = PATCH_M + GAP_M
    return [((c - (COLUMNS - 1) / 2) * pitch, ((ROWS - 1) / 2 - r) * pitch) for r in range(ROWS) for c in range(COLUMNS)]


def chart_in_glowing_sphere(illuminant: str, patches=None):
    """(scene, [(row slice, column slice) of each patch's inner pixels]) lit by ``illuminant``."""
    patches = patches or checker_patches(CHECKER)
    width_m, height_m = COLUMNS * (PATCH_M + GAP_M), ROWS * (PATCH_M + GAP_M)
    resolution = (int(width_m * PIXELS_PER_M), int(height_m * PIXELS_PER_M))
    distance = 2.5
    film_mm = 36.0 * width_m / distance * 50.0 / 36.0
    camera = Camera("cam", look_at((0, 0, distance), (0, 0, 0), up=(0, 1, 0)), resolution,
                    film_width_mm=film_mm, film_height_mm=film_mm * resolution[1] / resolution[0])
    parts, materials, windows = [], [], []
    margin = 0.3 * PATCH_M
    for i, ((x, y), name) in enumerate(zip(patch_centres(), patches)):
        parts.append((*quad((x, y, 0.0), (PATCH_M / 2, 0, 0), (0, PATCH_M / 2, 0)), i))
        materials.append(Material(name, reflectance=ReflectanceSpec(kind="measured", name=name)))
        columns = slice(int((x - PATCH_M / 2 + margin + width_m / 2) * PIXELS_PER_M),
                        int((x + PATCH_M / 2 - margin + width_m / 2) * PIXELS_PER_M))
        rows = slice(int((height_m / 2 - y - PATCH_M / 2 + margin) * PIXELS_PER_M),
                     int((height_m / 2 - y + PATCH_M / 2 - margin) * PIXELS_PER_M))
        windows.append((rows, columns))
    sphere = uv_sphere((0, 0, 0), 4.0, rings=16, segments=32, inward=True)
    parts.append((*sphere, len(materials)))
    materials.append(Material("sky", base_color=(0.0, 0.0, 0.0), emission_strength=1.0,
                              emission=SpectrumSpec(kind="illuminant", illuminant=illuminant)))
    return make_scene(parts, materials, camera), windows


def patch_means(image, windows) -> np.ndarray:
    """Mean colour [24, 3] of each patch's inner pixels."""
    return np.array([image[rows, columns].reshape(-1, 3).mean(axis=0) for rows, columns in windows])
