"""A Volume object's lattice too large to run its nodes on every voxel: the program runs on every few voxels
(``voxel_inputs.sample_axes``) and its result is interpolated between them (``upsample``)."""

from __future__ import annotations

import numpy as np
import pytest

from engine.tracer.media import voxel_inputs


def test_small_lattices_run_on_every_voxel():
    axes = voxel_inputs.sample_axes((5, 1, 7))
    assert [list(axis) for axis in axes] == [list(range(5)), [0], list(range(7))]
    samples = np.random.default_rng(0).random((5, 1, 7)).astype(np.float32)
    np.testing.assert_array_equal(voxel_inputs.upsample(samples, axes, (5, 1, 7)), samples)


@pytest.mark.parametrize("shape, most", [((20, 9, 31), 600), ((64, 64, 64), 1 << 15), ((100, 3, 2), 60)])
def test_large_lattices_run_on_every_stride_th_voxel_and_the_last(monkeypatch, shape, most):
    monkeypatch.setattr(voxel_inputs, "MAX_BAKED_VOXELS", most)
    axes = voxel_inputs.sample_axes(shape)
    assert int(np.prod([len(a) for a in axes])) <= most
    stride = int(axes[0][1] - axes[0][0])
    assert stride > 1
    for n, axis in zip(shape, axes):
        assert axis[0] == 0 and axis[-1] == n - 1
        assert np.all(np.diff(axis)[:-1] == stride) and 0 < np.diff(axis)[-1] <= stride
    # The smallest such stride: one less would exceed the limit.
    assert np.prod([-(-(n - 1) // (stride - 1)) + 1 for n in shape]) > most


def test_the_upsampled_field_is_exact_for_a_trilinear_field_and_between_its_samples_otherwise(monkeypatch):
    monkeypatch.setattr(voxel_inputs, "MAX_BAKED_VOXELS", 2000)
    shape = (30, 17, 23)
    axes = voxel_inputs.sample_axes(shape)
    i, j, k = np.meshgrid(*[np.arange(n, dtype=np.float64) for n in shape], indexing="ij")
    field = 0.5 + 0.1 * i - 0.03 * j + 0.02 * k + 0.001 * i * j * k  # trilinear: interpolated exactly
    samples = field[np.ix_(*axes)].astype(np.float32)
    np.testing.assert_allclose(voxel_inputs.upsample(samples, axes, shape), field, rtol=1e-5, atol=1e-5)
    curved = np.sin(0.3 * i) * np.cos(0.2 * j) + 0.01 * k * k
    up = voxel_inputs.upsample(curved[np.ix_(*axes)].astype(np.float32), axes, shape)
    np.testing.assert_allclose(up[np.ix_(*axes)], curved[np.ix_(*axes)], atol=1e-6)  # the samples themselves
    assert np.all((up >= curved.min() - 1e-6) & (up <= curved.max() + 1e-6))
