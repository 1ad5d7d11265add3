"""Scene analysis: only what the scene needs is switched on, and the strategy says so."""

import numpy as np

from engine.tracer.renderer import Renderer
from engine.tracer.scene import Light, Material, SpectrumSpec

from .tracer_scenes import plane_under_point_light, settings


def _with_material(mat):
    scene = plane_under_point_light(size=8)
    scene.materials = [mat]
    return scene


def test_plain_scene_keeps_all_wavelengths_and_no_mesh_lights():
    r = Renderer(plane_under_point_light(size=8), settings())
    a = r.tables.analysis
    assert not a.dispersion and not a.mesh_lights and r.tables.light_table.arrays.mesh_index == -1
    assert "no dispersion" in r.strategy and "lights: point" in r.strategy and "cie x4" in r.strategy


def test_dispersive_glass_turns_on_hero_termination_constant_glass_does_not():
    r = Renderer(_with_material(Material("g", kind="dielectric", glass="N-BK7")), settings())
    assert r.tables.analysis.dispersion and "hero-wavelength termination (N-BK7)" in r.strategy
    assert "smooth dielectric" in r.strategy
    r = Renderer(_with_material(Material("g", kind="dielectric", ior=1.5, roughness=0.3)), settings())
    assert not r.tables.analysis.dispersion and "rough dielectric" in r.strategy


def test_emissive_material_turns_on_mesh_lights_and_features_are_listed():
    mat = Material("glow", emission=SpectrumSpec(kind="blackbody", temperature_k=4000), emission_strength=2.0)
    r = Renderer(_with_material(mat), settings(wavelength_mode="gaussian_rgb", use_mis=False))
    assert r.tables.analysis.mesh_lights and len(r.tables.light_table.arrays.mesh.triangle) == 2
    assert "emissive meshes" in r.strategy and "gaussian_rgb x3" in r.strategy and "no MIS" in r.strategy
    r = Renderer(_with_material(Material("m", kind="conductor", conductor="Cu", roughness=0.4,
                                         coating_thickness_nm=200.0)), settings(pixel_filter="gaussian"))
    assert "rough conductor" in r.strategy and "thin-film coating" in r.strategy and "gaussian filter" in r.strategy
    r.render_pass()
    assert r.stats["nan_samples"] == 0 and np.all(np.isfinite(r.image_rgb()))


def test_light_tracing_is_chosen_where_specular_objects_can_focus_a_small_light():
    from engine.tracer.analysis import choose_light_tracing

    lamp = ["Lamp"]
    assert choose_light_tracing("auto", ["Glass"], [], True, lamp, True) == (True, "caustics by light tracing (Glass)")
    assert choose_light_tracing("auto", ["Glass"], [], True, [], True) == (
        False, "caustics by path tracing (lights large enough)")
    assert choose_light_tracing("on", ["Glass"], [], True, [], True)[0] is True
    assert choose_light_tracing("auto", [], ["Soap"], True, lamp, True)[0] is False  # films focus little
    assert choose_light_tracing("on", [], ["Soap"], True, lamp, True)[0] is True
    assert choose_light_tracing("auto", ["Glass"], [], False, lamp, True) == (False, "no caustics to light-trace")
    assert choose_light_tracing("on", ["Glass"], [], True, [], False)[0] is False  # only the world emits
    assert choose_light_tracing("on", ["Glass"], [], True, lamp, True, "real lens") == (
        False, "caustics by path tracing (real lens)")
    assert choose_light_tracing("off", ["Glass"], [], True, lamp, True) == (False, "light tracing off")


def test_lights_small_seen_from_the_specular_objects():
    from benchmarks.scenes import build, cornell_light

    scene = build("cornell_glass", (8, 8))  # a 0.5 m light 1.6 m above the ball: 0.1 sr
    r = Renderer(scene, settings())
    assert not r.tables.analysis.light_tracing and "caustics by path tracing (lights large enough)" in r.strategy
    small = cornell_light()
    small.size_u_m = small.size_v_m = 0.12
    for light in (small, Light("bulb", "point", np.array([0.0, 0.0, 1.9]), power_w=20.0),
                  Light("sun", "sun", np.zeros(3), direction=np.array([0.3, 0.2, -1.0]), irradiance_w_m2=2.0,
                        sun_angle_rad=np.radians(2))):
        scene.lights = [light]
        assert Renderer(scene, settings()).tables.analysis.light_tracing, light.name
    scene.lights = [Light("spot", "spot", np.array([0.0, 0.0, 1.9]), direction=np.array([1.0, 0.0, 0.0]),
                          power_w=20.0, spot_size_rad=np.radians(30))]  # pointing away from the ball
    assert not Renderer(scene, settings()).tables.analysis.light_tracing


def test_the_analysis_reads_materials_lights_and_the_camera_for_light_tracing():
    from pathlib import Path

    scene = plane_under_point_light(size=8)
    scene.materials = [Material("Mirror", kind="conductor", base_color=(1, 1, 1))]
    r = Renderer(scene, settings())  # a mirror plane and nothing else to receive its light
    assert not r.tables.analysis.light_tracing and "no caustics to light-trace" in r.strategy
    scene.materials.append(Material("Floor"))
    scene.triangle_material = np.array([0, 1])
    r = Renderer(scene, settings())
    assert r.tables.analysis.light_tracing and r.tables.caustic_targets.spheres.shape == (1, 4)
    assert r.strategy.endswith("caustics by light tracing (Mirror)")
    scene.camera.model = "real_lens"
    scene.camera.lens_file = str(Path(__file__).parents[2] / "lenses" / "double_gauss_50mm.lens")
    r = Renderer(scene, settings())
    assert not r.tables.analysis.light_tracing and "caustics by path tracing (real lens)" in r.strategy
    scene.camera.model = "pinhole"
    r = Renderer(scene, settings(spectral_band_nm=10.0))  # the spectral film takes camera samples only
    assert not r.tables.analysis.light_tracing and "caustics by path tracing (spectral output)" in r.strategy
    from engine.tracer.pass_table import PassRequest

    for request in (PassRequest(passes=("DiffInd",)), PassRequest(light_groups=("key",))):
        r = Renderer(scene, settings(passes=request))  # they split Combined by the path tracer's paths
        assert not r.tables.analysis.light_tracing and "caustics by path tracing (light passes)" in r.strategy
    r = Renderer(scene, settings(passes=PassRequest(passes=("Depth", "Denoising Albedo"))))
    assert r.tables.analysis.light_tracing


def test_light_tracing_needs_a_perspective_camera_that_sees_every_object():
    """Connections reach a perspective camera's pinhole or lens, and see what Embree's full scene holds:
    other projections, holdouts and ray visibility leave caustics to path tracing."""
    from engine.tracer.visibility import ALL_RAYS, HOLDOUT, RAY_CAMERA

    scene = plane_under_point_light(size=8)
    scene.materials = [Material("Mirror", kind="conductor", base_color=(1, 1, 1)), Material("Floor")]
    scene.triangle_material = np.array([0, 1])
    scene.camera.projection, scene.camera.ortho_width_m, scene.camera.ortho_height_m = "orthographic", 2.0, 2.0
    r = Renderer(scene, settings())
    assert not r.tables.analysis.light_tracing and "caustics by path tracing (orthographic camera)" in r.strategy
    scene.camera.projection = "equirectangular"
    r = Renderer(scene, settings())
    assert not r.tables.analysis.light_tracing and "caustics by path tracing (panoramic camera)" in r.strategy
    scene.camera.projection = "perspective"
    scene.triangle_object, scene.object_names = np.array([0, 1]), ["Mirror", "Floor"]
    for flags in ((ALL_RAYS | HOLDOUT, ALL_RAYS), (ALL_RAYS, ALL_RAYS & ~RAY_CAMERA)):
        scene.object_flags = np.array(flags, np.uint8)
        r = Renderer(scene, settings())
        assert not r.tables.analysis.light_tracing and "(ray visibility or holdouts)" in r.strategy
    scene.object_flags = np.array([ALL_RAYS, ALL_RAYS], np.uint8)
    r = Renderer(scene, settings())
    assert r.tables.analysis.light_tracing


def test_an_unknown_light_tracing_mode_is_refused():
    import pytest

    from engine.tracer.errors import PrismInputError

    with pytest.raises(PrismInputError, match="Unknown light tracing mode 'sometimes': use one of auto, off, on."):
        Renderer(plane_under_point_light(size=4), settings(light_tracing="sometimes"))
