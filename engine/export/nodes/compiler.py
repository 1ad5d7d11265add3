"""Compiling one Blender material's node tree into a ``ShaderProgram``: the walk, values and weights.

The shader sockets are walked from the Material Output (``shaders``): Mix and Add Shader split and sum
weights at any depth, BSDF nodes add closures with their weight, Emission adds to the emission. Every
value a closure reads is compiled on demand (``value``) into program instructions by the node handlers
(``converters``, ``inputs``, ``textures``), once per node, group context and bump variant; constant
results fold as they are emitted, so an untextured material costs no program. Weights are kept as a
scalar times a colour so the common case (a constant colour scaled by a varying factor) needs no
per-hit colour upsampling.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ...properties.node_links import invalid_links
from ...tracer.bsdf.closure import TRANSPARENT
from ...tracer.data_passes import AO_DISTANCE_DEFAULT
from ...tracer.errors import PrismInputError
from ...tracer.materials import opcodes as op
from ...tracer.materials.program_builder import ProgramBuilder, Value
from .graph import Source, follow, output_node
from .registry import NODE_HANDLERS, SHADER_HANDLERS
from .terms import COLOR, FLOAT, SOCKET_KINDS, EmissionTerm, PendingClosure, Weight

_VECTOR_MATH = {name: i for i, name in enumerate(op.VECTOR_MATH_OPERATIONS)}
_MATH = {name: i for i, name in enumerate(op.MATH_OPERATIONS)}
#: The deepest chain of nodes (from the Material Output, through values and shaders) Prism compiles. The
#: walk recurses a few Python frames per node; ``compile_material`` makes room for this many.
MAX_NODE_DEPTH = 200


@dataclass
class MaterialCompiler:
    material: object
    settings: object = None  # Material.prism
    slots: object = None  # export.nodes.slots.AttributeSlots
    evaluate: object = None
    load_pixels: bool = True
    builder: ProgramBuilder = None
    warnings: list = field(default_factory=list)
    closures: list = field(default_factory=list)
    emission: list = field(default_factory=list)
    images: list = field(default_factory=list)
    image_keys: dict = field(default_factory=dict)
    image_cache: dict = field(default_factory=dict)  # shared by the materials of one export
    needs: set = field(default_factory=set)
    glass_description: tuple | None = None
    conductor: str | None = None
    displacement: object = None
    overrides: dict = field(default_factory=dict)  # see ``nodes.compile_material``
    measured_nodes: list = field(default_factory=list)  # names of the nodes whose colour ``reflectance`` replaced
    medium: object = None  # tracer.media.spec.MediumSpec of the Volume socket, or None
    volume_density: object = None  # the Value of its varying Density (``volume_density``), or None
    volume_emission: object = None  # the Value of its varying Emission Strength (``volume_density``), or None
    aov_outputs: dict = field(default_factory=dict)  # linked AOV Output sockets (``aov_outputs``)
    ao_distance: float = AO_DISTANCE_DEFAULT  # World ▸ Ambient Occlusion ▸ Distance (m)
    _outputs: dict = field(default_factory=dict)
    _warned: set = field(default_factory=set)
    _depth: int = 0  # nodes between the Material Output and the node being compiled
    bakes_volume_density = True  # a varying volume Density is baked over the meshes (``volume_density``)

    def __post_init__(self):
        if self.builder is None:
            self.builder = ProgramBuilder(self.evaluate)

    # -- messages ----------------------------------------------------------------------------------
    #: What the warnings name first (a world's tree is compiled by a subclass that says "World").
    subject = "Material"

    def warn(self, node, what):
        """One warning per node and message: ``Material 'M': the 'N' node (Label) <what>.``"""
        key = (node.name if node is not None else None, what)
        if key in self._warned:
            return
        self._warned.add(key)
        where = f"the '{node.name}' node ({node.bl_label}) " if node is not None else ""
        self.warnings.append(f"{self.subject} '{self.material.name}': {where}{what}")

    # -- constants and arithmetic --------------------------------------------------------------------
    def const(self, *values) -> Value:
        return self.builder.constant(*values)

    def known(self, value):
        """The constant of ``value`` (float or tuple), or None if it varies."""
        return self.builder.value(value)

    def emit(self, opcode, args=(), mode=0, width=1, reads=(), extra=None) -> Value:
        return self.builder.emit(opcode, args, mode=mode, width=width, reads=reads, extra=extra)

    def math(self, operation, a, b=None, c=None) -> Value:
        return self.emit(op.MATH, [a, b if b is not None else a, c], mode=_MATH[operation])

    def vector_math(self, operation, a, b=None, c=None, s=None) -> Value:
        width = 1 if operation in op.VECTOR_MATH_SCALAR else 3
        return self.emit(op.VECTOR_MATH, [a, b, c, s], mode=_VECTOR_MATH[operation], width=width)

    def multiply(self, a: Value, b: Value) -> Value:
        """a × b for scalars or vectors (a vector times a scalar scales it); constant 1 factors vanish and
        a constant 0 factor gives 0 (a lobe weighted 0 is left out even where the rest varies)."""
        width = max(a.width, b.width)
        if 0.0 in (self.known(a), self.known(b)) or (0.0,) * 3 in (self.known(a), self.known(b)):
            return self.const(*(0.0,) * width)
        if self.known(a) in (1.0, (1.0, 1.0, 1.0)) and a.width >= b.width:
            return b if a.width == b.width else self.broadcast(b)
        if self.known(b) in (1.0, (1.0, 1.0, 1.0)) and b.width >= a.width:
            return a if a.width == b.width else self.broadcast(a)
        if a.width == 1 and b.width == 1:
            return self.math("MULTIPLY", a, b)
        if a.width == 3 and b.width == 3:
            return self.vector_math("MULTIPLY", a, b)
        vector, scalar = (a, b) if a.width == 3 else (b, a)
        return self.vector_math("SCALE", vector, s=scalar)

    def broadcast(self, scalar: Value) -> Value:
        return scalar if scalar.width == 3 else self.emit(op.FLOAT_TO_COLOR, [scalar], width=3)

    def one_minus(self, a: Value) -> Value:
        return self.math("SUBTRACT", self.const(1.0), a)

    def clamp01(self, a: Value) -> Value:
        known = self.known(a)
        if known is not None and 0.0 <= known <= 1.0:
            return a
        return self.emit(op.CLAMP, [a, self.const(0.0), self.const(1.0)])

    def convert(self, value: Value, source_kind: str, kind: str) -> Value:
        """Blender's implicit conversion between socket types (colour → float is luminance, vector →
        float the mean, float → vector/colour broadcasts)."""
        if source_kind == kind or (source_kind != FLOAT and kind != FLOAT):
            return value
        if kind != FLOAT:
            return self.broadcast(value)
        if source_kind == COLOR:
            return self.emit(op.RGB_TO_BW, [value])
        return self.emit(op.VECTOR_TO_FLOAT, [value])

    # -- values --------------------------------------------------------------------------------------
    def socket(self, node, name):
        socket = node.inputs.get(name) if not isinstance(name, int) else node.inputs[name]
        if socket is None:
            socket = next((s for s in node.inputs if s.identifier == name), None)
        return socket

    def linked(self, node, name, context) -> Source | None:
        socket = self.socket(node, name)
        return follow(socket, context)[0] if socket is not None else None

    def value(self, node, name, context, kind, variant=0, default=None) -> Value:
        """The value of input ``name`` of ``node`` as ``kind`` (compiling what feeds it); ``default`` (a
        callable) gives the value of an unlinked vector input (texture coordinates, the normal)."""
        socket = self.socket(node, name)
        if socket is None:
            raise KeyError(f"{node.bl_idname} has no input '{name}'")
        source, value_socket = follow(socket, context)
        if source is None:
            if default is not None:
                return default()
            return self.default_value(value_socket, kind)
        value, source_kind = self.output(source, variant)
        return self.convert(value, source_kind, kind)

    def value_of_socket(self, socket, context, kind, variant=0) -> Value:
        """The value arriving at input ``socket`` (e.g. the Material Output's Displacement) as ``kind``."""
        source, value_socket = follow(socket, context)
        if source is None:
            return self.default_value(value_socket, kind)
        value, source_kind = self.output(source, variant)
        return self.convert(value, source_kind, kind)

    def constant_of(self, node, name, context, kind=FLOAT, variant=0):
        """The input's value if it is constant (float or tuple), else None."""
        return self.known(self.value(node, name, context, kind, variant))

    def default_value(self, socket, kind) -> Value:
        raw = getattr(socket, "default_value", 0.0)
        try:
            values = [float(x) for x in raw]
        except TypeError:
            values = [float(raw)]
        if not all(math.isfinite(v) for v in values):
            raise PrismInputError(f"Material '{self.material.name}': {socket.node.name} ▸ {socket.name} is "
                                  f"{', '.join(f'{v:g}' for v in values)}; enter a finite number.")
        socket_kind = SOCKET_KINDS.get(socket.type, FLOAT)
        if socket_kind == COLOR:
            values = values[:3]
        value = self.const(*values[:3]) if len(values) > 1 else self.const(values[0])
        return self.convert(value, socket_kind if value.width == 3 else FLOAT, kind)

    def output(self, source: Source, variant=0):
        """(Value, kind) of an output socket, compiling its node once per context and variant."""
        key = (source.key[0], source.key[2], variant)
        outputs = self._outputs.get(key)
        if outputs is None or source.identifier not in outputs:
            node = source.node
            handler = NODE_HANDLERS.get(node.bl_idname)
            if handler is None:
                self.warn(node, "is not supported by Prism; its outputs are taken as 0. Replace it or bake it to "
                                "an image texture.")
                computed = {}
            else:
                self._enter(node)
                try:
                    computed = handler(self, node, source.context, variant, source.identifier)
                finally:
                    self._depth -= 1
            outputs = {**(outputs or {}), **computed}
            self._outputs[key] = outputs
        if source.identifier not in outputs:
            socket = next(s for s in source.node.outputs if s.identifier == source.identifier)
            kind = SOCKET_KINDS.get(socket.type, FLOAT)
            if socket.type == "SHADER":
                self.warn(source.node, "is a shader used as a value; Prism takes 0 there.")
            zero = self.const(0.0, 0.0, 0.0) if kind != FLOAT else self.const(0.0)
            outputs[source.identifier] = (zero, kind)
        return outputs[source.identifier]

    # -- hit inputs ----------------------------------------------------------------------------------
    def hit(self, opcode, variant=0, mode=0, slot=None, width=3) -> Value:
        return self.emit(opcode, [slot, None, None, None, None, None, variant], mode=mode, width=width)

    def normal(self, variant=0) -> Value:
        return self.hit(op.NORMAL, variant)

    def image_index(self, image) -> int:
        """The program-local index of a ``TextureImage``."""
        key = id(image)
        if key not in self.image_keys:
            self.image_keys[key] = len(self.images)
            self.images.append(image)
        return self.image_keys[key]

    # -- shaders -------------------------------------------------------------------------------------
    def shader(self, socket, context, weight: Weight) -> None:
        """Add the closures and emission of whatever feeds shader input ``socket``, scaled by ``weight``."""
        source, _ = follow(socket, context)
        if source is None:
            return
        handler = SHADER_HANDLERS.get(source.node.bl_idname)
        if handler is None:
            self.warn(source.node, "is not a shader Prism renders; it is left out (black). Use a Principled BSDF or "
                                   "another supported BSDF.")
            return
        self._enter(source.node)
        try:
            handler(self, source.node, source.context, weight)
        finally:
            self._depth -= 1

    def _enter(self, node) -> None:
        """One node deeper; a tree deeper than ``MAX_NODE_DEPTH`` (or a loop of links Blender has not marked
        invalid) is refused here, naming the node, before Python's recursion limit is reached."""
        self._depth += 1
        if self._depth > MAX_NODE_DEPTH:
            raise PrismInputError(
                f"Material '{self.material.name}': node tree deeper than {MAX_NODE_DEPTH} nodes at '{node.name}'; "
                f"Prism compiles trees up to {MAX_NODE_DEPTH} deep: simplify it (bake part of it to an image "
                "texture, or shorten the chain).")

    def weighted(self, weight: Weight, scale: Value | None = None, colour: Value | None = None) -> Weight:
        return Weight(self.multiply(weight.scale, scale) if scale is not None else weight.scale,
                      self.multiply(weight.colour, colour) if colour is not None else weight.colour, weight.layer)

    def add_closure(self, closure: PendingClosure) -> None:
        if self.known(closure.weight.scale) == 0.0 or self.known(closure.weight.colour) == (0.0, 0.0, 0.0):
            return
        self.closures.append(closure)
        if closure.measured is not None and closure.node.name not in self.measured_nodes:
            self.measured_nodes.append(closure.node.name)

    def add_emission(self, weight: Weight, colour: Value | None, strength: Value, spectrum=None, node=None,
                     setting="Strength") -> None:
        """Add ``weight`` × ``strength`` × ``colour`` (or ``spectrum``) to the emission; a constant radiance
        float32 cannot carry is refused naming ``node`` and ``setting``."""
        if weight.layer is not None:  # Principled adds its emission above its specular layer
            raise ValueError("an emission under a constant specular layer is not compiled")
        scale = self.multiply(weight.scale, strength)
        if 0.0 in (self.known(strength), self.known(weight.scale), self.known(scale)):
            return
        colour = self.multiply(weight.colour, colour) if colour is not None else weight.colour
        known_scale, known_colour = self.known(scale), self.known(colour)
        if known_scale is not None and known_colour is not None and node is not None:
            from ..float_range import check_light_value

            where = f"Material '{self.material.name}', {node.bl_label} '{node.name}'"
            check_light_value(abs(known_scale) * max(abs(x) for x in known_colour), where, setting)
        if spectrum is not None and self.known(weight.colour) != (1.0, 1.0, 1.0):
            spectrum = None
        if self.known(colour) == (0.0, 0.0, 0.0) and spectrum is None:
            return
        self.emission.append(EmissionTerm(scale, colour, spectrum))

    def compile_surface(self) -> bool:
        """Walk the Material Output's Surface; False when there is nothing to walk."""
        tree = self.material.node_tree
        out = output_node(tree) if tree is not None else None
        if out is None:
            return False
        for link in invalid_links(tree):
            self.warn(None, f"the link from '{link.from_node.name}' to '{link.to_node.name}' is invalid (a loop, or "
                            "sockets that cannot connect: Blender draws it red); Prism ignores it, as Cycles does. "
                            "Remove it.")
        surface, volume = out.inputs["Surface"], out.inputs.get("Volume")
        has_volume = volume is not None and follow(volume)[0] is not None
        volume_only = has_volume and follow(surface)[0] is None
        socket = out.inputs.get("Displacement")
        if socket is not None and follow(socket)[0] is not None:
            self.displacement = socket
        self.output_node = out
        if has_volume:  # the closed mesh's inside (``volumes``); a missing surface is a null one, as in Cycles
            from .volumes import compile_volume

            self.medium = compile_volume(self, volume)
        one = Weight(self.const(1.0), self.const(1.0, 1.0, 1.0))
        self.surface_missing = volume_only
        if volume_only:  # Cycles: a volume's missing surface lets light through unchanged
            self.add_closure(PendingClosure(TRANSPARENT, one, out))
        else:
            self.shader(surface, (), one)
        from .aov_outputs import compile_aov_outputs

        self.aov_outputs = compile_aov_outputs(self, tree)
        return True
