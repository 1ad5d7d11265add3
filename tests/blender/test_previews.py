"""Material and light previews rendered by Prism itself (``bl_use_preview``), in Blender's preview scene."""

from __future__ import annotations

import time

import bpy
import numpy as np
import pytest


def _preview(data_block, timeout=120.0) -> np.ndarray:
    """Blender's preview of ``data_block`` (RGBA [H, W, 4], display-encoded), rendered as the UI does:
    by a job thread Blender starts (headless, it is waited for here)."""
    with bpy.context.temp_override(id=data_block):
        assert bpy.ops.ed.lib_id_generate_preview() == {"FINISHED"}
    preview = data_block.preview
    end = time.perf_counter() + timeout
    while True:
        width, height = preview.image_size
        pixels = np.array(preview.image_pixels_float[:], np.float32)
        if pixels.any():
            return pixels.reshape(height, width, 4)
        assert time.perf_counter() < end, "the preview was not rendered"
        time.sleep(0.05)


def _glass(name, catalogue_glass=None):
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    principled = material.node_tree.nodes["Principled BSDF"]
    principled.inputs["Transmission Weight"].default_value = 1.0
    principled.inputs["Roughness"].default_value = 0.0
    principled.inputs["IOR"].default_value = 1.78
    if catalogue_glass:
        material.prism.glass_source, material.prism.glass_name = "CATALOGUE", catalogue_glass
    return material


def _chroma(rgb):
    return rgb.max(axis=-1) - rgb.min(axis=-1)


def test_a_dispersive_glass_preview_shows_its_colours(fresh_scene):
    """N-SF11 (V_d 25.7) against a glass of the same index that does not disperse: the preview
    sphere's refracted light splits into colours only in the first."""
    dispersive = _preview(_glass("Flint", "N-SF11"))
    plain = _preview(_glass("Constant index"))
    h, w = dispersive.shape[:2]
    sphere = (slice(h // 4, 3 * h // 4), slice(w // 4, 3 * w // 4))
    assert plain[sphere][..., :3].mean() > 0.2 and dispersive[sphere][..., :3].mean() > 0.2
    assert _chroma(dispersive[sphere][..., :3]).mean() > 4.0 * _chroma(plain[sphere][..., :3]).mean()


@pytest.mark.parametrize("source", ["RGB", "BLACKBODY"])
def test_light_previews_render_their_spectrum(fresh_scene, source):
    light = bpy.data.lights.new(f"Lamp {source}", "AREA")
    light.prism.color_source = source
    light.prism.temperature_k = 2000.0
    pixels = _preview(light)[..., :3]
    assert np.isfinite(pixels).all() and pixels.mean() > 0.05
    red, blue = pixels[..., 0].mean(), pixels[..., 2].mean()
    assert (red > 1.3 * blue) if source == "BLACKBODY" else (red < 1.1 * blue)
