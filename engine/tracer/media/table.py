"""The media of a render as the kernels read them (``MediaArrays``), built with the material table.

Every coefficient is a tabulated spectrum of the render's ``SpectrumTable`` on its 1 nm grid, per metre:
``scattering`` σ_s and ``absorption`` σ_a (spectrum ids [M]); ``emission`` (spectrum id [M], -1: none)
with ``emission_strength`` [M] (radiance per metre per unit strength, as surfaces' Emission Strength);
``anisotropy`` [M] (Henyey-Greenstein g); ``grid`` [M] (-1: homogeneous, else the row of ``grids``, a
``density_grid.GridArrays``, whose density scales σ_s and σ_a: the one flag the kernels branch on). The
emission is the sum of the medium's emission terms (``spec.MediumSpec``) tabulated as one spectrum, of
strength 1; a grid medium's emission varies with the value of its ``emission_grid`` [M] (a row of ``grids``,
-1: none, the same everywhere): ``emission_rows`` [M] spectra from id ``emission`` on, one per
``emission_step`` [M] of the grid's value (``temperature_emission``). ``emission_rate`` [M] (per metre) is
added to an emitting grid medium's majorant so that delta tracking gathers its emission where nothing
scatters (``grid_emission``). ``phase_row`` [M] is the row of ``phase_cdf`` [R, BINS + 1] holding a medium's
tabulated phase function (``tabulated_phase``; -1: Henyey-Greenstein of its ``anisotropy``). ``next_medium``
[R + 1, M, 2]: the row a path in row r (index r + 1, 0: none) travels in after crossing the surface of the
medium of row j < M out of it (0) or into it (1) (``nesting``: media nest, and the World's fog is everywhere).
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import replace

import numpy as np

from ..errors import PrismInputError
from .density_grid import DensityGrid, build_grids, check_grid
from .nesting import combined_spec, transitions
from .phase_functions import phase_table
from .tabulated_phase import BINS
from .temperature_emission import emission_key, emission_rows
from ..spectra.tinted_blackbody import reflectance_on_grid, tinted_blackbody
from ..spectra.wavelengths import VISIBLE_MIN_NM, VISIBLE_NM_GRID

MediaArrays = namedtuple("MediaArrays", "scattering absorption emission emission_strength anisotropy grid grids "
                                         "emission_grid emission_rows emission_step emission_rate phase_row phase_cdf "
                                         "next_medium")

#: Tentative collisions per voxel (of the finest grid's smallest edge) that an emitting grid medium's walk
#: takes at least, to gather its emission as Cycles 4.5 gathers it once per ray-marching step of a voxel.
EMISSION_SAMPLES_PER_VOXEL = 1.0

#: g is kept inside (-1, 1): at |g| = 1 the phase function is a delta and its density infinite.
MAX_ANISOTROPY = 0.999


def coefficient_spectra(spec):
    """(σ_s, σ_a) per metre on the 1 nm grid for a ``MediumSpec``."""
    sigma_s = np.zeros(len(VISIBLE_NM_GRID))
    sigma_a = np.zeros(len(VISIBLE_NM_GRID))
    for density, rgb in spec.scatter:
        # Cycles scales σ_s by the colour as given: a colour above 1 scatters more (its shape is upsampled).
        scale = max(max(float(c) for c in rgb), 1.0)
        sigma_s += max(float(density), 0.0) * scale * reflectance_on_grid(np.asarray(rgb, float) / scale)
    for density, *colours in spec.absorb:
        term = np.full(len(VISIBLE_NM_GRID), max(float(density), 0.0))
        for rgb in colours:
            term *= 1.0 - reflectance_on_grid(rgb)
        sigma_a += term
    return sigma_s, sigma_a


def emission_on_grid(spec):
    """Emitted radiance per metre on the 1 nm grid for a ``MediumSpec`` (zeros if it emits nothing)."""
    from ..spectra.emission_spectrum import RGBEmissionSpectrum

    lam = np.asarray(VISIBLE_NM_GRID, dtype=np.float64)
    total = np.zeros(len(lam))
    for strength, rgb, temperature_k in spec.emission:
        rgb = np.maximum(np.asarray(rgb, dtype=np.float64), 0.0)
        if not (strength > 0.0 and rgb.max() > 0.0):
            continue
        if temperature_k is None:
            scale = float(rgb.max())
            total += strength * scale * np.asarray(RGBEmissionSpectrum(tuple(rgb / scale)).evaluate(lam))
        else:  # the tint filters the blackbody as a reflectance of its colour would
            total += strength * tinted_blackbody(temperature_k, rgb)[0]
    return total


def _check(spec):
    values = [d for d, *_ in spec.scatter + spec.absorb] + [s for s, *_ in spec.emission] + [spec.anisotropy]
    colours = [c for _, *cs in spec.scatter + spec.absorb for c in cs] + [rgb for _, rgb, _ in spec.emission]
    if not all(np.isfinite(values)) or not all(np.all(np.isfinite(c)) for c in colours):
        raise PrismInputError(f"Material '{spec.name}': a volume setting is NaN or infinite; set it again.")
    grid = getattr(spec, "density_grid", None)
    if grid is not None:
        check_grid(grid, spec.name)
    if spec.emitting_grid is not None:
        if grid is None:
            raise ValueError(f"medium '{spec.name}': an emission grid needs a density grid")
        check_grid(spec.emitting_grid, spec.name)


def _emission(spec, spectra, key, made):
    """(first spectrum id or -1, rows, grid value per row) of a medium's emission (``MediaArrays``); ``made``
    remembers the rows of each emitting grid's voxels (temperature or strength) and settings, which the
    instances of one Volume object share, so that they are tabulated once."""
    if spec.emitting_grid is None:
        emitted = emission_on_grid(spec)
        if not emitted.max() > 0.0:
            return -1, 1, 1.0
        return spectra.tabulated(key + ("emission",), float(VISIBLE_MIN_NM), 1.0, emitted), 1, 1.0
    same = (id(spec.emitting_grid.values), tuple(spec.emission), tuple(spec.blackbody), tuple(spec.emission_field))
    if same not in made:  # the grids outlive the build, so no id is reused meanwhile
        made[same] = _grid_rows(spec, spectra)
    return made[same]


def _grid_rows(spec, spectra):
    table, step = emission_rows(spec)
    if not table.max() > 0.0:
        return -1, 1, 1.0
    shared = ("grid emission",) + emission_key(spec)
    ids = [spectra.tabulated(shared + (r,), float(VISIBLE_MIN_NM), 1.0, row) for r, row in enumerate(table)]
    if ids != list(range(ids[0], ids[0] + len(ids))):
        raise AssertionError("a grid medium's emission rows must be consecutive spectra")
    return ids[0], len(ids), step


def _emission_rate(spec) -> float:
    """``EMISSION_SAMPLES_PER_VOXEL`` per the smallest voxel edge (m) of an emitting grid medium's grids."""
    edges = [np.linalg.norm(np.asarray(g.index_to_world, dtype=np.float64)[:3, :3], axis=0).min()
             for g in (spec.density_grid, spec.emitting_grid) if g is not None]
    return EMISSION_SAMPLES_PER_VOXEL / float(min(edges))


def _phase_row(spec, tables) -> int:
    """The ``phase_cdf`` row of ``spec``'s phase lobes (added to ``tables`` once per set of lobes), or -1."""
    if not spec.phase:
        return -1
    key = tuple((float(w), kind, tuple(float(x) for x in parameters)) for w, kind, parameters in spec.phase)
    if key not in tables:
        tables[key] = (len(tables), phase_table(spec.phase))
    return tables[key][0]


def _phase_cdf(tables) -> np.ndarray:
    """float64 [R, BINS + 1] of the rows ``_phase_row`` made (one unused row where there are none)."""
    if not tables:
        return np.zeros((1, BINS + 1))
    return np.stack([cdf for _, cdf in sorted(tables.values(), key=lambda entry: entry[0])])


def _with_baked(spec, fields):
    """``spec`` with its baked fields (``baked_density.BakedFields``, or None: as it is): the density grid,
    the Emission Strength grid (over a density grid of ones where the density is constant)."""
    if fields is None or spec is None:
        return spec
    density, strength = fields
    if density is None and strength is not None and spec.density_grid is None:
        density = DensityGrid(np.ones_like(strength.values), strength.index_to_world, "constant density")
    return replace(spec, density_grid=density if density is not None else spec.density_grid, strength_grid=strength)


def build_media(materials, used, spectra, outside=None, origin=None, baked=None, overlaps=()):
    """(medium index int32 [len(materials)] (-1: none), ``MediaArrays``, the row of ``outside`` or -1, the rows
    of nested media) for the ``scene.Material`` list, whose indices in ``used`` get a medium, and ``outside`` (a
    ``MediumSpec``: the World's Volume, the medium everywhere, inside meshes too; None: vacuum). ``spectra``:
    the render's ``SpectrumTable``; ``origin`` (m) the point the kernels' positions are relative to (grids);
    ``baked``: material index → the ``BakedFields`` its varying density and emission were baked to
    (``baked_density``); ``overlaps``: sets of material indices whose media a path can be inside at once
    (``nesting.overlapping_sets``). The rows of nested media: {frozenset of material indices: row} for the
    empty set (the World's fog or -1), every medium alone and every set of ``overlaps`` (``nesting``)."""
    index = np.full(len(materials), -1, np.int32)
    columns = {name: [] for name in MediaArrays._fields if name not in ("grids", "phase_cdf", "next_medium")}
    grids, made, phase_tables = [], {}, {}  # phase: lobes → (row, CDF)
    specs = {m: _with_baked(getattr(material, "medium", None), (baked or {}).get(m))
             for m, material in enumerate(materials) if m in used}
    specs = {m: spec for m, spec in specs.items() if spec is not None}

    def add_row(spec, key):
        _check(spec)
        _append_row(columns, grids, made, phase_tables, spec, spectra, key)
        return len(columns["scattering"]) - 1

    def copy_row(row):
        for values in columns.values():
            values.append(values[row])
        return len(columns["scattering"]) - 1

    for m, spec in specs.items():
        index[m] = add_row(spec, ("medium", m, spec.name))
    states = {frozenset(): add_row(outside, ("medium", -1, outside.name)) if outside is not None else -1}
    for members in [(m,) for m in specs] + [s for s in overlaps if all(m in specs for m in s)]:
        parts = [specs[m] for m in members] + ([outside] if outside is not None else [])
        gridded = [m for m in members if specs[m].density_grid is not None]
        if len(parts) == 1:
            states[frozenset(members)] = int(index[members[0]])
        elif gridded:  # a grid medium and others: the grid's alone (``nesting``)
            states[frozenset(members)] = copy_row(int(index[gridded[0]]))
        else:
            states[frozenset(members)] = add_row(combined_spec(parts), ("nested medium", members))
    rows = len(columns["scattering"])
    member_of = {m: int(index[m]) for m in specs}
    arrays = MediaArrays(
        **{name: np.array(values or [_EMPTY[name]], _DTYPES.get(name, np.float64)) for name, values in columns.items()},
        grids=build_grids(grids, origin), phase_cdf=_phase_cdf(phase_tables),
        next_medium=transitions(states, member_of, rows))
    return index, arrays, states[frozenset()], states


#: A medium table without media holds one row of these (the kernels' arrays are never empty).
_EMPTY = dict(scattering=0, absorption=0, emission=-1, emission_strength=0.0, anisotropy=0.0, grid=-1, emission_grid=-1,
              emission_rows=1, emission_step=1.0, emission_rate=0.0, phase_row=-1)
_DTYPES = dict(scattering=np.int32, absorption=np.int32, emission=np.int32, grid=np.int32, emission_grid=np.int32,
               emission_rows=np.int32, phase_row=np.int32)


def _append_row(columns, grids, made, phase_tables, spec, spectra, key):
    """Append ``spec``'s row to ``columns`` (lists by ``MediaArrays`` field), its grids to ``grids``."""
    sigma_s, sigma_a = coefficient_spectra(spec)
    columns["scattering"].append(spectra.tabulated(key + ("sigma_s",), float(VISIBLE_MIN_NM), 1.0, sigma_s))
    columns["absorption"].append(spectra.tabulated(key + ("sigma_a",), float(VISIBLE_MIN_NM), 1.0, sigma_a))
    columns["anisotropy"].append(float(np.clip(spec.anisotropy, -MAX_ANISOTROPY, MAX_ANISOTROPY)))
    density_grid = getattr(spec, "density_grid", None)
    columns["grid"].append(len(grids) if density_grid is not None else -1)
    if density_grid is not None:
        grids.append(density_grid)
    columns["emission_grid"].append(len(grids) if spec.emitting_grid is not None else -1)
    if spec.emitting_grid is not None:
        grids.append(spec.emitting_grid)
    first, count, step = _emission(spec, spectra, key, made)
    columns["emission"].append(first)
    columns["emission_strength"].append(1.0 if first >= 0 else 0.0)
    columns["emission_rows"].append(count)
    columns["emission_step"].append(step)
    columns["emission_rate"].append(_emission_rate(spec) if first >= 0 and density_grid is not None else 0.0)
    columns["phase_row"].append(_phase_row(spec, phase_tables))
