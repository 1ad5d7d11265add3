"""The per-corner data and object data node materials read, gathered part by part in the order the
triangles are assembled (``meshes``) into one ``scene.SurfaceAttributes``.

Instances repeat their mesh's corner data; UV tangents turn with each instance's matrix (and flip their
bitangent sign where a mirroring transform flips the winding). Object rows hold each instance's
world→object transform, texture space, location, colour, pass index and random number.
"""

from __future__ import annotations

import numpy as np

from ..tracer.materials.hit_inputs import (O_COLOR, O_GENERATED_OFFSET, O_GENERATED_SCALE, O_LOCATION, O_PASS_INDEX,
                                           O_RANDOM, OBJECT_ROW)
from ..tracer.scene import SurfaceAttributes


def object_rows(matrices, infos, texture_space):
    """float64 [K, OBJECT_ROW] for instances placed by ``matrices`` [K, 4, 4] with ``infos`` (colour RGBA, pass
    index, random id) and the mesh's texture space (location, size)."""
    rows = np.zeros((len(matrices), OBJECT_ROW))
    with np.errstate(all="ignore"):
        inverse = np.linalg.pinv(matrices)
    rows[:, :12] = inverse[:, :3, :4].reshape(-1, 12)
    location, size = (np.asarray(v, np.float64) for v in texture_space)
    size = np.where(np.abs(size) > 1e-12, size, 1.0)
    rows[:, O_GENERATED_SCALE:O_GENERATED_SCALE + 3] = 1.0 / (2.0 * size)
    rows[:, O_GENERATED_OFFSET:O_GENERATED_OFFSET + 3] = (size - location) / (2.0 * size)
    rows[:, O_LOCATION:O_LOCATION + 3] = matrices[:, :3, 3]
    for k, (colour, pass_index, random_id) in enumerate(infos):
        rows[k, O_COLOR:O_COLOR + 4] = colour
        rows[k, O_PASS_INDEX] = pass_index
        rows[k, O_RANDOM] = (int(random_id) & 0xFFFFFFFF) / 4294967295.0
    return rows


class SurfaceCollector:
    """Collects the parts' data; ``surface()`` assembles it (None when no material reads any)."""

    def __init__(self, slots):
        self.slots = slots
        self.parts = []  # (triangle count, {kind: {slot: [K*T, 3, w]}}, triangle → instance row or None)
        self.rows = []

    @property
    def active(self) -> bool:
        return self.slots.any

    def add_mesh(self, local, matrices, infos, mirrored):
        """A mesh placed at ``matrices`` [K, 4, 4] (``mirrored`` [K] bool: winding flipped)."""
        count, triangles = len(matrices), len(local.triangles)
        if not self.active:
            self.parts.append((count * triangles, {}, None))
            return
        data = {"uvs": {}, "colors": {}, "tangents": {}}
        for slot, values in local.uvs.items():
            data["uvs"][slot] = self._placed(values, count, mirrored)
        for slot, values in local.attributes.items():
            data["colors"][slot] = self._placed(values, count, mirrored)
        for slot, values in local.tangents.items():
            linear = matrices[:, :3, :3]
            turned = np.einsum("kij,tcj->ktci", linear, values[..., :3].astype(np.float64))
            turned /= np.maximum(np.linalg.norm(turned, axis=-1, keepdims=True), 1e-20)
            sign = np.where(mirrored[:, None, None], -1.0, 1.0) * values[None, ..., 3]
            placed = np.concatenate([turned, sign[..., None]], axis=-1).astype(np.float32)
            placed[mirrored] = placed[mirrored][:, :, [0, 2, 1]]
            data["tangents"][slot] = placed.reshape(-1, 3, 4)
        instance = None
        if self.slots.objects:
            first = sum(len(r) for r in self.rows)
            self.rows.append(object_rows(matrices, infos, local.texture_space))
            instance = np.repeat(np.arange(first, first + count, dtype=np.int32), triangles)
            data["positions"] = self._placed(local.vertices[local.triangles].astype(np.float32), count, mirrored)
        self.parts.append((count * triangles, data, instance))

    @staticmethod
    def _placed(values, count, mirrored):
        placed = np.broadcast_to(values, (count, *values.shape)).copy()
        placed[mirrored] = placed[mirrored][:, :, [0, 2, 1]]
        return placed.reshape(-1, *values.shape[1:])

    def add_points(self, matrices, infos, texture_space):
        """Object rows of a point cloud's instances at ``matrices`` [K, 4, 4]: int32 [K] (None when no
        material reads object data). Points have no corner data."""
        if not (self.active and self.slots.objects):
            return None
        first = sum(len(r) for r in self.rows)
        self.rows.append(object_rows(matrices, infos, texture_space))
        return np.arange(first, first + len(matrices), dtype=np.int32)

    def surface(self) -> SurfaceAttributes | None:
        if not self.active:
            return None
        total = sum(n for n, _, _ in self.parts)

        def stack(kind, names, width):
            out = np.zeros((len(names), total, 3, width), np.float32)
            start = 0
            for n, data, _ in self.parts:
                for slot, values in (data.get(kind) or {}).items():
                    out[slot, start:start + n] = values
                start += n
            return out

        instance = np.full(total, -1, np.int32)
        start = 0
        for n, _, rows in self.parts:
            if rows is not None:
                instance[start:start + n] = rows
            start += n
        objects = np.concatenate(self.rows) if self.rows else np.zeros((0, OBJECT_ROW))
        positions = np.zeros((total if self.slots.objects else 0, 3, 3), np.float32)
        start = 0
        for n, data, _ in self.parts:
            if "positions" in data:
                positions[start:start + n] = data["positions"]
            start += n
        return SurfaceAttributes(positions=positions, uvs=stack("uvs", self.slots.uv_names, 2),
                                 colors=stack("colors", self.slots.attribute_names, 4),
                                 tangents=stack("tangents", self.slots.tangent_names, 4),
                                 triangle_instance=instance if self.slots.objects else None, instances=objects)


def stacked_slots(pieces: list, slot_count: int, tail: tuple) -> np.ndarray | None:
    """float32 [slot_count, N, *tail] of the values per slot of every piece of points or curve segments
    (``pieces``: (row count, {slot: [rows, *tail]}) in the order the rows are assembled), zeros where a piece
    lacks a slot; None when no piece has any."""
    if slot_count == 0 or not any(values for _, values in pieces):
        return None
    out = np.zeros((slot_count, sum(n for n, _ in pieces), *tail), np.float32)
    start = 0
    for n, values in pieces:
        for slot, rows in values.items():
            out[slot, start:start + n] = rows
        start += n
    return out
