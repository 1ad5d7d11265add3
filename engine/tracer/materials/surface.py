"""A material evaluated at a surface point: closures for shading, emitted radiance, and transparency
for shadow rays.

Materials with a program (``MAT_PROGRAM``) start each hit from their constant register file, run their
instructions (``program.run_program``) and then resolve their closures; the others are resolved from
their constant rows (``resolve.resolve_material``). Closures under a constant layer (``MAT_LAYERED``) are
then scaled by what the layer lets through from the view direction (``layering.under_layer``), and closures
whose distribution is Multiscatter GGX by the energy their single scattering misses (``MAT_MULTISCATTER``,
``energy.compensate_energy``); sheen closures are fitted to the view (``MAT_SHEEN``, ``sheen_setup``), fibres
(``MAT_HAIR``) to the curve's tangent and the view (``hair_setup``). Nothing here allocates: the register file
and closure rows are the caller's scratch memory. Where a ray found the surface its program may trace rays of
its own (Ambient Occlusion, Bevel: ``shader_rays``); transparency for shadow rays, and emission for light
sampling and light paths, are evaluated without them, as Cycles evaluates them.
"""

from __future__ import annotations

import numpy as np

from ..bsdf.closure import C_KIND, C_MIRROR, C_TINT, C_TINT_SCALE, DIELECTRIC, TRANSPARENT
from ..bsdf.closure_frame import view_cosine
from ..jit import inlined
from ..spectra.table import spectrum_value
from .program import run_program
from .energy import compensate_energy
from .resolve import _fill, copy_rows, resolve_material, resolve_spectral, selection_weights
from .layering import under_layer
from .sheen_setup import set_up_sheen
from .hair_setup import set_up_hair
from .shader_rays import ray_time
from .closure_normals import SAME_NORMAL, set_up_normals
from .table import (MAT_BUMP_CORRECTION, MAT_CLOSURE_NORMALS, MAT_HAIR, MAT_LAYERED, MAT_MULTISCATTER, MAT_ONE_SIDED,
                    MAT_OWN_NORMALS, MAT_PROGRAM, MAT_SHEEN)


@inlined
def run_material(materials, geometry, material, triangle, u, v, p, ng, n, wo, backfacing, rows, regs, rays):
    """Run ``material``'s program at a hit from its constant register file (``regs``, ``rows``: scratch)."""
    programs = materials.programs
    first = programs.const_start[material]
    for r in range(programs.const_count[material]):
        regs[r] = programs.constants[first + r]
    # One signature whether the hit comes from Embree (int32, float32) or from the path state (int64,
    # float64): each combination would compile the whole interpreter again.
    run_program(programs.instructions, programs.start[material], programs.count[material], regs, rows,
                programs.tables, materials.textures, geometry, np.int64(triangle), np.float64(u), np.float64(v), p,
                ng, n, wo, backfacing, rays)


@inlined
def _apply_layers(tables, rows, spectral, count, cos_o):
    for c in range(count):
        through = under_layer(tables, rows[c], view_cosine(rows[c], cos_o))
        if through != 1.0:
            for k in range(spectral.shape[2]):
                spectral[c, 2, k] *= through


@inlined
def shade_surface(materials, spectra, geometry, material, triangle, u, v, p, ng, n, wo, backfacing, wavelength_nm,
                  hero, rows, spectral, eta, regs, glass_clamps, rays):
    """Resolve ``material`` at a hit into ``rows`` / ``spectral`` / ``eta``: (closure count, shading normal).
    ``ng`` and ``n`` face ``wo``; the returned normal is the program's (Normal Map, Bump) or ``n``. ``rays``:
    what the program's own rays need (``shader_rays.ShaderRays``), or None where it cannot trace."""
    flags = materials.flags[material]
    sources = regs
    if not flags & MAT_PROGRAM:
        count = resolve_material(materials, spectra, material, wavelength_nm, hero, rows, spectral, eta,
                                 glass_clamps)
        shading = n
        sources = materials.programs.constants
    else:
        count = copy_rows(materials, material, rows)
        run_material(materials, geometry, material, triangle, u, v, p, ng, n, wo, backfacing, rows, regs, rays)
        resolve_spectral(materials, spectra, count, wavelength_nm, hero, rows, spectral, eta, glass_clamps, regs)
        r = materials.programs.normal[material]
        shading = (regs[r], regs[r + 1], regs[r + 2]) if r >= 0 else n
    if flags & MAT_HAIR:
        set_up_hair(rows, spectral, count, geometry, triangle, u, ng, wo, wavelength_nm, regs, ray_time(rays))
    if flags & MAT_CLOSURE_NORMALS and (flags & MAT_OWN_NORMALS or
                                        shading[0] * ng[0] + shading[1] * ng[1] + shading[2] * ng[2] < SAME_NORMAL):
        set_up_normals(rows, count, regs, wo, ng, n, shading, flags & MAT_BUMP_CORRECTION != 0)
    if flags & (MAT_PROGRAM | MAT_LAYERED | MAT_MULTISCATTER | MAT_SHEEN):
        cos_o = wo[0] * shading[0] + wo[1] * shading[1] + wo[2] * shading[2]
        if flags & MAT_MULTISCATTER:
            compensate_energy(materials, spectra, materials.programs.tables.energy, rows, spectral, eta, count, cos_o,
                              backfacing, wavelength_nm, sources)
        if flags & MAT_LAYERED:
            _apply_layers(materials.programs.tables, rows, spectral, count, cos_o)
        if flags & MAT_SHEEN:
            set_up_sheen(materials.programs.tables.sheen, rows, spectral, count, cos_o)
        if count > 1:
            selection_weights(rows, spectral, count, wavelength_nm, cos_o)
    if flags & MAT_ONE_SIDED and backfacing and count > 1:
        for c in range(count):
            kind = int(rows[c, C_KIND])
            if kind != DIELECTRIC and kind != TRANSPARENT:
                rows[c, C_MIRROR] = 1.0
    return count, shading


@inlined
def surface_emission(materials, spectra, geometry, material, triangle, u, v, p, ng, n, wo, backfacing, wavelength_nm,
                     rows, regs, out, rays):
    """``out[k]`` = radiance emitted towards ``wo`` at wavelength ``k`` by a material whose emission varies
    (``MAT_EMISSION_VARIES``): the program's emission colour as an RGB illuminant spectrum, or the constant
    emission spectrum, times the program's factor."""
    run_material(materials, geometry, material, triangle, u, v, p, ng, n, wo, backfacing, rows, regs, rays)
    programs = materials.programs
    r = programs.emission[material]
    s = programs.emission_scale[material]
    scale = regs[s] if s >= 0 else 1.0
    if r >= 0:
        _fill(materials, spectra, -2.0 - r, wavelength_nm, regs, False, out)
        white = materials.white_emission
        for k in range(out.shape[0]):
            out[k] *= scale * spectrum_value(spectra, white, wavelength_nm[k])
    else:
        sid = materials.emission_spectrum[material]
        for k in range(out.shape[0]):
            out[k] = scale * spectrum_value(spectra, sid, wavelength_nm[k])


@inlined
def surface_transparency(materials, spectra, geometry, material, triangle, u, v, p, ng, n, wo, backfacing,
                         wavelength_nm, rows, regs, out, tmp):
    """``out[k]`` = fraction of light passing straight through (the Transparent closures' tints)."""
    count = copy_rows(materials, material, rows)
    if materials.flags[material] & MAT_PROGRAM:
        run_material(materials, geometry, material, triangle, u, v, p, ng, n, wo, backfacing, rows, regs, None)
    for k in range(out.shape[0]):
        out[k] = 0.0
    for c in range(count):
        if int(rows[c, C_KIND]) != TRANSPARENT:
            continue
        _fill(materials, spectra, rows[c, C_TINT], wavelength_nm, regs, False, tmp)
        scale = rows[c, C_TINT_SCALE]
        for k in range(out.shape[0]):
            out[k] += scale * tmp[k]
    for k in range(out.shape[0]):
        out[k] = min(max(out[k], 0.0), 1.0)
