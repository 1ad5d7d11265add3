"""A fibre's closure at a hit, as Cycles sets Principled Hair up (``svm/closure.h`` and
``bsdf_hair_chiang_setup``): roughnesses randomised per strand and mapped to the model's variances, the
absorption coefficient per wavelength from the chosen parametrization, and the fibre's frame from the curve's
tangent and the view.

Absorption (per fibre diameter) at each of the path's wavelengths, into ``spectral[c, 0]``:

- Direct Coloring: the colour upsampled as a reflectance (``spectral[c, 0]`` as resolved), then per wavelength
  Cycles' ``sigma_from_reflectance`` with the radial roughness: the colour's spectrum sets the absorption's.
- Absorption Coefficient: the coefficient upsampled as an unbounded spectrum (``C_S1``, Prism's upsampling of
  colours above 1: scale · reflectance(rgb / scale), ``spectra.rgb_lut``), times its scale.
- Melanin Concentration: Cycles' remapping (Random Color, -ln(1 - melanin), Bitterli's split by redness) into
  eumelanin and pheomelanin concentrations, their spectral absorption (``spectra.melanin``), plus the Tint's
  absorption as for Direct Coloring.

h, where the view met the fibre (-1..1), is Cycles' dot(Ng × X, Z) in the frame X = tangent, Y = X × view,
Z = X × Y (for a round curve it is the hit's offset across the fibre seen from the view; on a triangle, as in
Cycles, the same formula with the triangle's tangent ``geometry.hit_tangent``).
"""

from __future__ import annotations

import math

from ..bsdf.closure import (C_HAIR_COAT, C_HAIR_H, C_HAIR_M0, C_HAIR_MELANIN, C_HAIR_MODEL, C_HAIR_OFFSET,
                            C_HAIR_RADIAL, C_HAIR_RANDOM, C_HAIR_RANDOM_COLOUR, C_HAIR_RANDOM_ROUGHNESS, C_HAIR_REDNESS,
                            C_HAIR_ROUGHNESS, C_HAIR_S, C_HAIR_SIGMA_MODE, C_HAIR_SIGMA_SCALE, C_HAIR_STRAND_RANDOM,
                            C_HAIR_TANGENT, C_HAIR_TX, C_HAIR_TY, C_HAIR_TZ, C_HAIR_V, C_KIND, HAIR, SIGMA_ABSORPTION, SIGMA_MELANIN)
from ..bsdf.hair_chiang import azimuthal_scale, clamp_roughness, longitudinal_variance, sigma_from_reflectance
from ..geometry import hit_tangent, on_curve
from ..jit import inlined, kernel
from ..spectra.melanin import melanin_absorption
from ..vec3 import cross, dot, tangents

MELANIN_FLOOR = 1e-4  # Cycles floors 1 - melanin here before the logarithm


@kernel
def hair_parameters(row, spectral, wavelength_nm):
    """Cycles' lobe parameters into ``row`` and the absorption per wavelength into ``spectral[0]`` (its colour,
    as resolved, is read first)."""
    random = row[C_HAIR_RANDOM]
    factor = 1.0 + 2.0 * (random - 0.5) * row[C_HAIR_RANDOM_ROUGHNESS]
    roughness = row[C_HAIR_ROUGHNESS] * factor
    radial = row[C_HAIR_RADIAL] * factor
    v = clamp_roughness(roughness)
    coat = min(max(row[C_HAIR_COAT], 0.0), 1.0)
    row[C_HAIR_M0] = longitudinal_variance(clamp_roughness((1.0 - coat) * v))
    row[C_HAIR_V] = longitudinal_variance(v)
    row[C_HAIR_S] = azimuthal_scale(clamp_roughness(radial))
    mode = int(row[C_HAIR_SIGMA_MODE])
    sigma = spectral[0]
    if mode == SIGMA_ABSORPTION:
        scale = row[C_HAIR_SIGMA_SCALE]
        for k in range(sigma.shape[0]):
            sigma[k] = max(spectral[1, k], 0.0) * scale
        return
    for k in range(sigma.shape[0]):
        sigma[k] = sigma_from_reflectance(sigma[k], radial)
    if mode == SIGMA_MELANIN:
        melanin = row[C_HAIR_MELANIN] * (1.0 + 2.0 * (random - 0.5) * min(max(row[C_HAIR_RANDOM_COLOUR], 0.0), 1.0))
        melanin = -math.log(max(1.0 - melanin, MELANIN_FLOOR))
        redness = row[C_HAIR_REDNESS]
        for k in range(sigma.shape[0]):
            sigma[k] += melanin_absorption(melanin * (1.0 - redness), melanin * redness, wavelength_nm[k])


@kernel
def fibre_offset(tangent, ng, wo):
    """Cycles' h = dot(Ng × X, Z) with X = ``tangent``, Y = X × ``wo``, Z = X × Y (all unit; world)."""
    y = cross(tangent, wo)
    size = math.sqrt(dot(y, y))
    if not size > 1e-12:
        y = tangents(tangent)[0]
    else:
        y = (y[0] / size, y[1] / size, y[2] / size)
    z = cross(tangent, y)
    return min(max(dot(cross(ng, tangent), z), -1.0), 1.0)


@inlined
def _unit_or(regs, r, fallback):
    """The vector in registers ``r .. r + 2`` made unit; ``fallback`` where it has no length (Cycles' normalize
    would give NaN there)."""
    x, y, z = regs[r], regs[r + 1], regs[r + 2]
    length = math.sqrt(x * x + y * y + z * z)
    if not length > 1e-12:
        return fallback
    return (x / length, y / length, z / length)


@inlined
def set_up_hair(rows, spectral, count, geometry, triangle, u, ng, wo, wavelength_nm, regs, time):
    """Every ``HAIR`` closure among ``count`` at the hit (``triangle``, ``u``; ``ng`` facing the view ``wo``, world):
    parameters, absorption, h, and the unit tangent (world; turned into the shading frame by
    ``closure_normals.orient_closures``). As Cycles' ``svm/closure.h``, the Hair BSDF's lobes take the linked
    Tangent (``C_HAIR_TANGENT``, a register of ``regs``) where there is one, else off curves d position / d v and
    no Offset."""
    curve = on_curve(geometry, triangle)
    tangent = hit_tangent(geometry, triangle, u, ng, False, time)
    segment = triangle - geometry.triangles.shape[0] - geometry.spheres.shape[0]
    has_info = curve and segment < geometry.curve_info.shape[0]
    strand_random = float(geometry.curve_info[segment, 3]) if has_info else 0.0
    for c in range(count):
        if int(rows[c, C_KIND]) != HAIR:
            continue
        t = tangent
        if int(rows[c, C_HAIR_MODEL]) == 0:
            if curve and rows[c, C_HAIR_STRAND_RANDOM] > 0.0:  # Cycles: the curve's random attribute
                rows[c, C_HAIR_RANDOM] = strand_random
            hair_parameters(rows[c], spectral[c], wavelength_nm)
            rows[c, C_HAIR_H] = fibre_offset(t, ng, wo)
        elif rows[c, C_HAIR_TANGENT] >= 0.0:
            t = _unit_or(regs, int(rows[c, C_HAIR_TANGENT]), tangent)
        elif not curve:
            t = hit_tangent(geometry, triangle, u, ng, True, time)
            rows[c, C_HAIR_OFFSET] = 0.0
        rows[c, C_HAIR_TX], rows[c, C_HAIR_TY], rows[c, C_HAIR_TZ] = t
