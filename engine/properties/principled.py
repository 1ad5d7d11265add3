"""What Prism reads from a material: the Principled BSDF wired to the Material Output.

Plain reading of node sockets (no conversion to tracer materials — the export
layer does that), shared by the material panel and the exporter so the panel
shows exactly what a render uses. Inputs Prism does not model are reported, one
message per socket, instead of being silently dropped.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .node_links import is_linked, upstream_node

PRINCIPLED_IDNAME = "ShaderNodeBsdfPrincipled"

# Sockets Prism reads (present since Blender 4.0; the thin-film ones since 4.2).
READ_SOCKETS = (
    "Base Color",
    "Metallic",
    "Roughness",
    "IOR",
    "Transmission Weight",
    "Emission Color",
    "Emission Strength",
    "Thin Film Thickness",
    "Thin Film IOR",
)

# Sockets Prism ignores, with the value at which ignoring them changes nothing.
NEUTRAL_VALUES = {
    "Alpha": 1.0,
    "Diffuse Roughness": 0.0,
    "Subsurface Weight": 0.0,
    "Specular IOR Level": 0.5,
    "Specular Tint": (1.0, 1.0, 1.0, 1.0),
    "Anisotropic": 0.0,
    "Coat Weight": 0.0,
    "Sheen Weight": 0.0,
}
# Vector inputs whose only meaningful use is a link (bump or tangent maps).
LINK_ONLY_SOCKETS = ("Normal", "Tangent", "Coat Normal")


@dataclass
class PrincipledReading:
    """Values Prism uses for one material (linear Rec.709 colours; thin film in nm)."""

    material_name: str
    node_name: str | None
    base_color: tuple[float, float, float] = (0.8, 0.8, 0.8)
    metallic: float = 0.0
    roughness: float = 0.5
    ior: float = 1.5
    transmission: float = 0.0
    emission_color: tuple[float, float, float] = (1.0, 1.0, 1.0)
    emission_strength: float = 0.0
    thin_film_thickness_nm: float = 0.0
    thin_film_ior: float = 1.33
    ignored: list[str] = field(default_factory=list)


def surface_node(material):
    """The node wired into the active Material Output's Surface, or None."""
    tree = material.node_tree if material.use_nodes else None
    if tree is None:
        return None
    output = tree.get_output_node("ALL")
    if output is None:
        outputs = [n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial"]
        output = outputs[0] if outputs else None
    if output is None:
        return None
    return upstream_node(output.inputs["Surface"])


def _differs(value, neutral) -> bool:
    if isinstance(neutral, tuple):
        return any(abs(a - b) > 1e-6 for a, b in zip(value, neutral))
    return abs(value - neutral) > 1e-6


def read_principled(material) -> PrincipledReading:
    """Read ``material`` as Prism renders it; ``ignored`` lists what the render leaves out."""
    name = material.name
    node = surface_node(material) if material.use_nodes else None
    if node is None or node.bl_idname != PRINCIPLED_IDNAME:
        reading = PrincipledReading(
            material_name=name,
            node_name=None,
            base_color=tuple(material.diffuse_color[:3]),
            metallic=float(material.metallic),
            roughness=float(material.roughness),
        )
        if node is not None:
            reading.ignored.append(
                f"Material '{name}': the '{node.name}' node ({node.bl_label}) is not supported; "
                "Prism renders its viewport colour instead. Connect a Principled BSDF to the Material Output."
            )
        elif material.use_nodes and material.node_tree is not None:
            reading.ignored.append(
                f"Material '{name}': nothing is connected to the Material Output's Surface; "
                "Prism renders its viewport colour instead."
            )
        return reading

    inputs = node.inputs
    reading = PrincipledReading(material_name=name, node_name=node.name)
    for socket_name in READ_SOCKETS:
        socket = inputs.get(socket_name)
        if socket is None:
            continue
        if is_linked(socket):
            source = upstream_node(socket)
            what = f"'{source.name}'" if source is not None else "a link"
            reading.ignored.append(
                f"Material '{name}': {what} linked into '{socket_name}' is ignored; "
                f"Prism uses the socket's own value. Unlink it or bake it to a constant."
            )
    value = {s: inputs[s].default_value for s in READ_SOCKETS if inputs.get(s) is not None}
    reading.base_color = tuple(float(c) for c in value["Base Color"][:3])
    reading.metallic = float(value["Metallic"])
    reading.roughness = float(value["Roughness"])
    reading.ior = float(value["IOR"])
    reading.transmission = float(value["Transmission Weight"])
    reading.emission_color = tuple(float(c) for c in value["Emission Color"][:3])
    reading.emission_strength = float(value["Emission Strength"])
    reading.thin_film_thickness_nm = float(value.get("Thin Film Thickness", 0.0))
    reading.thin_film_ior = float(value.get("Thin Film IOR", 1.33))

    for socket_name, neutral in NEUTRAL_VALUES.items():
        socket = inputs.get(socket_name)
        if socket is None:
            continue
        if is_linked(socket):
            reading.ignored.append(f"Material '{name}': the link into '{socket_name}' is ignored (not modelled by Prism).")
        elif _differs(socket.default_value, neutral):
            reading.ignored.append(
                f"Material '{name}': '{socket_name}' is ignored (not modelled by Prism); "
                f"set it to {neutral if not isinstance(neutral, tuple) else 'white'} to silence this."
            )
    for socket_name in LINK_ONLY_SOCKETS:
        socket = inputs.get(socket_name)
        if socket is not None and is_linked(socket):
            reading.ignored.append(f"Material '{name}': the map linked into '{socket_name}' is ignored (no bump or tangent maps).")
    return reading
