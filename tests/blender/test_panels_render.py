"""Prism's render-level panels: every panel polls only for Prism, the render settings and farm panels draw
against real data, the wavelength plot follows the settings, Blender's own panels that apply are enabled
for Prism, and the viewport header shows the pause button.

``draw`` runs with the recording layout of ``helpers.panel_layout``, which fails on any call Blender's
RNA would reject.
"""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from helpers.panel_layout import RecordingLayout
from helpers.panel_layout import context as _context
from helpers.panel_layout import draw as _draw
from helpers.panel_layout import labels as _labels
from helpers.panel_layout import props as _props


def _panels(prism_addon):
    ui = prism_addon.ui
    return [
        cls
        for module in (ui.panels_render, ui.panel_farm, ui.panels_camera, ui.panels_light, ui.panels_material)
        for cls in module.CLASSES
    ]


def test_recording_layout_rejects_misspelt_properties(fresh_scene):
    layout = RecordingLayout([])
    layout.prop(fresh_scene.prism, "samples")
    with pytest.raises(AssertionError, match="no property 'sampels'"):
        layout.prop(fresh_scene.prism, "sampels")
    with pytest.raises(AssertionError, match="no method"):
        layout.lable(text="x")
    with pytest.raises(AssertionError, match="unknown icon"):
        layout.label(text="x", icon="NOT_AN_ICON")


def test_panels_poll_only_for_prism(prism_addon, fresh_scene):
    import bpy

    camera = bpy.data.cameras.new("Cam")
    light = bpy.data.lights.new("Lamp", "POINT")
    material = bpy.data.materials.new("Mat")
    for panel in _panels(prism_addon):
        if getattr(panel, "bl_parent_id", None) == "PRISM_PT_light" and panel.__name__.endswith("beam"):
            light.type = "SPOT"
            light = bpy.data.lights["Lamp"]
        ours = _context(fresh_scene, camera=camera, light=light, material=material)
        theirs = _context(fresh_scene, engine="CYCLES", camera=camera, light=light, material=material)
        assert panel.poll(ours), panel.__name__
        assert not panel.poll(theirs), panel.__name__
        assert panel.COMPAT_ENGINES == {"PRISM"}


def test_render_panels_draw_in_both_wavelength_modes(prism_addon, fresh_scene):
    render_panels = prism_addon.ui.panels_render.CLASSES
    for mode in ("CIE", "GAUSSIAN_RGB"):
        fresh_scene.prism.wavelength_mode = mode
        drawn = []
        for panel in render_panels:
            drawn += _props(_draw(panel, _context(fresh_scene)))
        for name in ("samples", "max_bounces", "seed", "wavelength_mode", "wavelengths_per_path", "threads",
                     "mean_r_nm", "sigma_r_nm", "mean_g_nm", "sigma_g_nm", "mean_b_nm", "sigma_b_nm",
                     "use_pass_variance", "use_pass_sample_count", "preview_samples", "preview_max_bounces", "use_mis",
                     "transparent_max_bounces",
                     "pixel_filter", "filter_width_px", "light_tracing"):
            assert name in drawn
    log = _draw(prism_addon.ui.panels_render.PRISM_PT_wavelengths, _context(fresh_scene))
    assert any(name == "template_icon" for name, _, _ in log)


def test_pass_panels_draw_every_pass_switch_prism_reads(prism_addon, fresh_scene):
    """Every view-layer pass Prism renders can be switched on from its panels, with Cycles' Alpha Threshold."""
    from engine.tracer.pass_table import CYCLES_VIEW_LAYER_SWITCH, VIEW_LAYER_SWITCH

    ui = prism_addon.ui.panels_render
    drawn = []
    for panel in (ui.PRISM_PT_passes_data, ui.PRISM_PT_passes_light):
        drawn += _props(_draw(panel, _context(fresh_scene)))
    expected = {*VIEW_LAYER_SWITCH.values(), *CYCLES_VIEW_LAYER_SWITCH.values(), "use_pass_combined",
                "pass_alpha_threshold"}
    assert expected <= set(drawn), expected - set(drawn)
    assert "VIEWLAYER_PT_layer_passes_cryptomatte" in prism_addon.ui.compat_panels.COMPATIBLE_PANELS


def test_farm_panel_shows_the_job_or_what_to_fix(prism_addon, fresh_scene):
    panel = prism_addon.ui.panel_farm.PRISM_PT_farm
    fresh_scene.frame_start, fresh_scene.frame_end = 1, 2
    fresh_scene.prism.samples = 6
    fresh_scene.prism.farm.chunks = 3
    log = _draw(panel, _context(fresh_scene))
    assert {"manager_url", "job_name", "priority", "chunks", "output_path", "render_script"} <= set(_props(log))
    assert "2 frames × 3 chunks of 2 samples: 6 render tasks + 2 merges" in _labels(log)
    assert ("operator", ("prism.farm_submit",), {"icon": "EXPORT"}) in log
    assert not any(text.startswith("Last job") for text in _labels(log))

    fresh_scene.prism.farm.chunks = 4
    fresh_scene.prism.farm.last_job_id = "0b5c"
    labels = _labels(_draw(panel, _context(fresh_scene)))
    assert any("6 samples do not split into 4 equal chunks: set Samples to 4 or 8" in text for text in labels)
    assert "Last job: 0b5c" in labels


def test_blender_panels_that_apply_are_enabled_and_restored(prism_addon, fresh_scene):
    import bpy

    compat = prism_addon.ui.compat_panels
    context = SimpleNamespace(engine="PRISM", camera=bpy.data.cameras.new("Cam"), scene=fresh_scene)
    names = {cls.__name__ for cls in compat.compatible_panel_classes()}
    assert {"RENDER_PT_format", "RENDER_PT_output", "RENDER_PT_color_management", "DATA_PT_lens"} <= names
    assert bpy.types.RENDER_PT_format.poll(context)
    assert bpy.types.DATA_PT_lens.poll(context)
    compat.unregister()
    try:
        assert "PRISM" not in bpy.types.RENDER_PT_format.COMPAT_ENGINES
        assert not bpy.types.DATA_PT_lens.poll(context)
        assert "BLENDER_EEVEE_NEXT" in bpy.types.RENDER_PT_format.COMPAT_ENGINES
    finally:
        compat.register()
    assert bpy.types.RENDER_PT_format.poll(context)


def test_wavelength_plot_follows_the_gaussians(prism_addon, fresh_scene):
    import numpy as np

    plot = prism_addon.ui.spectral_plot
    edges_nm = np.linspace(*plot.PLOT_RANGE_NM, plot.PLOT_WIDTH_PX + 1)
    cmf, _ = plot.cmf_curves(edges_nm)
    image = plot.render_plot((600.0, 550.0, 450.0), (25.0, 25.0, 15.0), cmf, True)
    assert image.shape == (plot.PLOT_HEIGHT_PX, plot.PLOT_WIDTH_PX, 4)
    centres_nm = 0.5 * (edges_nm[:-1] + edges_nm[1:])
    # The red fill reaches highest at the red mean: count reddish pixels per column.
    def red_peak_nm(img):
        # Rows count from the bottom: the red curve's top is the highest reddish pixel.
        reddish = (img[..., 0] > 0.9) & (img[..., 1] < 0.5) & (img[..., 2] < 0.5)
        top = np.where(reddish.any(axis=0), reddish.shape[0] - 1 - np.argmax(reddish[::-1], axis=0), -1)
        return centres_nm[top == top.max()].mean()

    assert red_peak_nm(image) == pytest.approx(600.0, abs=4.0)
    moved = plot.render_plot((650.0, 550.0, 450.0), (25.0, 25.0, 15.0), cmf, True)
    assert red_peak_nm(moved) == pytest.approx(650.0, abs=4.0)

    plot.plot_icon_id(fresh_scene.prism)
    key = plot._plot_key
    fresh_scene.prism.mean_r_nm = 610.0
    plot.plot_icon_id(fresh_scene.prism)
    assert plot._plot_key != key


@pytest.mark.parametrize("shading, engine, shown", [("RENDERED", "PRISM", True), ("SOLID", "PRISM", False),
                                                     ("RENDERED", "CYCLES", False)])
def test_viewport_header_pause_button_in_prisms_rendered_shading(prism_addon, fresh_scene, shading, engine, shown):
    log = []
    header = SimpleNamespace(layout=RecordingLayout(log))
    space = SimpleNamespace(shading=SimpleNamespace(type=shading))
    context = SimpleNamespace(engine=engine, scene=fresh_scene, space_data=space)
    for paused, icon in ((False, "PAUSE"), (True, "PLAY")):
        log.clear()
        fresh_scene.prism.preview_pause = paused
        prism_addon.ui.viewport_header.draw_pause(header, context)
        assert log == ([("prop", (fresh_scene.prism, "preview_pause"), {"text": "", "icon": icon})] if shown else [])
