"""Warps and sequences: uniformity (chi-square), unit length, frames, MIS weights."""

import numpy as np
from scipy import stats

from engine.tracer import sampling as s


def _chi2_uniform(values, bins=20):
    h, _ = np.histogram(values, bins=bins, range=(0, 1))
    return stats.chisquare(h).pvalue


def test_cosine_hemisphere_and_sphere_and_cone_are_distributed_as_claimed():
    rng = np.random.default_rng(0)
    u = rng.random((200_000, 2))
    c = s.cosine_hemisphere(u)
    assert np.allclose(np.linalg.norm(c, axis=1), 1)
    assert _chi2_uniform(c[:, 2] ** 2) > 1e-3  # cos^2 is uniform for a cosine density
    sp = s.uniform_sphere(u)
    assert _chi2_uniform(0.5 * (sp[:, 2] + 1)) > 1e-3
    cone = s.uniform_cone(u, 0.8)
    assert cone[:, 2].min() >= 0.8 - 1e-12 and _chi2_uniform((1 - cone[:, 2]) / 0.2) > 1e-3
    phi = np.mod(np.arctan2(c[:, 1], c[:, 0]), 2 * np.pi) / (2 * np.pi)
    assert _chi2_uniform(phi) > 1e-3
    b = s.uniform_triangle(u)
    assert _chi2_uniform((1 - b[:, 0]) ** 2) > 1e-3  # area fraction is uniform


def test_low_discrepancy_pixel_samples_are_stratified():
    rot = s.pixel_offsets(0, 1, 2, 1)
    pts = s.r2_samples(np.arange(64), np.repeat(rot, 64, 0))
    h, _, _ = np.histogram2d(pts[:, 0], pts[:, 1], bins=4, range=[[0, 1], [0, 1]])
    assert h.min() >= 2 and h.max() <= 6  # far more even than 64 random points
    r1 = s.r1_samples(np.arange(10), np.zeros(10))
    assert np.histogram(r1, bins=10, range=(0, 1))[0].max() <= 2  # three-gap theorem


def test_frames_and_mis():
    rng = np.random.default_rng(1)
    n = s.normalize(rng.normal(size=(1000, 3)))
    n[0] = [0, 0, -1]
    t1, t2 = s.orthonormal_basis(n)
    assert np.allclose((t1 * n).sum(1), 0) and np.allclose((t2 * n).sum(1), 0) and np.allclose((t1 * t2).sum(1), 0)
    v = rng.normal(size=(1000, 3))
    assert np.allclose(s.to_world(s.to_local(v, t1, t2, n), t1, t2, n), v)
    w = s.power_heuristic(np.array([1.0, 2.0, np.inf, 0.0]), np.array([1.0, 1.0, 3.0, 0.0]))
    assert np.allclose(w, [0.5, 0.8, 1.0, 0.0])
    a = s.pass_rng(3, 1, 2).random(4)
    assert np.array_equal(a, s.pass_rng(3, 1, 2).random(4)) and not np.array_equal(a, s.pass_rng(3, 2, 2).random(4))
