"""Blender materials → ``tracer.scene.Material``."""

from ..tracer.scene import Material, SpectrumSpec

DEFAULT_MATERIAL = Material(name="Default", kind="diffuse", base_color=(0.8, 0.8, 0.8))


def _principled_node(material):
    if not material.use_nodes or material.node_tree is None:
        return None
    for node in material.node_tree.nodes:
        if node.type == "BSDF_PRINCIPLED":
            return node
    return None


def export_material(material) -> Material:
    """Lambertian base colour and emission from the Principled BSDF (or the viewport colour)."""
    if material is None:
        return DEFAULT_MATERIAL
    node = _principled_node(material)
    if node is None:
        color = material.diffuse_color
        return Material(name=material.name, base_color=(color[0], color[1], color[2]))
    color = node.inputs["Base Color"].default_value
    emission = node.inputs["Emission Color"].default_value
    strength = float(node.inputs["Emission Strength"].default_value)
    exported = Material(name=material.name, base_color=(color[0], color[1], color[2]))
    if strength > 0 and max(emission[:3]) > 0:
        exported.emission = SpectrumSpec(kind="rgb", rgb=(emission[0], emission[1], emission[2]))
        exported.emission_strength = strength
    return exported
