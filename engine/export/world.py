"""The scene's world → a constant background radiance."""

from ..tracer.scene import World


def export_world(scene) -> World:
    """World colour x strength from the Background node, else the world colour."""
    world = scene.world
    if world is None:
        return World(color=(0.0, 0.0, 0.0), strength=0.0)
    if world.use_nodes and world.node_tree is not None:
        for node in world.node_tree.nodes:
            if node.type == "BACKGROUND":
                color = node.inputs["Color"].default_value
                strength = node.inputs["Strength"].default_value
                return World(color=(color[0], color[1], color[2]), strength=float(strength))
    return World(color=tuple(world.color), strength=1.0)
