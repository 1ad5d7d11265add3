"""Cycles' shadow terminator Geometry Offset (``engine.tracer.terminator``): the smooth surface it lifts shadow rays
to, which rays it lifts, and what it does to a coarse smooth-shaded sphere under a low sun."""

from __future__ import annotations

import math

import numpy as np
import pytest

from engine.tracer.geometry import prepare_geometry
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, World
from engine.tracer.terminator import lifted_ray, smooth_surface_offset, terminator_lift
from engine.tracer.visibility import ALL_RAYS, RAY_SHADOW

from .tracer_scenes import look_at, make_scene, quad, settings, uv_sphere


def _on_sphere(theta, phi):
    return (math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), math.cos(theta))


def _triangle(corners, normals, offset=0.1):
    """The render geometry of one triangle with ``corners`` and corner ``normals``, Geometry Offset ``offset`` (no
    Shading Offset)."""
    scene = make_scene([(np.asarray(corners, float), np.array([[0, 1, 2]]), 0)], [Material("m")],
                       Camera("cam", look_at((0, 0, 5), (0, 0, 0)), (4, 4)))
    scene.corner_normals = np.asarray([normals], np.float32)
    scene.triangle_terminator = np.array([[offset, 0.0]], np.float32)
    return prepare_geometry(scene, (0.0, 0.0, 0.0))[0]


def _sphere_patch(spread_deg):
    """A triangle of a unit sphere, its corners' normals the sphere's."""
    spread = math.radians(spread_deg)
    corners = [_on_sphere(0.5, 0.0), _on_sphere(0.5 + spread, 0.0), _on_sphere(0.5 + 0.5 * spread, spread)]
    return _triangle(corners, corners)


@pytest.mark.parametrize("spread_deg", [10.0, 30.0])
def test_the_lift_clears_the_sphere_the_corner_normals_describe(spread_deg):
    """On a triangle cut from a unit sphere, with the sphere's normals at its corners, the lifted point clears the
    sphere (so the neighbouring facets, inside it, cannot shadow it) and stays under each corner's tangent plane:
    on a convex patch the lift is the interpolated normal times the distance to the nearest of those planes
    (Hanika's linear envelope), which here is above half the quadratic patch's height."""
    geometry = _sphere_patch(spread_deg)
    corners = geometry.vertices.astype(np.float64)
    e1, e2 = corners[1] - corners[0], corners[2] - corners[0]
    ng = np.cross(e1, e2) / np.linalg.norm(np.cross(e1, e2))
    for u, v in ((1 / 3, 1 / 3), (0.2, 0.1), (0.6, 0.3)):
        p = corners[0] + u * e1 + v * e2
        lift = np.asarray(smooth_surface_offset(geometry, 0, u, v, tuple(ng), -1.0))
        normals = corners / np.linalg.norm(corners, axis=1, keepdims=True)
        n = (1.0 - u - v) * normals[0] + u * normals[1] + v * normals[2]
        nearest_plane = min(np.dot(corner - p, normal) for corner, normal in zip(corners, normals))
        assert lift == pytest.approx(n * nearest_plane, rel=1e-5)
        assert np.linalg.norm(p) < 1.0 <= np.linalg.norm(p + lift)
        for corner, normal in zip(corners, normals):
            assert np.dot(p + lift - corner, normal) <= 1e-7


def test_a_flat_shaded_triangle_is_not_lifted():
    """Corner normals equal to the face's: the corner planes are the triangle's own, the lift is 0."""
    corners = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    geometry = _triangle(corners, [(0.0, 0.0, 1.0)] * 3)
    assert smooth_surface_offset(geometry, 0, 0.3, 0.3, (0.0, 0.0, 1.0), -1.0) == (0.0, 0.0, 0.0)


def _lift_toward(geometry, angle_to_ns, angle_to_ng, cutoff_geometry=None):
    """The lift at the centroid toward a light at the given angles (degrees) from the shading normal (tilted
    toward +x) and the geometric normal (+z)."""
    ns = (math.sin(math.radians(angle_to_ng - angle_to_ns)), 0.0, math.cos(math.radians(angle_to_ng - angle_to_ns)))
    toward = (math.sin(math.radians(angle_to_ng)), 0.0, math.cos(math.radians(angle_to_ng)))
    return np.asarray(terminator_lift(cutoff_geometry or geometry, 0, 1 / 3, 1 / 3, (0.0, 0.0, 1.0), ns, toward,
                                      -1.0))


def test_only_rays_near_the_terminator_are_lifted():
    """Cycles' rule: a light whose cosines to the shading and the geometric normal are both above the offset
    (0.1) gets no lift; where the shading cosine drops below it the full lift applies once (cos_s + cos_g) <=
    the offset, and fades in linearly between; an offset of 0 lifts nothing."""
    corners = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    tilted = [(0.3, 0.0, 1.0), (0.0, 0.3, 1.0), (-0.3, -0.3, 1.0)]
    geometry = _triangle(corners, [np.asarray(n) / np.linalg.norm(n) for n in tilted])
    full = np.asarray(smooth_surface_offset(geometry, 0, 1 / 3, 1 / 3, (0.0, 0.0, 1.0), -1.0))
    assert np.linalg.norm(full) > 0.0
    assert not np.any(_lift_toward(geometry, 30.0, 40.0))  # well above the terminator
    # shading cosine 0.05, geometric cosine cos(92°) = -0.035: 2 - (0.05 - 0.035) / 0.1 > 1, the full lift
    cos_s = 0.05
    angle_s = math.degrees(math.acos(cos_s))
    assert _lift_toward(geometry, angle_s, 92.0) == pytest.approx(full, rel=1e-6)
    # geometric cosine 0.16, shading cosine 0.06 (light nearer the shading normal's horizon): 2 - 2.2 < 0: none
    assert not np.any(_lift_toward(geometry, math.degrees(math.acos(0.06)), math.degrees(math.acos(0.16))))
    # shading cosine 0.06, geometric 0.08: amount 2 - 1.4 = 0.6
    lifted = _lift_toward(geometry, math.degrees(math.acos(0.06)), math.degrees(math.acos(0.08)))
    assert lifted == pytest.approx(0.6 * full, rel=1e-4)
    none = _triangle(corners, [np.asarray(n) / np.linalg.norm(n) for n in tilted], offset=0.0)
    assert not np.any(_lift_toward(none, angle_s, 92.0))


def test_a_lifted_ray_is_aimed_again_at_the_light_sample():
    """From the lifted start the ray reaches the same point on the light (Cycles' ``shadow_ray_setup``); toward a
    distant light it keeps its direction; with no lift nothing changes, to the bit."""
    start, toward, distance = lifted_ray((0.0, 0.0, 0.0), (0.0, 0.0, 0.01), (1.0, 0.0, 0.0), 2.0)
    end = np.asarray(start) + distance * np.asarray(toward)
    assert end == pytest.approx((2.0, 0.0, 0.0), abs=1e-12)
    assert lifted_ray((0.0, 0.0, 0.0), (0.0, 0.0, 0.01), (1.0, 0.0, 0.0), math.inf)[1] == (1.0, 0.0, 0.0)
    assert lifted_ray((0.1, 0.2, 0.3), (0.0, 0.0, 0.0), (0.6, 0.0, 0.8), 2.0) == ((0.1, 0.2, 0.3), (0.6, 0.0, 0.8), 2.0)


def _coarse_sphere_under_low_sun(offset, casts_shadow=True):
    """A smooth-shaded 12 × 6 UV sphere (white Lambertian, Max Bounces 0) under a sun 80° from the camera's
    view, seen from the side; ``offset``: its Geometry Offset."""
    vertices, triangles = uv_sphere((0.0, 0.0, 0.0), 1.0, rings=6, segments=12)
    camera = Camera("cam", look_at((0.0, -4.0, 0.0), (0.0, 0.0, 0.0)), (32, 32), film_width_mm=36.0,
                    film_height_mm=36.0)
    travel = np.array([-math.sin(math.radians(80.0)), math.cos(math.radians(80.0)), 0.0])  # from +x, toward +y
    sun = Light("sun", "sun", np.zeros(3), direction=travel, irradiance_w_m2=3.0)
    scene = make_scene([(vertices, triangles, 0)], [Material("white", base_color=(0.8, 0.8, 0.8))], camera, [sun],
                       World(color=(0.0, 0.0, 0.0)))
    corners = vertices[triangles]
    scene.corner_normals = (corners / np.linalg.norm(corners, axis=-1, keepdims=True)).astype(np.float32)
    scene.triangle_terminator = np.tile(np.array([offset, 0.0], np.float32), (len(triangles), 1))
    scene.triangle_object = np.zeros(len(triangles), np.int32)
    scene.object_names = ["Sphere"]
    scene.object_flags = np.array([ALL_RAYS if casts_shadow else ALL_RAYS & ~RAY_SHADOW], np.uint8)
    return scene


def _mean(scene):
    renderer = Renderer(scene, settings(samples=16, samples_per_pass=16, max_bounces=0))
    renderer.render_pass()
    return float(renderer.image_rgb().astype(np.float64).mean())


def test_a_coarse_smooth_sphere_keeps_the_light_its_shading_normals_receive():
    """Without the offset, a coarse smooth sphere's facets shadow the band along the terminator that their
    interpolated normals still turn toward the sun; Cycles' 0.1 gives most of it back. Reference: the same sphere
    casting no shadow (Object ▸ Visibility ▸ Shadow off), which is exactly the shading without self-shadowing.
    The lift never adds light beyond that reference (within noise), and at 0.1 it loses less than a third of
    what the sphere loses without it."""
    unshadowed = _mean(_coarse_sphere_under_low_sun(0.0, casts_shadow=False))
    plain = _mean(_coarse_sphere_under_low_sun(0.0))
    lifted = _mean(_coarse_sphere_under_low_sun(0.1))
    lost, lost_lifted = 1.0 - plain / unshadowed, 1.0 - lifted / unshadowed
    print(f"MEASURED light lost to the facets: {lost:.4f} at Geometry Offset 0, {lost_lifted:.4f} at 0.1")
    assert lost > 0.02
    assert lost_lifted > -0.002
    assert lost_lifted < lost / 3.0


def _floor_under_sun(elevation_deg, multiplier):
    """A white Lambertian floor (flat-shaded) seen from above, under a sun ``elevation_deg`` above the horizon;
    ``multiplier``: its Shading Offset's (0: none)."""
    camera = Camera("cam", look_at((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), up=(0.0, 1.0, 0.0)), (8, 8),
                    film_width_mm=6.0, film_height_mm=6.0)
    sun = Light("sun", "sun", np.zeros(3), direction=np.array([-math.cos(math.radians(elevation_deg)), 0.0,
                                                                -math.sin(math.radians(elevation_deg))]),
                irradiance_w_m2=3.0)
    floor = quad((0.0, 0.0, 0.0), (5.0, 0.0, 0.0), (0.0, 5.0, 0.0))
    scene = make_scene([(*floor, 0)], [Material("white", base_color=(0.8, 0.8, 0.8))], camera, [sun],
                       World(color=(0.0, 0.0, 0.0)))
    scene.triangle_terminator = np.tile(np.array([0.0, multiplier], np.float32), (2, 1))
    return scene


@pytest.mark.parametrize("shading_offset", [0.2, 0.5])
def test_the_shading_offset_stretches_the_light_s_angle_as_cycles(shading_offset):
    """Cycles' Shading Offset s weights light arriving at θ from the normal by cos(m θ) / cos θ, m = 1 / (1 - s / 2)
    (``shift_cos_in``): a Lambertian floor under a sun 30° above the horizon (θ = 60°) shines ρ/π E cos(m θ), every
    pixel exactly (Max Bounces 0). Without the offset, ρ/π E cos θ."""
    m = 1.0 / (1.0 - 0.5 * shading_offset)
    plain = _mean(_floor_under_sun(30.0, 0.0))
    softened = _mean(_floor_under_sun(30.0, m))
    theta = math.radians(60.0)
    # absolute: the plain floor is ρ/π E cos θ, ρ = 0.8, E = 3 W/m²
    assert plain == pytest.approx(0.8 / math.pi * 3.0 * math.cos(theta), rel=0.02)
    assert softened / plain == pytest.approx(math.cos(m * theta) / math.cos(theta), rel=1e-6)
    print(f"MEASURED Shading Offset {shading_offset}: {softened / plain:.5f} of the plain floor "
          f"(closed form {math.cos(m * theta) / math.cos(theta):.5f})")
