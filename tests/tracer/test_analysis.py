"""Scene analysis: only what the scene needs is switched on, and the strategy says so."""

import numpy as np

from engine.tracer.renderer import Renderer
from engine.tracer.scene import Material, SpectrumSpec

from .tracer_scenes import plane_under_point_light, settings


def _with_material(mat):
    scene = plane_under_point_light(size=8)
    scene.materials = [mat]
    return scene


def test_plain_scene_keeps_all_wavelengths_and_no_mesh_lights():
    r = Renderer(plane_under_point_light(size=8), settings())
    a = r.analysis
    assert not a.dispersion and not a.mesh_lights and r.light_table.arrays.mesh_index == -1
    assert "no dispersion" in r.strategy and "lights: point" in r.strategy and "cie x4" in r.strategy


def test_dispersive_glass_turns_on_hero_termination_constant_glass_does_not():
    r = Renderer(_with_material(Material("g", kind="dielectric", glass="N-BK7")), settings())
    assert r.analysis.dispersion and "hero-wavelength termination (N-BK7)" in r.strategy
    assert "smooth dielectric" in r.strategy
    r = Renderer(_with_material(Material("g", kind="dielectric", ior=1.5, roughness=0.3)), settings())
    assert not r.analysis.dispersion and "rough dielectric" in r.strategy


def test_emissive_material_turns_on_mesh_lights_and_features_are_listed():
    mat = Material("glow", emission=SpectrumSpec(kind="blackbody", temperature_k=4000), emission_strength=2.0)
    r = Renderer(_with_material(mat), settings(wavelength_mode="gaussian_rgb", use_mis=False))
    assert r.analysis.mesh_lights and len(r.light_table.arrays.mesh.triangle) == 2
    assert "emissive meshes" in r.strategy and "gaussian_rgb x3" in r.strategy and "no MIS" in r.strategy
    r = Renderer(_with_material(Material("m", kind="conductor", conductor="Cu", roughness=0.4,
                                         coating_thickness_nm=200.0)), settings(pixel_filter="gaussian"))
    assert "rough conductor" in r.strategy and "thin-film coating" in r.strategy and "gaussian filter" in r.strategy
    r.render_pass()
    assert r.stats["nan_samples"] == 0 and np.all(np.isfinite(r.image_rgb()))


def test_light_tracing_is_chosen_where_specular_objects_can_focus_a_light():
    from engine.tracer.analysis import choose_light_tracing

    assert choose_light_tracing("auto", ["Glass"], [], True, True, False) == (
        True, "caustics by light tracing (Glass)")
    assert choose_light_tracing("auto", [], ["Soap"], True, True, False)[0] is False  # films focus little
    assert choose_light_tracing("on", [], ["Soap"], True, True, False)[0] is True
    assert choose_light_tracing("auto", ["Glass"], [], False, True, False) == (False, "no caustics to light-trace")
    assert choose_light_tracing("auto", ["Glass"], [], True, False, False)[0] is False  # only the world emits
    assert choose_light_tracing("on", ["Glass"], [], True, True, True) == (
        False, "caustics by path tracing (real lens)")
    assert choose_light_tracing("off", ["Glass"], [], True, True, False) == (False, "light tracing off")


def test_the_analysis_reads_materials_lights_and_the_camera_for_light_tracing():
    from pathlib import Path

    scene = plane_under_point_light(size=8)
    scene.materials = [Material("Mirror", kind="conductor", base_color=(1, 1, 1))]
    r = Renderer(scene, settings())  # a mirror plane and nothing else to receive its light
    assert not r.analysis.light_tracing and "no caustics to light-trace" in r.strategy
    scene.materials.append(Material("Floor"))
    scene.triangle_material = np.array([0, 1])
    r = Renderer(scene, settings())
    assert r.analysis.light_tracing and r.caustic_targets.spheres.shape == (1, 4)
    assert r.strategy.endswith("caustics by light tracing (Mirror)")
    scene.camera.model = "real_lens"
    scene.camera.lens_file = str(Path(__file__).parents[2] / "lenses" / "double_gauss_50mm.lens")
    r = Renderer(scene, settings())
    assert not r.analysis.light_tracing and "caustics by path tracing (real lens)" in r.strategy
