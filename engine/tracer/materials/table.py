"""``scene.Material`` list → ``MaterialArrays``: closure rows, glass rows, emission, programs, textures, flags.

Every material is a ``ShaderProgram`` (``materials.shader``): its node tree compiled by the export layer,
or one closure for a kind-described material (``legacy``). Each material is ``closure_count``
consecutive rows of ``closures`` (see ``bsdf.closure``) starting at ``closure_start``; an emission
(spectrum id and strength; strength 0 = not emissive); and, when something varies over the surface,
a program (``programs``, run per hit by ``materials.surface``) with the textures it reads. Flags let
the kernels decide without looking at kinds:

- ``MAT_DELTA``: every closure is a delta lobe, so no light sampling at its vertices;
- ``MAT_DISPERSIVE``: a closure refracts at a wavelength-dependent index (paths keep only their hero);
- ``MAT_NULL``: a free-standing film, which shadow rays pass through (attenuated) and which paths cross
  as a null event for MIS;
- ``MAT_ONE_SIDED``: the shading frame is not flipped to face the ray (glass: inside and outside differ);
- ``MAT_EMISSIVE``: the surface emits (and is light-sampled as part of the emissive meshes);
- ``MAT_PROGRAM``: a program runs at each hit (textures, layering, anything that varies);
- ``MAT_TRANSPARENT``: a Transparent closure lets light straight through (cut-outs): shadow rays pass,
  attenuated by it;
- ``MAT_EMISSION_VARIES``: the emission is computed per hit (its strength here is an estimate for light
  selection);
- ``MAT_LAYERED``: a closure lies under a constant dielectric layer (``C_LAYER_*``), whose albedo depends on
  the view direction: its tint and the closures' selection weights are computed per hit.
- ``MAT_MULTISCATTER``: a closure is energy-compensated (Blender's Multiscatter GGX, ``C_MULTISCATTER``), by a
  factor that depends on the view direction: its tint and the closures' selection weights are computed per
  hit (``energy.compensate_energy``).
- ``MAT_MEDIUM``: the closed mesh holds a medium (its volume shader; ``medium`` is its row of ``media``, a
  ``media.table.MediaArrays``): paths crossing the surface inward enter it, outward leave it.
- ``MAT_SHEEN``: a closure is Blender's microfiber sheen, fitted per hit to the view direction
  (``sheen_setup.set_up_sheen``): its tint and the closures' selection weights are computed per hit.
- ``MAT_BOUNDARY``: the material has a Volume and no Surface: its surface is only the medium's boundary, which
  paths cross as no bounce at all (Cycles' ``SD_HAS_ONLY_VOLUME``; ``stages.bounces``);
- ``MAT_HAIR``: a closure is a fibre's (``HAIR``), set up per hit from the curve's tangent and the view
  (``hair_setup``) and turned into the shading frame with the closures' normals (``closure_normals``).
- ``MAT_CLOSURE_NORMALS``: the closures' normals are set up per hit (``closure_normals``): a closure has a
  normal of its own (``MAT_OWN_NORMALS``: ``C_NORMAL``, a Coat Normal, shaders with different Normal inputs), the
  program bends the normal, or Bump Map Correction (``MAT_BUMP_CORRECTION``) may raise a microfacet or
  translucent closure's normal where it is not the geometric one.
- ``MAT_SUBSURFACE``: a closure scatters under the surface (``subsurface``): paths walk inside the object.
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from ..bsdf.closure import (C_HAIR_COAT, C_HAIR_H, C_HAIR_IOR, C_HAIR_M0, C_HAIR_MELANIN, C_HAIR_MODEL, C_HAIR_OFFSET,
                            C_HAIR_RADIAL, C_HAIR_RANDOM, C_HAIR_RANDOM_COLOUR, C_HAIR_RANDOM_ROUGHNESS, C_HAIR_REDNESS,
                            C_HAIR_STRAND_RANDOM, C_HAIR_TANGENT,
                            C_HAIR_ROUGHNESS, C_HAIR_S, C_HAIR_SIGMA_MODE, C_HAIR_SIGMA_SCALE, C_HAIR_TX, C_HAIR_TY,
                            C_HAIR_TZ, C_HAIR_V, C_ALPHA, C_COAT_IOR, C_COAT_NM, C_ETA, C_FILM_IOR, C_FILM_NM,
                            C_FRESNEL, C_GLASS,
                            C_KIND, C_LAYER_ETA, C_LAYER_F0, C_LAYER_MULTISCATTER, C_LAYER_ROUGHNESS, C_MIRROR,
                            C_MS_COLOUR, C_MULTISCATTER, C_NORMAL, C_S1, C_FRAMED, C_BUMPED,
                            C_SPECTRUM, C_SSS_ANISOTROPY, C_SSS_METHOD, C_SSS_RADIUS, C_TINT,
                            C_TINT_SCALE, C_WEIGHT, CLOSURE_ROW,
                            CONDUCTOR, DIELECTRIC, DIFFUSE, HAIR, MAX_CLOSURES, SHEEN, SMOOTH_ALPHA, SUBSURFACE,
                            THIN_FILM, TRANSLUCENT, TRANSPARENT, register_source)
from ..errors import PrismInputError
from ..scene import SpectrumSpec
from ..spectra.dispersion import GLASS_ROW, glass_row
from . import opcodes as op
from .legacy import glass_of, is_emissive, legacy_shader  # noqa: F401  (re-exported)
from .program import ProgramArrays

MAT_DELTA = 1
MAT_DISPERSIVE = 2
MAT_NULL = 4
MAT_ONE_SIDED = 8
MAT_EMISSIVE = 16
MAT_PROGRAM = 32
MAT_TRANSPARENT = 64
MAT_EMISSION_VARIES = 128
MAT_LAYERED = 256
MAT_MULTISCATTER = 512
MAT_SHEEN = 1024
MAT_MEDIUM = 2048
MAT_CLOSURE_NORMALS = 4096
MAT_OWN_NORMALS = 8192
MAT_BUMP_CORRECTION = 16384
MAT_SUBSURFACE = 32768
MAT_HAIR = 65536
MAT_BOUNDARY = 131072

MaterialArrays = namedtuple(
    "MaterialArrays",
    "flags closure_start closure_count emission_spectrum emission_strength closures glasses programs textures lut "
    "white_emission medium media",
)

_FEATURES = {DIFFUSE: "diffuse", TRANSLUCENT: "translucent", TRANSPARENT: "transparent", THIN_FILM: "thin_film",
             SHEEN: "sheen", HAIR: "hair"}


@dataclass
class MaterialTable:
    """Rows for the materials a render uses (unused ones get an empty entry), and what they need."""

    arrays: MaterialArrays
    glasses: list = field(default_factory=list)  # the Glass object of each glass row (names, warnings)
    features: list = field(default_factory=list)  # e.g. "smooth dielectric", for the render stats
    register_count: int = 1  # registers a program needs at most (the scratch size)
    outside_medium: int = -1  # the ``media`` row of the World's Volume (fog outside every mesh medium), or -1
    # {frozenset of material indices: ``media`` row}: the row of each set of media a path can be inside at once
    # (``media.nesting``), the empty set's the World's Volume (or -1)
    nested_rows: dict = field(default_factory=dict)
    # int32 [materials]: each program's register of its displacement vector (``shader.ShaderProgram.
    # displacement``), -1 for a material whose vertices stay (``materials.displacement`` reads it)
    displacement: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int32))
    # int32 [materials]: each program's register of its volume's varying Density (``shader.ShaderProgram.
    # volume_density``), -1 for none (``media.baked_density`` reads it)
    volume_density: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int32))
    volume_emission: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int32))  # the same, Emission Strength


def _source(colour, spectra, name, bounded=True):
    """A spectral source value for ``colour`` (``shader.Colour`` or None) and its scale."""
    if colour is None:
        return -1.0, 1.0
    if colour.register is not None:
        return register_source(colour.register), 1.0
    if colour.spectrum is not None:
        if not isinstance(colour.spectrum, tuple):  # a measured reflectance (scene.ReflectanceSpec)
            return float(spectra.measured_reflectance(colour.spectrum, f"Material '{name}'")), 1.0
        what, metal = colour.spectrum
        from ..spectra.conductors import _lookup

        table_nm, n, k = _lookup(metal)
        return float(spectra.resampled((what, metal), table_nm, n if what == "n" else k)), 1.0
    rgb = np.asarray(colour.rgb, dtype=np.float64)
    if not np.all(np.isfinite(rgb)) or np.any(rgb < 0):
        raise PrismInputError(f"Material '{name}': a colour is negative, NaN or infinite; pick a colour again.")
    scale = 1.0
    largest = float(rgb.max())
    if largest > 1.0:
        if bounded:
            rgb = np.minimum(rgb, 1.0)
        else:
            scale, rgb = largest, rgb / largest
    if largest >= 1.0 and not bounded and np.all(rgb == rgb[0]):
        return -1.0, scale
    return float(spectra.reflectance(tuple(rgb))), scale


def _row(spec, spectra, glasses, glass_index, name):
    row = np.full(CLOSURE_ROW, -1.0)
    row[C_KIND] = spec.kind
    row[C_WEIGHT] = max(float(spec.selection), 0.0)
    row[C_ALPHA] = float(spec.alpha)
    row[C_COAT_NM], row[C_COAT_IOR] = float(spec.coat_nm), float(spec.coat_ior)
    row[C_FILM_NM], row[C_FILM_IOR] = float(spec.film_nm), float(spec.film_ior)
    row[C_FRESNEL] = float(spec.fresnel)
    row[C_ETA] = float(spec.eta)
    row[C_MIRROR] = 0.0
    row[C_NORMAL] = float(spec.normal)
    row[C_FRAMED] = row[C_BUMPED] = 0.0  # set per hit (``closure_normals``)
    layer = spec.layer if spec.layer is not None else (0.0, 0.0, 0.0)
    row[C_LAYER_ETA], row[C_LAYER_ROUGHNESS], row[C_LAYER_F0] = (float(x) for x in layer[:3])
    row[C_LAYER_MULTISCATTER] = float(layer[3]) if len(layer) > 3 else 0.0
    row[C_SPECTRUM], _ = _source(spec.s0, spectra, name)
    row[C_S1], _ = _source(spec.s1, spectra, name)
    row[C_TINT], row[C_TINT_SCALE] = _source(spec.tint, spectra, name, bounded=False)
    row[C_TINT_SCALE] *= float(spec.scale)
    row[C_MULTISCATTER] = 1.0 if spec.multiscatter else 0.0
    row[C_MS_COLOUR], _ = _source(spec.multiscatter_colour, spectra, name)
    if spec.kind == SUBSURFACE:
        row[C_SSS_RADIUS], row[C_SSS_ANISOTROPY], row[C_SSS_METHOD] = (float(x) for x in spec.subsurface)
    if spec.kind == HAIR:
        _hair_columns(row, spec, spectra, name)
    if spec.kind == DIELECTRIC:
        glass = spec.glass
        if glass is None:
            from ..spectra import glass as glass_module

            glass = glass_module.constant_ior(spec.eta)
        key = id(glass)
        if key not in glass_index:
            glass_index[key] = len(glasses)
            glasses.append(glass)
        row[C_GLASS] = glass_index[key]
    return row


def _hair_columns(row, spec, spectra, name):
    """A fibre's node inputs into its ``C_HAIR_*`` columns; the per-hit ones start at 0."""
    from ..materials.shader import HairInputs

    hair = spec.hair if spec.hair is not None else HairInputs()
    row[C_HAIR_SIGMA_MODE], row[C_HAIR_MODEL] = float(hair.sigma_mode), float(hair.model)
    row[C_HAIR_ROUGHNESS], row[C_HAIR_RADIAL] = float(hair.roughness), float(hair.radial_roughness)
    row[C_HAIR_COAT], row[C_HAIR_IOR], row[C_HAIR_OFFSET] = float(hair.coat), float(hair.ior), float(hair.offset)
    row[C_HAIR_RANDOM_ROUGHNESS], row[C_HAIR_RANDOM] = float(hair.random_roughness), float(hair.random)
    row[C_HAIR_MELANIN], row[C_HAIR_REDNESS] = float(hair.melanin), float(hair.melanin_redness)
    row[C_HAIR_RANDOM_COLOUR] = float(hair.random_colour)
    row[C_HAIR_STRAND_RANDOM] = 1.0 if hair.strand_random else 0.0
    row[C_HAIR_TANGENT] = float(hair.tangent)
    row[C_S1], row[C_HAIR_SIGMA_SCALE] = _source(spec.s1, spectra, name, bounded=False)
    for column in (C_HAIR_V, C_HAIR_S, C_HAIR_M0, C_HAIR_H, C_HAIR_TX, C_HAIR_TY, C_HAIR_TZ):
        row[column] = 0.0


def _feature(spec):
    if spec.kind in _FEATURES:
        return _FEATURES[spec.kind]
    smooth = spec.alpha < SMOOTH_ALPHA
    if spec.kind == CONDUCTOR:
        return "mirror conductor" if smooth else "rough conductor"
    return "smooth dielectric" if smooth else "rough dielectric"


def _is_delta(spec):
    if spec.kind in (THIN_FILM, TRANSPARENT):
        return True
    return spec.kind in (CONDUCTOR, DIELECTRIC) and spec.alpha < SMOOTH_ALPHA


def build_materials(materials, used, spectra, outside_medium=None, origin=None, geometry=None,
                    overlaps=()) -> MaterialTable:
    """Tables for ``materials`` (``scene.Material``); only indices in ``used`` get closures.
    ``spectra`` is the render's ``SpectrumTable``; ``outside_medium`` the World's Volume (a ``MediumSpec``) or
    None; ``origin`` (m) the point the kernels' positions are relative to (density grids of media);
    ``geometry`` (a ``geometry.Geometry`` relative to ``origin``) where varying volume densities are baked
    over the meshes that hold them (``media.baked_density``; None: not baked); ``overlaps`` the sets of materials
    whose media a path can be inside at once (``media.nesting.overlapping_sets``)."""
    from ..spectra.rgb_lut import empty_lut, load_lut
    from ..media.table import build_media
    from ..media.voxel_inputs import program_sources
    from ..textures.image import build_textures
    from .layering import load_tables

    count = len(materials)
    flags = np.zeros(count, np.int32)
    start = np.zeros(count, np.int32)
    closure_count = np.zeros(count, np.int32)
    emission_spectrum = np.zeros(count, np.int32)
    emission_strength = np.zeros(count)
    p_start, p_count = np.zeros(count, np.int32), np.zeros(count, np.int32)
    c_start, c_count = np.zeros(count, np.int32), np.zeros(count, np.int32)
    normal, emission_register = np.full(count, -1, np.int32), np.full(count, -1, np.int32)
    emission_scale = np.full(count, -1, np.int32)
    displacement = np.full(count, -1, np.int32)
    volume_density, volume_emission = np.full(count, -1, np.int32), np.full(count, -1, np.int32)
    rows, glasses, glass_index, features = [], [], {}, set()
    instructions, constants, images, image_index = [], [], [], {}
    image_rows = 0
    needs_lut = False
    register_count = 1
    compiled = set(used) | program_sources(materials, used)  # a Volume object's density runs its material's program
    for m, material in enumerate(materials):
        if m not in compiled:
            continue
        shader = material.shader if material.shader is not None else legacy_shader(material)
        closures = shader.closures
        if len(closures) > MAX_CLOSURES:
            raise PrismInputError(
                f"Material '{material.name}' combines {len(closures)} shaders; Prism renders at most {MAX_CLOSURES} "
                "per material: simplify its Mix/Add shaders."
            )
        start[m], closure_count[m] = len(rows), len(closures)
        for spec in closures:
            rows.append(_row(spec, spectra, glasses, glass_index, material.name))
            features.add(_feature(spec))
            if spec.coat_nm > 0 and spec.kind in (CONDUCTOR, DIELECTRIC):
                features.add("thin-film coating")
            if spec.kind == DIELECTRIC:
                flags[m] |= MAT_ONE_SIDED
                if glasses[int(rows[-1][C_GLASS])].is_dispersive:
                    flags[m] |= MAT_DISPERSIVE
            if spec.kind == THIN_FILM:
                flags[m] |= MAT_NULL
            if spec.kind == TRANSPARENT:
                flags[m] |= MAT_TRANSPARENT
            if spec.layer is not None:
                flags[m] |= MAT_LAYERED
            if spec.multiscatter and spec.kind in (CONDUCTOR, DIELECTRIC) and spec.alpha >= SMOOTH_ALPHA:
                flags[m] |= MAT_MULTISCATTER
            if spec.kind == SHEEN:
                flags[m] |= MAT_SHEEN
            if spec.kind == SUBSURFACE:
                flags[m] |= MAT_SUBSURFACE
            if spec.kind == HAIR:
                flags[m] |= MAT_HAIR
            if spec.normal >= 0:
                flags[m] |= MAT_CLOSURE_NORMALS | MAT_OWN_NORMALS
            if shader.bump_map_correction and spec.kind in (CONDUCTOR, DIELECTRIC, TRANSLUCENT, SUBSURFACE):
                flags[m] |= MAT_CLOSURE_NORMALS
            needs_lut = needs_lut or any(c is not None and c.varies
                                         for c in (spec.tint, spec.s0, spec.s1, spec.multiscatter_colour))
        if shader.surface_missing:
            flags[m] |= MAT_BOUNDARY
        if shader.normal >= 0:
            flags[m] |= MAT_CLOSURE_NORMALS
        if shader.bump_map_correction:
            flags[m] |= MAT_BUMP_CORRECTION
        if closures and all(_is_delta(spec) for spec in closures):
            flags[m] |= MAT_DELTA
        binds = [[op.BIND, int(multiply), -1, c, column, register] + [-1] * (op.INSTRUCTION - 6)
                 for c, spec in enumerate(closures) for column, register, multiply in spec.bindings]
        if shader.has_program or binds or shader.displacement >= 0 or max(shader.volume_density,
                                                                           shader.volume_emission) >= 0:
            flags[m] |= MAT_PROGRAM
            features.add("node program")
            program = np.concatenate([np.array(shader.instructions, dtype=np.int32).reshape(-1, op.INSTRUCTION),
                                      np.array(binds, dtype=np.int32).reshape(-1, op.INSTRUCTION)])
            local = []
            for image in shader.images:
                key = id(image)
                if key not in image_index:
                    image_index[key] = image_rows  # the image's first row of the texture table
                    image_rows += image.rows
                    images.append(image)
                local.append(image_index[key])
            for ins in program:
                if ins[op.OP] == op.IMAGE:
                    ins[op.B] = local[ins[op.B]]
            if shader.images:
                features.add("image textures")
            p_start[m], p_count[m] = len(instructions), len(program)
            instructions.extend(program.tolist())
            c_start[m], c_count[m] = len(constants), len(shader.constants)
            constants.extend(np.asarray(shader.constants, dtype=np.float64).tolist())
            register_count = max(register_count, len(shader.constants), shader.register_count)
            normal[m] = shader.normal
            displacement[m] = shader.displacement
            volume_density[m], volume_emission[m] = shader.volume_density, shader.volume_emission
        emission = shader.emission
        if emission is not None and shader.emission_strength > 0:
            varies = emission.register is not None or shader.emission_scale >= 0
            if emission.register is not None:
                emission_register[m] = emission.register
                emission_spectrum[m] = spectra.emission(SpectrumSpec())  # what the wavelength guide follows
                needs_lut = True
            else:
                spec = emission.spectrum if emission.spectrum is not None else SpectrumSpec("rgb", tuple(emission.rgb))
                if spec.kind == "rgb" and not max(spec.rgb) > 0:
                    continue
                try:
                    emission_spectrum[m] = spectra.emission(spec)
                except PrismInputError as error:
                    raise PrismInputError(f"Material '{material.name}': {error}") from None
            flags[m] |= MAT_EMISSIVE
            emission_strength[m] = float(shader.emission_strength)
            if varies:
                if not flags[m] & MAT_PROGRAM:
                    raise PrismInputError(f"Material '{material.name}': a varying emission needs a program.")
                flags[m] |= MAT_EMISSION_VARIES
                emission_scale[m] = shader.emission_scale
    closure_rows = np.array(rows, dtype=np.float64).reshape(-1, CLOSURE_ROW)
    glass_rows = np.array([glass_row(g) for g in glasses] or [glass_row(None)]).reshape(-1, GLASS_ROW)
    programs = ProgramArrays(p_start, p_count, c_start, c_count, normal, emission_register, emission_scale,
                             np.array(instructions or [[0] * op.INSTRUCTION], dtype=np.int32).reshape(-1, op.INSTRUCTION),
                             np.array(constants or [0.0], dtype=np.float64), load_tables())
    white = spectra.emission(SpectrumSpec()) if needs_lut else 0
    textures, lut = build_textures(images), load_lut() if needs_lut else empty_lut()
    closures = closure_rows if len(closure_rows) else np.zeros((1, CLOSURE_ROW))

    def arrays_with(medium, media):
        return MaterialArrays(flags, start, closure_count, emission_spectrum, emission_strength, closures, glass_rows,
                              programs, textures, lut, white, medium, media)

    baked = {}
    if geometry is not None and max(volume_density.max(initial=-1), volume_emission.max(initial=-1)) >= 0:
        from ..media.baked_density import bake_fields

        no_media = build_media([], set(), spectra)
        baked = bake_fields(geometry, arrays_with(no_media[0], no_media[1]), volume_density, volume_emission,
                            register_count, materials, origin)
    medium, media, outside, nested = build_media(materials, used, spectra, outside_medium, origin, baked, overlaps)
    if baked:
        features.add("baked volume density or emission")
    flags[medium >= 0] |= MAT_MEDIUM
    gridded = np.zeros(len(materials), bool)
    gridded[medium >= 0] = media.grid[medium[medium >= 0]] >= 0
    if ((medium >= 0) & ~gridded).any():
        features.add("homogeneous media")
    if gridded.any():
        features.add("grid media (delta tracking)")
    if outside >= 0:
        features.add("world fog")
    if any(len(members) > 1 for members in nested):
        features.add("nested media")
    return MaterialTable(arrays_with(medium, media), glasses, sorted(features), register_count, outside, nested,
                         displacement, volume_density, volume_emission)
