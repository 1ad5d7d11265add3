"""A material as its node tree defines it: closures, and the program that computes what varies.

The export layer compiles a Blender node tree into a ``ShaderProgram`` (plain data: no bpy, no Python
callables); ``materials.table`` turns its closures into rows of the material table and its program
into instructions the kernels run per hit (``materials.program``). Tests build programs directly with
``materials.program_builder``.

- ``Colour``: a spectral parameter — a constant linear Rec.709 colour (upsampled once), a colour the
  program computes per hit (register of r; g and b follow), or a spectrum the table builds itself
  (``spectrum``: a ``scene.SpectrumSpec`` for emission, ``("n", metal)`` / ``("k", metal)`` for measured
  conductors).
- ``ClosureSpec``: one closure row. ``kind`` is a ``bsdf.closure`` kind; ``tint`` its weight per
  wavelength; ``s0``/``s1`` its spectral parameters (see ``bsdf.closure``); scalars that vary are bound
  by the program (``bindings``: the table appends ``opcodes.BIND`` instructions); a constant Principled
  specular layer above the closure is ``layer`` (applied per hit without a program); ``multiscatter`` asks for
  Blender's Multiscatter GGX (energy compensation, ``bsdf.multiscatter``). ``selection`` estimates the
  closure's share of the reflected light when nothing varies (one-sample MIS over closures); programs
  recompute it per hit.
- ``TextureImage``: an image's texels (row 0 at the bottom, as Blender stores them): scene-linear RGBA
  float32, or 8-bit levels with the table that decodes them (the image's colour space), with Blender's
  interpolation and extension.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Colour:
    rgb: tuple | None = None
    register: int | None = None
    spectrum: object = None

    @property
    def varies(self) -> bool:
        return self.register is not None


@dataclass
class ClosureSpec:
    kind: int
    tint: Colour | None = None
    s0: Colour | None = None
    s1: Colour | None = None
    alpha: float = 0.0
    fresnel: int = 0
    eta: float = 1.5
    glass: object = None  # a ``spectra.glass`` Glass (dielectrics)
    coat_nm: float = 0.0
    coat_ior: float = 1.0
    film_nm: float = 0.0
    film_ior: float = 1.0
    selection: float = 1.0
    scale: float = 1.0  # a constant factor of the tint
    bindings: list = field(default_factory=list)  # (column, register, multiply): scalars the program sets
    layer: tuple | None = None  # (index, roughness, largest f0[, multiscatter 0/1]) of a constant dielectric layer
    #                             above (C_LAYER_*)
    multiscatter: bool = False  # energy-compensated GGX (Blender's Multiscatter GGX, ``C_MULTISCATTER``)
    multiscatter_colour: Colour | None = None  # its Fss where the Fresnel model does not set it (``C_MS_COLOUR``)
    normal: int = -1  # register of the closure's own shading normal (``C_NORMAL``); -1: the material's
    subsurface: tuple | None = None  # (largest radius m, anisotropy, SSS_* method) of a SUBSURFACE closure (C_SSS_*)
    hair: HairInputs | None = None  # a ``HAIR`` closure's node inputs (``C_HAIR_*``)


@dataclass
class HairInputs:
    """Principled Hair's scalar inputs as the node gives them (``bsdf.closure`` ``C_HAIR_*``); the closure's
    ``s0`` is its colour (Direct Coloring) or tint (Melanin), ``s1`` its absorption coefficient. The Hair BSDF
    (``model`` > 0) reads RoughnessU, RoughnessV and Offset from ``roughness``, ``radial_roughness``, ``offset``."""

    sigma_mode: int = 2  # ``bsdf.closure.SIGMA_*``
    model: int = 0  # ``C_HAIR_MODEL``: 0 Principled Hair (Chiang); ``bsdf.hair_kajiya`` REFLECTION, TRANSMISSION
    roughness: float = 0.3
    radial_roughness: float = 0.3
    coat: float = 0.0
    ior: float = 1.55
    offset: float = 0.0349066  # radians (Blender's default 2 degrees)
    random_roughness: float = 0.0
    random: float = 0.0  # the Random input (its value on the node where unlinked)
    strand_random: bool = True  # Random unlinked: strands take their own random number (Hair Info ▸ Random)
    melanin: float = 0.8
    melanin_redness: float = 1.0
    random_colour: float = 0.0
    tangent: int = -1  # the Hair BSDF's Tangent where it varies: its register (``C_HAIR_TANGENT``)


@dataclass
class TextureImage:
    name: str
    texels: np.ndarray  # [H, W, 4] row 0 at the bottom: float32 scene-linear RGBA, or uint8 levels with ``decode``
    decode: np.ndarray | None = None  # float32 [256, 3]: scene-linear value of each 8-bit level per channel
    interpolation: str = "Linear"  # "Closest", "Linear" ("Cubic" and "Smart" render as Linear)
    extension: str = "REPEAT"  # "REPEAT", "EXTEND", "CLIP", "MIRROR"
    srgb_levels: bool = False  # 8-bit sRGB: levels are filtered, then decoded (Blender's order)

    rows = 1  # rows of the texture table (``textures.image``)


@dataclass
class UdimImage:
    """A UDIM image: its tiles ``(number, TextureImage)``, tile 1001 + u + 10 v covering texture
    coordinates [u, u + 1] × [v, v + 1]."""

    name: str
    tiles: list[tuple[int, TextureImage]]

    @property
    def rows(self) -> int:
        return 1 + len(self.tiles)  # a header, then the tiles


@dataclass
class ShaderProgram:
    """Everything the tracer needs of one node-built material."""

    closures: list[ClosureSpec]
    instructions: np.ndarray = field(default_factory=lambda: np.zeros((0, 10), np.int32))
    constants: np.ndarray = field(default_factory=lambda: np.zeros(0))
    register_count: int = 0
    emission: Colour | None = None  # radiance colour or a ``spectrum`` (a ``scene.SpectrumSpec``)
    emission_strength: float = 0.0  # its strength; an estimate for light selection when the emission varies
    emission_scale: int = -1  # register of a factor that varies (the emission is then colour × that factor)
    normal: int = -1  # register of the shading normal (normal maps, bump), or -1
    # register of the Material Output's Displacement vector where Material ▸ Settings ▸ Displacement is
    # "Displacement Only" or "Both" (the vertices move: ``materials.displacement``), or -1
    displacement: int = -1
    # register of the Volume's Density where nodes make it vary from point to point (``nodes.volume_density``:
    # baked onto a grid at render time, ``media.baked_density``), or -1
    volume_density: int = -1
    # register of a Principled Volume's Emission Strength where nodes make it vary (``nodes.volume_density``,
    # baked like the density: ``MediumSpec.emission_field``), or -1
    volume_emission: int = -1
    # AOV Output sockets fed by links: AOV name → {"Color" / "Value": register} where the value varies per hit,
    # {"Color" / "Value": constant} where it folded to one.
    aov_registers: dict = field(default_factory=dict)
    aov_constants: dict = field(default_factory=dict)
    images: list[TextureImage | UdimImage] = field(default_factory=list)
    # Material ▸ Settings ▸ Bump Map Correction (Cycles' default on): microfacet normals raised where their
    # reflection would leave below the surface, diffuse light softened near a bumped horizon (``closure_normals``)
    bump_map_correction: bool = True
    # the Material Output has a Volume and no Surface: the one Transparent closure is the medium's boundary, which
    # paths cross without a bounce, as Cycles' volume-only shaders (``stages.bounces``)
    surface_missing: bool = False

    @property
    def has_program(self) -> bool:
        return len(self.instructions) > 0
