"""A fingerprint of what decides a render's image, so chunks of different renders never merge.

The frame is a part of its own, written as the frame number (``"7"``, ``"7.5"`` with a
subframe): two frames of a scene are two renders even where nothing in them moves. The
scene as exported at that frame (geometry, materials, lights, camera, world) and the
settings each get a short hash, so a mismatch can be named. Names of objects and
materials are left out (they only label messages), and a lens file counts by its
content, not its path (farm machines mount the same file at different places). The
settings' sample count, thread count and seed are left out: samples and seed travel
with the chunk itself, threads never change the image.
"""

from __future__ import annotations

import dataclasses
import hashlib
import os

import numpy as np

#: Scene fields that only label messages (and Cryptomatte's names, which label its IDs the same way).
_LABELS = {"name", "object_names", "triangle_object", "asset_names", "material_names"}
#: Scene fields beside the triangles that change the image, hashed with the geometry where a scene has them
#: (absent: the hashes of scenes without them): per-object ray visibility and holdouts, flat shading, the UV maps,
#: colour attributes and object data node materials read, light groups, the data passes' inputs, and the
#: geometry at the shutter's time steps (motion blur).
_GEOMETRY_EXTRAS = ("object_flags", "triangle_flat", "surface", "object_light_groups", "data_passes", "motion",
                    "triangle_terminator")
#: Settings fields a chunk carries itself or that do not change the image.
_PER_CHUNK_SETTINGS = {"samples", "threads", "seed"}
PARTS = ("frame", "geometry", "materials", "lights", "camera", "world", "settings")


def render_fingerprint(scene, settings, frame: float) -> dict[str, str]:
    """Part name → 16 hex digits (the frame: its number), for a ``tracer.Scene`` exported at
    ``frame`` (Blender's current frame plus subframe) and its ``tracer.RenderSettings``."""
    geometry = (scene.vertices, scene.triangles, scene.triangle_material, scene.corner_normals)
    if getattr(scene, "points", None) is not None:  # point clouds (absent: the hashes of scenes before them)
        geometry += (scene.points,)
    if getattr(scene, "curves", None) is not None:  # hair as curves (absent: the hashes of scenes before them)
        geometry += (scene.curves,)
    for name in _GEOMETRY_EXTRAS:
        value = getattr(scene, name, None)
        if value is not None and not _is_default(scene, name, value):
            geometry += (name, value)
    settings_fields = {
        f.name: getattr(settings, f.name) for f in dataclasses.fields(settings) if f.name not in _PER_CHUNK_SETTINGS
    }
    links = getattr(scene, "light_links", None)  # light and shadow linking count with the lights
    lights = scene.lights if links is None else (scene.lights, links)
    values = (geometry, scene.materials, lights, scene.camera, scene.world, settings_fields)
    return {"frame": frame_label(frame), **{part: _digest(value) for part, value in zip(PARTS[1:], values)}}


def _is_default(scene, name: str, value) -> bool:
    """Whether ``value`` is what a scene without the field ``name`` holds (an empty list, the default record)."""
    if isinstance(value, list):
        return not value
    fields = {f.name: f for f in dataclasses.fields(scene)} if dataclasses.is_dataclass(scene) else {}
    factory = getattr(fields.get(name), "default_factory", dataclasses.MISSING)
    return factory is not dataclasses.MISSING and _digest(value) == _digest(factory())


def frame_label(frame: float) -> str:
    """``7.0`` → ``"7"``, ``7.5`` → ``"7.5"``: the frame as people write it."""
    frame = float(frame)
    return str(int(frame)) if frame.is_integer() else repr(frame)


def differing_parts(first: dict[str, str], second: dict[str, str]) -> list[str]:
    """The parts whose hashes differ (all parts when one side lacks them)."""
    return [part for part in PARTS if first.get(part) is None or first.get(part) != second.get(part)]


def _digest(value) -> str:
    hasher = hashlib.blake2b(digest_size=8)
    _feed(hasher, value)
    return hasher.hexdigest()


def _feed(hasher, value) -> None:
    if isinstance(value, np.generic):  # numpy 1 and 2 print scalars differently
        value = value.item()
    if isinstance(value, np.ndarray):
        array = np.ascontiguousarray(value)
        hasher.update(f"array {array.dtype.str} {array.shape}".encode())
        hasher.update(array.tobytes())
    elif dataclasses.is_dataclass(value):
        hasher.update(f"{type(value).__name__}(".encode())
        for item in dataclasses.fields(value):
            if item.name in _LABELS:
                continue
            hasher.update(f"{item.name}=".encode())
            if item.name == "lens_file" and value.lens_file:
                _feed_file(hasher, value.lens_file)
            else:
                _feed(hasher, getattr(value, item.name))
        hasher.update(b")")
    elif isinstance(value, dict):
        for key in sorted(value):
            hasher.update(f"{key}:".encode())
            _feed(hasher, value[key])
    elif isinstance(value, (list, tuple)):
        hasher.update(f"[{len(value)}".encode())
        for item in value:
            _feed(hasher, item)
    elif isinstance(value, float):
        hasher.update(float(value).hex().encode())
    else:
        hasher.update(f"{type(value).__name__}:{value!r};".encode())


def _feed_file(hasher, path) -> None:
    if os.path.isfile(path):
        with open(path, "rb") as handle:
            hasher.update(hashlib.sha256(handle.read()).digest())
    else:
        hasher.update(f"missing:{os.path.basename(path)}".encode())
