"""Point Cloud objects → spheres (``tracer.spheres.SpherePoints``), one per point, of the point's radius.

Points come from the evaluated depsgraph as Cycles reads them: Point Cloud objects and the point clouds
Geometry Nodes make (Mesh to Points, Distribute Points on Faces, Points), which ``object_instances`` lists
as POINTCLOUD instances of their own. Positions and the ``radius`` attribute are read with ``foreach_get``;
without a ``radius`` attribute Blender 4.5 gives every point 0.01 m (``Point.radius``, checked with bpy
4.5.15), which is what is read. The material is the slot the point's ``material_index`` attribute names
(slot 0 without one). An instance's transform moves the centres and scales the radii by the cube root of
its determinant's magnitude (a sphere stays a sphere, as in Cycles). The attributes node materials read
(Attribute, Color Attribute) are read per point, as the mesh export converts them (``mesh_attributes``), and
a point reads its own value anywhere on its sphere, as Cycles reads a point-cloud attribute; a cloud without
the attribute reads 0 (black, alpha 0). A 3D-vector ``velocity`` attribute on the points (m/s, what simulations
write; ``velocity``) is read too: motion blur moves points by it, as Cycles does (``point_motion``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .mesh_attributes import domain_rgba
from .velocity import read_velocity

DEFAULT_RADIUS_M = 0.01


@dataclass
class LocalPoints:
    """One evaluated point cloud in object space: ``positions`` float64 [P, 3], ``radii`` float64 [P] (m),
    ``slot`` int32 [P] (material slot of each point), ``slot_materials`` as ``mesh_data.LocalMesh``, ``colors``
    {slot: float32 [P, 4]} (the attributes node materials read, RGBA per point), ``velocity`` float64 [P, 3] (the
    points' ``velocity`` attribute, m/s, object space; None without one)."""

    positions: np.ndarray
    radii: np.ndarray
    slot: np.ndarray
    slot_materials: list
    colors: dict = field(default_factory=dict)
    velocity: np.ndarray | None = None

    @property
    def texture_space(self):
        """(location, size) of the points' bounds, Blender's automatic texture space."""
        lo, hi = self.positions.min(axis=0), self.positions.max(axis=0)
        return 0.5 * (lo + hi), 0.5 * (hi - lo)


def read_points(obj, request=None) -> LocalPoints | None:
    """The evaluated points of a POINTCLOUD object, with the attributes ``request`` (``AttributeRequest``) names;
    None when it has none."""
    cloud = obj.data
    count = len(cloud.points)
    if count == 0:
        return None
    positions = np.empty(count * 3, np.float32)
    cloud.points.foreach_get("co", positions)
    radii = np.empty(count, np.float32)
    cloud.points.foreach_get("radius", radii)  # DEFAULT_RADIUS_M where the cloud has no radius attribute
    slot = np.zeros(count, np.int32)
    material_index = cloud.attributes.get("material_index")
    if material_index is not None and material_index.domain == "POINT":
        material_index.data.foreach_get("value", slot)
    return LocalPoints(positions.reshape(-1, 3).astype(np.float64), radii.astype(np.float64), slot,
                       [slot.material for slot in obj.material_slots], _point_colors(cloud, request),
                       read_velocity(cloud, count))


def _point_colors(cloud, request) -> dict:
    """{slot: float32 [P, 4]}: the attributes ``request`` names ("" is the default colour attribute) at each point
    of ``cloud`` (``bpy.types.PointCloud``), for those it has on the point domain."""
    colors = {}
    for slot, name in (request.attributes.items() if request is not None else ()):
        rgba = domain_rgba(cloud, name, ("POINT",))[1]
        if rgba is not None:
            colors[slot] = rgba
    return colors


def place_points(local: LocalPoints, matrices: np.ndarray):
    """(centres float64 [K*P, 3], radii float64 [K*P]) of the points at each of ``matrices`` [K, 4, 4]."""
    linear, offset = matrices[:, :3, :3], matrices[:, :3, 3]
    centres = np.einsum("kij,pj->kpi", linear, local.positions) + offset[:, None, :]
    with np.errstate(invalid="ignore"):
        scale = np.cbrt(np.abs(np.linalg.det(linear)))
    radii = scale[:, None] * local.radii[None, :]
    return centres.reshape(-1, 3), radii.reshape(-1)


def point_random(count: int) -> np.ndarray:
    """float32 [count]: Point Info ▸ Random of points 0 .. count - 1, a hash of the point's index (the
    "lowbias32" integer hash) mapped to [0, 1]: uniform and the same for every instance of a cloud, but not
    Cycles' own values."""
    x = np.arange(count, dtype=np.uint64)
    mask = np.uint64(0xFFFFFFFF)
    x ^= x >> np.uint64(16)
    x = (x * np.uint64(0x7FEB352D)) & mask
    x ^= x >> np.uint64(15)
    x = (x * np.uint64(0x846CA68B)) & mask
    x ^= x >> np.uint64(16)
    return (x.astype(np.float64) / 4294967295.0).astype(np.float32)
