"""How much a scene's luminance ratio moves from seed to seed at its sample count: the evidence that the
2 % tolerance is not hit by noise. Both engines render the scene with seeds 0 .. K-1."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .compare import build
from .engines import render_cycles, render_prism
from .metrics import mean_luminance
from .record import ParityScene


@dataclass
class NoiseEstimate:
    """Over ``seeds`` seeds: the relative standard deviation of each engine's mean luminance and of the
    ratio Prism / Cycles (seed k against seed k), and the ratios themselves."""

    seeds: int
    prism_spread: float
    cycles_spread: float
    ratio_spread: float
    ratios: list[float]

    @property
    def margin_sigmas(self) -> float:
        """How many standard deviations of the ratio fit in the 2 % tolerance."""
        return 0.02 / self.ratio_spread if self.ratio_spread > 0 else float("inf")


def estimate_noise(scene: ParityScene, seeds: int) -> NoiseEstimate | None:
    """None when Prism refuses the scene (nothing to measure)."""
    prism_means, cycles_means = [], []
    for seed in range(seeds):
        bpy_scene = build(scene)
        cycles = render_cycles(bpy_scene, scene.samples, scene.bounces, scene.output, seed)
        prism = render_prism(bpy_scene, scene.samples, scene.bounces, scene.output, seed)
        if prism.rgba is None:
            return None
        prism_means.append(mean_luminance(prism.rgba))
        cycles_means.append(mean_luminance(cycles.rgba))
    p, c = np.array(prism_means), np.array(cycles_means)
    ratios = p / c
    spread = lambda values: float(np.std(values, ddof=1) / np.mean(values))  # noqa: E731
    return NoiseEstimate(seeds=seeds, prism_spread=spread(p), cycles_spread=spread(c), ratio_spread=spread(ratios),
                         ratios=ratios.tolist())
