"""Small scenes built in code for the tracer's tests (not a test module)."""

from __future__ import annotations

import numpy as np

from engine.tracer.scene import Camera, Light, Material, Scene, World
from engine.tracer.settings import RenderSettings


def look_at(eye, target, up=(0.0, 0.0, 1.0)):
    """4x4 camera-to-world matrix of a Blender camera at ``eye`` looking at ``target``."""
    eye = np.asarray(eye, float)
    forward = np.asarray(target, float) - eye
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, up)
    if np.linalg.norm(right) < 1e-9:
        right = np.cross(forward, (0.0, 1.0, 0.0))
    right /= np.linalg.norm(right)
    true_up = np.cross(right, forward)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2], m[:3, 3] = right, true_up, -forward, eye
    return m


def quad(center, u, v):
    """Two triangles of the parallelogram center +- u +- v, normal along u x v."""
    c, u, v = (np.asarray(a, float) for a in (center, u, v))
    verts = np.array([c - u - v, c + u - v, c + u + v, c - u + v])
    return verts, np.array([[0, 1, 2], [0, 2, 3]])


def uv_sphere(center, radius, rings=24, segments=48, inward=False):
    """Closed triangulated sphere (outward normals unless ``inward``)."""
    th = np.linspace(0, np.pi, rings + 1)
    ph = np.linspace(0, 2 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(th, ph, indexing="ij")
    verts = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], -1).reshape(-1, 3)
    verts = verts * radius + np.asarray(center, float)
    tris = []
    for i in range(rings):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            c, d = a + segments, b + segments
            tris += [[a, c, d], [a, d, b]]
    tris = np.array(tris)
    if inward:
        tris = tris[:, ::-1]
    return verts, tris


def merge(*parts):
    """Concatenate (verts, tris, material_index) parts into scene arrays."""
    verts, tris, mats, offset = [], [], [], 0
    for v, t, m in parts:
        verts.append(v)
        tris.append(t + offset)
        mats.append(np.full(len(t), m))
        offset += len(v)
    return (np.concatenate(verts).astype(np.float64), np.concatenate(tris).astype(np.int32),
            np.concatenate(mats).astype(np.int32))


def make_scene(parts, materials, camera, lights=(), world=None):
    v, t, m = merge(*parts) if parts else (np.zeros((0, 3)), np.zeros((0, 3), np.int32),
                                           np.zeros(0, np.int32))
    return Scene(vertices=v, triangles=t, triangle_material=m, materials=list(materials), camera=camera,
                 lights=list(lights), world=world or World())


def settings(**kw):
    base = dict(samples=4, samples_per_pass=4, seed=1, threads=2)
    base.update(kw)
    return RenderSettings(**base)


def plane_under_point_light(size=32, power=100.0, height=2.0, albedo=0.5, fov_half_width=1.0):
    """Diffuse plane z=0 seen from straight above, point light at (0,0,height)."""
    cam = Camera("cam", look_at((0, 0, 5.0), (0, 0, 0), up=(0, 1, 0)), (size, size), focal_length_mm=50.0,
                 film_width_mm=36.0 * fov_half_width, film_height_mm=36.0 * fov_half_width)
    floor = quad((0, 0, 0), (20, 0, 0), (0, 20, 0))
    light = Light("lamp", "point", np.array([0.0, 0.0, height]), power_w=power)
    return make_scene([(*floor, 0)], [Material("floor", base_color=(albedo,) * 3)], cam, [light])


def sphere_under_sky(size=24, albedo=1.0, mode="cie"):
    """Convex diffuse sphere under a uniform white sky: every pixel equals the sky."""
    cam = Camera("cam", look_at((0, -4.0, 0), (0, 0, 0)), (size, size), film_width_mm=36.0, film_height_mm=36.0)
    sphere = uv_sphere((0, 0, 0), 1.0, rings=16, segments=32)
    return make_scene([(*sphere, 0)], [Material("white", base_color=(albedo,) * 3)], cam,
                      world=World(color=(1.0, 1.0, 1.0), strength=1.0))


def inside_glowing_sphere(size=16, albedo=0.5, strength=1.0):
    """Camera inside a closed sphere that emits ``strength`` and reflects ``albedo``:
    radiance = strength * sum_{k=0}^{B+1} albedo^k with B = max_bounces."""
    from engine.tracer.scene import SpectrumSpec

    cam = Camera("cam", look_at((0.1, -0.2, 0.05), (0, 1, 0)), (size, size), film_width_mm=36.0, film_height_mm=36.0)
    sphere = uv_sphere((0, 0, 0), 1.0, rings=12, segments=24, inward=True)
    mat = Material("glow", base_color=(albedo,) * 3, emission=SpectrumSpec(), emission_strength=strength)
    return make_scene([(*sphere, 0)], [mat], cam)


def camera_rays(camera, xy, lens_uv=None, render_settings=None):
    """World-space (origins [N,3], unit directions [N,3]) of a pinhole or thin-lens ``scene.Camera``
    through raster positions ``xy`` [N,2] (pixels from the top-left) and lens samples [N,2]."""
    from engine.tracer.cameras import make_camera
    from engine.tracer.stages.camera import camera_ray

    setup = make_camera(camera, render_settings or RenderSettings())
    lens_uv = np.zeros((len(xy), 2)) if lens_uv is None else lens_uv
    rays = [camera_ray(setup.data, float(x), float(y), float(u), float(v), 0.5) for (x, y), (u, v) in zip(xy, lens_uv)]
    origins = np.array([o for o, _ in rays]) + setup.origin
    return origins, np.array([d for _, d in rays])
