"""Warps: uniformity of the mapped points (chi-square), unit directions, frames, MIS weights."""

import numpy as np
from scipy import stats

from engine.tracer import vec3, warps


def _chi2_uniform(values, bins=20):
    h, _ = np.histogram(values, bins=bins, range=(0, 1))
    return stats.chisquare(h).pvalue


def _map(fn, u, *extra):
    return np.array([fn(a, b, *extra) for a, b in u])


def test_cosine_hemisphere_sphere_cone_triangle_and_disk_are_distributed_as_claimed():
    u = np.random.default_rng(0).random((100_000, 2))
    c = _map(warps.cosine_hemisphere, u)
    assert np.allclose(np.linalg.norm(c, axis=1), 1)
    assert _chi2_uniform(c[:, 2] ** 2) > 1e-3  # cos^2 is uniform for a cosine density
    phi = np.mod(np.arctan2(c[:, 1], c[:, 0]), 2 * np.pi) / (2 * np.pi)
    assert _chi2_uniform(phi) > 1e-3
    sp = _map(warps.uniform_sphere, u)
    assert _chi2_uniform(0.5 * (sp[:, 2] + 1)) > 1e-3
    cone = _map(warps.uniform_cone, u, 0.8)
    assert cone[:, 2].min() >= 0.8 - 1e-12 and _chi2_uniform((1 - cone[:, 2]) / 0.2) > 1e-3
    b = _map(warps.uniform_triangle, u)
    assert _chi2_uniform((1 - b[:, 0]) ** 2) > 1e-3  # area fraction is uniform
    disk = _map(warps.concentric_disk, u)
    r2 = (disk**2).sum(1)
    assert r2.max() <= 1 + 1e-12 and _chi2_uniform(r2) > 1e-3
    assert warps.concentric_disk(0.5, 0.5) == (0.0, 0.0)


def test_frames_and_mis():
    rng = np.random.default_rng(1)
    n = rng.normal(size=(1000, 3))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    n[0] = [0, 0, -1]
    for normal in n:
        s, t = vec3.tangents(tuple(normal))
        m = np.array([s, t, normal])
        assert np.allclose(m @ m.T, np.eye(3), atol=1e-12) and np.linalg.det(m) > 0
        v = tuple(rng.normal(size=3))
        assert np.allclose(vec3.to_world(vec3.to_local(v, s, t, tuple(normal)), s, t, tuple(normal)), v)
    got = [warps.power_heuristic(a, b) for a, b in ((1.0, 1.0), (2.0, 1.0), (np.inf, 3.0), (0.0, 0.0), (1.0, np.inf))]
    assert np.allclose(got, [0.5, 0.8, 1.0, 0.0, 0.0])


def test_polynomial_sin_cos_match_libm():
    for x in np.linspace(-np.pi / 4, np.pi / 4, 2001):
        s, c = warps.sincos_quarter(x)
        assert abs(s - np.sin(x)) < 1e-11 and abs(c - np.cos(x)) < 1e-11
    for u in np.linspace(0.0, 1.0, 4001, endpoint=False):
        s, c = warps.sincos_turn(u)
        assert abs(s - np.sin(2 * np.pi * u)) < 1e-11 and abs(c - np.cos(2 * np.pi * u)) < 1e-11
