"""The bake camera (``stages.bake_camera``): paths start from a table of rays, one per texel, that find the
baked surface points; the bounce loop and the passes run as for camera rays. Closed forms: an open diffuse
plane (albedo ρ) under a uniform world of radiance L reflects ρ·L, its Diffuse Direct (divided by colour)
is L, its colour ρ; an emitter's Emit is its radiance; a texel without a point gets no path."""

import numpy as np
import pytest

from engine.render.bake_points import BakeTriangles, bake_ray_table, surface_points
from engine.tracer.pass_table import PassRequest
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, World
from engine.tracer.spectrum_specs import SpectrumSpec
from engine.tracer.stages.bake_camera import BakeRays
from tracer.tracer_scenes import look_at, make_scene, quad, settings

SIZE = 8  # texels a side
ALBEDO = 0.5
RADIANCE = 1.5


def _plane_scene(material):
    """A 2 m square plane at z = 0 facing +Z under a uniform world; the camera only sets the render's origin."""
    camera = Camera("bake", look_at((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), up=(0, 1, 0)), (SIZE, SIZE))
    verts, tris = quad((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    return make_scene([(verts, tris, 0)], [material], camera, world=World((1.0, 1.0, 1.0), RADIANCE)), verts, tris


def _bake(scene, verts, tris, names, samples=64):
    """Bake the plane's texels (its UV map spans the square; texel 0 left without a point) into ``names``
    passes: (Combined [S, S, 3], passes, sample counts)."""
    corners = verts[tris]
    triangles = BakeTriangles(corners, np.broadcast_to([0.0, 0.0, 1.0], corners.shape).copy())
    centres = (np.arange(SIZE) + 0.5) / SIZE * 2.0 - 1.0
    x, y = np.meshgrid(centres, centres)
    x, y = x.ravel(), y.ravel()
    # the quad's triangles are (c0, c1, c2) and (c0, c2, c3) of c0 (-1,-1) c1 (1,-1) c2 (1,1) c3 (-1,1)
    upper = y > x
    primitive = upper.astype(np.int64)
    a, b = (x + 1) / 2, (y + 1) / 2
    u = np.where(upper, 1.0 - b, 1.0 - a)  # weight of c0
    v = np.where(upper, a, a - b)  # weight of c1 (c2 upper)
    with Renderer(scene, settings(samples=samples, samples_per_pass=samples, light_tracing="off",
                                  passes=PassRequest(tuple(names)))) as r:
        r.set_region((0, 0, SIZE, SIZE))
        points = surface_points(triangles, primitive[1:], u[1:], v[1:])
        origin, direction = bake_ray_table(points, r.origin)
        table_origin = np.zeros((SIZE * SIZE, 3))
        table_direction = np.zeros((SIZE * SIZE, 3))
        table_origin[1:], table_direction[1:] = origin, direction
        rays = BakeRays(table_origin, table_direction, np.full(SIZE * SIZE, 0.5), 0, 0, SIZE, SIZE)
        r.set_bake_rays(rays, np.arange(1, SIZE * SIZE))
        while not r.finished:
            r.render_pass()
        return r.film.mean(), r.pass_images(), r.film.counts.copy()


def test_a_diffuse_plane_under_a_uniform_world_bakes_albedo_times_radiance():
    scene, verts, tris = _plane_scene(Material("grey", "diffuse", base_color=(ALBEDO,) * 3))
    image, passes, counts = _bake(scene, verts, tris, ["DiffDir", "DiffInd", "DiffCol", "Emit", "Normal"])
    assert counts.ravel()[0] == 0 and np.all(counts.ravel()[1:] == 64)
    lit = image.reshape(-1, 3)[1:]
    print(f"MEASURED Combined {lit.mean():.4f} (closed form {ALBEDO * RADIANCE})")
    assert lit.mean() == pytest.approx(ALBEDO * RADIANCE, rel=0.01)
    direct = passes["DiffDir"].reshape(-1, 3)[1:]
    assert direct.mean() == pytest.approx(RADIANCE, rel=0.01)  # divided by colour, as Cycles
    assert np.allclose(passes["DiffInd"].reshape(-1, 3)[1:], 0.0)  # nothing else to bounce off
    assert np.allclose(passes["DiffCol"].reshape(-1, 3)[1:], ALBEDO, rtol=0.02)
    assert np.allclose(passes["Emit"], 0.0)
    assert np.allclose(passes["Normal"].reshape(-1, 3)[1:], (0.0, 0.0, 1.0), atol=1e-6)


def test_an_emitter_bakes_its_radiance_into_emit():
    scene, verts, tris = _plane_scene(Material("lamp", "diffuse", base_color=(0.0, 0.0, 0.0),
                                              emission=SpectrumSpec("rgb", rgb=(1.0, 1.0, 1.0)), emission_strength=3.0))
    _, passes, _ = _bake(scene, verts, tris, ["Emit"], samples=16)
    emit = passes["Emit"].reshape(-1, 3)[1:]
    assert np.allclose(emit, 3.0, rtol=0.02)
