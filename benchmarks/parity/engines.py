"""Rendering the current bpy scene with Prism (its warnings captured) and with Cycles, set up so the two
are unbiased estimates of the same image: CPU, box filter of 1 px, no adaptive sampling, no denoising,
no clamping, Filter Glossy 0, caustics on, the same bounce limit and fixed seeds.

Every render goes through ``bpy.ops.render.render`` and Blender's own EXR writer, as an artist's F12 or
batch render would: the scene's resolution, percentage, border, film and view layers apply as Blender
applies them.
"""

from __future__ import annotations

import importlib
import io
import tempfile
import time
from pathlib import Path

import bpy
import numpy as np

from .exr_files import read_frames, read_layers, read_still
from .quiet import blender_output_silenced
from .record import EngineImage


def _prism_modules():
    """The registered add-on's ``render_request`` module (registering this checkout's copy if needed)."""
    from render import prism_package_name

    return importlib.import_module(f"{prism_package_name()}.engine.render.request")


def _configure_cycles(scene, samples: int, seed: int, bounces: int) -> None:
    cycles = scene.cycles
    cycles.device = "CPU"
    cycles.samples, cycles.seed = samples, seed
    cycles.use_animated_seed = False
    cycles.use_adaptive_sampling = False
    cycles.use_denoising = False
    cycles.sample_clamp_direct = cycles.sample_clamp_indirect = 0.0
    cycles.pixel_filter_type, cycles.filter_width = "BOX", 1.0
    cycles.blur_glossy = 0.0
    cycles.caustics_reflective = cycles.caustics_refractive = True
    for name in ("max_bounces", "diffuse_bounces", "glossy_bounces", "transmission_bounces", "volume_bounces",
                 "transparent_max_bounces"):
        setattr(cycles, name, bounces)
    scene.render.threads_mode, scene.render.threads = "FIXED", 2
    for layer in scene.view_layers:
        layer.cycles.use_denoising = False


def _write_and_read(scene, output: str) -> np.ndarray:
    """Render ``scene`` with its current engine into EXR file(s) in a temporary folder and read them back."""
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR_MULTILAYER" if output == "layers" else "OPEN_EXR"
    settings.color_depth, settings.color_mode = "32", "RGBA"
    with tempfile.TemporaryDirectory() as directory:
        folder = Path(directory)
        if output == "frames":
            scene.render.filepath = str(folder / "frame_####")
            scene.render.use_file_extension = True
            bpy.ops.render.render(animation=True)
            return read_frames(sorted(folder.glob("frame_*.exr")))
        path = folder / "render.exr"
        scene.render.filepath = str(path)
        scene.render.use_file_extension = False
        bpy.ops.render.render(write_still=True)
        if output == "layers":
            return read_layers(path, [layer.name for layer in scene.view_layers if layer.use])
        return read_still(path)


def render_cycles(scene, samples: int, bounces: int, output: str = "still", seed: int = 0) -> EngineImage:
    """Cycles' render of ``scene`` (see the module docstring for its settings)."""
    engine = scene.render.engine
    scene.render.engine = "CYCLES"
    _configure_cycles(scene, samples, seed, bounces)
    started = time.perf_counter()
    try:
        with blender_output_silenced():  # Cycles' progress lines
            rgba = _write_and_read(scene, output)
    finally:
        scene.render.engine = engine
    return EngineImage(rgba=rgba, seconds=time.perf_counter() - started)


def render_prism(scene, samples: int, bounces: int, output: str = "still", seed: int = 0) -> EngineImage:
    """Prism's render of ``scene`` through Blender, with every warning it printed (a refusal leaves
    ``rgba`` None and the message in ``error``). A warning repeated for several layers or frames is kept
    once."""
    requests = _prism_modules()
    engine = scene.render.engine
    scene.render.engine = "PRISM"
    scene.prism.max_bounces = bounces
    printed = io.StringIO()
    request = requests.RenderRequest(samples=samples, seed=seed, quick_first_pass=False, progress_stream=printed)
    started = time.perf_counter()
    rgba, error = None, None
    try:
        with requests.render_request(request) as report, blender_output_silenced():
            try:
                rgba = _write_and_read(scene, output)
            except RuntimeError as refused:  # Blender raises the engine's error report
                error = report.error or str(refused).strip()
            error = error or report.error
    finally:
        scene.render.engine = engine
    warnings = _warnings_printed(printed.getvalue())
    return EngineImage(rgba=None if error else rgba, seconds=time.perf_counter() - started, warnings=warnings,
                       error=error)


def _warnings_printed(text: str) -> list[str]:
    prefix = "Prism: warning: "
    found = [line[len(prefix):].strip() for line in text.splitlines() if line.startswith(prefix)]
    return list(dict.fromkeys(found))
