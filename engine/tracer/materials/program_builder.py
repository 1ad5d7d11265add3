"""Writing material programs: registers, constants, instructions, and folding what does not vary.

    b = ProgramBuilder()
    uv = b.emit(UV, width=3, args=[0])                       # a hit input: varies
    scaled = b.emit(VECTOR_MATH, mode=..., width=3, args=[uv, b.constant(2, 2, 2), ...])
    b.fold(evaluate)                                          # constant sub-programs run once
    b.value(scaled)                                           # its constant value, or None

Every value lives in registers (``Value``: first register and width). Constants get registers whose
initial value is set (``initial_registers``); the interpreter starts each hit from that register file.
``fold`` runs the instructions whose inputs are all constant once, through the kernels' own interpreter
(one implementation of every node), and turns their results into constants, so a hit only runs what
depends on the surface point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import opcodes as op

#: Instructions that read the hit, an image or write the closure rows: never folded.
_HIT_INPUTS = {op.UV, op.COLOR_ATTRIBUTE, op.POSITION, op.NORMAL, op.TRUE_NORMAL, op.INCOMING, op.GENERATED,
               op.OBJECT_COORDINATES, op.OBJECT_INFO, op.BACKFACING, op.TANGENT, op.PARAMETRIC, op.FRESNEL,
               op.LAYER_WEIGHT, op.NORMAL_MAP, op.BUMP, op.BIND, op.BIND_RGB, op.IMAGE}


@dataclass(frozen=True)
class Value:
    register: int
    width: int = 1

    def component(self, index: int) -> "Value":
        return Value(self.register + index, 1)


class ProgramBuilder:
    def __init__(self):
        self._initial: list[float] = []
        self._constant: list[bool] = []
        self._rows: list[list[int]] = []
        self._reads: list[list[Value]] = []
        self._writes: list[Value | None] = []

    # -- registers ---------------------------------------------------------------------------------
    def constant(self, *values) -> Value:
        """Registers holding ``values`` (floats)."""
        first = len(self._initial)
        for value in values:
            self._initial.append(float(value))
            self._constant.append(True)
        return Value(first, len(values))

    def allocate(self, width: int) -> Value:
        first = len(self._initial)
        self._initial.extend([0.0] * width)
        self._constant.extend([False] * width)
        return Value(first, width)

    def is_constant(self, value: Value) -> bool:
        return all(self._constant[value.register + i] for i in range(value.width))

    def value(self, value: Value):
        """The constant value (float, or tuple for width > 1) of ``value``, or None if it varies."""
        if not self.is_constant(value):
            return None
        values = tuple(self._initial[value.register:value.register + value.width])
        return values[0] if value.width == 1 else values

    # -- instructions ------------------------------------------------------------------------------
    def emit(self, opcode: int, args=(), mode: int = 0, width: int = 0, reads=None) -> Value | None:
        """Append an instruction; returns its result (``width`` registers, allocated here) or None.

        ``args`` fill operands a-g in order: a ``Value`` gives its first register (and is an input),
        an int is an immediate (texture id, slot, constant offset). ``reads`` lists further registers
        the instruction reads beyond the ``Value`` arguments (e.g. the next components of a ramp)."""
        if len(args) > op.INSTRUCTION - 3:
            raise ValueError(f"opcode {opcode}: {len(args)} operands do not fit one instruction")
        out = self.allocate(width) if width else None
        row = [opcode, mode, out.register if out else -1] + [-1] * (op.INSTRUCTION - 3)
        inputs = []
        for i, arg in enumerate(args):
            if isinstance(arg, Value):
                row[3 + i] = arg.register
                inputs.append(arg)
            else:
                row[3 + i] = int(arg)
        inputs.extend(reads or ())
        self._rows.append(row)
        self._reads.append(inputs)
        self._writes.append(out)
        return out

    @property
    def instruction_count(self) -> int:
        return len(self._rows)

    @property
    def register_count(self) -> int:
        return len(self._initial)

    def initial_registers(self) -> np.ndarray:
        return np.asarray(self._initial, dtype=np.float64)

    def instructions(self) -> np.ndarray:
        return np.asarray(self._rows, dtype=np.int32).reshape(-1, op.INSTRUCTION)

    # -- folding ---------------------------------------------------------------------------------
    def fold(self, evaluate) -> None:
        """Run every instruction whose inputs are constant once, with ``evaluate(instructions,
        registers)`` (the kernels' interpreter on a register file, in place), and keep only the rest.
        An ``EXTRA`` row belongs to the instruction before it."""
        groups = []
        for i, row in enumerate(self._rows):
            if row[op.OP] == op.EXTRA and groups:
                groups[-1].append(i)
            else:
                groups.append([i])
        kept, folded = [], []
        for group in groups:
            head = self._rows[group[0]][op.OP]
            inputs = [v for i in group for v in self._reads[i]]
            if head in _HIT_INPUTS or not all(self.is_constant(v) for v in inputs):
                kept.extend(group)
            else:
                folded.extend(group)
                for i in group:
                    out = self._writes[i]
                    if out is not None:
                        for r in range(out.register, out.register + out.width):
                            self._constant[r] = True
        if not folded:
            return
        registers = self.initial_registers()
        evaluate(np.asarray([self._rows[i] for i in folded], dtype=np.int32), registers)
        for i in folded:
            out = self._writes[i]
            if out is not None:
                self._initial[out.register:out.register + out.width] = registers[
                    out.register:out.register + out.width].tolist()
        self._rows = [self._rows[i] for i in kept]
        self._reads = [self._reads[i] for i in kept]
        self._writes = [self._writes[i] for i in kept]
