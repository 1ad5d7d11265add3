"""Where a light path starts: one light chosen ∝ power, a point on it and a direction toward the
specular objects (``caustic_targets``), dispatched on the light's kind.

The path's weight is what the light sends through that (point, direction) divided by the density of
drawing it: L cos / (p_select p_area p_direction) for surfaces, I / (p_select p_direction) for points,
E / (p_select p_beam) for a delta sun and L / (p_select p_direction p_beam) for a sun disc — flux, so
that its expected sum over the paths is the light's power toward the targets. The world's background
sends no light paths: the light is chosen among the others (∝ power), and the world's caustics stay with
path tracing, which never skips escapes.
"""

from __future__ import annotations

from ..geometry import offset_origin
from ..jit import inlined
from ..materials.emitters import emission_at
from ..materials.table import MAT_EMISSION_VARIES
from ..spectra.table import spectrum_value
from . import area, mesh, point, sun
from .caustic_targets import sample_beam, sample_direction
from .dispatch import pick_light
from .row import ENVIRONMENT, L_KIND, L_SPECTRUM, MESH, POINT, SPHERE, SUN, SUN_DISK


@inlined
def sample_emission(lights, materials, spectra, geometry, targets, u_select, u_position, u_target, u_direction,
                    wavelength_nm, beta, rows, regs, time):
    """(origin, unit direction, light index) of a new light path at ray time ``time`` (emitting triangles where
    they stand then); ``beta[k]`` = its weight at
    ``wavelength_nm[k]`` (0 when the light sends nothing that way). ``u_position`` and ``u_direction``
    are pairs of uniforms; ``rows`` and ``regs`` are scratch memory for emissive materials whose emission
    varies over the surface (their program runs where the path starts)."""
    others = 1.0  # the share of the lights that send light paths: all but the world (the last row)
    if lights.environment_index >= 0:
        others = lights.select_cdf[lights.environment_index - 1] if lights.environment_index > 0 else 0.0
    index, u_rest = pick_light(lights, u_select * others)
    row = lights.rows[index]
    kind = int(row[L_KIND])
    select = lights.select_prob[index] / others if others > 0.0 else 1.0
    if kind == ENVIRONMENT:
        origin, direction, scale, sid = (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.0, 0
    elif kind == SUN or kind == SUN_DISK:
        direction, pdf_direction, factor = sun.sample_emission_direction(row, u_direction[0], u_direction[1])
        origin, pdf_beam = sample_beam(targets, direction, u_target, u_position[0], u_position[1])
        scale = factor / (select * pdf_direction * pdf_beam) if pdf_beam > 0.0 else 0.0
        sid = int(row[L_SPECTRUM])
    elif kind == MESH:
        p, ng, pdf_area, material, e, b1, b2 = mesh.sample_position(lights.mesh, geometry, u_rest, u_position[0],
                                                                   u_position[1], time)
        direction, pdf_direction = sample_direction(targets, p, u_target, u_direction[0], u_direction[1])
        cos_l = abs(direction[0] * ng[0] + direction[1] * ng[1] + direction[2] * ng[2])
        origin = offset_origin(p, ng, direction)
        if not pdf_area > 0.0:  # a triangle degenerate at this time sends nothing
            pdf_direction = 0.0
        if materials.flags[material] & MAT_EMISSION_VARIES:
            scale = cos_l / (select * pdf_area * pdf_direction) if pdf_direction > 0.0 else 0.0
            emission_at(materials, spectra, geometry, material, lights.mesh.triangle[e], b1, b2, time, direction,
                        wavelength_nm, rows, regs, beta, None)
            for k in range(beta.shape[0]):
                beta[k] = scale * beta[k] if scale > 0.0 else 0.0
            return origin, direction, index
        strength = materials.emission_strength[material]
        scale = strength * cos_l / (select * pdf_area * pdf_direction) if pdf_direction > 0.0 else 0.0
        sid = materials.emission_spectrum[material]
    elif kind == POINT or kind == SPHERE:
        origin, n, pdf_area = point.sample_position(row, u_position[0], u_position[1])
        direction, pdf_direction = sample_direction(targets, origin, u_target, u_direction[0], u_direction[1])
        factor = point.emitted(row, n, direction)
        scale = factor / (select * pdf_area * pdf_direction) if pdf_direction > 0.0 else 0.0
        sid = int(row[L_SPECTRUM])
    else:
        origin, pdf_area = area.sample_position(row, u_position[0], u_position[1])
        direction, pdf_direction = sample_direction(targets, origin, u_target, u_direction[0], u_direction[1])
        factor = area.emitted(row, direction)
        scale = factor / (select * pdf_area * pdf_direction) if pdf_direction > 0.0 else 0.0
        sid = int(row[L_SPECTRUM])
    for k in range(beta.shape[0]):
        beta[k] = scale * spectrum_value(spectra, sid, wavelength_nm[k]) if scale > 0.0 else 0.0
    return origin, direction, index
