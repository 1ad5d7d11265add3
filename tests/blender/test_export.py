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


def _closures(exported):
    return exported.shader.closures


def test_emission_coating_and_thin_film(prism_addon, basic):
    closure = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.bsdf.closure")
    node = _principled(basic)
    node.inputs["Emission Color"].default_value = (1.0, 0.5, 0.25, 1.0)
    node.inputs["Emission Strength"].default_value = 3.0
    node.inputs["Thin Film Thickness"].default_value = 300.0
    node.inputs["Thin Film IOR"].default_value = 1.5
    exported = _material(_export(prism_addon))
    assert exported.emission.kind == "rgb" and exported.emission.rgb == pytest.approx((1.0, 0.5, 0.25))
    assert exported.emission_strength == pytest.approx(3.0)
    # Blender's thin film sits on the Principled's dielectric specular layer.
    specular = next(c for c in _closures(exported) if c.fresnel == closure.FRESNEL_DIELECTRIC)
    assert (specular.coat_nm, specular.coat_ior) == (pytest.approx(300.0), pytest.approx(1.5))
    node.inputs["Metallic"].default_value = 1.0
    settings = basic.active_material.prism
    settings.coating_thickness_nm, settings.coating_ior = 120.0, 1.38  # Prism's coating: on metal and glass
    metal = next(c for c in _closures(_material(_export(prism_addon))) if c.fresnel == closure.FRESNEL_F82)
    assert (metal.coat_nm, metal.coat_ior) == (pytest.approx(120.0), pytest.approx(1.38))
    settings.is_thin_film = True
    settings.film_thickness_nm, settings.film_ior = 420.0, 1.34
    exported = _material(_export(prism_addon))
    assert (exported.kind, exported.film_thickness_nm, exported.film_ior) == (
        "thin_film",
        pytest.approx(420.0),
        pytest.approx(1.34),
    )


def test_what_prism_leaves_out_warns_once_naming_material_node_and_what_it_did(prism_addon, basic):
    material = basic.active_material
    node = _principled(basic)
    texture = material.node_tree.nodes.new("ShaderNodeTexChecker")
    material.node_tree.links.new(texture.outputs["Color"], node.inputs["Base Color"])
    node.inputs["Sheen Weight"].default_value = 0.3
    node.distribution = "GGX"
    warnings = []
    _export(prism_addon, warnings)
    assert warnings == []  # Sheen is rendered (microfiber sheen, as Cycles renders it)

    toon = material.node_tree.nodes.new("ShaderNodeBsdfToon")
    output = material.node_tree.nodes["Material Output"]
    material.node_tree.links.new(toon.outputs["BSDF"], output.inputs["Surface"])
    warnings = []
    _export(prism_addon, warnings)
    assert warnings == ["Material 'Thing material': the 'Toon BSDF' node (Toon BSDF) is not modelled by Prism; it "
                        "is left out (black)."]


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
    prism.transparent_max_bounces = 3
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
    assert exported.transparent_max_bounces == 3
    preview = settings_module.export_settings(fresh_scene, preview=True)  # a material or light preview
    assert (preview.samples, preview.max_bounces) == (settings_module.PREVIEW_SAMPLES, 3)
    overridden = settings_module.export_settings(fresh_scene, samples=7, seed=1, threads=2)
    assert (overridden.samples, overridden.seed, overridden.threads) == (7, 1, 2)


def test_constant_principled_materials_run_no_program_per_hit(prism_addon, basic):
    """Plastic, metal and glass Principled BSDFs with constant inputs compile to closures alone: the
    specular layer over the diffuse is a constant layer of the diffuse row (applied per hit without an
    interpreter), and the layer weights metal and glass never read are left out. A textured roughness keeps
    its program."""
    op = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.materials.opcodes")
    node = _principled(basic)
    node.inputs["Roughness"].default_value = 0.3
    shader = _material(_export(prism_addon)).shader
    assert len(shader.instructions) == 0 and shader.normal < 0
    layers = [spec.layer for spec in shader.closures]
    # specular, then diffuse under it (a Multiscatter GGX layer: Blender's default distribution)
    assert layers[0] is None and layers[-1] == pytest.approx((1.5, 0.3, 0.04, 1.0))

    for inputs in ({"Metallic": 1.0}, {"Metallic": 0.0, "Transmission Weight": 1.0}):
        for name, value in inputs.items():
            node.inputs[name].default_value = value
        shader = _material(_export(prism_addon)).shader
        assert len(shader.instructions) == 0, inputs

    node.inputs["Transmission Weight"].default_value = 0.0
    tree = basic.active_material.node_tree
    noise = tree.nodes.new("ShaderNodeTexNoise")
    tree.links.new(noise.outputs["Fac"], node.inputs["Roughness"])
    shader = _material(_export(prism_addon)).shader
    assert op.LAYER_ALBEDO in shader.instructions[:, op.OP] and op.NOISE in shader.instructions[:, op.OP]


def test_ray_visibility_prism_does_not_have_is_named(prism_addon, basic):
    """Object ▸ Visibility ▸ Ray Visibility ▸ Volume Scatter off: Prism has no such ray kind, and says so, naming the
    object or light; on (the default) nothing is said."""
    warnings = []
    _export(prism_addon, warnings)
    assert not any("Volume Scatter" in w for w in warnings), warnings
    basic.visible_volume_scatter = False
    _export(prism_addon, warnings)
    assert any("Object 'Thing': Ray Visibility ▸ Volume Scatter is off" in w for w in warnings), warnings
    bpy.data.objects["Bulb"].visible_volume_scatter = False
    _export(prism_addon, warnings)
    assert any("Light 'Bulb': Ray Visibility Volume Scatter off is ignored" in w for w in warnings), warnings
