"""Error metrics against a reference image, and reading error-vs-time curves.

relMSE (relative mean squared error) of an image ``x`` against a reference ``r``::

    relMSE = mean over pixels and R, G, B of (x - r)^2 / (r^2 + eps),  eps = 1e-2

on scene-linear Rec.709 values. ``eps`` keeps black pixels from dividing by zero;
with it, pixels darker than 0.1 count by absolute rather than relative error.

FLIP is NVIDIA's perceptual difference (HDR-FLIP, mean over the error map; 0 =
identical, 1 = maximal), computed by the ``flip-evaluator`` package with its
defaults (67 pixels per degree, ACES tone mapper, exposure range taken from the
reference).

Without a reference, two renders that differ only in their seed estimate either one's relMSE
(``relmse_from_two_seeds``).

A reference is itself noisy: its expected contribution to the measured relMSE is
``noise_floor = mean(var_ref / (r^2 + eps))``, reported beside each table so a
reader can see how far above the floor a measurement sits.
"""

from __future__ import annotations

import numpy as np

RELMSE_EPSILON = 1e-2


def _as_image(image, name):
    image = np.asarray(image, dtype=np.float64)
    if image.ndim != 3 or image.shape[2] != 3:
        raise ValueError(f"{name} must be an [H, W, 3] image, got shape {image.shape}")
    return image


def relmse(image, reference, epsilon: float = RELMSE_EPSILON) -> float:
    """Relative MSE of ``image`` against ``reference`` (both [H, W, 3] scene-linear)."""
    image, reference = _as_image(image, "image"), _as_image(reference, "reference")
    if image.shape != reference.shape:
        raise ValueError(f"image {image.shape} and reference {reference.shape} differ in shape")
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + epsilon)))


def relmse_from_two_seeds(first, second, epsilon: float = RELMSE_EPSILON) -> float:
    """relMSE of one render, estimated from two renders of the same spp that differ only in the seed, without a
    reference: for independent ``a`` and ``b`` of the same mean, E[(a - b)^2] / 2 is one render's variance, and
    their mean stands in for the truth in the denominator. relmse(a, (a + b) / 2) divides (a - b)^2 / 4 by it,
    so twice that is mean((a - b)^2 / 2 / (((a + b) / 2)^2 + eps)).
    Unbiased while the noise is small against the pixel values (the mean's own noise adds to the denominator)."""
    first, second = _as_image(first, "first"), _as_image(second, "second")
    return 2.0 * relmse(first, 0.5 * (first + second), epsilon)


def relmse_noise_floor(reference, reference_variance, epsilon: float = RELMSE_EPSILON) -> float:
    """Expected relMSE contributed by the reference's own noise (its variance of the mean)."""
    reference = _as_image(reference, "reference")
    variance = _as_image(reference_variance, "reference_variance")
    return float(np.mean(variance / (reference ** 2 + epsilon)))


def flip(image, reference) -> float:
    """Mean HDR-FLIP of ``image`` against ``reference`` (linear Rec.709, negatives clamped to 0)."""
    import flip_evaluator

    image, reference = _as_image(image, "image"), _as_image(reference, "reference")
    test = np.ascontiguousarray(np.clip(np.nan_to_num(image), 0.0, None), dtype=np.float32)
    ref = np.ascontiguousarray(np.clip(np.nan_to_num(reference), 0.0, None), dtype=np.float32)
    _, mean_error, _ = flip_evaluator.evaluate(ref, test, "HDR", applyMagma=False)
    return float(mean_error)


def _loglog(times, errors):
    times = np.asarray(times, dtype=np.float64)
    errors = np.asarray(errors, dtype=np.float64)
    keep = (times > 0) & (errors > 0) & np.isfinite(times) & np.isfinite(errors)
    order = np.argsort(times[keep])
    return np.log(times[keep][order]), np.log(errors[keep][order])


def error_at_time(times, errors, seconds: float):
    """Error of a curve at ``seconds``, interpolated linearly in log-log.

    Returns ``(error, extrapolated)``; outside the measured range the end segment's
    slope is extended (so ``extrapolated`` is True and the value is a fit)."""
    lt, le = _loglog(times, errors)
    if len(lt) < 2:
        return float("nan"), True
    x = np.log(seconds)
    if lt[0] <= x <= lt[-1]:
        return float(np.exp(np.interp(x, lt, le))), False
    i = (0, 1) if x < lt[0] else (-2, -1)
    slope = (le[i[1]] - le[i[0]]) / (lt[i[1]] - lt[i[0]])
    return float(np.exp(le[i[0]] + slope * (x - lt[i[0]]))), True


def time_to_error(times, errors, target: float):
    """Wall time at which a curve reaches ``target`` error, log-log interpolated.

    Returns ``(seconds, extrapolated)``; beyond the measured range the end segment
    of the curve is extended (a fit, flagged); NaN if the curve never falls."""
    lt, le = _loglog(times, errors)
    if len(lt) < 2:
        return float("nan"), True
    y = np.log(target)
    for k in range(len(le) - 1):
        lo, hi = sorted((le[k], le[k + 1]))
        if lo <= y <= hi and le[k] != le[k + 1]:
            f = (y - le[k]) / (le[k + 1] - le[k])
            return float(np.exp(lt[k] + f * (lt[k + 1] - lt[k]))), False
    i = (0, 1) if y > le[0] else (-2, -1)
    slope = (le[i[1]] - le[i[0]]) / (lt[i[1]] - lt[i[0]])
    if not slope < 0:
        return float("nan"), True
    return float(np.exp(lt[i[0]] + (y - le[i[0]]) / slope)), True
