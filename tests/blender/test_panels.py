"""Prism's panels: poll on the engine, and every draw() executed against real data.

Headless Blender has no Properties editor to draw into, so ``draw`` runs with a
recording layout that checks every call against Blender's own RNA: the method and
its keyword arguments must exist on ``UILayout``, every ``prop(data, name)`` must
name a property of ``data``, icons must be real icon names. A misspelt property
fails the test just as it would print an error in Blender.
"""

from __future__ import annotations

import importlib
from types import SimpleNamespace

import pytest


class RecordingLayout:
    """Stands in for ``bpy.types.UILayout``: validates and records each call."""

    def __init__(self, log):
        object.__setattr__(self, "_log", log)

    def __setattr__(self, name, value):
        import bpy

        assert name in bpy.types.UILayout.bl_rna.properties, f"UILayout has no attribute '{name}'"

    def __getattr__(self, name):
        import bpy

        function = bpy.types.UILayout.bl_rna.functions.get(name)
        assert function is not None, f"UILayout has no method '{name}'"
        parameters = function.parameters

        def call(*args, **kwargs):
            for key in kwargs:
                assert key in parameters, f"UILayout.{name}() has no argument '{key}'"
            icon = kwargs.get("icon")
            if icon is not None:
                assert icon in parameters["icon"].enum_items, f"unknown icon '{icon}'"
            self._check(name, args, kwargs)
            self._log.append((name, args, kwargs))
            if name == "operator":
                return SimpleNamespace()
            return RecordingLayout(self._log)

        return call

    @staticmethod
    def _check(name, args, kwargs):
        pairs = []
        if name in {"prop", "prop_decorator", "template_ID"}:
            pairs.append((args[0] if args else kwargs["data"], args[1] if len(args) > 1 else kwargs["property"]))
        elif name == "prop_search":
            pairs += [(args[0], args[1]), (args[2], args[3])]
        for data, prop in pairs:
            assert data is not None, f"{name}() was given None for '{prop}'"
            assert prop in data.bl_rna.properties, f"{data.bl_rna.identifier} has no property '{prop}'"


def _panels(prism_addon):
    ui = prism_addon.ui
    return [
        cls
        for module in (ui.panels_render, ui.panel_farm, ui.panels_camera, ui.panels_light, ui.panels_material)
        for cls in module.CLASSES
    ]


class _PanelStandIn(SimpleNamespace):
    """``self`` for a panel's draw(): a recording layout, and the panel class's attributes and methods
    (Blender panels cannot be instantiated outside a redraw)."""

    def __getattr__(self, name):
        value = getattr(self.panel_class, name)
        return value.__get__(self) if callable(value) and hasattr(value, "__get__") else value


def _draw(panel_class, context):
    log = []
    panel = _PanelStandIn(layout=RecordingLayout(log), bl_space_type="PROPERTIES", panel_class=panel_class)
    panel_class.draw(panel, context)
    return log


def _context(scene, engine="PRISM", camera=None, light=None, material=None, obj=None, world=None):
    return SimpleNamespace(engine=engine, scene=scene, camera=camera, light=light, material=material, object=obj,
                           world=world, view_layer=scene.view_layers[0])


def _labels(log):
    return [kwargs.get("text", "") for name, _, kwargs in log if name == "label"]


def _props(log):
    return [args[1] for name, args, _ in log if name == "prop"]


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
                     "pixel_filter", "filter_width_px", "light_tracing"):
            assert name in drawn
    log = _draw(prism_addon.ui.panels_render.PRISM_PT_wavelengths, _context(fresh_scene))
    assert any(name == "template_icon" for name, _, _ in log)


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


def test_camera_panels_draw_for_every_lens_model(prism_addon, fresh_scene, tmp_path):
    import bpy

    camera = bpy.data.cameras.new("Cam")
    panels = prism_addon.ui.panels_camera.CLASSES
    for model in ("PINHOLE", "THIN_LENS", "REAL_LENS"):
        for source in ("BUNDLED", "FILE"):
            camera.prism.lens_model = model
            camera.prism.lens_source = source
            for panel in panels:
                _draw(panel, _context(fresh_scene, camera=camera))
    camera.prism.lens_model = "REAL_LENS"
    camera.prism.lens_source = "BUNDLED"
    camera.prism.bundled_lens = "double_gauss_50mm"
    log = _draw(prism_addon.ui.panels_camera.PRISM_PT_camera_lens, _context(fresh_scene, camera=camera))
    assert {"Focal length", "Field of view"} <= set(_labels(log))  # read-outs of the bundled lens
    camera.prism.lens_model = "THIN_LENS"
    log = _draw(prism_addon.ui.panels_camera.PRISM_PT_camera_focus, _context(fresh_scene, camera=camera))
    assert {"focus_distance", "aperture_fstop", "focus_object"} <= set(_props(log))
    assert ("operator", ("prism.autofocus",), {"icon": "VIEWZOOM"}) in log

    # A broken lens file is a red label naming the problem, never a traceback.
    camera.prism.lens_model = "REAL_LENS"
    camera.prism.lens_source = "FILE"
    camera.prism.lens_file = str(tmp_path / "missing.lens")
    log = _draw(prism_addon.ui.panels_camera.PRISM_PT_camera_lens, _context(fresh_scene, camera=camera))
    assert any("not found" in text for text in _labels(log))
    broken = tmp_path / "broken.lens"
    broken.write_text("this is not a lens\n")
    camera.prism.lens_file = str(broken)
    log = _draw(prism_addon.ui.panels_camera.PRISM_PT_camera_lens, _context(fresh_scene, camera=camera))
    assert any("broken.lens" in text and "line 1" in text for text in _labels(log))

    camera.type = "ORTHO"
    log = _draw(prism_addon.ui.panels_camera.PRISM_PT_camera_lens, _context(fresh_scene, camera=camera))
    assert any("forms a perspective image" in text for text in _labels(log))
    camera.prism.lens_model = "PINHOLE"  # Blender's camera: orthographic is fine, DoF behind its checkbox
    log = _draw(prism_addon.ui.panels_camera.PRISM_PT_camera_lens, _context(fresh_scene, camera=camera))
    assert not any("perspective" in text for text in _labels(log))
    log = _draw(prism_addon.ui.panels_camera.PRISM_PT_camera_focus, _context(fresh_scene, camera=camera))
    assert "use_dof" in _props(log) and "aperture_fstop" not in _props(log)
    camera.dof.use_dof = True
    log = _draw(prism_addon.ui.panels_camera.PRISM_PT_camera_focus, _context(fresh_scene, camera=camera))
    assert {"aperture_fstop", "aperture_blades", "aperture_rotation", "aperture_ratio"} <= set(_props(log))


@pytest.mark.parametrize("light_type", ["POINT", "SPOT", "SUN", "AREA"])
def test_light_panels_draw_for_every_type_and_colour_source(prism_addon, fresh_scene, light_type):
    import bpy

    light = bpy.data.lights.new("Lamp", light_type)
    for source in ("RGB", "BLACKBODY", "MONOCHROMATIC", "ILLUMINANT", "FILE"):
        light.prism.color_source = source
        shapes = ("SQUARE", "RECTANGLE", "DISK", "ELLIPSE") if light_type == "AREA" else (None,)
        for shape in shapes:
            if shape:
                light.shape = shape
            context = _context(fresh_scene, light=light)
            drawn = []
            for panel in prism_addon.ui.panels_light.CLASSES:
                if panel.poll(context):
                    drawn += _props(_draw(panel, context))
            assert "energy" in drawn and "color_source" in drawn
            if source != "RGB":
                assert "preview_color" in drawn
    light.prism.color_source = "BLACKBODY"
    light.prism.temperature_k = 100.0
    log = _draw(prism_addon.ui.panels_light.PRISM_PT_light, _context(fresh_scene, light=light))
    assert any("1000-40000 K" in text for text in _labels(log))


def _principled(material):
    material.use_nodes = True
    return material.node_tree.nodes["Principled BSDF"]


def test_material_panels_show_what_prism_reads(prism_addon, fresh_scene, monkeypatch):
    import bpy

    # The summary folds constant weights with the compiled kernels, which a panel only loads once a render
    # has compiled them; here they may have to be compiled.
    monkeypatch.setattr(importlib.import_module(f"{prism_addon.__name__}.engine.tracer.jit"), "cache_is_warm",
                        lambda: True)
    panels = prism_addon.ui.panels_material.CLASSES
    material = bpy.data.materials.new("Mat")

    def draw_all():
        log = []
        for panel in panels:
            log += _draw(panel, _context(fresh_scene, material=material))
        return log

    log = draw_all()  # no node tree: the viewport values
    assert "diffuse_color" in _props(log)

    node = _principled(material)
    log = draw_all()
    assert any(text == "Renders as: Specular + Diffuse" for text in _labels(log)), _labels(log)

    node.inputs["Transmission Weight"].default_value = 1.0
    for source in ("PRINCIPLED_IOR", "CATALOGUE", "ABBE"):
        material.prism.glass_source = source
        log = draw_all()
    assert any(text.startswith("Renders as: Glass (refractive)") for text in _labels(log)), _labels(log)
    assert {"glass_nd", "glass_vd"} <= set(_props(log))

    node.inputs["Transmission Weight"].default_value = 0.0
    node.inputs["Metallic"].default_value = 1.0
    node.inputs["Emission Strength"].default_value = 2.0
    texture = material.node_tree.nodes.new("ShaderNodeTexNoise")
    material.node_tree.links.new(texture.outputs["Color"], node.inputs["Base Color"])
    node.inputs["Sheen Weight"].default_value = 0.5
    material.prism.is_thin_film = False
    log = draw_all()
    labels = _labels(log)
    assert any(text == "Renders as: Metal + emission" for text in labels), labels
    assert any("has Sheen, which Prism does not model" in text for text in labels)
    assert "conductor" in _props(log)

    material.prism.is_thin_film = True
    assert any(text.startswith("Renders as: Thin film") for text in _labels(draw_all()))


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


def test_spectrum_panels_plot_the_spectrum_and_the_lights_colour_rendering(prism_addon, fresh_scene, tmp_path):
    import bpy

    preview = importlib.import_module(f"{prism_addon.__name__}.engine.spectrum_preview")
    sources = importlib.import_module(f"{prism_addon.__name__}.engine.export.spectra")
    light = bpy.data.lights.new("Lamp", "AREA")
    light.prism.color_source, light.prism.illuminant = "ILLUMINANT", "FL2"
    preview.emission_preview(sources.light_emission_source("Lamp", light), wait=True)
    log = _draw(prism_addon.ui.panels_light.PRISM_PT_light_spectrum, _context(fresh_scene, light=light))
    labels = _labels(log)
    assert any(name == "template_icon" for name, _, _ in log)
    assert "CCT 4225 K, Duv +0.0019" in labels and "CRI Ra 64" in labels and "TM-30 Rf 70, Rg 86" in labels
    assert light.prism.preview_color[0] == 1.0 and 0.6 < light.prism.preview_color[1] < 0.8  # warm white

    light.prism.color_source, light.prism.spectrum_file = "FILE", str(tmp_path / "nowhere.csv")
    preview.emission_preview(sources.light_emission_source("Lamp", light), wait=True)
    labels = _labels(_draw(prism_addon.ui.panels_light.PRISM_PT_light_spectrum, _context(fresh_scene, light=light)))
    assert any("nowhere.csv' does not exist" in text for text in labels)

    material = bpy.data.materials.new("Patch")
    material.use_nodes = True
    material.prism.reflectance_source = "MEASURED"
    material.prism.measured_reflectance = "ColorChecker N Ohta: blue"
    node = material.node_tree.nodes["Principled BSDF"]
    preview.reflectance_preview(sources.material_reflectance_source(material, (0.8, 0.8, 0.8)), wait=True)
    log = _draw(prism_addon.ui.panels_material.PRISM_PT_material_base_spectrum, _context(fresh_scene, material=material))
    assert "measured_reflectance" in _props(log) and any(name == "template_icon" for name, _, _ in log)
    node.inputs["Emission Strength"].default_value = 3.0
    material.prism.emission_source, material.prism.emission_wavelength_nm = "MONOCHROMATIC", 589.0
    emission = sources.material_emission_source(material, (1.0, 1.0, 1.0))
    preview.emission_preview(emission, wait=True)
    log = _draw(prism_addon.ui.panels_material.PRISM_PT_material_emission_spectrum,
                _context(fresh_scene, material=material))
    assert {"emission_source", "emission_wavelength_nm", "emission_line_width_nm"} <= set(_props(log))
    assert any(text.startswith("CCT") or text.startswith("CCT, CRI: not defined") for text in _labels(log))


def test_spectrum_plot_fills_each_wavelength_in_its_colour(prism_addon):
    import numpy as np

    plot = prism_addon.ui.spectral_plot
    wavelengths = np.arange(360.0, 831.0)
    line = np.exp(-0.5 * ((wavelengths - 610.0) / 2.0) ** 2)
    image = plot.render_spectrum_plot(line)
    assert image.shape == (plot.PLOT_HEIGHT_PX, plot.PLOT_WIDTH_PX, 4)
    filled = image[plot.PLOT_HEIGHT_PX // 2, :, :3]  # halfway up: only the line's columns reach it
    columns = np.flatnonzero(filled.max(axis=1) > 0.5)
    centres = np.linspace(360.0, 830.0, plot.PLOT_WIDTH_PX + 1)
    assert abs(0.5 * (centres[columns[0]] + centres[columns[-1] + 1]) - 610.0) < 4.0
    column = image[2 * plot.PLOT_HEIGHT_PX // 5, columns[len(columns) // 2], :3]
    assert column[0] > 3 * max(column[1], column[2])  # red under the curve


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


def test_light_group_panels_poll_and_draw(prism_addon, fresh_scene):
    import bpy

    obj = bpy.data.objects.new("Lamp", bpy.data.lights.new("Lamp", "POINT"))
    world = bpy.data.worlds.new("Sky")
    fresh_scene.view_layers[0].lightgroups.add(name="key")
    obj.lightgroup = "key"
    world.lightgroup = "fill"  # not a group of the view layer yet: the + button adds it
    for panel in prism_addon.ui.panels_lightgroup.CLASSES:
        assert panel.poll(_context(fresh_scene, obj=obj, world=world))
        assert not panel.poll(_context(fresh_scene))
        assert not panel.poll(_context(fresh_scene, engine="CYCLES", obj=obj, world=world))
        log = _draw(panel, _context(fresh_scene, obj=obj, world=world))
        assert [name for name, *_ in log].count("prop_search") == 1
