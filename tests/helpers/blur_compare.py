"""Motion blur against Cycles in absolute light over a transparent film: the blurred render's mean luminance and
coverage (mean alpha), and how a smear spreads the coverage thinner, which a sharp render misses."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba


def mean_alpha_squared(rgba) -> float:
    alpha = rgba[..., 3].astype(np.float64)
    return float((alpha * alpha).mean())


def spread(rgba) -> float:
    """Mean of alpha² over mean alpha: how concentrated the coverage is (a smear spreads it thinner)."""
    return mean_alpha_squared(rgba) / float(rgba[..., 3].astype(np.float64).mean())


@dataclass
class BlurRatios:
    """Prism / Cycles, both blurred: mean ``light`` (luminance), ``coverage`` (alpha), ``squared`` (alpha²) and
    ``spread``; and Prism rendered sharp (Render ▸ Motion Blur off) / Cycles blurred: ``sharp_squared``,
    ``sharp_spread``."""

    light: float
    coverage: float
    squared: float
    spread: float
    sharp_squared: float
    sharp_spread: float


def blur_ratios(scene, samples: int, label: str) -> BlurRatios:
    """Render ``scene`` (motion blur on, a transparent film) with Cycles and Prism, then with Prism sharp, and print
    the ratios as ``MEASURED label``."""
    cycles = render_cycles_rgba(scene, samples)
    prism = render_prism_rgba(scene, samples)
    scene.render.use_motion_blur = False
    sharp = render_prism_rgba(scene, samples)
    scene.render.use_motion_blur = True
    ratios = BlurRatios(float(luminance(prism).mean() / luminance(cycles).mean()),
                        float(prism[..., 3].mean() / cycles[..., 3].mean()),
                        mean_alpha_squared(prism) / mean_alpha_squared(cycles), spread(prism) / spread(cycles),
                        mean_alpha_squared(sharp) / mean_alpha_squared(cycles), spread(sharp) / spread(cycles))
    print(f"MEASURED {label}: Prism / Cycles luminance {ratios.light:.4f}, coverage {ratios.coverage:.4f}, mean "
          f"alpha² {ratios.squared:.4f}, spread {ratios.spread:.4f}; rendered sharp: mean alpha² "
          f"{ratios.sharp_squared:.4f}, spread {ratios.sharp_spread:.4f}")
    return ratios
