"""Render passes through Blender: Blender's names in a multilayer EXR, the same passes as Cycles renders
of the same scene, the compositor's Denoise node fed by Prism's passes, and huge frames."""

from __future__ import annotations

import importlib
import time

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import build_lit_card_scene

DATA = ("z", "normal", "position")
LIGHT = ("emit", "environment", "diffuse_direct", "diffuse_indirect", "diffuse_color", "glossy_direct",
         "glossy_indirect", "glossy_color", "transmission_direct", "transmission_indirect", "transmission_color")


def _read_layers(prism_addon, path) -> dict[str, np.ndarray]:
    """Pass name → [H, W, C] (row 0 on top) of a multilayer EXR Blender wrote."""
    oiio = importlib.import_module(f"{prism_addon.__name__}.engine.render.chunks")._oiio()
    image = oiio.ImageInput.open(str(path))
    spec = image.spec()
    pixels = np.asarray(image.read_image(0, 0, 0, spec.nchannels, "float")).reshape(spec.height, spec.width, -1)
    image.close()
    layers: dict[str, list] = {}
    for index, name in enumerate(spec.channelnames):
        _, pass_name, _ = name.split(".")
        layers.setdefault(pass_name, []).append(index)
    return {name: pixels[..., columns] for name, columns in layers.items()}


def _render_layers(prism_addon, scene, path, engine="PRISM") -> dict[str, np.ndarray]:
    scene.render.engine = engine
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth = "OPEN_EXR_MULTILAYER", "32"
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    return _read_layers(prism_addon, path)


def _switch_on(scene, names):
    layer = scene.view_layers[0]
    for name in names:
        setattr(layer, "use_pass_" + name, True)


@pytest.fixture
def card_scene(fresh_scene):
    build_lit_card_scene(resolution=(24, 16))
    fresh_scene.render.use_compositing = False
    fresh_scene.prism.samples = fresh_scene.prism.samples_per_pass = 16
    return fresh_scene


def test_passes_land_in_a_multilayer_exr_with_blenders_names(prism_addon, card_scene, tmp_path):
    _switch_on(card_scene, DATA + LIGHT)
    card_scene.prism.use_pass_denoising_data = True
    layer = card_scene.view_layers[0]
    layer.lightgroups.add(name="bulb")
    bpy.data.objects["Bulb"].lightgroup = "bulb"
    aov = layer.aovs.add()
    aov.name, aov.type = "card_id", "VALUE"
    card = bpy.data.objects["Card"].active_material
    node = card.node_tree.nodes.new("ShaderNodeOutputAOV")
    node.aov_name = "card_id"
    node.inputs["Value"].default_value = 7.0
    layers = _render_layers(prism_addon, card_scene, tmp_path / "passes.exr")
    assert set(layers) == {"Combined", "Depth", "Normal", "Position", "Emit", "Env", "DiffDir", "DiffInd", "DiffCol",
                           "GlossDir", "GlossInd", "GlossCol", "TransDir", "TransInd", "TransCol", "Denoising Normal",
                           "Denoising Albedo", "Denoising Depth", "card_id", "Combined_bulb"}
    combined = layers["Combined"][..., :3]
    assert np.allclose(layers["Combined_bulb"], combined, rtol=1e-5, atol=1e-6)  # the bulb is the only light
    recomposed = sum((layers[f"{lobe}Dir"] + layers[f"{lobe}Ind"]) * layers[f"{lobe}Col"]
                     for lobe in ("Diff", "Gloss", "Trans")) + layers["Emit"] + layers["Env"]
    assert np.allclose(recomposed, combined, rtol=1e-4, atol=1e-5)
    on_card = layers["card_id"][..., 0] == 7.0
    assert 0.02 < on_card.mean() < 0.6  # card pixels; its edges hold the covered fraction of 7
    assert layers["card_id"].min() == 0 and layers["card_id"].max() == 7.0


def _cycles(scene):
    scene.cycles.device = "CPU"
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.sample_clamp_direct = scene.cycles.sample_clamp_indirect = 0.0
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 1.0
    scene.cycles.samples = 64
    scene.view_layers[0].cycles.denoising_store_passes = True


def test_data_and_light_passes_match_cycles(prism_addon, card_scene, tmp_path):
    _switch_on(card_scene, DATA + ("diffuse_direct", "diffuse_indirect", "diffuse_color"))
    card_scene.prism.use_pass_denoising_data = True
    card_scene.prism.samples = card_scene.prism.samples_per_pass = 64
    for material in bpy.data.materials:  # pure diffuse in Cycles too (Prism exports these as diffuse)
        material.node_tree.nodes["Principled BSDF"].inputs["Specular IOR Level"].default_value = 0.0
    prism = _render_layers(prism_addon, card_scene, tmp_path / "prism.exr")
    _cycles(card_scene)
    cycles = _render_layers(prism_addon, card_scene, tmp_path / "cycles.exr", engine="CYCLES")
    # Pixels inside one surface (not at the card's edges): Normal and Position are means over the pixel.
    colour = cycles["DiffCol"]
    same = np.ones(colour.shape[:2], bool)
    same[1:-1, 1:-1] = np.all([np.abs(colour[1:-1, 1:-1] - np.roll(colour, shift, axis)[1:-1, 1:-1]).max(-1) < 1e-3
                               for shift in (1, -1) for axis in (0, 1)], axis=0)
    inside = same & (np.linalg.norm(prism["Normal"], axis=-1) > 0.9999) & (np.linalg.norm(cycles["Normal"], axis=-1) > 0.9999)
    assert inside.mean() > 0.3
    # Cycles writes a pixel centre's depth and position, Prism their mean over the pixel: equal to about
    # the curvature of depth across a pixel.
    for name, tolerance in (("Depth", 1e-3), ("Normal", 1e-4), ("Position", 1e-3), ("Denoising Normal", 1e-4)):
        difference = np.abs(prism[name][inside] - cycles[name][inside]) / np.maximum(1.0, np.abs(cycles[name][inside]))
        assert np.percentile(difference, 95) < tolerance and difference.max() < 10 * tolerance, name
    for name in ("Denoising Albedo", "DiffCol"):
        assert np.allclose(prism[name][inside], cycles[name][inside], atol=0.02), name
    for name in ("DiffDir", "DiffInd"):
        assert prism[name].mean() == pytest.approx(cycles[name].mean(), rel=0.05), name


def test_light_passes_through_a_cut_out_match_cycles(prism_addon, card_scene, tmp_path):
    """A card of Principled Alpha 0.3 over the floor: both engines split the light of the floor seen through it as
    the floor's own (Diffuse Direct and Color, alpha-blended with the card's), none of it as Transmission."""
    _switch_on(card_scene, ("diffuse_direct", "diffuse_indirect", "diffuse_color", "transmission_direct",
                            "transmission_color", "environment"))
    card_scene.prism.samples = card_scene.prism.samples_per_pass = 1024  # Indirect: 3 % apart at 1024, 8 % at 64
    for material in bpy.data.materials:  # pure diffuse in Cycles too (Prism exports these as diffuse)
        material.node_tree.nodes["Principled BSDF"].inputs["Specular IOR Level"].default_value = 0.0
    bpy.data.objects["Card"].active_material.node_tree.nodes["Principled BSDF"].inputs["Alpha"].default_value = 0.3
    prism = _render_layers(prism_addon, card_scene, tmp_path / "prism.exr")
    _cycles(card_scene)
    card_scene.cycles.samples = 1024
    cycles = _render_layers(prism_addon, card_scene, tmp_path / "cycles.exr", engine="CYCLES")
    expected = 0.3 * np.array([0.8, 0.2, 0.1]) + 0.7 * 0.6  # the card's albedo blended with the floor's
    card = np.all(np.abs(cycles["DiffCol"] - expected) < 0.05, axis=-1)
    assert card.sum() >= 6, card.sum()
    print("measured: DiffCol", prism["DiffCol"][card].mean(0), cycles["DiffCol"][card].mean(0))
    assert np.allclose(prism["DiffCol"][card].mean(0), cycles["DiffCol"][card].mean(0), atol=0.02)
    for name in ("TransDir", "TransCol"):
        assert not prism[name].any() and not cycles[name].any(), name
    for name, where, bound in (("DiffDir", card, 0.01), ("DiffInd", np.ones_like(card), 0.07)):  # Indirect: 0.3 %
        light_p = (prism[name] * prism["DiffCol"])[where].mean()                               # of Direct, noisy
        light_c = (cycles[name] * cycles["DiffCol"])[where].mean()
        print("measured:", name, light_p, light_c)
        assert light_p == pytest.approx(light_c, rel=bound), name


def _denoise_tree(scene):
    scene.use_nodes = True
    tree = scene.node_tree
    tree.nodes.clear()
    layers = tree.nodes.new("CompositorNodeRLayers")
    denoise = tree.nodes.new("CompositorNodeDenoise")
    composite = tree.nodes.new("CompositorNodeComposite")
    tree.links.new(layers.outputs["Image"], denoise.inputs["Image"])
    tree.links.new(layers.outputs["Denoising Albedo"], denoise.inputs["Albedo"])
    tree.links.new(layers.outputs["Denoising Normal"], denoise.inputs["Normal"])
    tree.links.new(denoise.outputs["Image"], composite.inputs["Image"])
    return denoise


def _render_exr(scene, path):
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth = "OPEN_EXR", "32"
    scene.render.filepath = str(path)
    scene.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(str(path))
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)[::-1, :, :3]


def test_compositor_denoise_node_and_the_denoise_option_clean_the_frame(prism_addon, card_scene, tmp_path):
    card_scene.render.resolution_x, card_scene.render.resolution_y = 64, 48
    card_scene.prism.samples = card_scene.prism.samples_per_pass = 256
    reference = _render_exr(card_scene, tmp_path / "reference.exr")
    card_scene.prism.samples = card_scene.prism.samples_per_pass = 2
    card_scene.prism.use_pass_denoising_data = True
    noisy = _render_exr(card_scene, tmp_path / "noisy.exr")
    _denoise_tree(card_scene)
    card_scene.render.use_compositing = True
    composited = _render_exr(card_scene, tmp_path / "composited.exr")
    card_scene.render.use_compositing = False
    card_scene.prism.use_denoising = True
    layers = _render_layers(prism_addon, card_scene, tmp_path / "denoised.exr")
    denoised = layers["Combined"][..., :3]
    assert np.array_equal(layers["Noisy Image"][..., :3], noisy)
    error = lambda image: float(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)))  # noqa: E731
    # Both run Blender's OpenImageDenoise on Prism's passes (Blender's node differs in details of its own).
    assert error(denoised) < 0.33 * error(noisy) and error(composited) < 0.33 * error(noisy)


def test_a_frame_too_large_for_memory_fails_at_once(prism_addon, card_scene, bad_input):
    session = importlib.import_module(f"{prism_addon.__name__}.engine.render.request")
    _switch_on(card_scene, DATA + LIGHT)
    card_scene.prism.use_pass_denoising_data = True
    card_scene.render.resolution_x = card_scene.render.resolution_y = 20000
    started = time.perf_counter()
    with session.render_request(session.RenderRequest(quick_first_pass=False)) as report:
        with pytest.raises(RuntimeError):
            bpy.ops.render.render()
    assert time.perf_counter() - started < 30
    bad_input("a 20000 x 20000 frame with every pass on", 1, report.error)
    assert report.error.startswith("Scene 'Scene': a 20000 x 20000 frame needs about ")
    assert "for the image Blender keeps: Combined and 47 more pass channels" in report.error
    assert "GB of memory is available" in report.error


def test_batch_noise_threshold_and_time_limit(prism_addon, card_scene, tmp_path, capsys):
    from helpers.batch import run_batch_stderr

    path = tmp_path / "card.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    status, stderr = run_batch_stderr(capsys, path, "--samples", 64, "--noise-threshold", 0.05, "--min-samples", 8,
                                      "--time-limit", 60, "--output", tmp_path / "out.exr", in_blender=False)
    assert status == 0, stderr
    assert "of pixels sampling" in stderr or "converged" in stderr
    status, stderr = run_batch_stderr(capsys, path, "--samples", 4, "--chunk-seed", 0, "--noise-threshold", 0.05,
                                      "--output", tmp_path / "chunk.exr", in_blender=False)
    assert status == 2 and "leave out --noise-threshold" in stderr
