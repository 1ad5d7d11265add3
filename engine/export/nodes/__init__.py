"""Blender shader node trees → ``ShaderProgram`` (closures + a program of what varies per hit).

    compiled = compile_material(material, slots=slots, image_cache={}, evaluate=fold_evaluator())
    compiled.shader, compiled.warnings, compiled.needs

``compiler`` walks the tree; ``shaders``, ``inputs``, ``converters``, ``textures`` and ``vectors`` hold one
handler per Blender node; ``finish`` turns the walk into the tracer's data. Without ``evaluate`` nothing
is folded and without ``load_pixels`` no image is read: enough for the material panel's warnings.
"""

from __future__ import annotations

import sys
from contextlib import contextmanager
from dataclasses import dataclass, field

from .compiler import MAX_NODE_DEPTH, MaterialCompiler
from ...tracer.data_passes import AO_DISTANCE_DEFAULT
from .finish import finish
from .measured_base import check_measured_used
from .slots import AttributeSlots


@dataclass
class CompiledMaterial:
    shader: object  # tracer.materials.shader.ShaderProgram, or None when nothing is connected
    warnings: list = field(default_factory=list)
    needs: set = field(default_factory=set)  # ("uv" | "attribute" | "tangent" | "objects", name)
    glass: tuple | None = None  # ("catalogue", name) or ("abbe", (n_d, V_d)) when Material.prism sets one
    conductor: str | None = None  # a measured metal Material.prism sets
    kinds: set = field(default_factory=set)  # closure kinds, for the panel's summary
    measured_nodes: list = field(default_factory=list)  # nodes whose colour the measured reflectance replaced
    medium: object = None  # tracer.media.spec.MediumSpec of the Volume socket (the mesh's inside), or None


def compile_material(material, slots=None, image_cache=None, evaluate=None, load_pixels=True,
                     overrides=None, ao_distance=AO_DISTANCE_DEFAULT) -> CompiledMaterial:
    """Compile ``material``'s node tree (its Material Output for Cycles). ``overrides``: Material ▸ Prism's
    spectra for the Principled BSDF, ``reflectance`` (a ``scene.ReflectanceSpec`` for its base colour) and
    ``emission`` (a ``scene.SpectrumSpec`` for its emission). ``ao_distance``: the scene's World ▸ Ambient
    Occlusion ▸ Distance (m), which Ambient Occlusion nodes whose own distance is 0 use."""
    compiler = MaterialCompiler(material, getattr(material, "prism", None), slots, evaluate, load_pixels,
                                image_cache=image_cache if image_cache is not None else {},
                                overrides=dict(overrides or {}), ao_distance=float(ao_distance))
    with _room_to_recurse():
        if not compiler.compile_surface():
            compiler.warn(None, "has no Material Output for Cycles; Prism renders it black.")
            return CompiledMaterial(None, compiler.warnings, compiler.needs)
        check_measured_used(compiler, compiler.measured_nodes)
        shader = finish(compiler)
    return CompiledMaterial(shader, compiler.warnings, compiler.needs, compiler.glass_description, compiler.conductor,
                            {p.kind for p in compiler.closures}, list(compiler.measured_nodes), compiler.medium)


#: Python frames the walk takes per node at most (value → output → handler → helper → value, and the
#: shader walk's shader → handler → shader): the recursion limit must leave room for MAX_NODE_DEPTH nodes.
_FRAMES_PER_NODE = 8


@contextmanager
def _room_to_recurse():
    """Raise Python's recursion limit (never lower it) for the walk, so a tree ``MAX_NODE_DEPTH`` deep meets
    the compiler's own depth guard, with its message, and never a RecursionError."""
    previous = sys.getrecursionlimit()
    sys.setrecursionlimit(max(previous, previous + MAX_NODE_DEPTH * _FRAMES_PER_NODE))
    try:
        yield
    finally:
        sys.setrecursionlimit(previous)


__all__ = ["AttributeSlots", "CompiledMaterial", "compile_material"]
