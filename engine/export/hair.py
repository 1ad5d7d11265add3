"""Hair Curves objects → round curves: each strand a Catmull-Rom curve through its points swept by a circle of
the interpolated radius (``placed_strands`` → ``tracer.curves.CurveSegments``, Embree's round curves).

Render ▸ Curves ▸ Shape "3D Curves" (``THICK``) is what Cycles renders this way too. "Rounded Ribbons"
(``RIBBONS``, the shape of a new scene) renders the same way: Cycles makes each strand a flat ribbon turned to
face every ray that meets it, as wide as the strand, with a normal rounded across it as if it were a tube; a
round curve shows every ray that same width and those same normals. They differ in where a ray meets the strand
(on the tube's front, not on the ribbon's middle plane: at most one radius), which is far below a pixel for hair.
Measured against Cycles' ribbons on a sunlit groom: within 1.7 % in mean luminance from three sides, where Prism's
former camera-facing triangles were up to 19 % brighter (``tests/blender/test_hair_curves.py -k ribbons``).

The radius is the ``radius`` attribute, or 5 mm where the curves have none (as Cycles); an instance's transform
scales it by the cube root of its determinant's magnitude (Cycles' ``Hair::apply_transform``). Strands are read
with ``foreach_get`` and placed for all strands at once, with the attributes and UV maps their materials read
(``hair_attributes``). With motion blur, curves move with their points, or by their ``velocity`` attribute where
they have one (``hair_motion``).
"""

from __future__ import annotations

from collections import namedtuple
from dataclasses import dataclass, field

import numpy as np

from .hair_attributes import point_values, segment_ends
from .hair_info import strand_info
from .velocity import placed_velocity, read_velocity

DEFAULT_RADIUS_M = 0.005


@dataclass
class LocalHair:
    """Strands in object space: ``points`` float64 [P, 3], ``radii`` float64 [P], ``offsets``
    int64 [C + 1] (curve c holds points offsets[c]..offsets[c+1]-1), ``curve_slot`` int32 [C]
    (material slot of each curve), ``slot_materials`` as ``LocalMesh``, ``attributes`` {slot: float32 [P, 4]}
    and ``uvs`` {slot: float32 [P, 2]} (the attributes and UV maps node materials read, per point:
    ``hair_attributes``; for particle hair the emitter's at each root, ``emitter_roots``) and ``uncarried``,
    the (kind, name) reads the strands have no value for though their source has the data (particle hair)."""

    points: np.ndarray
    radii: np.ndarray
    offsets: np.ndarray
    curve_slot: np.ndarray
    slot_materials: list
    attributes: dict = field(default_factory=dict)
    uvs: dict = field(default_factory=dict)
    uncarried: tuple = ()
    velocity: np.ndarray | None = None  # float64 [P, 3]: the points' ``velocity`` attribute (m/s), or None

    @property
    def texture_space(self):
        """(location, size) of the strands' bounds, Blender's automatic texture space."""
        lo, hi = self.points.min(axis=0), self.points.max(axis=0)
        return 0.5 * (lo + hi), 0.5 * (hi - lo)


def read_hair(obj, request=None) -> LocalHair | None:
    """The evaluated strands of a Curves object, with the attributes and UV maps ``request`` names
    (``AttributeRequest``); None when it has no segment."""
    curves = obj.data
    point_count, curve_count = len(curves.points), len(curves.curves)
    if point_count < 2 or curve_count == 0:
        return None
    points = np.empty(point_count * 3, np.float32)
    curves.points.foreach_get("position", points)
    offsets = np.empty(curve_count + 1, np.int32)
    curves.curve_offset_data.foreach_get("value", offsets)
    radii = np.full(point_count, DEFAULT_RADIUS_M, np.float32)
    if "radius" in curves.attributes:
        curves.points.foreach_get("radius", radii)
    curve_slot = np.zeros(curve_count, np.int32)
    material_index = curves.attributes.get("material_index")
    if material_index is not None and material_index.domain == "CURVE":
        material_index.data.foreach_get("value", curve_slot)
    colors, uvs = point_values(curves, request)
    return LocalHair(
        points=points.reshape(-1, 3).astype(np.float64),
        radii=radii.astype(np.float64),
        offsets=offsets.astype(np.int64),
        curve_slot=curve_slot,
        slot_materials=[slot.material for slot in obj.material_slots],
        attributes=colors,
        uvs=uvs,
        velocity=read_velocity(curves, point_count),
    )


#: One hair's strands placed at its instances (``placed_strands``).
PlacedStrands = namedtuple("PlacedStrands", "points radii offsets curve_slot info colors uvs velocity")


def placed_strands(hair: LocalHair, matrices: np.ndarray) -> PlacedStrands:
    """One hair's strands at each of ``matrices`` [K, 4, 4], the strands with at least 2 points and every point
    finite (C' of them): ``points`` float64 [K*P, 3], ``radii`` float64 [K*P] (scaled by the cube root of each
    transform's determinant's magnitude), ``offsets`` int64 [K*C' + 1], ``curve_slot`` int32 [K*C'], ``info``
    float32 [K*S, 4] (Hair Info per segment: intercept at its two points, the strand's length and random,
    ``hair_info``), ``colors`` {slot: float32 [K*S, 2, 4]} and ``uvs`` {slot: float32 [K*S, 2, 2]} (each
    segment's ends: ``hair_attributes.segment_ends``), ``velocity`` float64 [K*P, 3] (world; None without one)."""
    counts = np.diff(hair.offsets)
    finite = np.isfinite(hair.points).all(axis=1) & np.isfinite(hair.radii)
    strand_of_point = np.repeat(np.arange(len(counts)), counts)
    bad = np.zeros(len(counts), bool)
    bad[strand_of_point[~finite]] = True
    keep = (counts >= 2) & ~bad
    point_kept = keep[strand_of_point]
    local, radii = hair.points[point_kept], np.maximum(hair.radii[point_kept], 0.0)
    kept_counts = counts[keep]
    linear, offset = matrices[:, :3, :3], matrices[:, :3, 3]
    points = np.einsum("kij,pj->kpi", linear, local) + offset[:, None, :]
    with np.errstate(invalid="ignore"):
        scale = np.cbrt(np.abs(np.linalg.det(linear)))
    offsets = np.concatenate([[0], np.cumsum(np.tile(kept_counts, len(matrices)))]).astype(np.int64)
    intercept, length, random = strand_info(hair.points, hair.offsets)
    kept_offsets = np.concatenate([[0], np.cumsum(kept_counts)]).astype(np.int64)
    starts = segment_starts(kept_offsets)
    strand = np.searchsorted(kept_offsets, starts, side="right") - 1
    kept_intercept = intercept[point_kept]
    info = np.column_stack([kept_intercept[starts], kept_intercept[starts + 1], length[keep][strand],
                            random[keep][strand]]).astype(np.float32)
    return PlacedStrands(points.reshape(-1, 3), (scale[:, None] * radii[None, :]).reshape(-1), offsets,
                         np.tile(hair.curve_slot[keep], len(matrices)).astype(np.int32),
                         np.tile(info, (len(matrices), 1)),
                         segment_ends(hair.attributes, point_kept, starts, len(matrices)),
                         segment_ends(hair.uvs, point_kept, starts, len(matrices)),
                         None if hair.velocity is None else placed_velocity(hair.velocity[point_kept],
                                                                            int(point_kept.sum()), matrices))


def segment_starts(offsets: np.ndarray) -> np.ndarray:
    """Index of the first point of every segment (each point but the last of its curve)."""
    is_last = np.zeros(offsets[-1], dtype=bool)
    ends = offsets[1:] - 1
    is_last[ends[ends >= offsets[:-1]]] = True
    return np.flatnonzero(~is_last)
