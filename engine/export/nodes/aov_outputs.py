"""The AOV Output nodes of a material, compiled with its surface: a linked Color or Value becomes a
register of the material's program (read at the first surface a camera ray hits, ``stages.pass_writes``),
or a constant where what feeds it folds to one. Unlinked sockets are read by ``export.aovs``."""

from __future__ import annotations

from ...properties.node_links import is_linked
from .terms import COLOR, FLOAT


def compile_aov_outputs(c, tree) -> dict[str, dict[str, object]]:
    """AOV name → {"Color": Value, "Value": Value} of the linked sockets of the first AOV Output node of
    each name (the node Blender reads), compiled into ``c``'s program."""
    compiled: dict[str, dict[str, object]] = {}
    seen = set()
    for node in tree.nodes:
        if node.bl_idname != "ShaderNodeOutputAOV" or node.mute or not node.aov_name or node.aov_name in seen:
            continue
        seen.add(node.aov_name)
        values = {}
        for name, kind in (("Color", COLOR), ("Value", FLOAT)):
            if is_linked(node.inputs[name]):
                values[name] = c.value(node, name, (), kind)
        if values:
            compiled[node.aov_name] = values
    return compiled


def aov_results(c, compiled) -> tuple[dict, dict]:
    """(AOV name → {"Color"/"Value": register}, AOV name → {"Color"/"Value": constant}) of ``compiled``."""
    registers: dict[str, dict[str, int]] = {}
    constants: dict[str, dict[str, object]] = {}
    for aov, values in compiled.items():
        for name, value in values.items():
            known = c.known(value)
            if known is None:
                registers.setdefault(aov, {})[name] = value.register
            else:
                constants.setdefault(aov, {})[name] = known
    return registers, constants
