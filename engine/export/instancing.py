"""Many instances of one object-space mesh → world-space triangles, all at once (numpy, no loop).

Embree as embreex exposes it has no instancing, so every instance becomes its own
triangles. Per instance that costs the mesh's ``T`` triangles x 56 bytes (int32
indices 12, float32 corner normals 36, material and object ids 4 + 4) plus its
``V`` vertices x 24 bytes (float64 world positions); the export also holds a
float64 4x4 matrix (128 bytes) per instance while it runs.

A mirroring transform (negative determinant) turns a triangle's winding over,
which would point its geometric normal inwards; the winding is flipped back (as
Cycles does for negatively scaled objects) so glass still knows its inside.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class WorldTriangles:
    """Triangles of K instances: ``vertices`` float64 [K*V, 3], ``triangles`` int64 [K*T, 3]
    (indices into these vertices), ``corner_normals`` float32 [K*T, 3, 3] (unit)."""

    vertices: np.ndarray
    triangles: np.ndarray
    corner_normals: np.ndarray


def normal_matrices(linear: np.ndarray) -> np.ndarray:
    """[K, 3, 3] matrices that carry normals through ``linear`` [K, 3, 3], up to a positive scale.

    The cofactor matrix (det · inverse-transpose) exists even for a singular matrix;
    multiplied by the sign of the determinant it keeps outward normals outward.
    """
    c0, c1, c2 = (linear[:, :, i] for i in range(3))
    cofactor = np.stack([np.cross(c1, c2), np.cross(c2, c0), np.cross(c0, c1)], axis=2)
    determinant = np.einsum("ki,ki->k", c0, cofactor[:, :, 0])
    # Scaled to entries of at most 1, so float32 holds it for any object scale.
    largest = np.abs(cofactor).max(axis=(1, 2))
    scale = np.where((largest > 0) & np.isfinite(largest), largest, 1.0)
    return cofactor * (np.where(determinant < 0, -1.0, 1.0) / scale)[:, None, None]


#: Vectors per instance from which one matrix product per instance beats one batched product over all of
#: them (numpy hands a 2-D product to BLAS; a batch of many small ones is cheaper in one call).
_VECTORS_FOR_A_PRODUCT_EACH = 256


def _apply(linear: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """``linear`` [K, 3, 3] applied to each of ``vectors`` [N, 3] → [K, N, 3], in their common dtype."""
    if len(vectors) < _VECTORS_FOR_A_PRODUCT_EACH:
        return np.matmul(vectors[None], linear.transpose(0, 2, 1))
    out = np.empty((len(linear), len(vectors), 3), np.result_type(linear, vectors))
    for k in range(len(linear)):
        np.matmul(vectors, linear[k].T, out=out[k])
    return out


def _unit(vectors: np.ndarray) -> np.ndarray:
    length = np.sqrt(np.einsum("...i,...i->...", vectors, vectors))[..., None]
    return vectors / np.where(length > 0, length, 1.0)


def instance_triangles(
    vertices: np.ndarray, triangles: np.ndarray, corner_normals: np.ndarray, matrices: np.ndarray
) -> WorldTriangles:
    """Place one mesh (object space: ``vertices`` [V, 3], ``triangles`` [T, 3], ``corner_normals``
    [T, 3, 3]) at each of ``matrices`` float64 [K, 4, 4] (Blender's ``matrix_world``)."""
    count = len(matrices)
    linear, offset = matrices[:, :3, :3], matrices[:, :3, 3]
    world = _apply(linear, vertices)
    world += offset[:, None, :]
    with np.errstate(invalid="ignore"):  # a NaN transform: Scene.validate names the object
        normal_linear = normal_matrices(linear).astype(np.float32)
    normals = _unit(_apply(normal_linear, corner_normals.reshape(-1, 3).astype(np.float32))).reshape(count, -1, 3, 3)
    base = (np.arange(count, dtype=np.int64) * len(vertices))[:, None, None]
    indices = np.broadcast_to(triangles.astype(np.int64), (count, *triangles.shape)) + base
    mirrored = np.linalg.det(linear) < 0
    if mirrored.any():
        indices[mirrored] = indices[mirrored][:, :, [0, 2, 1]]
        normals[mirrored] = normals[mirrored][:, :, [0, 2, 1]]
    return WorldTriangles(
        vertices=world.reshape(-1, 3),
        triangles=indices.reshape(-1, 3),
        corner_normals=normals.reshape(-1, 3, 3),
    )
