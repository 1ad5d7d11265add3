"""Writing material programs: instructions whose results nothing outside the program reads are left
out, with everything a kept one depends on kept."""

from engine.tracer.materials import opcodes as op
from engine.tracer.materials.program_builder import ProgramBuilder


def test_instructions_nothing_reads_are_left_out():
    b = ProgramBuilder()
    uv = b.emit(op.UV, [0], width=3)
    incoming = b.emit(op.INCOMING, width=3)
    length = b.emit(op.VECTOR_MATH, [uv], mode=op.VECTOR_MATH_OPERATIONS.index("LENGTH"), width=1)
    b.emit(op.VECTOR_MATH, [incoming, uv], mode=op.VECTOR_MATH_OPERATIONS.index("DOT_PRODUCT"), width=1)
    doubled = b.emit(op.MATH, [length, b.constant(2.0)], mode=op.MATH_OPERATIONS.index("MULTIPLY"), width=1)

    assert [row[op.OP] for row in b.instructions()] == [op.UV, op.INCOMING, op.VECTOR_MATH, op.VECTOR_MATH, op.MATH]
    kept = b.instructions(live={doubled.register})
    assert [row[op.OP] for row in kept] == [op.UV, op.VECTOR_MATH, op.MATH]
    assert kept[1][op.DST] == length.register
    assert len(b.instructions(live=set())) == 0
