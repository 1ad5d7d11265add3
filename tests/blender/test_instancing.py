"""Placing instances in one numpy step: positions as the matrices say, normals through the
inverse-transpose (outward even when mirrored or flattened), winding kept outward."""

from __future__ import annotations

import numpy as np

from engine.export.instancing import instance_triangles, normal_matrices


def test_normal_matrices_are_the_inverse_transpose_up_to_a_positive_factor():
    rng = np.random.default_rng(3)
    linear = rng.normal(size=(50, 3, 3))
    linear[::2, :, 0] *= -1  # mirrored ones too
    expected = np.linalg.inv(linear).transpose(0, 2, 1)
    ratio = normal_matrices(linear) / expected
    assert np.allclose(ratio, ratio[:, :1, :1], rtol=1e-9) and (ratio[:, 0, 0] > 0).all()


def test_a_flattened_instance_keeps_the_normal_of_its_flat_side():
    flat = np.diag([2.0, 3.0, 0.0])[None]  # scaled to zero along z: the xy plane survives
    normal = normal_matrices(flat)[0] @ np.array([0.0, 0.0, 1.0])
    assert np.allclose(normal / np.linalg.norm(normal), [0.0, 0.0, 1.0])


def test_positions_triangles_and_winding_of_each_instance():
    vertices = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    triangles = np.array([[0, 1, 2]])
    normals = np.tile([0.0, 0.0, 1.0], (1, 3, 1)).astype(np.float32)
    plain, mirrored = np.eye(4), np.diag([-1.0, 1.0, 1.0, 1.0])
    plain[:3, 3] = (5.0, 0.0, 0.0)
    placed = instance_triangles(vertices, triangles, normals, np.stack([plain, mirrored]))
    assert np.allclose(placed.vertices[:3], vertices + (5.0, 0.0, 0.0))
    assert np.allclose(placed.vertices[3:], vertices * (-1.0, 1.0, 1.0))
    corners = placed.vertices[placed.triangles]
    geometric = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    assert np.allclose(geometric, [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0]])  # the mirror turned the winding back
    assert np.allclose(placed.corner_normals, [0.0, 0.0, 1.0])
