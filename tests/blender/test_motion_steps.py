"""Rows of hair, point clouds and meshes followed through the shutter (``export.motion_steps.object_steps``),
without Blender: a step's export may list its objects in another order, instances of one object by occurrence; an
object whose number of rows changes stays still, warned; an object with a velocity attribute follows the rows
it gives, whether or not its rows could be matched; one whose rows stop being finite stays still, warned."""

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


def _follow(steps, by_velocity=None):
    frame = _export(NAMES, SIZES, 0.0)
    rows = StepRows(frame.table, frame.owner, matched_steps(NAMES, steps, lambda r: r.table, lambda r: r.owner),
                    lambda name: f"changing {name}", lambda name: f"deforming {name}", by_velocity)
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


def test_an_object_whose_rows_change_follows_its_velocity_rows():
    frame = _export(NAMES, SIZES, 0.0)
    sparks = frame.owner == NAMES.index("Sparks")
    by_velocity = np.full((3, len(frame.owner), 4), np.nan)  # only Sparks has a velocity
    by_velocity[:, sparks] = frame.table[sparks]
    by_velocity[:, sparks, 1] += np.array([-1.0, 0.0, 1.0])[:, None]  # its rows move along y instead
    _, table, warnings = _follow(_steps(changing_size=3), by_velocity)
    assert warnings == []
    np.testing.assert_allclose(table[:, sparks], by_velocity[:, sparks])
    np.testing.assert_allclose(table[2, ~sparks, 0], frame.table[~sparks, 0] + 0.1)


def test_velocity_rows_are_taken_over_followable_steps_and_skip_the_deformation_warning():
    """Cycles takes a velocity attribute over the steps even where the rows could be followed, and whatever Object ▸
    Motion Blur ▸ Deformation says; rows without a radius keep their negative fourth column."""
    frame = _export(NAMES, SIZES, 0.0)
    frame.table[:, 3] = -0.5  # a coordinate, not a radius
    steps = _steps()
    for step, _ in steps:
        step.table[:, 3] = -0.5
    by_velocity = np.full((3, len(frame.owner), 4), np.nan)
    dust = np.isin(frame.owner, [k for k, name in enumerate(NAMES) if name == "Dust"])
    along_y = np.array([0.0, 1.0, 0.0, 0.0]) * np.array([-1.0, 0.0, 1.0])[:, None, None]
    by_velocity[:, dust] = frame.table[dust] + along_y
    rows = StepRows(frame.table, frame.owner, matched_steps(NAMES, steps, lambda r: r.table, lambda r: r.owner),
                    lambda name: f"changing {name}", lambda name: f"deforming {name}", by_velocity, has_radius=False)
    warnings = []
    settings = {name: (True, 1, name != "Dust") for name in NAMES}
    table = object_steps(rows, NAMES, settings, len(SHIFTS), warnings)
    assert warnings == []
    np.testing.assert_allclose(table[:, dust], by_velocity[:, dust])  # both Dust instances, by velocity
    np.testing.assert_allclose(table[2, ~dust, 0], frame.table[~dust, 0] + 0.1)  # the others, by their steps
    np.testing.assert_array_equal(table[..., 3], -0.5)


def test_velocity_moved_positions_follow_each_instances_own_transform_motion():
    """Two instances of one object (rows in blocks, instance by instance) moved by a velocity, whose transforms
    at the last step turn the first a quarter turn about z and slide the second 1 m along y: each block is the
    frame's point plus its drift, carried by its own instance's motion; a step whose export lost an instance, and
    an object without velocity, are left as the drift alone and as NaN."""
    from engine.export.velocity import Transforms, moved_positions

    def translate(x, y, z):
        m = np.eye(4)
        m[:3, 3] = (x, y, z)
        return m

    turn = np.array([[0.0, -1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]])
    frame = [np.stack([np.eye(4), translate(5.0, 0.0, 0.0)]), np.eye(4)[None]]
    last = [np.stack([turn, translate(5.0, 1.0, 0.0)]), np.eye(4)[None]]
    transforms = Transforms(["Spray", "Still"], frame, [(frame, ["Spray", "Still"]),
                                                        ([last[1], last[0]], ["Still", "Spray"]),  # another order
                                                        ([frame[0][:1]], ["Spray"])])
    positions = np.array([[1.0, 0.0, 0.0], [6.0, 0.0, 0.0], [0.0, 0.0, 9.0]])
    owner = np.array([0, 0, 1])
    drift = np.zeros((3, 3, 3))
    drift[:, :2, 2] = [[0.0], [0.5], [1.0]]  # Spray rises by its velocity; Still has none
    drift[:, 2] = np.nan
    moved = moved_positions(positions, drift, owner, transforms)
    np.testing.assert_allclose(moved[0, :2], positions[:2])
    np.testing.assert_allclose(moved[1, 0], [0.0, 1.0, 0.5])  # (1, 0, 0.5) turned a quarter about z
    np.testing.assert_allclose(moved[1, 1], [6.0, 1.0, 0.5])  # slid 1 m along y
    np.testing.assert_allclose(moved[2, :2], positions[:2] + [0.0, 0.0, 1.0])  # one instance lost: drift alone
    assert np.isnan(moved[:, 2]).all()
