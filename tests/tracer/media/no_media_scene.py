"""A fixed scene without media (diffuse floor, glass sphere, point light, sky): ``test_no_media_unchanged``
checks that the media code leaves it bit for bit."""

from __future__ import annotations

import hashlib

import numpy as np

from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, World

from ..tracer_scenes import look_at, make_scene, quad, settings, uv_sphere


def no_media_scene():
    cam = Camera("cam", look_at((0.0, -4.0, 1.5), (0.0, 0.0, 0.3)), (16, 12), film_width_mm=36.0,
                 film_height_mm=27.0)
    floor = quad((0, 0, 0), (4, 0, 0), (0, 4, 0))
    ball = uv_sphere((0.0, 0.0, 0.6), 0.6, rings=12, segments=24)
    materials = [Material("floor", base_color=(0.6, 0.5, 0.4)), Material("glass", kind="dielectric", ior=1.5)]
    light = Light("lamp", "point", np.array([1.0, -1.0, 3.0]), power_w=200.0)
    return make_scene([(*floor, 0), (*ball, 1)], materials, cam, [light],
                      World(color=(0.2, 0.3, 0.5), strength=1.0))


def image_hash(mode="cie", media_code=False):
    """sha256 of the float32 image of ``no_media_scene`` at 8 samples, seed 1; ``media_code``: with the
    kernels' media code switched on (``KernelSettings.has_media``) although no material has a medium."""
    r = Renderer(no_media_scene(), settings(samples=8, samples_per_pass=8, wavelength_mode=mode, max_bounces=6))
    if media_code:
        tables = r.tables
        tables.kernel_settings = tables.kernel_settings._replace(has_media=True)
        tables.arrays = tables.arrays._replace(settings=tables.kernel_settings)
    r.render_pass()
    return hashlib.sha256(np.ascontiguousarray(r.image_rgb(), np.float32).tobytes()).hexdigest()


if __name__ == "__main__":
    for mode in ("cie", "gaussian_rgb"):
        print(mode, image_hash(mode))
