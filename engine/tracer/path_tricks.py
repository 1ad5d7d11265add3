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
- **Max Bounces per kind** (``diffuse_bounces``, ``glossy_bounces``, ``transmission_bounces``,
  ``volume_bounces``; None = no limit of its own): a path that has made more diffuse reflections, glossy
  reflections, transmissions or volume scatterings than its limit scatters no more, as it does past Max
  Bounces (``stages.bounces.bounces_left``; Cycles' ``path_state_next``).

Prism's default is none of them: each biases the image, and Prism's images are meant to converge to the
physical answer unless a scene asks otherwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .errors import PrismInputError

#: The per-kind limits, as Cycles' Light Paths panel names them.
BOUNCE_KINDS = ("Diffuse", "Glossy", "Transmission", "Volume")


@dataclass
class LightPathTricks:
    clamp_direct: float = 0.0  # Cycles' sample_clamp_direct (0: off)
    clamp_indirect: float = 0.0  # Cycles' sample_clamp_indirect (0: off)
    caustics_reflective: bool = True
    caustics_refractive: bool = True
    filter_glossy: float = 0.0  # Cycles' blur_glossy (0: off)
    diffuse_bounces: int | None = None  # Cycles' Max Bounces ▸ Diffuse (None: only Max Bounces limits them)
    glossy_bounces: int | None = None
    transmission_bounces: int | None = None
    volume_bounces: int | None = None

    def validate(self) -> None:
        for name, value in (("Clamp Direct", self.clamp_direct), ("Clamp Indirect", self.clamp_indirect),
                            ("Filter Glossy", self.filter_glossy)):
            if not (value >= 0.0 and math.isfinite(value)):
                raise PrismInputError(f"Light Paths ▸ {name} {value} is not a finite value ≥ 0: set 0 (off) or "
                                      "a positive limit.")
        for name, value in zip(BOUNCE_KINDS, self._kind_limits()):
            if value is not None and value < 0:
                raise PrismInputError(f"Light Paths ▸ Max Bounces ▸ {name} {value} is negative: set 0 or more.")

    def _kind_limits(self):
        return self.diffuse_bounces, self.glossy_bounces, self.transmission_bounces, self.volume_bounces

    def bounce_limits(self, max_bounces: int) -> tuple[int, int, int, int]:
        """(diffuse, glossy, transmission, volume) bounces a path may make: each kind's limit where set, else
        ``max_bounces`` (which no count can pass anyway)."""
        return tuple(int(max_bounces) if value is None else min(int(value), int(max_bounces))
                     for value in self._kind_limits())

    def limits_kinds(self, max_bounces: int) -> bool:
        """Some kind's limit is below Max Bounces, so paths must count their bounces by kind."""
        return min(self.bounce_limits(max_bounces)) < max_bounces

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
