"""Radiance of an emissive material whose emission varies over the surface (a texture or node math
feeding an Emission), at a point given by triangle and barycentrics: what a ray finds when it hits such
a surface and what light sampling finds at a point it picked on it."""

from __future__ import annotations

from ..geometry import surface_at
from ..jit import inlined
from .surface import surface_emission


@inlined
def emission_at(materials, spectra, geometry, material, triangle, u, v, time, wo, wavelength_nm, rows, regs, out, rays):
    """``out[k]`` = radiance leaving barycentrics (u, v) of ``triangle`` at ray time ``time`` (``geometry.
    FRAME_TIME`` for a point the light table picked) towards ``wo`` (unit, pointing away). ``rays``: a
    ``shader_rays.ShaderRays`` where a ray found the point (its program may trace), else None."""
    p, ng, ns = surface_at(geometry, triangle, u, v, time)
    backfacing = wo[0] * ng[0] + wo[1] * ng[1] + wo[2] * ng[2] < 0.0
    if backfacing:
        ng = (-ng[0], -ng[1], -ng[2])
        ns = (-ns[0], -ns[1], -ns[2])
    surface_emission(materials, spectra, geometry, material, triangle, u, v, p, ng, ns, wo, backfacing,
                     wavelength_nm, rows, regs, out, rays)
