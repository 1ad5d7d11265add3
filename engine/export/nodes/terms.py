"""What the node compiler and its handlers hand each other: value kinds, closure weights, closures
waiting to be finished and emission terms.

Its own module so the handlers (``shaders``, ``inputs``, ``converters``, ``textures``, ``vectors``) need
not import the compiler that calls them: the compiler imports ``registry``, which imports the handlers,
which import only this.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...tracer.materials.program_builder import Value

FLOAT, VECTOR, COLOR = "float", "vector", "color"
SOCKET_KINDS = {"VALUE": FLOAT, "INT": FLOAT, "BOOLEAN": FLOAT, "VECTOR": VECTOR, "RGBA": COLOR, "ROTATION": VECTOR}


@dataclass
class Weight:
    """A closure weight: ``scale`` (scalar) × ``colour`` (RGB), under a constant Principled specular layer
    when ``layer`` is set ((index, roughness, largest f0, multiscatter): see ``ClosureSpec.layer``)."""

    scale: Value
    colour: Value
    layer: tuple | None = None


@dataclass
class PendingClosure:
    kind: int
    weight: Weight
    node: object
    s0: Value | None = None
    s1: Value | None = None
    alpha: Value | None = None
    eta: Value | None = None
    fresnel: int = 0
    glass: object = None
    coat_nm: float = 0.0
    coat_ior: float = 1.0
    normal: Value | None = None
    measured: object = None  # a scene.ReflectanceSpec replacing the colour part of the tint (diffuse) or s0
    multiscatter: bool = False  # Blender's Multiscatter GGX: energy-compensated (``bsdf.multiscatter``)
    multiscatter_colour: Value | None = None  # the lobe's Fss where its Fresnel model does not set it
    subsurface: tuple | None = None  # (largest radius m, anisotropy, SSS_* method): a SUBSURFACE closure's walk
    # a fibre's (sigma mode, model, {C_HAIR_* column: (HairInputs field, Value)}, Random from the strand, the
    # Hair BSDF's linked Tangent Value or None) (``hair``)
    hair: tuple | None = None


@dataclass
class EmissionTerm:
    scale: Value
    colour: Value | None = None
    spectrum: object = None  # a scene.SpectrumSpec (Blackbody feeding an emission)
