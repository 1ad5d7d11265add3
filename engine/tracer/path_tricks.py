"""Cycles' Light Paths tricks, as plain settings: Clamp Direct / Clamp Indirect, Filter Glossy and the
Reflective / Refractive caustics toggles (``scene.cycles.sample_clamp_direct``, ``sample_clamp_indirect``,
``blur_glossy``, ``caustics_reflective``, ``caustics_refractive``), with Cycles' meanings:

- **Clamp** (0 = off): each light contribution a sample adds (an emitter or the world hit by a ray, a
  light-sampled shadow ray) is scaled down so that |R| + |G| + |B| of it is at most 3 × the limit.
  Direct: light sampled at the first surface and emission found by the camera ray or the ray leaving
  the first surface; Indirect: everything later (Cycles' ``film_clamp_light``).
- **Caustics toggles** (on = physical): after a diffuse reflection, the glossy reflection closures
  (Reflective off) or the refraction closures (Refractive off) of the surface hit are left out; a glass
  whose reflection and refraction are both off is left out whole (Cycles' ``svm/closure.h``).
- **Filter Glossy** (0 = off): a microfacet lobe reached after unlikely bounces is shaded rougher, by
  Cycles' rule (``stages.filter_glossy``).

Prism's default is none of them: each biases the image, and Prism's images are meant to converge to the
physical answer unless a scene asks otherwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import PrismInputError


@dataclass
class LightPathTricks:
    clamp_direct: float = 0.0  # Cycles' sample_clamp_direct (0: off)
    clamp_indirect: float = 0.0  # Cycles' sample_clamp_indirect (0: off)
    caustics_reflective: bool = True
    caustics_refractive: bool = True
    filter_glossy: float = 0.0  # Cycles' blur_glossy (0: off)

    def validate(self) -> None:
        for name, value in (("Clamp Direct", self.clamp_direct), ("Clamp Indirect", self.clamp_indirect),
                            ("Filter Glossy", self.filter_glossy)):
            if not (value >= 0.0 and math.isfinite(value)):
                raise PrismInputError(f"Light Paths ▸ {name} {value} is not a finite value ≥ 0: set 0 (off) or "
                                      "a positive limit.")

    @property
    def clamping(self) -> bool:
        return self.clamp_direct > 0.0 or self.clamp_indirect > 0.0

    @property
    def caustics_filtered(self) -> bool:
        return not (self.caustics_reflective and self.caustics_refractive)

    @property
    def biased(self) -> bool:
        """Some trick changes which light is counted (light tracing then stays off: its caustics would
        escape the clamps, toggles and blur)."""
        return self.clamping or self.caustics_filtered or self.filter_glossy > 0.0

    def kernel_limits(self) -> tuple[float, float]:
        """(direct, indirect) limits on |R| + |G| + |B| of a contribution: 3 × Cycles' value, inf when off."""
        return tuple(3.0 * value if value > 0.0 else math.inf for value in (self.clamp_direct, self.clamp_indirect))
