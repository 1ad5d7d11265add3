"""Grid media with a majorant per block of voxels against one majorant for the whole grid."""

from __future__ import annotations

import statistics
import time

import numpy as np

TITLE = "Grid media: a majorant per block of 8³ voxels against the whole grid's"
LUMINANCE = np.array([0.2126729, 0.7151522, 0.0721750])


def _scene(size: int, resolution: int):
    """A 2 m box of a white-ish scattering medium whose ``size``³ density grid is empty but for a lumpy plume
    (about 1 % of the voxels, density 2-6), under a sun and a blue sky, seen from 6 m."""
    from engine.tracer.media.density_grid import DensityGrid
    from engine.tracer.media.spec import MediumSpec
    from engine.tracer.scene import Camera, Light, Material, Scene, World
    from benchmarks.scenes import look_at

    rng = np.random.default_rng(4)
    x, y, z = np.meshgrid(*(np.linspace(-1.0, 1.0, size),) * 3, indexing="ij")
    plume = (x - 0.3) ** 2 / 0.09 + (y + 0.2) ** 2 / 0.04 + z ** 2 / 0.16 < 1.0
    values = np.where(plume, rng.uniform(2.0, 6.0, plume.shape), 0.0).astype(np.float32)
    step = 2.0 / (size - 1)
    grid = DensityGrid(values, np.array([[step, 0, 0, -1.0], [0, step, 0, -1.0], [0, 0, step, -1.0], [0, 0, 0, 1.0]]))
    spec = MediumSpec("plume", scatter=[(4.0, (0.9, 0.85, 0.8))], absorb=[(0.5, (0.5, 0.5, 0.5))], anisotropy=0.3,
                      density_grid=grid)
    corners = np.array([[a, b, c] for c in (-1, 1) for b in (-1, 1) for a in (-1, 1)], float) * 1.001
    faces = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    triangles = np.array([[f[0], f[1], f[2]] for f in faces] + [[f[0], f[2], f[3]] for f in faces], np.int32)
    camera = Camera("cam", look_at((0.0, -6.0, 1.5), (0.0, 0.0, 0.0)), (resolution, resolution),
                    film_width_mm=24.0, film_height_mm=24.0)
    sun = Light("sun", "sun", np.zeros(3), direction=np.array([0.3, 0.5, -0.8]) / np.linalg.norm([0.3, 0.5, -0.8]),
                irradiance_w_m2=3.0)
    return Scene(vertices=corners, triangles=triangles, triangle_material=np.zeros(12, np.int32),
                 materials=[Material("plume", kind="null", medium=spec)], camera=camera, lights=[sun],
                 world=World(color=(0.2, 0.3, 0.5), strength=1.0))


def _render(size: int, resolution: int, spp: int, brick_voxels: int):
    """(seconds of the timed pass, mean luminance, its standard error) with blocks of ``brick_voxels``."""
    from benchmarks.prism_runs import settings_for
    from engine.tracer.media import brick_majorants
    from engine.tracer.renderer import Renderer

    kept = brick_majorants.BRICK_VOXELS
    brick_majorants.BRICK_VOXELS = brick_voxels
    try:
        settings = settings_for(dict(max_bounces=16, samples_per_pass=spp), spp, 0, 2)
        with Renderer(_scene(size, resolution), settings) as r:
            start = time.perf_counter()
            r.render_pass()
            seconds = time.perf_counter() - start
            image = r.image_rgb().astype(np.float64)
            variance = r.variance_rgb().astype(np.float64).mean((0, 1)) @ LUMINANCE ** 2
    finally:
        brick_majorants.BRICK_VOXELS = kept
    return seconds, float(image.mean((0, 1)) @ LUMINANCE), float(np.sqrt(variance / image[..., 0].size))


def run(quick: bool) -> dict:
    size, resolution, spp, repeats = (32, 16, 4, 1) if quick else (128, 64, 32, 3)
    variants = {"one block (the grid's majorant)": 1 << 20, "blocks of 8³ voxels": 8}
    _render(size, 8, 1, 8)  # untimed: kernels loaded, tables built
    times = {name: [] for name in variants}
    light = {}
    for _ in range(repeats):  # interleaved
        for name, voxels in variants.items():
            seconds, mean, stderr = _render(size, resolution, spp, voxels)
            times[name].append(seconds)
            light[name] = (mean, stderr)
    rows = [{"majorant": name, "pass (s), median": statistics.median(times[name]),
             "mean luminance": light[name][0], "standard error": light[name][1]} for name in variants]
    one, blocks = (statistics.median(times[name]) for name in variants)
    apart = abs(rows[0]["mean luminance"] - rows[1]["mean luminance"]) / max(rows[1]["mean luminance"], 1e-12)
    summary = (f"A {size}³ grid, empty but for a plume of about 1 % of its voxels (density 2-6), in a 2 m box under "
               f"a sun and a sky, {resolution}×{resolution} px, {spp} spp, 16 bounces, 2 threads, median of "
               f"{repeats} interleaved passes: with one majorant for the whole grid a pass takes "
               f"{one / blocks:.2f}× as long as with blocks; their mean luminances differ by {apart:.2%} (standard errors "
               f"{rows[0]['standard error'] / rows[0]['mean luminance']:.2%} and "
               f"{rows[1]['standard error'] / rows[1]['mean luminance']:.2%}).")
    return {"rows": rows, "summary": summary}
