"""Blender data → tracer Scene: Principled materials, Material.prism overrides, lights, camera models."""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane, add_point_light


def _export(prism_addon, warnings=None):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    return export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)


def _principled(obj):
    return obj.active_material.node_tree.nodes["Principled BSDF"]


@pytest.fixture
def basic(fresh_scene):
    plane = add_plane("Thing", 2.0, color=(0.2, 0.4, 0.6))
    add_point_light("Bulb", 100.0, (0.0, 0.0, 3.0))
    add_camera((0.0, -4.0, 1.0), (1.4, 0.0, 0.0), resolution=(24, 24))
    return plane


def _material(scene, name="Thing material"):
    return next(m for m in scene.materials if m.name == name)


def test_principled_glass_becomes_dispersive_catalogue_glass(prism_addon, basic):
    node = _principled(basic)
    node.inputs["Transmission Weight"].default_value = 1.0
    node.inputs["IOR"].default_value = 1.45
    node.inputs["Roughness"].default_value = 0.1
    settings = basic.active_material.prism

    exported = _material(_export(prism_addon))
    assert (exported.kind, exported.ior, exported.glass) == ("dielectric", pytest.approx(1.45), None)
    assert exported.roughness == pytest.approx(0.1)

    settings.glass_source = "CATALOGUE"
    settings.glass_name = "SF11"
    exported = _material(_export(prism_addon))
    assert exported.kind == "dielectric" and exported.glass == "SF11"
    # The tracer's glass for it disperses: n(450 nm) > n(650 nm), n_d as published (Schott SF11 1.78472).
    glass = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.spectra.glass").glass_by_name(exported.glass)
    n_blue, n_d, n_red = (float(np.asarray(glass.index(np.array([w])))[0]) for w in (450.0, 587.56, 650.0))
    assert n_blue > n_d > n_red and n_d == pytest.approx(1.78472, abs=2e-4)

    settings.glass_source = "ABBE"
    settings.glass_nd, settings.glass_vd = 1.6, 40.0
    exported = _material(_export(prism_addon))
    assert (exported.glass, exported.glass_nd, exported.glass_vd) == (None, pytest.approx(1.6), pytest.approx(40.0))


def test_metallic_becomes_a_conductor(prism_addon, basic):
    node = _principled(basic)
    node.inputs["Metallic"].default_value = 1.0
    exported = _material(_export(prism_addon))
    assert exported.kind == "conductor" and exported.conductor is None
    assert exported.base_color == pytest.approx((0.2, 0.4, 0.6))
    basic.active_material.prism.conductor = "AU"
    assert _material(_export(prism_addon)).conductor == "Au"


def test_emission_coating_and_thin_film(prism_addon, basic):
    node = _principled(basic)
    node.inputs["Emission Color"].default_value = (1.0, 0.5, 0.25, 1.0)
    node.inputs["Emission Strength"].default_value = 3.0
    node.inputs["Metallic"].default_value = 1.0
    node.inputs["Thin Film Thickness"].default_value = 300.0
    node.inputs["Thin Film IOR"].default_value = 1.5
    exported = _material(_export(prism_addon))
    assert exported.emission.kind == "rgb" and exported.emission.rgb == pytest.approx((1.0, 0.5, 0.25))
    assert exported.emission_strength == pytest.approx(3.0)
    assert (exported.coating_thickness_nm, exported.coating_ior) == (pytest.approx(300.0), pytest.approx(1.5))
    settings = basic.active_material.prism
    settings.coating_thickness_nm, settings.coating_ior = 120.0, 1.38  # the override wins
    assert _material(_export(prism_addon)).coating_thickness_nm == pytest.approx(120.0)
    settings.is_thin_film = True
    settings.film_thickness_nm, settings.film_ior = 420.0, 1.34
    exported = _material(_export(prism_addon))
    assert (exported.kind, exported.film_thickness_nm, exported.film_ior) == (
        "thin_film",
        pytest.approx(420.0),
        pytest.approx(1.34),
    )


def test_unmodelled_inputs_warn_once_naming_material_and_socket(prism_addon, basic):
    material = basic.active_material
    node = _principled(basic)
    texture = material.node_tree.nodes.new("ShaderNodeTexChecker")
    material.node_tree.links.new(texture.outputs["Color"], node.inputs["Base Color"])
    node.inputs["Sheen Weight"].default_value = 0.3
    warnings = []
    _export(prism_addon, warnings)
    assert len(warnings) == 2
    assert "Material 'Thing material'" in warnings[0] and "'Base Color'" in warnings[0]
    assert "'Sheen Weight'" in warnings[1]

    other = material.node_tree.nodes.new("ShaderNodeBsdfDiffuse")
    output = material.node_tree.nodes["Material Output"]
    material.node_tree.links.new(other.outputs["BSDF"], output.inputs["Surface"])
    warnings = []
    _export(prism_addon, warnings)
    assert warnings == [
        "Material 'Thing material': the 'Diffuse BSDF' node (Diffuse BSDF) is not supported; Prism renders its "
        "viewport colour instead. Connect a Principled BSDF to the Material Output."
    ]


@pytest.mark.parametrize(
    ("light_type", "shape", "expected_shape"),
    [("SPOT", None, None), ("SUN", None, None), ("AREA", "RECTANGLE", "rectangle"), ("AREA", "ELLIPSE", "disk")],
)
def test_light_kinds_and_spectra(prism_addon, basic, light_type, shape, expected_shape):
    bpy.data.objects.remove(bpy.data.objects["Bulb"])
    data = bpy.data.lights.new("Lamp", light_type)
    data.energy = 5.0
    if light_type == "SPOT":
        data.spot_size, data.spot_blend = 0.8, 0.3
    if light_type == "SUN":
        data.angle = 0.1
    if shape:
        data.shape, data.size, data.size_y = shape, 0.5, 0.25
    obj = bpy.data.objects.new("Lamp", data)
    obj.location = (0.0, 0.0, 2.0)
    obj.scale = (2.0, 2.0, 1.0)
    bpy.context.scene.collection.objects.link(obj)
    data.prism.color_source = "BLACKBODY"
    data.prism.temperature_k = 3200.0
    (light,) = _export(prism_addon).lights
    assert light.kind == light_type.lower()
    assert light.spectrum.kind == "blackbody" and light.spectrum.temperature_k == pytest.approx(3200.0)
    assert np.allclose(light.direction, (0.0, 0.0, -1.0))
    if light_type == "SPOT":
        assert (light.spot_size_rad, light.spot_blend, light.power_w) == (
            pytest.approx(0.8),
            pytest.approx(0.3),
            pytest.approx(5.0),
        )
    if light_type == "SUN":
        assert (light.irradiance_w_m2, light.sun_angle_rad) == (pytest.approx(5.0), pytest.approx(0.1))
    if shape:
        assert light.area_shape == expected_shape
        assert (light.size_u_m, light.size_v_m) == (pytest.approx(1.0), pytest.approx(0.5))
        data.normalize = False  # power per m² of a 1 m x 0.5 m light (x pi/4 for an ellipse)
        area = 0.5 * (math.pi / 4 if shape == "ELLIPSE" else 1.0)
        assert _export(prism_addon).lights[0].power_w == pytest.approx(5.0 * area)
        data.normalize = True
    data.exposure = 1.0
    (light,) = _export(prism_addon).lights
    assert max(light.power_w, light.irradiance_w_m2) == pytest.approx(10.0)
    data.prism.color_source = "MONOCHROMATIC"
    data.prism.wavelength_nm, data.prism.line_width_nm = 589.0, 2.0
    (light,) = _export(prism_addon).lights
    assert (light.spectrum.kind, light.spectrum.wavelength_nm, light.spectrum.width_nm) == (
        "monochromatic",
        pytest.approx(589.0),
        pytest.approx(2.0),
    )


def test_camera_models_focus_and_resolution(prism_addon, basic, tmp_path):
    scene = bpy.context.scene
    camera = scene.camera
    scene.render.resolution_percentage = 50
    exported = _export(prism_addon).camera
    assert exported.model == "pinhole" and exported.resolution == (12, 12)

    camera.data.prism.lens_model = "THIN_LENS"
    camera.data.dof.aperture_fstop = 2.0
    camera.data.dof.focus_distance = 3.0
    exported = _export(prism_addon).camera
    assert (exported.model, exported.fstop, exported.focus_distance_m) == ("thin_lens", 2.0, pytest.approx(3.0))

    target = bpy.data.objects.new("Target", None)
    target.location = (0.5, 2.0, 0.7)  # 6 m in front along the view axis (camera looks down +Y, tilted)
    scene.collection.objects.link(target)
    camera.data.dof.focus_object = target
    bpy.context.view_layer.update()
    view_axis = -np.array(camera.matrix_world)[:3, 2]
    expected = float(np.dot(np.array(target.location) - np.array(camera.location), view_axis))
    assert _export(prism_addon).camera.focus_distance_m == pytest.approx(expected)


def test_real_lens_camera_exports_its_prescription_and_renders(prism_addon, basic):
    from helpers.bpy_scenes import render_linear_rgb

    camera = bpy.context.scene.camera.data
    camera.prism.lens_model = "REAL_LENS"
    camera.prism.bundled_lens = "double_gauss_50mm"
    camera.dof.aperture_fstop, camera.dof.focus_distance = 4.0, 4.0
    exported = _export(prism_addon).camera
    assert exported.model == "real_lens" and exported.lens_file.endswith("lenses/double_gauss_50mm.lens")
    assert (exported.fstop, exported.focus_distance_m) == (4.0, pytest.approx(4.0))
    camera.prism.lens_source = "FILE"
    camera.prism.lens_file = exported.lens_file
    assert _export(prism_addon).camera.lens_file == exported.lens_file
    bpy.context.scene.render.resolution_x = bpy.context.scene.render.resolution_y = 12
    image = render_linear_rgb(bpy.context.scene, samples=1)
    assert image.shape == (12, 12, 3) and np.isfinite(image).all() and image.mean() > 0


def test_scene_settings_become_render_settings(prism_addon, fresh_scene):
    settings_module = importlib.import_module(f"{prism_addon.__name__}.engine.export.settings")
    prism = fresh_scene.prism
    prism.samples, prism.preview_max_bounces, prism.samples_per_pass = 32, 3, 2
    prism.max_bounces, prism.seed, prism.threads = 5, 9, 1
    prism.wavelength_mode, prism.wavelengths_per_path = "GAUSSIAN_RGB", 2
    prism.mean_r_nm, prism.sigma_b_nm = 610.0, 12.0
    prism.use_mis, prism.russian_roulette_depth = False, 4
    prism.pixel_filter, prism.filter_width_px = "GAUSSIAN", 2.0
    prism.light_tracing = "ON"
    exported = settings_module.export_settings(fresh_scene, border=(1, 2, 3, 4))
    assert (exported.samples, exported.samples_per_pass, exported.max_bounces, exported.seed) == (32, 2, 5, 9)
    assert (exported.wavelength_mode, exported.wavelengths_per_path, exported.threads) == ("gaussian_rgb", 2, 1)
    assert exported.channel_means_nm == pytest.approx((610.0, 550.0, 450.0))
    assert exported.channel_sigmas_nm == pytest.approx((25.0, 25.0, 12.0))
    assert (exported.use_mis, exported.russian_roulette_depth, exported.border) == (False, 4, (1, 2, 3, 4))
    assert (exported.pixel_filter, exported.filter_width_px) == ("gaussian", pytest.approx(2.0))
    assert exported.light_tracing == "on"
    preview = settings_module.export_settings(fresh_scene, preview=True)  # a material or light preview
    assert (preview.samples, preview.max_bounces) == (settings_module.PREVIEW_SAMPLES, 3)
    overridden = settings_module.export_settings(fresh_scene, samples=7, seed=1, threads=2)
    assert (overridden.samples, overridden.seed, overridden.threads) == (7, 1, 2)
