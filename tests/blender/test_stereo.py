"""Output ▸ Stereoscopy (multi-view) as Cycles renders it: every view, each from the camera Blender places for
it (half the Interocular Distance along the camera's X; Off-Axis convergence shifts the film so the eyes'
images agree at the Convergence Plane Distance). Both engines render the same .blend; each view's image is
compared with Cycles' in absolute light and with the closed form of where the card lands."""

from __future__ import annotations

import importlib
import os
import tempfile

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, shader_material
from helpers.cycles import luminance

WIDTH, HEIGHT = 48, 16
DEPTH_M = 4.0  # camera height over the card
INTEROCULAR_M = 0.4
LENS_MM, SENSOR_MM = 50.0, 36.0


def _emissive_card(size_m: float, location):
    """A square card facing +Z that emits radiance 1 (no light needed, nothing else to shade)."""
    half = size_m / 2
    mesh = bpy.data.meshes.new("Card")
    mesh.from_pydata([(-half, -half, 0), (half, -half, 0), (half, half, 0), (-half, half, 0)], [], [(0, 1, 2, 3)])
    mesh.materials.append(shader_material("Glow", "ShaderNodeEmission"))
    card = bpy.data.objects.new("Card", mesh)
    card.location = location
    bpy.context.scene.collection.objects.link(card)


def _stereo_scene(scene, convergence: str):
    world = bpy.data.worlds.new("Black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    _emissive_card(0.5, (0.0, 0.0, 0.0))
    camera = add_camera((0.0, 0.0, DEPTH_M), (0.0, 0.0, 0.0), lens_mm=LENS_MM, resolution=(WIDTH, HEIGHT))
    camera.data.sensor_width = SENSOR_MM
    stereo = camera.data.stereo
    stereo.convergence_mode = convergence
    stereo.interocular_distance = INTEROCULAR_M
    stereo.convergence_distance = DEPTH_M
    stereo.pivot = "CENTER"  # the eyes either side of the camera (Blender's default puts the left eye at it)
    scene.render.use_multiview = True
    scene.render.views_format = "STEREO_3D"
    scene.render.image_settings.views_format = "INDIVIDUAL"


def _render_views(scene, engine: str, samples: int, import_openimageio) -> dict[str, np.ndarray]:
    """{view suffix: RGBA [H, W, 4]} of ``engine``'s render (Blender writes one EXR per view)."""
    scene.render.engine = engine
    if engine == "CYCLES":
        scene.cycles.device, scene.cycles.samples, scene.cycles.use_denoising = "CPU", samples, False
        scene.cycles.use_adaptive_sampling, scene.cycles.pixel_filter_type = False, "BOX"
        scene.cycles.filter_width = 1.0
    else:
        scene.prism.samples = samples
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.color_mode = "OPEN_EXR", "32", "RGBA"
    with tempfile.TemporaryDirectory() as directory:
        scene.render.filepath = os.path.join(directory, "render.exr")
        scene.render.use_file_extension = False
        bpy.ops.render.render(write_still=True)
        return {suffix: _read_rgba(os.path.join(directory, f"render{suffix}.exr"), import_openimageio) for suffix in ("_L", "_R")}


def _read_rgba(path, import_openimageio) -> np.ndarray:
    """RGBA [H, W, 4], row 0 on top, of one view's EXR (read with OpenImageIO: the file names its view, and
    ``bpy.data.images.load`` then opens it as an empty stereo image)."""
    oiio = import_openimageio()
    image = oiio.ImageInput.open(path)
    spec = image.spec()
    pixels = np.asarray(image.read_image(0, 0, 0, spec.nchannels, "float")).reshape(spec.height, spec.width, -1)
    image.close()
    return pixels[..., [spec.channelnames.index(name) for name in ("R", "G", "B", "A")]]


def _centre_x(image) -> float:
    """The luminance-weighted mean column of the card (pixel centres at 0.5, 1.5, ...)."""
    lum = luminance(image).sum(axis=0)
    return float((lum * (np.arange(WIDTH) + 0.5)).sum() / lum.sum())


@pytest.mark.parametrize("convergence", ["PARALLEL", "OFFAXIS", "TOE"])
def test_each_view_is_seen_from_its_eye_as_in_cycles(prism_addon, fresh_scene, convergence):
    """Parallel: each eye sees the card moved by f·(IOD/2)/depth on the film, opposite ways; Off-Axis (film
    shifted) and Toe-in (eyes turned) with the convergence plane at the card: both eyes see it centred."""
    _stereo_scene(fresh_scene, convergence)
    reader = importlib.import_module(f"{prism_addon.__name__}.engine.output.openimageio").import_openimageio
    cycles = _render_views(fresh_scene, "CYCLES", 64, reader)
    prism = _render_views(fresh_scene, "PRISM", 64, reader)
    moved_px = LENS_MM * (INTEROCULAR_M / 2) / DEPTH_M / SENSOR_MM * WIDTH if convergence == "PARALLEL" else 0.0
    for suffix, sign in (("_L", 1.0), ("_R", -1.0)):
        expected = WIDTH / 2 + sign * moved_px  # the left eye sits at -X, so the card appears right of centre
        ratio = luminance(prism[suffix]).mean() / luminance(cycles[suffix]).mean()
        print(f"MEASURED stereo {convergence} {suffix}: card centre Prism {_centre_x(prism[suffix]):.3f} px, "
              f"Cycles {_centre_x(cycles[suffix]):.3f} px, closed form {expected:.3f} px; Prism / Cycles {ratio:.4f}")
        assert _centre_x(prism[suffix]) == pytest.approx(expected, abs=0.1)
        assert _centre_x(prism[suffix]) == pytest.approx(_centre_x(cycles[suffix]), abs=0.1)
        assert ratio == pytest.approx(1.0, abs=0.02)


def test_a_mono_render_has_one_unnamed_view(prism_addon, fresh_scene):
    """Without Stereoscopy the camera is the scene camera itself."""
    import importlib

    stereo = importlib.import_module(f"{prism_addon.__name__}.engine.render.stereo")

    class _Engine:  # a render without Stereoscopy never asks Blender for views
        pass

    _stereo_scene(fresh_scene, "PARALLEL")
    fresh_scene.render.use_multiview = False
    depsgraph = bpy.context.evaluated_depsgraph_get()
    camera = object()
    assert stereo.render_views(_Engine(), depsgraph, camera, []) == [stereo.RenderView("", camera)]
