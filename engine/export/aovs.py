"""Shader AOVs: the AOV Output nodes of a material, as the values its AOV passes show on its surfaces.

Prism evaluates an AOV Output's Color and Value where they are not linked (a constant per material, e.g.
an ID matte); a linked input is reported and its socket's own value used.
"""

from __future__ import annotations

import math

from ..properties.node_links import is_linked
from ..tracer.errors import PrismInputError


def read_aovs(material, warnings: list[str] | None = None) -> dict[str, tuple[float, float, float, float]]:
    """AOV name → (r, g, b, value) of the material's AOV Output nodes (first node of a name wins)."""
    tree = material.node_tree if getattr(material, "use_nodes", False) else None
    if tree is None:
        return {}
    out: dict[str, tuple[float, float, float, float]] = {}
    for node in tree.nodes:
        if node.bl_idname != "ShaderNodeOutputAOV" or node.mute or not node.aov_name or node.aov_name in out:
            continue
        colour, value = node.inputs["Color"], node.inputs["Value"]
        for socket in (colour, value):
            if is_linked(socket) and warnings is not None:
                warnings.append(f"Material '{material.name}': the link into AOV Output '{node.aov_name}' "
                                f"{socket.name} is ignored; Prism writes the socket's own value.")
        values = (*(float(c) for c in colour.default_value[:3]), float(value.default_value))
        if not all(math.isfinite(v) for v in values):
            raise PrismInputError(f"Material '{material.name}': AOV Output '{node.aov_name}' is not a finite number.")
        out[node.aov_name] = values
    return out
