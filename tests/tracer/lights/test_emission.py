"""Where light paths start (``lights.emission`` toward ``lights.caustic_targets``): for every light
kind the sampled points and directions follow their densities (chi-square), and the paths' mean
weight is the power the light sends toward the specular objects (closed forms and quadrature)."""

import numpy as np
import pytest

from engine.tracer.lights.row import L_SCALE
from engine.tracer.scene import Camera, Light, Material, SpectrumSpec
from engine.tracer.spectra.table import spectrum_value
from engine.tracer.vec3 import tangents

from ..tracer_scenes import make_scene, quad, uv_sphere
from .emission_checks import (Emission, beam_pdfs, chi_square_p, direction_pdfs, reference_directions,
                              same_distribution_p, sample_beams, sample_directions, sphere_bins, targets_of)

N = 200_000
GLASS = Material("glass", kind="dielectric", glass="N-BK7")


def _scene(balls, lights=(), extra=(), materials=()):
    """Glass balls ((centre, radius), ...) as the specular targets, plus ``extra`` (verts, tris, material)."""
    parts = [(*uv_sphere(c, r, rings=12, segments=24), 0) for c, r in balls] + list(extra)
    return make_scene(parts, [GLASS, *materials], Camera("c", np.eye(4), (1, 1)), list(lights))


def _uniforms(seed, n=N, dims=6):
    return np.random.default_rng(seed).random((n, dims))


def _mean_and_error(x):
    """The mean and four standard errors (at least the rounding of a constant)."""
    return x.mean(), max(4 * x.std() / np.sqrt(len(x)), 1e-12 * abs(x.mean()))


def _cone_of(targets, s, x):
    """(unit axis, sin² of the half-angle) of target sphere ``s`` seen from ``x``."""
    w = targets.spheres[s, :3] - x
    d = np.linalg.norm(w, axis=-1, keepdims=True)
    return w / d, (targets.spheres[s, 3] / d[..., 0]) ** 2


def test_directions_toward_overlapping_targets_follow_their_density():
    glass = [GLASS, Material("glass 2", kind="dielectric", glass="N-SF11"), Material("glass 3", kind="dielectric", ior=1.4)]
    balls = [((1.0, 0.2, 0.0), 0.6), ((0.9, -0.6, 0.3), 0.5), ((-0.3, 0.0, -1.2), 0.4)]
    scene = make_scene([(*uv_sphere(c, r, rings=12, segments=24), m) for m, (c, r) in enumerate(balls)], glass,
                       Camera("c", np.eye(4), (1, 1)))
    targets = targets_of(scene)  # one sphere per material here (no objects)
    assert len(targets.spheres) == 3
    for seed, x in enumerate((np.zeros(3), targets.spheres[0, :3])):  # outside all; inside the first
        d, pdf = sample_directions(targets, x, _uniforms(seed, dims=3))
        assert np.allclose(pdf, direction_pdfs(targets, x, d), rtol=1e-12)
        reference = reference_directions(targets, x, N, seed + 10)
        assert same_distribution_p(sphere_bins(d), sphere_bins(reference)) > 1e-3


def test_beam_crossings_follow_their_density_and_start_outside_the_scene():
    scene = _scene([((0.0, 0.0, 0.0), 0.5), ((0.4, 0.3, 0.2), 0.3)], extra=[(*quad((0, 0, -1), (3, 0, 0), (0, 3, 0)), 1)],
                   materials=[Material("floor")])
    targets = targets_of(scene)
    d = np.array([0.3, -0.2, -1.0]) / np.sqrt(1.13)
    origin, pdf = sample_beams(targets, d, _uniforms(3, dims=3))
    assert np.allclose(pdf, beam_pdfs(targets, d, origin), rtol=1e-12)
    assert np.all((origin - targets.centre) @ d < -targets.radius)
    e1, e2 = (np.array(v) for v in tangents(tuple(d)))
    xy = np.stack([origin @ e1, origin @ e2], -1)
    lo, hi, bins, sub = xy.min(0) - 1e-9, xy.max(0) + 1e-9, 20, 16
    counts = np.histogram2d(xy[:, 0], xy[:, 1], bins, [[lo[0], hi[0]], [lo[1], hi[1]]])[0]
    step = (hi - lo) / (bins * sub)
    gx, gy = (lo[i] + (np.arange(bins * sub) + 0.5) * step[i] for i in (0, 1))
    q = gx[:, None, None] * e1 + gy[None, :, None] * e2
    expected = beam_pdfs(targets, d, q.reshape(-1, 3)).reshape(bins, sub, bins, sub).sum((1, 3)) * step.prod()
    assert expected.sum() == pytest.approx(1.0, abs=5e-3)
    assert chi_square_p(counts, expected) > 1e-3


def _area_light(shape, position, direction, power=40.0):
    return Light("a", "area", np.asarray(position, float), direction=np.asarray(direction, float),
                 axis_u=np.array([1.0, 0.0, 0.0]), axis_v=np.array([0.0, 1.0, 0.0]), power_w=power, area_shape=shape,
                 size_u_m=0.6, size_v_m=0.4, spectrum=SpectrumSpec(kind="blackbody", temperature_k=4000.0))


@pytest.mark.parametrize("shape", ["rectangle", "disk"])
def test_area_light_starts_uniformly_and_sends_its_power(shape):
    # inside a target sphere: every direction, so the mean weight is the whole power
    emission = Emission(_scene([((0.0, 0.0, 1.0), 2.0)], [_area_light(shape, (0, 0, 1), (0, 0, -1))]))
    s = emission.sample(_uniforms(4))
    spectrum = emission.lights.spectrum_at(0)
    mean, error = _mean_and_error(s.beta / spectrum)
    assert mean == pytest.approx(40.0, abs=error)
    u, v = s.origin[:, 0] / 0.3, s.origin[:, 1] / 0.4 * 2
    assert np.allclose(s.origin[:, 2], 1.0)
    if shape == "rectangle":
        counts = np.histogram2d(u, v, 8, [[-1, 1], [-1, 1]])[0]
    else:
        counts = np.histogram2d(u * u + v * v, np.arctan2(v, u), 8, [[0, 1], [-np.pi, np.pi]])[0]
    assert chi_square_p(counts, np.ones_like(counts)) > 1e-3
    # a target below: the power into its cone, π sin²α (axis · normal) per unit area (quadrature)
    emission = Emission(_scene([((0.4, 0.3, -0.5), 0.4)], [_area_light(shape, (0, 0, 1), (0, 0, -1))]))
    s = emission.sample(_uniforms(5))
    g = (np.arange(200) + 0.5) / 200 * 2 - 1
    gu, gv = np.meshgrid(g, g)
    inside = (gu ** 2 + gv ** 2 <= 1) if shape == "disk" else np.ones_like(gu, bool)
    points = np.stack([gu * 0.3, gv * 0.2, np.ones_like(gu)], -1)[inside]
    axis, sin2 = _cone_of(emission.targets, 0, points)
    radiance = 40.0 / (np.pi * (np.pi if shape == "disk" else 4.0) * 0.3 * 0.2)
    flux = (radiance * np.pi * sin2 * -axis[:, 2]).sum() * 0.6 * 0.4 / 200 ** 2
    mean, error = _mean_and_error(s.beta / spectrum)
    assert mean == pytest.approx(flux, abs=error + 2e-3 * flux)


def test_area_light_spread_keeps_its_power_and_its_cone():
    """Cycles' Spread narrows the emission (same power): light paths carry the whole power into a
    target around the light, and nothing into one outside the spread's cone."""
    light = _area_light("rectangle", (0, 0, 1), (0, 0, -1))
    light.spread_rad = np.radians(40.0)
    emission = Emission(_scene([((0.0, 0.0, 1.0), 2.0)], [light]))
    s = emission.sample(_uniforms(6))
    mean, error = _mean_and_error(s.beta / emission.lights.spectrum_at(0))
    assert mean == pytest.approx(40.0, abs=error)
    cos_out = -s.direction[s.beta > 0][:, 2]
    assert cos_out.min() > np.cos(np.radians(20.0)) - 1e-9  # within the spread's half-angle of the normal
    aside = Emission(_scene([((2.0, 0.0, 0.0), 0.3)], [light]))  # 50° and more from the normal
    assert aside.sample(_uniforms(7, n=20_000)).beta.max() == 0.0


def test_the_world_sends_no_light_paths_and_the_other_lights_keep_their_power():
    """Under a bright light-sampled HDRI (most of the scene's power), every light path starts on the area
    light, whose mean weight is still its whole power."""
    from engine.tracer.scene import World

    scene = _scene([((0.0, 0.0, 1.0), 2.0)], [_area_light("rectangle", (0, 0, 1), (0, 0, -1))])
    scene.world = World(kind="image", image_rgb=np.full((8, 16, 3), 50.0, np.float32))
    emission = Emission(scene)
    assert emission.lights.arrays.environment_index == 1 and emission.lights.arrays.select_prob[1] > 0.9
    s = emission.sample(_uniforms(8))
    assert np.all(s.light == 0)
    mean, error = _mean_and_error(s.beta / emission.lights.spectrum_at(0))
    assert mean == pytest.approx(40.0, abs=error)


@pytest.mark.parametrize("kind", ["point", "spot"])
def test_point_light_sends_its_intensity_into_the_target_cone(kind):
    light = Light("p", kind, np.array([0.0, 0.0, 1.0]), direction=np.array([0.0, 0.0, -1.0]), power_w=30.0,
                  spot_size_rad=np.radians(40))
    emission = Emission(_scene([((0.5, 0.2, -0.3), 0.35), ((-0.4, 0.1, -0.2), 0.3)], [light]))
    s = emission.sample(_uniforms(6))
    x = np.array([0.0, 0.0, 1.0])
    assert np.allclose(s.origin, x)
    reference = reference_directions(emission.targets, x, N, 11)
    assert same_distribution_p(sphere_bins(s.direction), sphere_bins(reference)) > 1e-3
    assert len(emission.targets.spheres) == 1  # one material: one sphere around both balls
    solid_angle = 2 * np.pi * (1 - np.sqrt(1 - _cone_of(emission.targets, 0, x)[1]))
    mean, error = _mean_and_error(s.beta / emission.lights.spectrum_at(0))
    assert mean == pytest.approx(30.0 / (4 * np.pi) * solid_angle, abs=error)  # the spot's cut comes at the hit


def test_sphere_light_starts_uniformly_on_its_surface():
    light = Light("s", "point", np.array([0.2, 0.1, 0.5]), power_w=25.0, radius_m=0.1)
    emission = Emission(_scene([((0.0, 0.0, 0.5), 1.5)], [light]))
    s = emission.sample(_uniforms(7))
    normal = (s.origin - light.position) / 0.1
    assert np.allclose(np.linalg.norm(normal, axis=1), 1.0)
    assert chi_square_p(sphere_bins(normal, 8, 16), np.ones((8, 16))) > 1e-3
    assert np.all(np.einsum("ij,ij->i", normal, s.direction)[s.beta > 0] > 0)
    mean, error = _mean_and_error(s.beta / emission.lights.spectrum_at(0))
    assert mean == pytest.approx(25.0, abs=error)


def test_suns_send_their_beam_through_the_targets():
    to_sun = np.array([0.2, -0.3, 1.0]) / np.sqrt(1.13)
    ball = ((0.1, 0.0, 0.2), 0.5)
    delta = Light("sun", "sun", np.zeros(3), direction=-to_sun, irradiance_w_m2=3.0)
    emission = Emission(_scene([ball], [delta]))
    s = emission.sample(_uniforms(8))
    radius = emission.targets.spheres[0, 3]
    assert np.allclose(s.direction, -to_sun)
    mean, error = _mean_and_error(s.beta / emission.lights.spectrum_at(0))
    assert mean == pytest.approx(3.0 * np.pi * radius ** 2, abs=error)
    half = np.radians(10.0)
    disc = Light("sun", "sun", np.zeros(3), direction=-to_sun, irradiance_w_m2=3.0, sun_angle_rad=2 * half)
    emission = Emission(_scene([ball], [disc]))
    s = emission.sample(_uniforms(9))
    e1, e2 = (np.array(v) for v in tangents(tuple(to_sun)))
    w = -s.direction
    counts = np.histogram2d((1 - w @ to_sun) / (1 - np.cos(half)), np.arctan2(w @ e2, w @ e1), 8,
                            [[0, 1], [-np.pi, np.pi]])[0]
    assert chi_square_p(counts, np.ones_like(counts)) > 1e-3
    radiance = emission.lights.arrays.rows[0, L_SCALE]
    mean, error = _mean_and_error(s.beta / emission.lights.spectrum_at(0))
    assert mean == pytest.approx(radiance * 2 * np.pi * (1 - np.cos(half)) * np.pi * radius ** 2,
                                 abs=error)


def test_emissive_triangles_start_in_proportion_to_their_power():
    bright = Material("bright", emission=SpectrumSpec(), emission_strength=3.0)
    dim = Material("dim", emission=SpectrumSpec(), emission_strength=1.0)
    tri_a = (np.array([[-0.6, 0, 0], [-0.2, 0, 0], [-0.6, 0.5, 0]]), np.array([[0, 1, 2]]))  # area 0.1
    tri_b = (np.array([[0.2, 0, 0], [0.6, 0, 0.1], [0.2, 0.3, 0]]), np.array([[0, 1, 2]]))
    emission = Emission(_scene([((0.0, 0.2, 0.0), 1.5)], extra=[(*tri_a, 1), (*tri_b, 2)], materials=[bright, dim]))
    area_b = 0.5 * np.linalg.norm(np.cross(tri_b[0][1] - tri_b[0][0], tri_b[0][2] - tri_b[0][0]))
    powers = np.array([3.0 * 0.1, 1.0 * area_b])
    s = emission.sample(_uniforms(10))
    counts = np.bincount((s.origin[:, 0] > 0).astype(int), minlength=2)
    assert chi_square_p(counts, powers / powers.sum()) > 1e-3
    lights = emission.lights
    white = spectrum_value(lights.spectra, int(lights.materials.emission_spectrum[1]), 550.0)
    mean, error = _mean_and_error(s.beta / white)
    assert mean == pytest.approx(2 * np.pi * powers.sum(), abs=error)  # both faces, π each
