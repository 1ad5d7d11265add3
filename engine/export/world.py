"""The scene's world → a constant background radiance."""

from __future__ import annotations

import math

from ..tracer.errors import PrismInputError
from ..tracer.scene import World


def _background_node(world):
    tree = world.node_tree if world.use_nodes else None
    if tree is None:
        return None
    output = tree.get_output_node("ALL")
    if output is not None and output.inputs["Surface"].is_linked:
        node = output.inputs["Surface"].links[0].from_node
        if node.type == "BACKGROUND":
            return node
    return next((node for node in tree.nodes if node.type == "BACKGROUND"), None)


def export_world(scene, warnings: list[str] | None = None) -> World:
    """World colour x strength from the Background node, else the world colour."""
    world = scene.world
    if world is None:
        return World(color=(0.0, 0.0, 0.0), strength=0.0)
    node = _background_node(world)
    if node is None:
        return World(color=tuple(float(c) for c in world.color), strength=1.0)
    for socket_name in ("Color", "Strength"):
        if node.inputs[socket_name].is_linked and warnings is not None:
            warnings.append(
                f"World '{world.name}': the link into Background '{socket_name}' is ignored; "
                "Prism uses a constant background (the socket's own value)."
            )
    color = tuple(float(c) for c in node.inputs["Color"].default_value[:3])
    strength = float(node.inputs["Strength"].default_value)
    if not (all(math.isfinite(c) and c >= 0 for c in color) and math.isfinite(strength) and strength >= 0):
        raise PrismInputError(f"World '{world.name}': background colour and strength must be finite and not negative.")
    return World(color=color, strength=strength)
