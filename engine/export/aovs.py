"""Shader AOVs: the AOV Output nodes of a material, as the values its AOV passes show on its surfaces.

An unlinked Color or Value is a constant per material (e.g. an ID matte), read here; a linked one is
compiled with the material's surface (``nodes.aov_outputs``): a constant where what feeds it folds to one
(``merge_compiled``), else evaluated at each first hit.
"""

from __future__ import annotations

import math

from ..tracer.errors import PrismInputError


def read_aovs(material) -> dict[str, tuple[float, float, float, float]]:
    """AOV name → (r, g, b, value) of the material's AOV Output nodes' own socket values (first node of a name
    wins)."""
    tree = material.node_tree if getattr(material, "use_nodes", False) else None
    if tree is None:
        return {}
    out: dict[str, tuple[float, float, float, float]] = {}
    for node in tree.nodes:
        if node.bl_idname != "ShaderNodeOutputAOV" or node.mute or not node.aov_name or node.aov_name in out:
            continue
        colour, value = node.inputs["Color"], node.inputs["Value"]
        values = (*(float(c) for c in colour.default_value[:3]), float(value.default_value))
        if not all(math.isfinite(v) for v in values):
            raise PrismInputError(f"Material '{material.name}': AOV Output '{node.aov_name}' is not a finite number.")
        out[node.aov_name] = values
    return out


def merge_compiled(aovs: dict, shader) -> dict[str, tuple[float, float, float, float]]:
    """``aovs`` (``read_aovs``) with the linked sockets that folded to constants in ``shader``
    (``ShaderProgram.aov_constants``) in place of the sockets' own values."""
    merged = dict(aovs)
    for name, constants in (shader.aov_constants if shader is not None else {}).items():
        r, g, b, value = merged[name]
        if "Color" in constants:
            r, g, b = (float(x) for x in constants["Color"][:3])
        if "Value" in constants:
            value = float(constants["Value"])
        merged[name] = (r, g, b, value)
    return merged
