"""The Bevel node's disk sampling (``materials.shader_rays``): Cycles' cubic falloff is a density over the disk,
and its radius sampler draws from it (chi-square), and the slots of a material's own rays leave every other
sample dimension alone."""

from __future__ import annotations

import math

import numpy as np
from scipy import integrate, stats

from engine.tracer import sampler
from engine.tracer.materials.shader_rays import cubic_pdf, cubic_radius

RADIUS = 0.3


def test_cubic_falloff_is_a_density_over_the_disk():
    total, _ = integrate.quad(lambda r: 2.0 * math.pi * r * cubic_pdf(RADIUS, r), 0.0, RADIUS)
    assert abs(total - 1.0) < 1e-9
    assert cubic_pdf(RADIUS, RADIUS) == 0.0 and cubic_pdf(RADIUS, 2.0 * RADIUS) == 0.0


def test_cubic_radius_is_distributed_as_the_falloff():
    """Chi-square of 40 000 radii (from uniform numbers) in 20 bins of equal probability under the falloff's
    radial law, 2πr · pdf(r), whose cumulative is 10x² - 20x³ + 15x⁴ - 4x⁵ with x = r / R."""
    rng = np.random.default_rng(7)
    radii = np.array([cubic_radius(RADIUS, xi) for xi in rng.random(40_000)])
    assert radii.min() >= 0.0 and radii.max() <= RADIUS
    x = radii / RADIUS
    cumulative = 10 * x**2 - 20 * x**3 + 15 * x**4 - 4 * x**5
    counts = np.bincount(np.minimum((cumulative * 20).astype(int), 19), minlength=20)
    assert stats.chisquare(counts).pvalue > 1e-3
    for xi in (0.001, 0.3, 0.5, 0.9, 0.999):  # Newton converges to the quintic's root
        y = cubic_radius(RADIUS, xi) / RADIUS
        assert abs(10 * y**2 - 20 * y**3 + 15 * y**4 - 4 * y**5 - xi) < 1e-5


def test_shader_ray_slots_are_apart_from_every_other_slot():
    slots = {sampler.shader_ray_slot(depth, kind) for depth in range(64) for kind in range(sampler.SHADER_RAY_KINDS)}
    assert len(slots) == 64 * sampler.SHADER_RAY_KINDS
    others = {sampler.bounce_slot(depth, which) for depth in range(64) for which in range(sampler.SLOTS_PER_BOUNCE)}
    others |= {sampler.medium_slot(d) for d in range(64)} | {sampler.medium_light_slot(d) for d in range(64)}
    others |= {sampler.SLOT_TIME, sampler.SLOT_PIXEL, sampler.SLOT_LENS, sampler.SLOT_HERO}
    assert not slots & others
