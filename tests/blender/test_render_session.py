"""F12 renders end to end through ``bpy.ops.render.render``: spectra, cancel, border, passes."""

from __future__ import annotations

import importlib

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane, add_point_light, render_linear_rgb

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Rec.709 Y of linear RGB


def _session(prism_addon):
    return importlib.import_module(f"{prism_addon.__name__}.engine.render.session")


def _reporting(prism_addon):
    """``with _reporting(addon) as report:`` around a render: the F12 defaults, and its report."""
    return importlib.import_module(f"{prism_addon.__name__}.engine.render.request").render_request()


def _count_passes(prism_addon, monkeypatch) -> list:
    """The ``samples_done`` after each finished ``Renderer.render_pass``, appended as the render goes."""
    renderer_module = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.renderer")
    done = []
    original_pass = renderer_module.Renderer.render_pass

    def counting_pass(self, samples_per_pixel=None):
        original_pass(self, samples_per_pixel)
        done.append(self.samples_done)

    monkeypatch.setattr(renderer_module.Renderer, "render_pass", counting_pass)
    return done


def _press_esc_when(prism_addon, monkeypatch, pressed) -> None:
    """Renders see the real engine, except that ``test_break`` (Esc) answers ``pressed()``."""
    session = _session(prism_addon)

    class EscWhen:
        def __init__(self, engine):
            self._engine = engine

        def test_break(self):
            return pressed()

        def __getattr__(self, name):
            return getattr(self._engine, name)

    original_init = session.RenderSession.__init__

    def init(self, engine, depsgraph, *handed_over):
        original_init(self, EscWhen(engine), depsgraph, *handed_over)

    monkeypatch.setattr(session.RenderSession, "__init__", init)


def _press_esc_after(prism_addon, monkeypatch, done: list, passes: int) -> None:
    """Esc is 'pressed' once ``passes`` passes have finished (``done``: see ``_count_passes``)."""
    _press_esc_when(prism_addon, monkeypatch, lambda: len(done) >= passes)


@pytest.fixture
def lit_plane(fresh_scene):
    add_plane("Floor", 8.0, color=(0.8, 0.8, 0.8))
    add_point_light("Bulb", 400.0, (0.0, 0.0, 2.0))
    add_camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), lens_mm=35.0, resolution=(24, 24))
    fresh_scene.world = None
    return fresh_scene


def test_blackbody_light_changes_colour_not_luminance(lit_plane):
    settings = bpy.data.lights["Bulb"].prism
    settings.color_source = "BLACKBODY"
    means = {}
    for temperature in (2700.0, 10000.0):
        settings.temperature_k = temperature
        means[temperature] = render_linear_rgb(lit_plane, samples=4).reshape(-1, 3).mean(axis=0)
    warm, cool = means[2700.0], means[10000.0]
    assert warm @ LUMINANCE == pytest.approx(cool @ LUMINANCE, rel=0.03)
    assert warm[0] / warm[2] > 2.0 > 1.0 > cool[0] / cool[2]  # candle-warm vs sky-blue


def test_cancelling_after_the_first_pass_keeps_the_partial_image(prism_addon, lit_plane, monkeypatch):
    passes = _count_passes(prism_addon, monkeypatch)
    _press_esc_after(prism_addon, monkeypatch, passes, 1)
    with _reporting(prism_addon) as report:
        image = render_linear_rgb(lit_plane, samples=64)
    assert passes == [1]
    assert report.error is None and report.cancelled
    assert np.isfinite(image).all() and image.mean() > 0.05  # the first pass's image is there
    assert (image > 0).mean() > 0.9


def test_first_pass_is_quick_then_full_passes(prism_addon, lit_plane, monkeypatch):
    done = _count_passes(prism_addon, monkeypatch)
    lit_plane.prism.samples_per_pass = 4
    with _reporting(prism_addon) as report:
        render_linear_rgb(lit_plane, samples=9)
    assert done == [1, 5, 9]
    assert "9/9 spp" in report.stats and not report.cancelled


def test_the_render_result_is_refreshed_at_intervals_and_holds_every_finished_pass(prism_addon, lit_plane,
                                                                                     monkeypatch):
    """Copying the image into Blender's Render Result costs ~50 ms at 480 x 320, more than a small frame's
    pass: it happens after the first pass, then at most every ``DISPLAY_INTERVAL_S``, and always after the
    last pass, or after the last finished pass when the render is stopped between refreshes."""
    session = _session(prism_addon)
    monkeypatch.setattr(session, "DISPLAY_INTERVAL_S", 3600.0)
    writes = []
    original_write = session.RenderSession._write

    def counting_write(self, result, renderer, wanted, denoise):
        writes.append(renderer.samples_done)
        original_write(self, result, renderer, wanted, denoise)

    monkeypatch.setattr(session.RenderSession, "_write", counting_write)
    lit_plane.prism.samples_per_pass = 1
    render_linear_rgb(lit_plane, samples=6)
    assert writes == [1, 6]

    writes.clear()
    done = _count_passes(prism_addon, monkeypatch)
    _press_esc_after(prism_addon, monkeypatch, done, 3)
    with _reporting(prism_addon) as report:
        image = render_linear_rgb(lit_plane, samples=64)
    assert report.cancelled and done == [1, 2, 3]
    assert writes == [1, 3]  # the stop came between refreshes: the third pass is written all the same
    assert np.isfinite(image).all() and (image > 0).mean() > 0.9


@pytest.mark.parametrize("crop", [True, False])
def test_render_border_and_resolution_percentage(prism_addon, lit_plane, crop):
    full = render_linear_rgb(lit_plane, samples=4)
    render = lit_plane.render
    render.resolution_x = render.resolution_y = 48
    render.resolution_percentage = 50  # back to 24 x 24 pixels
    render.use_border, render.use_crop_to_border = True, crop
    render.border_min_x, render.border_max_x = 0.25, 0.75
    render.border_min_y, render.border_max_y = 0.5, 1.0  # the top half (Blender's y is up)
    image = render_linear_rgb(lit_plane, samples=4)
    region = full[0:12, 6:18]
    if crop:
        assert image.shape == (12, 12, 3)
        inside = image
    else:
        assert image.shape == (24, 24, 3)
        inside = image[0:12, 6:18]
        outside = image.copy()
        outside[0:12, 6:18] = 0
        assert not outside.any()
    assert inside.mean() == pytest.approx(region.mean(), rel=0.05)
    assert np.corrcoef(inside[..., 1].ravel(), region[..., 1].ravel())[0, 1] > 0.9


def test_noise_and_sample_count_passes(prism_addon, lit_plane, tmp_path):
    chunks = importlib.import_module(f"{prism_addon.__name__}.engine.render.chunks")
    lit_plane.prism.use_pass_variance = True
    lit_plane.prism.use_pass_sample_count = True
    lit_plane.prism.samples = 6
    settings = lit_plane.render.image_settings
    settings.file_format, settings.color_depth = "OPEN_EXR_MULTILAYER", "32"
    path = tmp_path / "passes.exr"
    lit_plane.render.filepath = str(path)
    lit_plane.render.use_file_extension = False
    bpy.ops.render.render(write_still=True)
    oiio = chunks._oiio()
    image = oiio.ImageInput.open(str(path))
    spec = image.spec()
    names = list(spec.channelnames)
    pixels = np.asarray(image.read_image(0, 0, 0, spec.nchannels, "float")).reshape(24, 24, -1)
    image.close()
    count = pixels[..., names.index("ViewLayer.Sample Count.X")]
    noise = np.stack([pixels[..., names.index(f"ViewLayer.Noise.{c}")] for c in "RGB"], axis=-1)
    combined = np.stack([pixels[..., names.index(f"ViewLayer.Combined.{c}")] for c in "RGB"], axis=-1)
    assert (count == 6).all()
    assert np.isfinite(noise).all() and (noise >= 0).all() and noise.mean() > 0
    # The variance of a 6-sample mean is far below the squared mean of a well-lit plane.
    assert noise.mean() < 0.1 * (combined**2).mean()


def test_dispersive_glass_reaches_the_renderer(prism_addon, lit_plane):
    slab = add_plane("Slab", 1.0, location=(0.0, 0.0, 1.0))
    material = slab.active_material
    material.node_tree.nodes["Principled BSDF"].inputs["Transmission Weight"].default_value = 1.0
    material.prism.glass_source = "CATALOGUE"
    material.prism.glass_name = "SF11"
    with _reporting(prism_addon) as report:
        image = render_linear_rgb(lit_plane, samples=2)
    stats = report.stats
    assert "hero-wavelength termination (SF11)" in stats
    assert np.isfinite(image).all()


def test_cancelling_inside_a_pass_stops_after_the_current_chunk(prism_addon, lit_plane, monkeypatch):
    calls = []

    def pressed():  # Esc from the second check on: that check runs after the pass's first chunk
        calls.append(True)
        return len(calls) >= 2

    _press_esc_when(prism_addon, monkeypatch, pressed)
    lit_plane.prism.samples_per_pass = 64  # one pass of 24 x 24 x 64 paths, cut into two chunks
    with _reporting(prism_addon) as report:
        image = render_linear_rgb(lit_plane, samples=64)
    assert report.error is None and report.cancelled
    assert len(calls) == 2  # stopped at the check after the first chunk, not after the pass
    assert "0/64 spp" in report.stats  # the pass never completed...
    assert np.isfinite(image).all() and image.mean() > 0.05  # ...but its first chunk's samples are shown
