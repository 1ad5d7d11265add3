"""Integrator: white furnace, multi-bounce closed form with Russian roulette, MIS
consistency, 1/spp convergence, NaN-free renders."""

import numpy as np
import pytest

from engine.tracer.renderer import Renderer
from engine.tracer.spectra.rgb_to_spectrum import white_rgb
from engine.tracer.scene import Light, Material, SpectrumSpec

from .test_renderer import _gaussian_white
from .tracer_scenes import inside_glowing_sphere, look_at, make_scene, quad, settings, sphere_under_sky, uv_sphere


def _white(s):
    return np.asarray(white_rgb()) if s.wavelength_mode == "cie" else _gaussian_white(s)


@pytest.mark.parametrize("mode", ["cie", "gaussian_rgb"])
def test_white_furnace(mode):
    """Albedo-1 convex sphere under a sky of radiance 1: it vanishes. Every pixel equals
    the sky seen with the same wavelengths (an empty scene, same seed), and the image
    mean is the sky's white within its Monte Carlo error."""
    s = settings(wavelength_mode=mode, samples=4, samples_per_pass=4)
    scene = sphere_under_sky()
    r = Renderer(scene, s)
    r.render_pass()
    img = r.image_rgb().astype(np.float64)
    scene.triangles = scene.triangles[:0]
    scene.triangle_material = scene.triangle_material[:0]
    sky = Renderer(scene, s)
    sky.render_pass()
    assert np.allclose(img, sky.image_rgb(), rtol=1e-5, atol=0)
    stderr = np.sqrt(r.variance_rgb().astype(np.float64).mean((0, 1)) / img[..., 0].size)
    assert np.all(np.abs(img.mean((0, 1)) - _white(s)) < 4 * stderr + 1e-3), (img.mean((0, 1)) / _white(s), stderr)
    assert r.stats["nan_samples"] == 0


@pytest.mark.parametrize(
    "mode, bounces, albedo, roulette_depth",
    [
        ("cie", 6, 0.5, 2),
        ("gaussian_rgb", 6, 0.5, 2),
        # Dark sphere, roulette from the first bounce: most paths are killed, the series must still hold.
        ("gaussian_rgb", 12, 0.2, 1),
    ],
)
def test_multibounce_closed_form_with_russian_roulette(mode, bounces, albedo, roulette_depth):
    s = settings(wavelength_mode=mode, samples=64, samples_per_pass=64, max_bounces=bounces,
                 russian_roulette_depth=roulette_depth)
    r = Renderer(inside_glowing_sphere(albedo=albedo), s)
    r.render_pass()
    expected = sum(albedo**k for k in range(bounces + 2)) * _white(s)
    mean = r.image_rgb().astype(np.float64).mean((0, 1))
    stderr = np.sqrt(r.variance_rgb().astype(np.float64).mean((0, 1)) / r.image_rgb()[..., 0].size)
    assert np.all(np.abs(mean - expected) < 4 * stderr), (mean / expected, stderr / expected)
    assert np.allclose(mean / expected, 1.0, atol=0.01), mean / expected
    assert r.stats["nan_samples"] == 0


def test_error_falls_as_one_over_spp():
    s = settings(wavelength_mode="gaussian_rgb", samples=64, samples_per_pass=1, max_bounces=4)
    scene = inside_glowing_sphere(size=12, albedo=0.6)
    r = Renderer(scene, s)
    expected = sum(0.6**k for k in range(6)) * _white(s)
    spp, mse = [], []
    for i in range(64):
        r.render_pass()
        if (i + 1) in (2, 4, 8, 16, 32, 64):
            spp.append(i + 1)
            mse.append(((r.image_rgb() - expected) ** 2).mean())
    slope = np.polyfit(np.log(spp), np.log(mse), 1)[0]
    assert -1.25 < slope < -0.75, slope


def _mixed_scene():
    """Box floor + rough metal + every light type, to compare MIS on/off."""
    cam_m = look_at((0, -3.0, 1.2), (0, 0, 0.3))
    from engine.tracer.scene import Camera

    cam = Camera("cam", cam_m, (16, 16))
    floor = quad((0, 0, 0), (2, 0, 0), (0, 2, 0))
    wall = quad((0, 1, 1), (2, 0, 0), (0, 0, 1))
    ball = uv_sphere((0.3, 0.2, 0.4), 0.4, rings=8, segments=16)
    lamp = quad((-0.8, 0.5, 1.5), (0.15, 0, 0), (0, 0.15, 0))
    mats = [Material("floor", base_color=(0.7, 0.6, 0.5)), Material("wall", base_color=(0.3, 0.5, 0.7)),
            Material("metal", kind="conductor", base_color=(0.9, 0.8, 0.5), roughness=0.3),
            Material("lamp", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(kind="blackbody", temperature_k=3000),
                     emission_strength=20.0)]
    lights = [Light("area", "area", np.array([0.8, -0.5, 1.5]), power_w=30.0, size_u_m=0.5, size_v_m=0.3),
              Light("ball", "point", np.array([-0.5, -0.8, 0.8]), power_w=15.0, radius_m=0.1),
              Light("sun", "sun", np.zeros(3), direction=np.array([0.3, 0.4, -1.0]), irradiance_w_m2=1.0,
                    sun_angle_rad=0.2),
              Light("spot", "spot", np.array([0.0, -1.0, 2.0]), direction=np.array([0.0, 0.4, -1.0]), power_w=40.0,
                    spot_size_rad=0.8, spot_blend=0.3)]
    return make_scene([(*floor, 0), (*wall, 1), (*ball, 2), (*lamp, 3)], mats, cam, lights)


def test_mis_and_nee_only_agree_on_every_light_type():
    scene = _mixed_scene()
    out = []
    for mis in (True, False):
        r = Renderer(scene, settings(samples=48, samples_per_pass=48, use_mis=mis, max_bounces=3))
        r.render_pass()
        assert r.stats["nan_samples"] == 0
        out.append((r.image_rgb().astype(np.float64), r.variance_rgb().astype(np.float64)))
    (a, va), (b, vb) = out
    npix = a[..., 0].size
    diff = a.mean((0, 1)) - b.mean((0, 1))
    sigma = np.sqrt((va.mean((0, 1)) + vb.mean((0, 1))) / npix)
    assert np.all(np.abs(diff) < 4 * sigma + 1e-3 * a.mean()), (diff, sigma)
    assert a.mean() > 0.01
    # MIS must not be noisier than light sampling alone overall
    assert va.mean() < 1.5 * vb.mean()


@pytest.mark.parametrize("mode", ["cie", "gaussian_rgb"])
@pytest.mark.parametrize("material", [
    Material("glass", kind="dielectric", ior=1.5),
    Material("rough glass", kind="dielectric", ior=1.5, roughness=0.1),  # single-scatter GGX: ~2 % lost at 0.3
    Material("flint", kind="dielectric", glass="N-SF11"),
    Material("soap", kind="thin_film", film_thickness_nm=350.0, film_ior=1.33),
    Material("coated", kind="dielectric", ior=1.6, coating_thickness_nm=120.0, coating_ior=1.38),
], ids=lambda m: m.name)
def test_non_absorbing_objects_vanish_in_the_furnace(mode, material):
    """Glass (smooth, rough, dispersive, coated) and soap films neither absorb nor emit:
    under a uniform sky they must render as the sky itself, on average."""
    s = settings(wavelength_mode=mode, samples=16, samples_per_pass=16, max_bounces=24)
    scene = sphere_under_sky(size=12)
    scene.materials = [material]
    r = Renderer(scene, s)
    r.render_pass()
    mean = r.image_rgb().astype(np.float64).mean((0, 1)) / _white(s)
    stderr = np.sqrt(r.variance_rgb().astype(np.float64).mean((0, 1)) / 144) / _white(s)
    assert np.all(np.abs(mean - 1) < 4 * stderr + 0.003), (mean, stderr)
    assert r.stats["nan_samples"] == 0


@pytest.mark.parametrize("light", [
    Light("panel", "area", np.array([0.0, 0.0, 2.0]), direction=np.array([0.0, 0.0, -1.0]), power_w=50.0,
          size_u_m=3.0, size_v_m=3.0),
    Light("sun", "sun", np.zeros(3), direction=np.array([0.0, 0.0, -1.0]), irradiance_w_m2=2.0,
          sun_angle_rad=np.radians(60.0)),
    Light("bulb", "point", np.array([0.0, 0.0, 3.0]), power_w=40.0, radius_m=2.0),
], ids=lambda light: light.name)
def test_lights_seen_in_a_perfect_mirror_have_their_radiance(light):
    """Camera looks straight down at a mirror (F = 1): every pixel reflects the light's
    own radiance (lights are invisible to camera rays but not to reflections)."""
    from engine.tracer.scene import Camera

    cam = Camera("cam", look_at((0, 0, 1.0), (0, 0, 0), up=(0, 1, 0)), (8, 8), film_width_mm=6.0,
                 film_height_mm=6.0)
    mirror = quad((0, 0, 0), (5, 0, 0), (0, 5, 0))
    scene = make_scene([(*mirror, 0)], [Material("mirror", kind="conductor", base_color=(1.0, 1.0, 1.0))], cam,
                       [light])
    s = settings(samples=16, samples_per_pass=16)
    r = Renderer(scene, s)
    r.render_pass()
    if light.kind == "area":
        radiance = light.power_w / (np.pi * light.size_u_m * light.size_v_m)
    elif light.kind == "sun":
        radiance = light.irradiance_w_m2 / (np.pi * np.sin(light.sun_angle_rad / 2) ** 2)
    else:
        radiance = light.power_w / (4 * np.pi) / (np.pi * light.radius_m**2)
    ratio = r.image_rgb().astype(np.float64) / (radiance * _white(s))
    assert np.allclose(ratio.mean((0, 1)), 1.0, atol=0.01) and np.allclose(ratio, 1.0, atol=0.15)
    assert r.stats["nan_samples"] == 0


def test_non_finite_camera_rays_add_nothing():
    """A ray Embree cannot take (NaN direction) ends its path with no radiance, instead of being
    mistaken for an escape to the sky: a camera whose film is NaN on its left half."""
    scene = sphere_under_sky(size=8)
    r = Renderer(scene, settings(samples=4, samples_per_pass=4))
    data = r.camera.data
    r.camera.data = data._replace(tan_w=float("nan"))
    r.render_pass()
    assert np.all(r.image_rgb() == 0) and r.stats["nan_samples"] == 0
    assert r.stats["rejected_rays"] == 8 * 8 * 4


def test_roulette_survival_is_sqrt_of_throughput_capped_at_one():
    """A path of weight 1/4 survives half the time (Cycles' rule, gentler than pbrt's)."""
    from engine.tracer.stages.roulette import continuation_probability

    got = [continuation_probability(t) for t in (0.0, 0.04, 0.25, 1.0, 3.0)]
    assert np.allclose(got, [0, 0.2, 0.5, 1, 1])
