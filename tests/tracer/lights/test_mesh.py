"""Emissive triangles: area sampling against the closed form, pdf of hits, two-sided emission."""

import numpy as np
import pytest

from engine.tracer.scene import Camera, Material, SpectrumSpec

from ..tracer_scenes import make_scene
from .light_checks import SceneLights


def test_emissive_quad_irradiance_and_pdf():
    quad_v = np.array([[-0.5, -0.5, 1.0], [0.5, -0.5, 1.0], [0.5, 0.5, 1.0], [-0.5, 0.5, 1.0]])
    other_v = np.array([[5, 5, 5], [6, 5, 5], [5, 6, 5.0]])
    glow = Material("glow", base_color=(0, 0, 0), emission=SpectrumSpec(), emission_strength=2.0)
    scene = make_scene([(quad_v, np.array([[0, 1, 2], [0, 2, 3]]), 0), (other_v, np.array([[0, 1, 2]]), 1)],
                       [glow, Material("plain")], Camera("c", np.eye(4), (1, 1)))
    lights = SceneLights(scene)
    mesh = lights.arrays.mesh
    assert mesh.triangle.tolist() == [0, 1] and mesh.of_triangle.tolist() == [0, 1, -1]
    n = 200_000
    p = np.zeros((n, 3))
    s = lights.sample(p, np.random.default_rng(7).random((n, 3)), 500.0)
    white = lights.spectra
    from engine.tracer.spectra.table import spectrum_value

    radiance = 2.0 * spectrum_value(white, int(lights.materials.emission_spectrum[0]), 500.0)
    assert np.allclose(s.li, radiance)
    est = s.li / radiance * 2.0 * s.wi[:, 2] / s.pdf
    # irradiance under a unit square of radiance 2 at height 1 (exact form for a square: 4 x corner patch)
    a = b = 0.5
    corner = (a / np.sqrt(1 + a * a) * np.arctan(b / np.sqrt(1 + a * a))
              + b / np.sqrt(1 + b * b) * np.arctan(a / np.sqrt(1 + b * b))) / (2 * np.pi)
    assert est.mean() == pytest.approx(2.0 * np.pi * 4 * corner, rel=0.005)
    # triangle 1 holds the points with y > x; its pdf for hits matches the sampling density
    hit_tri = np.where(np.cross(np.array([1, 1, 0.0]), (p + s.dist[:, None] * s.wi) - quad_v[0])[:, 2] > 0, 1, 0)
    assert np.allclose(lights.emitter_pdf(hit_tri, s.wi, s.dist), s.pdf, rtol=1e-6)
    # two-sided: sampled from above the quad too; the plain triangle never emits
    above = lights.sample(np.array([[0.0, 0.0, 2.0]]), np.array([[0.3, 0.6, 0.2]]), 500.0)
    assert above.pdf[0] > 0 and above.li[0] == pytest.approx(radiance)
    assert lights.emitter_pdf([2], s.wi[:1], s.dist[:1])[0] == 0.0


@pytest.mark.parametrize("time", [0.0, 0.3, 1.0])
def test_a_moving_emitter_is_sampled_where_it_stands_at_the_ray_time(time):
    """Motion blur: the quad slides 2 m along x, rises 0.5 m and stretches from 0.5 to 1.5 m wide over the shutter
    (3 steps). A point drawn at ray time τ lies on the quad where it stands then, the irradiance below it is the
    closed form of the quad there, and the density of a hit at τ is the sampler's, not the frame's quad's."""
    from engine.tracer.motion import Motion

    quad_v = np.array([[-0.5, -0.5, 1.0], [0.5, -0.5, 1.0], [0.5, 0.5, 1.0], [-0.5, 0.5, 1.0]])
    glow = Material("glow", base_color=(0, 0, 0), emission=SpectrumSpec(), emission_strength=2.0)
    scene = make_scene([(quad_v, np.array([[0, 1, 2], [0, 2, 3]]), 0)], [glow], Camera("c", np.eye(4), (1, 1)))
    shift, width = np.array([[-1.0, 0.0, -0.25], [0.0, 0.0, 0.0], [1.0, 0.0, 0.25]]), np.array([0.5, 1.0, 1.5])
    scene.motion = Motion(np.stack([quad_v * [w, 1.0, 1.0] + s for s, w in zip(shift, width)]))
    lights = SceneLights(scene)
    x, rise, w = (np.interp(time, [0.0, 0.5, 1.0], values) for values in (shift[:, 0], shift[:, 2], width))
    n = 100_000
    p = np.tile([x, 0.0, 0.0], (n, 1))  # right under the quad's centre at τ
    s = lights.sample(p, np.random.default_rng(3).random((n, 3)), 500.0, time=time)
    points = p + s.dist[:, None] * s.wi
    assert np.allclose(points[:, 2], 1.0 + rise, atol=1e-9)
    assert np.all(np.abs(points[:, 0] - x) <= w / 2 + 1e-9) and np.all(np.abs(points[:, 1]) <= 0.5 + 1e-9)
    h = 1.0 + rise
    a, b = w / 2 / h, 0.5 / h  # the closed form of test_emissive_quad_irradiance_and_pdf, a w × 1 m quad at h
    corner = (a / np.sqrt(1 + a * a) * np.arctan(b / np.sqrt(1 + a * a))
              + b / np.sqrt(1 + b * b) * np.arctan(a / np.sqrt(1 + b * b))) / (2 * np.pi)
    est = 2.0 * s.wi[:, 2] / s.pdf  # s.li / radiance is 1
    assert est.mean() == pytest.approx(2.0 * np.pi * 4 * corner, rel=0.01)
    local = (points - [x, 0.0, 0.0]) / [w, 1.0, 1.0]  # back on the frame's quad, to tell its two triangles apart
    hit_tri = np.where(np.cross(np.array([1, 1, 0.0]), local - quad_v[0])[:, 2] > 0, 1, 0)
    assert np.allclose(lights.emitter_pdf(hit_tri, s.wi, s.dist, time=time), s.pdf, rtol=1e-6)
    frame = lights.emitter_pdf(hit_tri, s.wi, s.dist)  # the frame's quad, 1 m wide: another area
    assert not np.allclose(frame, s.pdf, rtol=1e-3)
