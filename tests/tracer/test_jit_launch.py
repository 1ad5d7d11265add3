"""``jit.Launch`` calls the machine code numba compiled for exactly the arguments' types, and leaves every
other call to numba's dispatcher: same results as calling the kernel, new types compile, nothing is
confused for something else."""

from collections import namedtuple

import numpy as np

from engine.tracer.jit import Launch, kernel

Tables = namedtuple("Tables", "weights offsets")


@kernel
def _weighted_sum(tables, values, count, scale):
    total = 0.0
    for i in range(count):
        total += tables.weights[i] * values[i] + tables.offsets[i]
    return total * scale


def test_launch_gives_the_kernels_results_and_compiles_for_new_types():
    launch = Launch(_weighted_sum)
    tables = Tables(np.arange(4.0), np.ones(4))
    values = np.array([1.0, 2.0, 3.0, 4.0])
    expected = (0 * 1 + 1 * 2 + 2 * 3 + 3 * 4 + 4) * 0.5
    assert _weighted_sum(tables, values, 4, 0.5) == expected
    assert launch(tables, values, 4, 0.5) == expected  # the overload the dispatcher compiled
    assert launch(tables, values, 3, 2.0) == (0 + 2 + 6 + 3) * 2.0
    signatures = len(_weighted_sum.signatures)

    # other dtypes, a read-only array, a non-contiguous view, an integer scale: each is a type of its own
    as_int = Tables(np.arange(4, dtype=np.int32), np.ones(4, dtype=np.int64))
    assert launch(as_int, values, 4, 0.5) == expected
    frozen = values.copy()
    frozen.flags.writeable = False
    assert launch(tables, frozen, 4, 0.5) == expected
    strided = np.repeat(values, 2)[::2]
    assert launch(tables, strided, 4, 0.5) == expected
    assert launch(tables, values, 4, 2) == expected * 4
    assert len(_weighted_sum.signatures) > signatures  # compiled through the dispatcher, not guessed

    # a new table tuple (a new render's tables) is typed afresh, also when an old one's id is reused
    for n in range(100):
        fresh = Tables(np.full(4, float(n)), np.zeros(4))
        assert launch(fresh, values, 4, 1.0) == n * 10.0
