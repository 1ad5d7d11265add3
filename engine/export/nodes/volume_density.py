"""A volume's Density driven by nodes (a Noise Texture, a gradient over Generated coordinates): compiled into
the material's program, so that the render bakes it onto a voxel grid over the mesh (``tracer.media.
baked_density``) and renders the medium as a grid medium, as Cycles evaluates the shader at each step inside.

A baked value is a value per point: it may read where the point is (Position, Generated and Object
coordinates, Object Info), the Attribute node (a Volume object's grid of that name, sampled at the voxel, as
Cycles reads it there; inside a mesh Cycles has no voxels and reads 0, as the bake's points do) and anything
computed from that. Inside a volume Cycles has no surface, UV map or normal there, and the ray's direction
changes per sample; a Density that reads those (a UV map, Normal, Incoming, Fresnel, Light Path, ...) cannot
be one grid, so it is rendered at the socket's own value, as before, and the warning names why.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ...tracer.materials import opcodes as op
from .graph import follow
from .inputs import COLOR_ATTRIBUTE_NODE, needs_objects
from .terms import FLOAT

#: What a program can read only on a surface or along a ray (Cycles' names in the warning).
_NOT_AT_A_POINT = {op.UV: "UV", op.NORMAL: "Normal",
                   op.TRUE_NORMAL: "True Normal", op.INCOMING: "Incoming", op.BACKFACING: "Backfacing",
                   op.TANGENT: "Tangent", op.PARAMETRIC: "Parametric", op.POINT_INFO: "Point Info",
                   op.HAIR_INFO: "Hair Info", op.LIGHT_PATH: "Light Path", op.AMBIENT_OCCLUSION: "Ambient Occlusion",
                   op.BEVEL: "Bevel", op.FRESNEL: "Fresnel", op.LAYER_WEIGHT: "Layer Weight",
                   op.NORMAL_MAP: "Normal Map", op.BUMP: "Bump", op.VALID_REFLECTION: "Bump"}


@dataclass
class DensityField:
    """The varying Density a volume's nodes share: ``value`` (the program's ``Value``) and the nodes reading it
    (``varying``), the nodes whose Density stays constant (``constant``), the attributes ``value`` reads
    ({name: colour slot}: a Volume object's grids)."""

    value: object = None
    varying: list = field(default_factory=list)
    constant: list = field(default_factory=list)
    attributes: dict = field(default_factory=dict)


@dataclass
class VolumeFields:
    """What a volume's nodes compute per point: its ``density`` and its Emission Strength (``emission``)."""

    density: DensityField = field(default_factory=DensityField)
    emission: DensityField = field(default_factory=DensityField)


def _rows(c, value):
    return c.builder.instructions(live=set(range(value.register, value.register + value.width)))


def _surface_reads(c, value) -> list[str]:
    """Names of what ``value``'s instructions read that exists only on a surface or along a ray."""
    return sorted({_NOT_AT_A_POINT[int(code)] for code in _rows(c, value)[:, op.OP] if int(code) in _NOT_AT_A_POINT})


def _attributes(c, value) -> dict:
    """{attribute name: colour slot} of the Attribute nodes ``value`` reads (not Color Attribute nodes)."""
    rows = _rows(c, value)
    read = (rows[:, op.OP] == op.COLOR_ATTRIBUTE) & (rows[:, op.MODE] != COLOR_ATTRIBUTE_NODE)
    slots = sorted({int(a) for a in rows[read, op.A]})
    names = c.slots.attribute_names if c.slots else []  # no slots: compiled alone, not for a render
    return {names[slot]: slot for slot in slots if slot < len(names)}


def _constant(node, value, found):
    if value > 0.0:
        found.constant.append(node)
    return value


def varying_input(c, node, context, weight, found: DensityField, name="Density") -> float:
    """The node's input ``name`` (its Density, or a Principled Volume's Emission Strength) times ``weight`` as a
    constant (clamped at 0, as Cycles clamps it), or ``weight`` where it varies per point (the medium's
    coefficients, or its emission, then scale by ``found.value``, baked)."""
    socket = c.socket(node, name)
    source, value_socket = follow(socket, context)
    own = c.known(c.default_value(value_socket, FLOAT))
    if source is None:
        return _constant(node, weight * max(own, 0.0), found)
    value = c.value(node, name, context, FLOAT)
    known = c.known(value)
    if known is not None:
        return _constant(node, weight * max(known, 0.0), found)
    a = "an" if name[0] in "AEIOU" else "a"
    if not c.bakes_volume_density:
        c.warn(node, f"has its {name} driven by nodes that vary; Prism bakes such {a} {name.lower()} inside meshes "
                     f"only (fog fills all space), so it uses the {name} set on the socket, {own:g}, throughout the "
                     "volume.")
        return _constant(node, weight * max(own, 0.0), found)
    reads = _surface_reads(c, value)
    if reads:
        c.warn(node, f"has its {name} driven by nodes that read {', '.join(reads)}, which a point inside a volume "
                     f"does not have (no surface there, and the ray's direction changes); Prism uses the {name} set "
                     f"on the socket, {own:g}, throughout the volume.")
        return _constant(node, weight * max(own, 0.0), found)
    if found.value is None:
        found.value = value
        found.attributes = _attributes(c, value)
        needs_objects(c)  # Generated, Object coordinates and Object Info read the instance's row
    elif value.register != found.value.register:
        c.warn(node, f"has {a} {name} driven by other nodes than '{found.varying[0].name}''s; Prism bakes one "
                     f"{name.lower()} per volume and scales this node by '{found.varying[0].name}''s {name}.")
    found.varying.append(node)
    return weight


def finish_field(c, spec, found: DensityField) -> None:
    """Mark ``spec`` (``MediumSpec``) as baked from ``found`` (when some Density varies) and warn what a single
    field changes: nodes of constant Density beside it scale with it too."""
    if found.value is None:
        return
    spec.density_varies = True
    spec.density_attributes = dict(found.attributes)
    c.volume_density = found.value
    _step_rate(c, spec)
    if getattr(getattr(c.material, "cycles", None), "homogeneous_volume", False):
        c.warn(c.output_node, "has Settings ▸ Volume ▸ Homogeneous on, so Cycles reads its varying Density at one "
                              "point of each ray's path through the volume; Prism renders the Density varying "
                              "through the volume.")
    for node in found.constant:
        c.warn(node, f"has a constant Density beside '{found.varying[0].name}''s varying one; Prism bakes one density "
                     f"per volume and scales this node by '{found.varying[0].name}''s Density too.")


def finish_emission(c, spec, found: DensityField) -> None:
    """Mark ``spec`` as emitting per unit of the Emission Strength ``found`` holds (when some varies): its
    ``emission_field`` terms were added by the nodes; constant strengths beside it stay constant terms."""
    if found.value is None:
        return
    spec.emission_attributes = dict(found.attributes)
    c.volume_emission = found.value
    _step_rate(c, spec)


def _step_rate(c, spec) -> None:
    """Material ▸ Settings ▸ Volume ▸ Step Rate, which sets how fine the bake's voxels are."""
    spec.step_rate = float(getattr(getattr(c.material, "cycles", None), "volume_step_rate", 1.0))
    if not spec.step_rate > 0.0:
        spec.step_rate = 1.0
