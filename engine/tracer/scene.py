"""The scene the tracer renders: plain numpy arrays and dataclasses.

The export layer (``engine/export``) builds a ``Scene`` from Blender's evaluated
depsgraph; tests and benchmarks build one directly. Everything is in world space,
in metres, with Blender's axis conventions (Z up; a camera looks down its local -Z
with +Y up). Colours are scene-linear Rec.709 (Blender's default working space).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .data_passes import DataPassInputs
from .errors import PrismInputError
from .primitive_checks import MAX_DISTANCE_M, check_curves, check_points
from .curves import CurveSegments
from .spheres import SpherePoints
from .spectrum_specs import ReflectanceSpec, SampledSpectrum, SpectrumSpec  # noqa: F401 - part of the scene's API


@dataclass
class Material:
    """One surface material.

    kind: ``"diffuse"`` (Lambertian, ``base_color`` albedo), ``"conductor"``
    (``conductor`` names a metal with measured n,k: "Au", "Ag", "Cu", "Al"; when
    None the ``base_color`` is the normal-incidence reflectance), ``"dielectric"``
    (glass: ``glass`` catalogue name, or ``glass_nd``/``glass_vd``, else the
    constant ``ior``), ``"thin_film"`` (free-standing film such as a soap bubble of
    ``film_thickness_nm`` and ``film_ior``: reflects and transmits).
    ``roughness`` is Blender's roughness (GGX alpha = roughness**2).
    A coating of ``coating_thickness_nm`` > 0 (index ``coating_ior``) puts
    thin-film interference over a dielectric or conductor.
    ``emission_strength`` > 0 makes the surface an emitter (radiance =
    strength x spectrum, as Cycles' Emission strength).
    ``reflectance``, when set, replaces ``base_color`` wherever a base colour is
    used (diffuse albedo, a conductor's normal-incidence reflectance).
    ``shader`` (a ``materials.shader.ShaderProgram``), when set, is the material as its Blender node
    tree defines it and replaces the kind-based closure; the other fields then only describe it for
    messages. ``holdout`` (Blender's Holdout shader): camera rays see a transparent black hole in the
    image; other rays a black surface. ``medium`` (a ``media.spec.MediumSpec``), when set, fills the
    closed mesh: its volume shader. Kind ``"null"`` is no surface at all (a volume's boundary).
    """

    name: str
    kind: str = "diffuse"
    base_color: tuple[float, float, float] = (0.8, 0.8, 0.8)
    roughness: float = 0.0
    conductor: str | None = None
    glass: str | None = None
    glass_nd: float | None = None
    glass_vd: float | None = None
    ior: float = 1.5
    coating_thickness_nm: float = 0.0
    coating_ior: float = 1.38
    film_thickness_nm: float = 500.0
    film_ior: float = 1.33
    emission: SpectrumSpec | None = None
    emission_strength: float = 0.0
    aovs: dict = field(default_factory=dict)  # shader AOV name -> (r, g, b, value) on this material
    reflectance: ReflectanceSpec | None = None
    shader: object = None
    holdout: bool = False
    medium: object = None


@dataclass
class Light:
    """A Blender light, in world space.

    kind: ``"point"``, ``"spot"``, ``"area"`` or ``"sun"``.
    ``power_w`` is Blender's Power in watts (point, spot, area): a point light of
    power P has radiant intensity P / (4 pi) W/sr, an area light emits P over its
    area into the hemisphere (radiance P / (pi * area)), as in Cycles.
    ``irradiance_w_m2`` is a sun's Strength. ``direction`` is the light's local -Z
    (where spots, areas and suns point); ``axis_u``/``axis_v`` are its local X/Y.
    ``radius_m`` is the soft radius of point/spot lights (0 = a true point); with
    ``soft_falloff`` (Blender's Soft Falloff, on in new lights) that radius is a disc facing what it
    lights, as Cycles, else a sphere (``lights.point``).
    ``spot_size_rad`` is the full cone angle, ``spot_blend`` Blender's blend.
    ``area_shape``: ``"rectangle"`` or ``"disk"`` with ``size_u_m`` x ``size_v_m``
    (full extents; a disk uses them as diameters); ``spread_rad`` (Cycles' Spread, π:
    a Lambertian emitter) narrows an area light's beam like a soft-box grid.
    ``sun_angle_rad`` is the sun's angular diameter. ``visible_camera``: camera rays see
    the light (area, sphere and sun discs; Object ▸ Visibility ▸ Camera).
    """

    name: str
    kind: str
    position: np.ndarray
    direction: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, -1.0]))
    axis_u: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))
    axis_v: np.ndarray = field(default_factory=lambda: np.array([0.0, 1.0, 0.0]))
    spectrum: SpectrumSpec = field(default_factory=SpectrumSpec)
    power_w: float = 0.0
    irradiance_w_m2: float = 0.0
    radius_m: float = 0.0
    soft_falloff: bool = False
    spot_size_rad: float = np.pi / 4
    spot_blend: float = 0.15
    area_shape: str = "rectangle"
    size_u_m: float = 1.0
    size_v_m: float = 1.0
    sun_angle_rad: float = 0.0
    spread_rad: float = np.pi
    visible_camera: bool = False
    light_group: str = ""  # Blender's Object ▸ Shading ▸ Light Group ("" = none)
    shadow_catcher: bool = True  # Object ▸ Visibility ▸ Shadow Catcher: it lights the shadow catcher pass


@dataclass
class Camera:
    """The active camera.

    ``camera_to_world`` is a 4x4 rigid transform (scale removed); the camera looks
    down local -Z, +Y up, as Blender's. ``film_width_mm`` x ``film_height_mm`` is
    the part of the sensor that maps onto the image (after Blender's sensor fit).
    ``model``: ``"pinhole"``, ``"thin_lens"`` (``fstop`` and
    ``focus_distance_m``; an aperture of ``aperture_blades`` straight blades (below 3: a
    disc) turned by ``aperture_rotation_rad``, anamorphic ``aperture_ratio``) or
    ``"real_lens"`` (``lens_file``, traced element by element; ``fstop`` scales its
    aperture stop, ``sensor_distance_mm`` None means focus at ``focus_distance_m``).
    ``shift_x``/``shift_y`` are Blender's lens shift in units of the larger film
    dimension. ``projection``: ``"perspective"``, ``"orthographic"`` (the view is
    ``ortho_width_m`` x ``ortho_height_m``), ``"equirectangular"`` (longitudes and
    latitudes in radians), ``"fisheye_equidistant"`` (``fisheye_fov_rad``) or
    ``"fisheye_equisolid"`` (``fisheye_lens_mm``, ``fisheye_fov_rad``, the film as its
    sensor), as Cycles defines them (``stages.panorama``). Orthographic rays start ``ortho_start_m``
    behind the camera's plane (Blender's orthographic viewport sees half its clip range behind its
    centre); keeping the camera at the view's centre keeps the camera-relative geometry precise.
    ``clip_start_m`` / ``clip_end_m``: Blender's Clip Start / Clip End; camera rays see only geometry at
    depths between them (along the view axis; along the ray for panoramas), as in Cycles. Clip Start
    beyond Clip End leaves camera rays no geometry to see (Cycles: the world only). Motion blur:
    ``shutter_times`` (``motion.shutter_times``, the ray time's inverse CDF; None: no motion blur) and
    ``motion_to_world`` (the camera's matrices at the shutter's time steps when it moves, else None).
    """

    name: str
    camera_to_world: np.ndarray
    resolution: tuple[int, int]
    focal_length_mm: float = 50.0
    film_width_mm: float = 36.0
    film_height_mm: float = 24.0
    model: str = "pinhole"
    fstop: float = 2.8
    focus_distance_m: float = 10.0
    lens_file: str | None = None
    sensor_distance_mm: float | None = None
    shift_x: float = 0.0
    shift_y: float = 0.0
    aperture_blades: int = 0
    aperture_rotation_rad: float = 0.0
    aperture_ratio: float = 1.0
    projection: str = "perspective"
    ortho_width_m: float = 6.0
    ortho_height_m: float = 4.0
    fisheye_fov_rad: float = np.pi
    fisheye_lens_mm: float = 10.5
    latitude_min_rad: float = -np.pi / 2
    latitude_max_rad: float = np.pi / 2
    longitude_min_rad: float = -np.pi
    longitude_max_rad: float = np.pi
    ortho_start_m: float = 0.0
    clip_start_m: float = 0.0
    clip_end_m: float = float("inf")
    shutter_times: np.ndarray | None = None  # motion blur: ``motion.shutter_times``; None: a still image
    motion_to_world: np.ndarray | None = None  # [S, 4, 4] camera_to_world at the shutter's steps, or None


@dataclass
class Sky:
    """Blender's Nishita Sky Texture (single scattering in a spherical atmosphere, evaluated per
    wavelength): the sun at ``sun_elevation_rad`` above the horizon and ``sun_rotation_rad`` about -Z
    (0 puts it toward +Y, growing toward +X, as Blender's), seen from ``altitude_m``; densities
    relative to Earth's air, dust (aerosols) and ozone. With ``sun_disc`` the sun is a disc of angular
    diameter ``sun_size_rad`` whose radiance is multiplied by ``sun_intensity``."""

    sun_elevation_rad: float = 0.2618
    sun_rotation_rad: float = 0.0
    sun_disc: bool = True
    sun_size_rad: float = 0.009512
    sun_intensity: float = 1.0
    altitude_m: float = 0.0
    air_density: float = 1.0
    dust_density: float = 1.0
    ozone_density: float = 1.0


@dataclass
class World:
    """The background: radiance ``strength`` x (``color``, an equirectangular image or a sky).

    ``kind``: ``"constant"`` (``color``, linear Rec.709), ``"image"`` (``image_rgb`` float32
    [H, W, 3] linear Rec.709, Blender's equirectangular layout: row 0 is the zenith, column 0 the
    direction -X, the image centre +X; ``interpolation`` ``"linear"`` or ``"closest"``) or ``"sky"``
    (``sky``). ``to_texture`` [3, 3] maps a world direction to the direction the texture is looked
    up with (Blender's Mapping node; identity by default; any invertible matrix). ``sampled``: light
    sampling of the world (Cycles' World ▸ Settings ▸ Sampling), else it is found by escaping rays
    only.
    """

    color: tuple[float, float, float] = (0.0, 0.0, 0.0)
    strength: float = 1.0
    light_group: str = ""
    kind: str = "constant"
    image_rgb: np.ndarray | None = None
    interpolation: str = "linear"
    sky: Sky | None = None
    to_texture: np.ndarray = field(default_factory=lambda: np.eye(3))
    sampled: bool = True
    name: str = "World"
    # What camera rays see instead, when the Surface picks a shader by Light Path ▸ Is Camera Ray (a backplate:
    # one background lights the scene, another is seen); None: camera rays see this world too.
    camera_background: "World | None" = None
    # The World Output's Volume (a ``media.spec.MediumSpec``): fog everywhere, the camera included, added to the
    # media of meshes inside them (``media.nesting``); None: vacuum.
    medium: object = None

    def is_black(self) -> bool:
        """True when the background emits nothing (no light to sample or to see)."""
        if not self.strength > 0:
            return True
        if self.kind == "constant":
            return not max(self.color) > 0
        if self.kind == "image":
            return self.image_rgb is None or not np.nanmax(self.image_rgb, initial=0.0) > 0
        return False


@dataclass
class SurfaceAttributes:
    """What node materials read at a hit besides positions and normals (``materials.hit_inputs``).

    ``uvs`` float32 [S, T, 3, 2] (UV slot, triangle, corner), ``colors`` float32 [A, T, 3, 4] (colour
    attributes, RGBA scene-linear), ``tangents`` float32 [S2, T, 3, 4] (unit UV tangent in world space and
    the bitangent sign, per tangent slot), ``triangle_instance`` int32 [T] (row of ``instances``) and
    ``instances`` float64 [I, OBJECT_ROW] (world→object transform, texture space, object info; see
    ``materials.hit_inputs``), ``positions`` float32 [T, 3, 3] (object-space corner positions, exact where
    a world→object round trip would not be: a flat plane's generated z is exactly 0.5). Slots are
    numbered by the material programs that read them.
    """

    uvs: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 3, 2), np.float32))
    colors: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 3, 4), np.float32))
    tangents: np.ndarray = field(default_factory=lambda: np.zeros((0, 0, 3, 4), np.float32))
    triangle_instance: np.ndarray | None = None
    instances: np.ndarray = field(default_factory=lambda: np.zeros((0, 27)))
    positions: np.ndarray = field(default_factory=lambda: np.zeros((0, 3, 3), np.float32))


@dataclass
class Scene:
    """Triangle soup plus materials, lights, camera and world.

    ``vertices`` float64 [V, 3] (m, world space: float64 keeps small objects far from the origin
    exact; the tracer subtracts the camera position before handing geometry to Embree in float32),
    ``triangles`` int32 [T, 3],
    ``triangle_material`` int32 [T] indexes ``materials``, ``triangle_object``
    int32 [T] indexes ``object_names`` (for messages), ``corner_normals`` float32
    [T, 3, 3] (unit shading normals at each triangle corner) or None for flat
    shading. ``object_light_groups`` (parallel to ``object_names``, may be empty): each object's light
    group, for the light its emissive triangles give. ``surface`` holds UV maps, colour attributes,
    tangents and object data for node materials (None when no material reads them). ``object_flags``
    uint8 [objects] (parallel to ``object_names``: ``visibility.RAY_*`` and ``HOLDOUT`` bits; None: every
    object seen by every ray, no holdout). ``data_passes``: what the Mist, UV, Index and AO passes read.
    ``motion`` (``motion.Motion``): the vertices at the shutter's time steps when motion blur is on and
    something moves or deforms, else None. ``light_links`` (``light_linking.LightLinks``): Blender's light
    and shadow linking, per object and per light, or None. ``points`` (``spheres.SpherePoints``): the points
    of point clouds, one sphere each, or None. ``curves`` (``curves.CurveSegments``): the strands of hair
    curves, round Catmull-Rom segments, or None.
    """

    vertices: np.ndarray
    triangles: np.ndarray
    triangle_material: np.ndarray
    materials: list[Material]
    camera: Camera
    lights: list[Light] = field(default_factory=list)
    world: World = field(default_factory=World)
    triangle_object: np.ndarray | None = None
    object_names: list[str] = field(default_factory=list)
    corner_normals: np.ndarray | None = None
    object_flags: np.ndarray | None = None
    object_light_groups: list[str] = field(default_factory=list)
    surface: SurfaceAttributes | None = None
    data_passes: DataPassInputs = field(default_factory=DataPassInputs)
    motion: object = None  # motion.Motion
    light_links: object = None  # light_linking.LightLinks: light and shadow linking (None: none)
    points: SpherePoints | None = None
    curves: CurveSegments | None = None
    triangle_flat: np.ndarray | None = None  # bool [T]: shaded flat (displacement recomputes the others' normals)
    # float32 [T, 2]: each triangle's object's shadow terminator Geometry Offset (0 where shaded flat) and Cycles'
    # Shading Offset multiplier 1 / (1 - offset / 2) (0: none) (``terminator``)
    triangle_terminator: np.ndarray | None = None

    @property
    def triangle_count(self) -> int:
        return int(len(self.triangles))

    def object_name_of_triangle(self, index: int) -> str:
        if self.triangle_object is None or not self.object_names:
            return f"triangle {index}"
        return self.object_names[int(self.triangle_object[index])]

    def validate(self, triangles: bool = True) -> None:
        """Raise ``PrismInputError`` naming the object if the scene cannot render (or would
        render wrong without a word): malformed arrays, non-finite or absurdly distant
        positions, indices that point nowhere. ``triangles=False`` skips the geometry (already
        checked: the viewport changed only materials or lights)."""
        if self.vertices.ndim != 2 or self.vertices.shape[1:] != (3,):
            raise PrismInputError("Scene vertices must be an array of shape [V, 3].")
        self._validate_camera()
        if triangles and len(self.triangles):
            self._validate_triangles()
        slots = (self.surface.colors.shape[0], self.surface.uvs.shape[0]) if self.surface is not None else (0, 0)
        if triangles and self.points is not None and len(self.points):
            check_points(self.points, len(self.materials), self.object_names, slots[0],
                         motion=getattr(self.motion, "points", None))
        if triangles and self.curves is not None and len(self.curves):
            check_curves(self.curves, len(self.materials), self.object_names, *slots,
                         motion=getattr(self.motion, "curves", None))
        for light in self.lights:
            _check_position(f"Light '{light.name}'", light.position)

    def _validate_camera(self) -> None:
        camera = self.camera
        if not np.all(np.isfinite(camera.camera_to_world)):
            raise PrismInputError(
                f"Camera '{camera.name}' has a non-finite transform: reset its location and rotation."
            )
        _check_position(f"Camera '{camera.name}'", camera.camera_to_world[:3, 3])
        width, height = camera.resolution
        if not (int(width) >= 1 and int(height) >= 1):
            raise PrismInputError(f"Camera '{camera.name}': the resolution {width}x{height} has no pixels.")

    def _validate_triangles(self) -> None:
        triangles = np.asarray(self.triangles)
        if triangles.min() < 0 or triangles.max() >= len(self.vertices):
            raise PrismInputError(
                f"Scene triangles refer to vertex {int(triangles.max())} but there are only {len(self.vertices)} "
                "vertices: the exported geometry is inconsistent."
            )
        materials = np.asarray(self.triangle_material)
        if len(materials) != len(triangles) or materials.min() < 0 or materials.max() >= len(self.materials):
            raise PrismInputError(
                f"Scene triangles refer to material {int(materials.max())} but there are only "
                f"{len(self.materials)} materials: the exported materials are inconsistent."
            )
        # Per vertex, then gathered per triangle: a loose vertex no triangle uses cannot spoil the image.
        with np.errstate(invalid="ignore"):
            reach = np.abs(self.vertices).max(axis=1)
        if np.all(reach <= MAX_DISTANCE_M):  # every vertex fine (NaN compares False): no gathering needed
            return
        bad = ~np.isfinite(reach)[triangles].all(axis=1)
        if bad.any():
            name = self.object_name_of_triangle(int(np.flatnonzero(bad)[0]))
            raise PrismInputError(
                f"Object '{name}' has vertices that are NaN or infinite: "
                "fix or delete them (Mesh > Clean Up) before rendering."
            )
        far = (reach > MAX_DISTANCE_M)[triangles].any(axis=1)
        if far.any():
            first = int(np.flatnonzero(far)[0])
            raise PrismInputError(
                f"Object '{self.object_name_of_triangle(first)}' has vertices {reach[triangles[first]].max():.3g} m "
                f"from the world origin; Prism renders scenes within {MAX_DISTANCE_M:.0e} m of it: check the "
                "object's scale and location (Object ▸ Transform), or delete stray vertices."
            )


def _check_position(what: str, position) -> None:
    position = np.asarray(position, dtype=np.float64)
    if not np.all(np.isfinite(position)):
        raise PrismInputError(f"{what} has a non-finite location: reset it (Object ▸ Transform ▸ Location).")
    distance = float(np.abs(position).max())
    if distance > MAX_DISTANCE_M:
        raise PrismInputError(
            f"{what} is {distance:.3g} m from the world origin; Prism renders scenes within {MAX_DISTANCE_M:.0e} m "
            "of it: move it closer (Object ▸ Transform ▸ Location)."
        )
