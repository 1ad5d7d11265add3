"""What the data passes read besides the hit itself (Mist, UV, Object and Material Index, AO, Vector), from the
scene (``DataPassInputs``, filled by the export) to the kernels' arrays (``first_hit_tables``)."""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass

import numpy as np

#: ``PassData.first_hit_data`` [FIRST_HIT_DATA]: World ▸ Mist Pass start (m), 1 / depth (1/m; 0 for depth 0),
#: falloff exponent, 1 for an orthographic camera (mist then measures along the view axis, as Cycles'
#: ``camera_distance``), World ▸ Ambient Occlusion ▸ Distance (m), View Layer ▸ Passes ▸ Data ▸ Alpha Threshold.
MIST_START, MIST_INV_DEPTH, MIST_FALLOFF, ORTHOGRAPHIC, AO_DISTANCE, ALPHA_THRESHOLD = range(6)
FIRST_HIT_DATA = 6

#: Blender's mist falloffs (World ▸ Mist Pass ▸ Falloff) as Cycles' exponents.
MIST_FALLOFFS = {"QUADRATIC": 2.0, "LINEAR": 1.0, "INVERSE_QUADRATIC": 0.5}
AO_FAR_M = 1e30  # an AO ray's length where the distance is unbounded (float32-representable)
#: Blender's World ▸ Ambient Occlusion ▸ Distance (m) of a new world: the AO pass's, and an Ambient Occlusion
#: node's where its own Distance is 0.
AO_DISTANCE_DEFAULT = 10.0
#: Blender's View Layer ▸ Passes ▸ Data ▸ Alpha Threshold of a new view layer (``ViewLayer.pass_alpha_threshold``).
ALPHA_THRESHOLD_DEFAULT = 0.5


@dataclass
class DataPassInputs:
    """``object_pass_index`` float32 [T] (Object ▸ Relations ▸ Pass Index per triangle) and ``uv`` float32
    [T, 3, 3] (the render UV map per triangle corner as u, v, 1; 0, 0, 0 on a mesh without one, as Cycles): None unless their pass is asked
    for; ``material_pass_index`` one per scene material; World ▸ Mist Pass (m; falloff a ``MIST_FALLOFFS``
    key), World ▸ Ambient Occlusion ▸ Distance (m) and View Layer ▸ Passes ▸ Data ▸ Alpha Threshold (the data
    passes are those of the first surface whose alpha reaches it; 0: the first surface, ``stages.pass_writes``).
    Defaults are Blender's.

    The Vector pass (None unless asked for, and with Render ▸ Motion Blur off, as Cycles):
    ``triangle_motion`` float32 [T, 2, 3, 3], per triangle corner its world displacement to where it is at
    the previous frame (row 0) and at the next frame (row 1), m; ``world_to_raster`` float64 [3, 4, 4], the
    camera's projection from world to pixels (x right, y up, from the image's lower left corner) at the
    previous frame, the frame and the next frame."""

    object_pass_index: np.ndarray | None = None
    uv: np.ndarray | None = None
    material_pass_index: tuple = ()
    mist_start_m: float = 5.0
    mist_depth_m: float = 25.0
    mist_falloff: str = "QUADRATIC"
    ao_distance_m: float = AO_DISTANCE_DEFAULT
    alpha_threshold: float = ALPHA_THRESHOLD_DEFAULT
    triangle_motion: np.ndarray | None = None
    world_to_raster: np.ndarray | None = None
    asset_names: tuple = ()  # Cryptomatte: per scene object, its topmost parent's name (empty: its own)
    material_names: tuple = ()  # Cryptomatte: per scene material, Cycles' name of it (empty: Material.name)


#: The ``stages.pass_writes.PassData`` arrays of a render: see there.
FirstHitTables = namedtuple("FirstHitTables", "first_hit_data object_index material_index triangle_uv "
                                               "triangle_motion world_to_raster row_object")


def first_hit_tables(inputs: DataPassInputs, original_triangle, materials: int, layout, orthographic: bool,
                     sphere_pass_index=None, row_objects=None):
    """The kernels' arrays for ``inputs`` with triangles kept as ``original_triangle`` (their scene
    indices), ``materials`` scene materials and the passes of ``layout`` (``PassLayout``); the rendered
    spheres and curve segments, rows after the triangles, with Object ▸ Pass Index ``sphere_pass_index``
    float32 [S + C] and no UV map (0, 0, 0, as a mesh without one). ``row_objects`` [rows]: the scene object of each row (None:
    object 0), read by Cryptomatte only."""
    spheres = np.zeros(0, np.float32) if sphere_pass_index is None else np.asarray(sphere_pass_index, np.float32)
    data = np.zeros(FIRST_HIT_DATA)
    data[MIST_START] = inputs.mist_start_m
    data[MIST_INV_DEPTH] = 1.0 / inputs.mist_depth_m if inputs.mist_depth_m > 0.0 else 0.0
    data[MIST_FALLOFF] = MIST_FALLOFFS[inputs.mist_falloff]
    data[ORTHOGRAPHIC] = 1.0 if orthographic else 0.0
    data[AO_DISTANCE] = min(float(inputs.ao_distance_m), AO_FAR_M)
    data[ALPHA_THRESHOLD] = min(max(float(inputs.alpha_threshold), 0.0), 1.0)
    object_index = np.zeros(0, np.float32)
    if layout.object_index >= 0 and inputs.object_pass_index is not None:
        object_index = np.ascontiguousarray(np.concatenate(
            [np.asarray(inputs.object_pass_index, np.float32)[original_triangle], spheres]))
    material_index = np.zeros(max(materials, 1))
    material_index[:len(inputs.material_pass_index)] = inputs.material_pass_index
    uv = np.zeros((0, 3, 3), np.float32)
    if layout.uv >= 0 and inputs.uv is not None:
        uv = np.ascontiguousarray(np.concatenate([np.asarray(inputs.uv, np.float32)[original_triangle],
                                                  np.zeros((len(spheres), 3, 3), np.float32)]))
    motion = np.zeros((0, 2, 3, 3), np.float32)
    world_to_raster = np.zeros((3, 4, 4))
    if layout.vector >= 0 and inputs.triangle_motion is not None:  # spheres: still (their motion is not read)
        motion = np.ascontiguousarray(np.concatenate([np.asarray(inputs.triangle_motion, np.float32)[original_triangle],
                                                      np.zeros((len(spheres), 2, 3, 3), np.float32)]))
        world_to_raster = np.ascontiguousarray(inputs.world_to_raster, np.float64)
    row_object = np.zeros(0)
    if layout.cryptomatte >= 0:
        rows = len(original_triangle) + len(spheres)
        row_object = (np.zeros(rows) if row_objects is None
                      else np.ascontiguousarray(np.asarray(row_objects, np.float64)))
    return FirstHitTables(data, object_index, material_index, uv, motion, world_to_raster, row_object)
