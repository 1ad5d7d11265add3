"""Shared check of a medium segment's estimator against closed forms (``test_grid_tracking``,
``test_segment``): per carried wavelength, the weight of the paths that pass estimates T_k(t) = exp(-σ_t,k t)
and that of the paths scattering in each stretch [a, b) estimates σ_s,k / σ_t,k (T_k(a) − T_k(b))."""

import math

import numpy as np


def assert_segment_estimates(collisions, weights, s_s, s_t, t, stretches, carried, label):
    """Each mean within 4.5 standard errors of its closed form; ``collisions`` inf for the paths that pass."""
    n = len(collisions)
    passed = np.isinf(collisions)
    checks = [(passed, np.exp(-s_t * t), "passes")]
    for a, b in stretches:
        inside = (collisions >= a) & (collisions < b)
        checks.append((inside, s_s / s_t * (np.exp(-s_t * a) - np.exp(-s_t * b)), f"scatters in [{a}, {b:.2f})"))
    for chosen, expected, what in checks:
        estimate = np.where(chosen[:, None], weights, 0.0)
        mean, stderr = estimate.mean(0), estimate.std(0) / math.sqrt(n)
        ratio = np.round(mean[carried] / expected[carried], 4).tolist()
        print(f"MEASURED {label} {what}: estimate / closed form", ratio)
        assert np.all(np.abs(mean - expected)[carried] < 4.5 * stderr[carried] + 1e-12)
