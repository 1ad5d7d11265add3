"""Writing material programs: registers, constants, instructions, and folding what does not vary.

    b = ProgramBuilder(evaluate=fold_evaluator())
    uv = b.emit(UV, width=3, args=[0])                        # a hit input: varies
    half = b.emit(VECTOR_MATH, mode=..., width=3, args=[b.constant(1, 2, 3), b.constant(2, 2, 2)])
    b.value(half)                                              # (0.5, 1.0, 1.5): folded when emitted

Every value lives in registers (``Value``: first register and width). Constants get registers whose
initial value is set (``initial_registers``); the interpreter starts each hit from that register file.
An instruction whose inputs are all constant is run once when emitted, through the kernels' own
interpreter (``evaluate``: one implementation of every node), and becomes a constant; a hit only runs
what depends on the surface point. Without ``evaluate`` (e.g. when a panel only wants the warnings)
nothing is folded. ``instructions(live=...)`` leaves out instructions whose results nothing reads (a
layer weight no closure binds, a texture whose output is unused), so a hit never runs them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import opcodes as op

#: Instructions that read the hit, the ray, an image or write the closure rows: never folded.
NEVER_FOLDED = {op.UV, op.COLOR_ATTRIBUTE, op.POSITION, op.NORMAL, op.TRUE_NORMAL, op.INCOMING, op.GENERATED,
                op.OBJECT_COORDINATES, op.OBJECT_INFO, op.BACKFACING, op.TANGENT, op.PARAMETRIC, op.POINT_INFO,
                op.HAIR_INFO, op.FRESNEL,
                op.LAYER_WEIGHT, op.NORMAL_MAP, op.BUMP, op.BIND, op.BIND_RGB, op.IMAGE, op.LIGHT_PATH,
                op.AMBIENT_OCCLUSION, op.BEVEL, op.VALID_REFLECTION}


@dataclass(frozen=True)
class Value:
    register: int
    width: int = 1

    def component(self, index: int) -> "Value":
        return Value(self.register + index, 1)


class ProgramBuilder:
    def __init__(self, evaluate=None):
        self._evaluate = evaluate
        self._initial: list[float] = []
        self._constant: list[bool] = []
        self._rows: list[list[int]] = []
        self._groups: list[tuple[int, int, frozenset, range]] = []  # (first row, rows, reads, writes)

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
    @staticmethod
    def _row(opcode, mode, dst, args):
        if len(args) > op.INSTRUCTION - 3:
            raise ValueError(f"opcode {opcode}: {len(args)} operands do not fit one instruction")
        row = [opcode, mode, dst] + [-1] * (op.INSTRUCTION - 3)
        inputs = []
        for i, arg in enumerate(args):
            if isinstance(arg, Value):
                row[3 + i] = arg.register
                inputs.append(arg)
            elif arg is not None:
                row[3 + i] = int(arg)
        return row, inputs

    def emit(self, opcode: int, args=(), mode: int = 0, width: int = 0, reads=(), extra=None) -> Value | None:
        """Append an instruction; returns its result (``width`` registers, allocated here) or None.

        ``args`` fill operands a-g in order: a ``Value`` gives its first register (and is an input), an int
        is an immediate (texture id, slot, table size), None leaves the operand unused (-1). ``reads`` lists
        further registers the instruction reads beyond its ``Value`` arguments (a ramp's table); ``extra``
        fills a second row of operands (``EXTRA``) for instructions that need more than seven."""
        out = self.allocate(width) if width else None
        row, inputs = self._row(opcode, mode, out.register if out else -1, args)
        rows = [row]
        if extra is not None:
            extra_row, extra_inputs = self._row(op.EXTRA, 0, -1, extra)
            rows.append(extra_row)
            inputs += extra_inputs
        inputs += list(reads)
        if (self._evaluate is not None and out is not None and opcode not in NEVER_FOLDED
                and all(self.is_constant(v) for v in inputs)):
            registers = np.asarray(self._initial, dtype=np.float64)
            self._evaluate(np.asarray(rows, dtype=np.int32), registers)
            for r in range(out.register, out.register + out.width):
                self._initial[r] = float(registers[r])
                self._constant[r] = True
            return out
        reads = frozenset(r for v in inputs for r in range(v.register, v.register + v.width))
        writes = range(out.register, out.register + out.width) if out is not None else range(0)
        self._groups.append((len(self._rows), len(rows), reads, writes))
        self._rows.extend(rows)
        return out

    @property
    def instruction_count(self) -> int:
        return len(self._rows)

    @property
    def register_count(self) -> int:
        return len(self._initial)

    def initial_registers(self) -> np.ndarray:
        return np.asarray(self._initial, dtype=np.float64)

    def instructions(self, live=None) -> np.ndarray:
        """The program's instructions: all of them, or with ``live`` (the registers read from outside the
        program: closure colours and bindings, the normal, the emission) only those these depend on."""
        if live is None:
            return np.asarray(self._rows, dtype=np.int32).reshape(-1, op.INSTRUCTION)
        needed = set(live)
        kept = []
        for first, size, reads, writes in reversed(self._groups):
            if not writes or any(r in needed for r in writes):
                kept.append((first, size))
                needed.update(reads)
        rows = [row for first, size in reversed(kept) for row in self._rows[first:first + size]]
        return np.asarray(rows, dtype=np.int32).reshape(-1, op.INSTRUCTION)
