"""Render the current bpy scene with Cycles, set up to compare with Prism by statistics: CPU, box
filter of 1 px, no adaptive sampling, no denoising, no clamping, single-scattering GGX where it
matters, every bounce limit at ``max_bounces``."""

from __future__ import annotations

import os
import tempfile

import bpy
import numpy as np


def read_exr_rgba(path: str) -> np.ndarray:
    """float32 [H, W, 4], row 0 on top."""
    image = bpy.data.images.load(path)
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)[::-1]


def _render_to_rgba(scene) -> np.ndarray:
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.color_mode = "OPEN_EXR", "32", "RGBA"
    with tempfile.TemporaryDirectory() as directory:
        path = os.path.join(directory, "render.exr")
        scene.render.filepath = path
        scene.render.use_file_extension = False
        bpy.ops.render.render(write_still=True)
        return read_exr_rgba(path)


def render_cycles_rgba(scene, samples: int, seed: int = 0, max_bounces: int = 8, filter_glossy: float = 0.0,
                       transparent_max_bounces: int | None = None, **kind_limits: int) -> np.ndarray:
    """Cycles' scene-linear RGBA [H, W, 4] of ``scene`` (row 0 on top), unbiased (no clamps, caustics on) unless
    ``filter_glossy`` is given (Light Paths ▸ Filter Glossy; it stays set on the scene, so Prism reads it too).
    Transparent Max Bounces is ``max_bounces`` unless ``transparent_max_bounces`` is given; so are the per-kind
    limits unless given by name (``diffuse_bounces=1``, ...; they stay set, so Prism reads them too)."""
    engine = scene.render.engine
    configure_cycles(scene, samples, seed, max_bounces, filter_glossy)
    if transparent_max_bounces is not None:
        scene.cycles.transparent_max_bounces = transparent_max_bounces
    for name, limit in kind_limits.items():
        setattr(scene.cycles, name, limit)
    try:
        return _render_to_rgba(scene)
    finally:
        scene.render.engine = engine


def configure_cycles(scene, samples: int, seed: int = 0, max_bounces: int = 8, filter_glossy: float = 0.0) -> None:
    """Make Cycles ``scene``'s engine, set up as ``render_cycles_rgba`` renders (for a bake, too)."""
    scene.render.engine = "CYCLES"
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples = samples
    cycles.seed = seed
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.sample_clamp_direct = 0.0
    cycles.sample_clamp_indirect = 0.0
    cycles.pixel_filter_type = "BOX"
    cycles.filter_width = 1.0
    cycles.blur_glossy = filter_glossy
    cycles.caustics_reflective = cycles.caustics_refractive = True
    for name in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces", "volume_bounces",
                 "transparent_max_bounces"):
        setattr(cycles, name, max_bounces)
    scene.render.threads_mode = "FIXED"
    scene.render.threads = 2


def render_prism_rgba(scene, samples: int, seed: int = 0) -> np.ndarray:
    """Prism's scene-linear RGBA [H, W, 4] of ``scene`` (row 0 on top)."""
    engine = scene.render.engine
    scene.render.engine = "PRISM"
    scene.prism.samples = samples
    scene.prism.seed = seed
    try:
        return _render_to_rgba(scene)
    finally:
        scene.render.engine = engine


def luminance(rgb: np.ndarray) -> np.ndarray:
    return rgb[..., :3] @ np.array([0.2126, 0.7152, 0.0722])


def compare_mean_luminance(scene, samples: int, region, what: str, max_bounces: int = 32):
    """(Prism / Cycles, Prism's luminance, Cycles' luminance): ``scene`` rendered by both engines with
    ``samples`` and ``max_bounces``, the ratio of their mean luminance over ``region`` (printed as MEASURED)."""
    cycles = luminance(render_cycles_rgba(scene, samples, max_bounces=max_bounces))
    scene.prism.max_bounces = max_bounces
    prism = luminance(render_prism_rgba(scene, samples))
    c, p = cycles[region].mean(), prism[region].mean()
    print(f"MEASURED {what}: Prism {p:.5f}, Cycles {c:.5f}, ratio {p / c:.4f}")
    return p / c, prism, cycles
