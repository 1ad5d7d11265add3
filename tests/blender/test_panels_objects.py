"""Prism's camera, light, material and light-group panels, drawn against real data for every lens model,
light type, colour source and material kind, and the spectrum plots and read-outs they show.

``draw`` runs with the recording layout of ``helpers.panel_layout``, which fails on any call Blender's
RNA would reject.
"""

from __future__ import annotations

import importlib

import pytest

from helpers.panel_layout import context as _context
from helpers.panel_layout import draw as _draw
from helpers.panel_layout import labels as _labels
from helpers.panel_layout import props as _props


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
    assert {"displacement_method", "use_bump_map_correction"} <= set(_props(log))  # Settings, read as Cycles does

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
    assert any(text == "Renders as: Sheen + Metal + emission" for text in labels), labels
    assert not any("Sheen" in text for text in labels if not text.startswith("Renders as")), labels
    assert "conductor" in _props(log)

    material.prism.is_thin_film = True
    assert any(text.startswith("Renders as: Thin film") for text in _labels(draw_all()))


def test_spectrum_panels_plot_the_spectrum_and_the_lights_colour_rendering(prism_addon, fresh_scene, tmp_path):
    import bpy

    preview = importlib.import_module(f"{prism_addon.__name__}.engine.output.spectrum_preview")
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
