"""Object ▸ Shading ▸ Shadow Terminator: the Geometry Offset that Cycles gives light sampling's shadow rays on
smooth-shaded triangles (``tracer.terminator``), and a warning for the Shading Offset, which Prism does not model."""

from __future__ import annotations

import math

#: Where the Shading Offset warning says how much darker Cycles shades: light arriving this far from the normal.
_SHOWN_ANGLE = math.radians(60.0)


def geometry_offset(obj, warnings: list[str] | None) -> float:
    """The Geometry Offset of ``obj`` (Cycles' default 0.1 where the property is missing); appends to ``warnings``
    what its Shading Offset changes in Cycles when it is set."""
    shading = float(getattr(obj, "shadow_terminator_shading_offset", 0.0))
    if shading > 0.0 and warnings is not None:
        warnings.append(shading_offset_warning(obj.name, shading))
    return max(float(getattr(obj, "shadow_terminator_geometry_offset", 0.1)), 0.0)


def shading_offset_factor(shading: float, angle: float) -> float:
    """What Cycles multiplies light arriving at ``angle`` (radians) from the normal by, at Shading Offset
    ``shading`` (``closure/bsdf.h``, ``shift_cos_in``: the cosine of the angle stretched by 1 / (1 - shading / 2),
    over the cosine; a factor of 1 / (1 - shading / 2) is ``kernel/types.h``'s ``shadow_terminator_shading_offset``)."""
    stretch = 1.0 / (1.0 - 0.5 * min(shading, 1.0))
    return max(math.cos(angle * stretch), 0.0) / math.cos(angle)


def shading_offset_warning(name: str, shading: float) -> str:
    darker = 1.0 - shading_offset_factor(shading, _SHOWN_ANGLE)
    black_from = 90.0 * (1.0 - 0.5 * min(shading, 1.0))
    return (f"Object '{name}': Shadow Terminator ▸ Shading Offset {shading:g} is not modelled: Prism renders it as 0. "
            f"Cycles shades light arriving at 60° from the surface's normal {100.0 * darker:.0f} % darker with it, "
            f"and light from beyond {black_from:.0f}° not at all.")
