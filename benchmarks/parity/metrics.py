"""The statistics a parity scene is judged by, on absolute scene-linear images (never normalised: both
engines use the same units, so a constant factor between them is a finding)."""

from __future__ import annotations

import numpy as np

#: Rec.709 / sRGB primaries' luminance weights (Blender's scene-linear space).
REC709_Y = np.array([0.2126729, 0.7151522, 0.0721750])

#: relMSE's ε: keeps near-black pixels from dominating (as benchmarks/metrics.py).
REL_MSE_EPSILON = 1e-2


def mean_luminance(rgba: np.ndarray) -> float:
    """Mean Rec.709 Y of the image's (premultiplied) RGB over every pixel."""
    return float((rgba[..., :3].astype(np.float64) @ REC709_Y).mean())


def luminance_ratio(prism: np.ndarray, cycles: np.ndarray) -> float:
    """Mean luminance of Prism's image / that of Cycles' (inf where Cycles' is black and Prism's is not)."""
    reference = mean_luminance(cycles)
    measured = mean_luminance(prism)
    if reference == 0.0:
        return 1.0 if measured == 0.0 else float("inf")
    return measured / reference


def relative_mse(prism: np.ndarray, cycles: np.ndarray) -> float:
    """Mean over pixels and RGB channels of (Prism - Cycles)² / (Cycles² + ε)."""
    a, b = prism[..., :3].astype(np.float64), cycles[..., :3].astype(np.float64)
    return float(np.mean((a - b) ** 2 / (b * b + REL_MSE_EPSILON)))


def alpha_difference(prism: np.ndarray, cycles: np.ndarray) -> float:
    """Mean |alpha Prism - alpha Cycles| over the pixels."""
    return float(np.abs(prism[..., 3].astype(np.float64) - cycles[..., 3]).mean())
