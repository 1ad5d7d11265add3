"""Rows of hair and point clouds followed through the shutter (``export.motion_steps.object_steps``), without
Blender: a step's export may list its objects in another order, instances of one object by occurrence; an object
whose number of rows changes stays still, warned, or follows the rows given for it (points moved by their
velocity); one whose rows stop being finite stays still, warned."""

from __future__ import annotations

import numpy as np

from engine.export.motion_steps import StepRows, matched_steps, object_steps

NAMES = ["Dust", "Spray", "Sparks", "Ash", "Dust"]  # two instances of Dust
SIZES = [2, 3, 2, 1, 2]
SHIFTS = (-0.1, 0.0, 0.1)  # x at the three steps, from the frame's


class _Rows:
    """A step's export: ``table`` [M, 4], ``owner`` [M] into its own ``names``."""

    def __init__(self, table, owner):
        self.table, self.owner = table, owner

    def __len__(self):
        return len(self.owner)


def _export(names, sizes, shift):
    """Rows of each object in ``names`` order: object k's j-th row at (10 k + j, 0, 0) + shift, radius 0.1 (the two
    Dust instances told apart by their place among the Dusts)."""
    table, owner, seen = [], [], {}
    for k, (name, size) in enumerate(zip(names, sizes)):
        occurrence = seen[name] = seen.get(name, -1) + 1
        for j in range(size):
            table.append([100.0 * occurrence + 10.0 * NAMES.index(name) + j + shift, 0.0, 0.0, 0.1])
            owner.append(k)
    return _Rows(np.array(table), np.array(owner))


def _steps(changing_size=2, nan_step=None):
    out = []
    for s, shift in enumerate(SHIFTS):
        names, sizes = list(reversed(NAMES)), list(reversed(SIZES))  # another order at every step
        sizes[names.index("Sparks")] = changing_size if s == 0 else 2
        step = _export(names, sizes, shift)
        if s == nan_step:
            step.table[step.owner == names.index("Ash")] = np.nan
        out.append((step, names))
    return out


def _follow(steps, unmatched=None):
    frame = _export(NAMES, SIZES, 0.0)
    rows = StepRows(frame.table, frame.owner, matched_steps(NAMES, steps, lambda r: r.table, lambda r: r.owner),
                    lambda name: f"changing {name}", lambda name: f"deforming {name}", unmatched)
    warnings = []
    settings = {name: (True, 1, True) for name in NAMES}
    return frame, object_steps(rows, NAMES, settings, len(SHIFTS), warnings), warnings


def test_rows_are_matched_per_object_and_order_whatever_the_order_of_a_steps_objects():
    frame, table, warnings = _follow(_steps())
    assert warnings == []
    for s, shift in enumerate(SHIFTS):
        np.testing.assert_allclose(table[s, :, 0], frame.table[:, 0] + shift)


def test_an_object_whose_rows_change_or_stop_being_finite_stays_still_warned():
    frame, table, warnings = _follow(_steps(changing_size=3, nan_step=2))
    still = np.isin(frame.owner, [NAMES.index("Sparks"), NAMES.index("Ash")])
    np.testing.assert_array_equal(table[:, still], np.broadcast_to(frame.table[still], (3, still.sum(), 4)))
    for s, shift in enumerate(SHIFTS):
        np.testing.assert_allclose(table[s, ~still, 0], frame.table[~still, 0] + shift)
    assert warnings == ["changing Sparks", "Object 'Ash': its positions are not finite (NaN or infinite) at a time "
                        "step of the shutter, so Prism renders it still where it is at the frame, without motion blur."]


def test_an_object_whose_rows_change_follows_the_rows_given_for_it():
    frame = _export(NAMES, SIZES, 0.0)
    unmatched = np.repeat(frame.table[None], 3, axis=0)
    unmatched[..., 1] += np.array([-1.0, 0.0, 1.0])[:, None]  # these rows move along y instead
    _, table, warnings = _follow(_steps(changing_size=3), unmatched)
    sparks = frame.owner == NAMES.index("Sparks")
    assert warnings == []
    np.testing.assert_allclose(table[:, sparks], unmatched[:, sparks])
    np.testing.assert_allclose(table[2, ~sparks, 0], frame.table[~sparks, 0] + 0.1)
