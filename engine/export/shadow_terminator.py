"""Object ▸ Shading ▸ Shadow Terminator, as Cycles renders it (``tracer.terminator``): the Geometry Offset lifts light
sampling's shadow rays on smooth-shaded triangles, the Shading Offset softens the light a closure receives toward
its normal's horizon. Prism applies both to meshes; a Shading Offset on hair or a point cloud is warned."""

from __future__ import annotations

import math

#: Where the Shading Offset warning says how much darker Cycles shades: light arriving this far from the normal.
_SHOWN_ANGLE = math.radians(60.0)


def shading_multiplier(shading: float) -> float:
    """Cycles' frequency multiplier of a Shading Offset (``scene/object.cpp``: 1 / (1 - offset / 2)), 0 for none."""
    return 1.0 / (1.0 - 0.5 * min(shading, 1.0)) if shading > 0.0 else 0.0


def terminator_offsets(obj, kind: str, warnings: list[str] | None) -> tuple[float, float]:
    """(Geometry Offset, shading multiplier) of ``obj``, a piece of ``kind`` (Cycles' defaults where the
    properties are missing: 0.1, 0); appends to ``warnings`` a Shading Offset Prism does not apply (not a mesh)."""
    shading = max(float(getattr(obj, "shadow_terminator_shading_offset", 0.0)), 0.0)
    if shading > 0.0 and kind != "MESH" and warnings is not None:
        warnings.append(shading_offset_warning(obj.name, shading))
    return max(float(getattr(obj, "shadow_terminator_geometry_offset", 0.1)), 0.0), shading_multiplier(shading)


def shading_offset_factor(shading: float, angle: float) -> float:
    """What Cycles multiplies light arriving at ``angle`` (radians) from the normal by, at Shading Offset
    ``shading`` (``closure/bsdf.h``, ``shift_cos_in``: the cosine of the angle stretched by the multiplier, over the
    cosine)."""
    return max(math.cos(angle * shading_multiplier(shading)), 0.0) / math.cos(angle)


def shading_offset_warning(name: str, shading: float) -> str:
    darker = 1.0 - shading_offset_factor(shading, _SHOWN_ANGLE)
    black_from = 90.0 / shading_multiplier(shading)
    return (f"Object '{name}': Shadow Terminator ▸ Shading Offset {shading:g} is applied to meshes only: Prism renders "
            f"it as 0 on this hair or point cloud. Cycles shades light arriving at 60° from the surface's normal "
            f"{100.0 * darker:.0f} % darker with it, and light from beyond {black_from:.0f}° not at all.")
