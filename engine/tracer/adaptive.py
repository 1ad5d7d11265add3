"""Adaptive sampling: which pixels still need samples, from the variance the film already keeps.

A pixel's error is the standard error of its mean summed over R, G, B, relative to the square root of
its brightness (noise is judged as the eye judges it after a gamma-like curve, so dark pixels are not
sampled for ever). A pixel has converged when that error is below the noise threshold; a pixel next
to an unconverged one keeps sampling too, so a noisy region ends with a soft edge, not a seam.
"""

from __future__ import annotations

import numpy as np

#: Brightness floor (scene-linear) under the square root: pure black pixels are judged in absolute terms.
DARK_FLOOR = 1e-4


def automatic_min_samples(samples: int, threshold: float) -> int:
    """Min Samples 0 means automatic: enough samples that a rare bright path has had a chance to show
    (more for a stricter threshold), at most the render's samples."""
    wanted = max(16, int(np.ceil(0.25 / np.sqrt(max(threshold, 1e-8)))))
    return min(int(samples), wanted)


def pixel_error(mean: np.ndarray, variance_of_mean: np.ndarray) -> np.ndarray:
    """[H, W] relative error of every pixel from its mean and variance of the mean [H, W, 3]."""
    brightness = np.maximum(mean, 0.0).sum(axis=-1)
    return np.sqrt(np.maximum(variance_of_mean, 0.0)).sum(axis=-1) / np.sqrt(brightness + DARK_FLOOR)


def still_sampling(mean: np.ndarray, variance_of_mean: np.ndarray, threshold: float) -> np.ndarray:
    """[H, W] bool: pixels whose error is at or above ``threshold``, grown by one pixel each way."""
    active = pixel_error(mean, variance_of_mean) >= threshold
    grown = active.copy()
    grown[1:] |= active[:-1]
    grown[:-1] |= active[1:]
    grown[:, 1:] |= active[:, :-1]
    grown[:, :-1] |= active[:, 1:]
    return grown


def samples_that_fit(spp: int, left_s: float, last_pass, pixels: int) -> int:
    """Samples per pixel of the next pass that fit in ``left_s`` seconds (0: none left), from the last pass's
    (seconds, samples per pixel) over ``pixels`` pixels, or None before the first pass."""
    if left_s <= 0.0:
        return 0
    if last_pass is not None and last_pass[1] > 0:
        per_sample = last_pass[0] / last_pass[1] * pixels
        if per_sample > 0:
            spp = min(spp, max(1, int(left_s / per_sample)))
    return spp


def time_to_check(threshold: float, done: int, settings, checked_at: int) -> bool:
    """Whether the pixels' convergence is due after ``done`` samples: adaptive sampling on, the minimum
    samples (Min Samples, or ``automatic_min_samples``) reached, and a few samples since the last check."""
    if not threshold > 0.0:
        return False
    minimum = settings.adaptive_min_samples or automatic_min_samples(settings.samples, threshold)
    return done >= minimum and done - checked_at >= min(4, minimum)


def still_active(film, threshold: float, done: int) -> np.ndarray:
    """bool [pixels] of ``film``'s region: still noisy, and not stopped earlier (its count is ``done``)."""
    active = still_sampling(film.mean(), film.variance_of_mean(), threshold).ravel()
    return active & (film.counts.ravel() == done)
