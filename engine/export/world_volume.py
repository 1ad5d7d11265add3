"""The World Output's Volume socket → the medium everywhere outside meshes with a volume (``World.medium``):
fog, as Cycles renders a world volume. Read with the material compiler's volume walk
(``nodes.volumes.compile_volume``: Volume Absorption, Volume Scatter, Principled Volume, Add and Mix
Shader), its warnings naming the world.

As in Cycles, the fog fills all space, the inside of meshes without a volume of their own included, and
the camera stands in it; a ray that leaves the scene never reaches the background through fog that
absorbs or scatters (its transmittance over an infinite distance is 0), and neither does sunlight (a Sun
light, the world's own light): fog is lit by lights and emitters inside it.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..properties.node_links import is_linked
from .nodes.compiler import MaterialCompiler


@dataclass
class _WorldCompiler(MaterialCompiler):
    """The material compiler for a world's node tree: its warnings name the world."""

    subject = "World"
    bakes_volume_density = False  # fog fills all space: no bounds to bake a varying density over


def export_world_volume(world, tree, warnings: list[str] | None):
    """The ``MediumSpec`` of ``world``'s Volume (its node ``tree``), or None when nothing is linked there or
    the shaders add nothing."""
    output = tree.get_output_node("ALL") if tree is not None else None
    volume = output.inputs.get("Volume") if output is not None else None
    if volume is None or not is_linked(volume):
        return None
    from ..tracer.materials.folding import fold_evaluator
    from .nodes.volumes import compile_volume

    compiler = _WorldCompiler(world, evaluate=fold_evaluator(), load_pixels=False)
    compiler.output_node = output
    spec = compile_volume(compiler, volume)
    if warnings is not None:
        warnings.extend(compiler.warnings)
    return spec
