"""Dispersion through a 60-degree N-SF11 prism, traced with the tracer's own geometry
and dielectric code, against Snell's law at both faces; and an end-to-end render."""

import numpy as np
import pytest

from engine.tracer.accel import Accel
from engine.tracer.geometry import offset_origin, prepare_geometry, surface_at
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, SpectrumSpec, World
from engine.tracer.spectra.glass import glass_by_name
from engine.tracer.state import new_ray_queue
from engine.tracer.vec3 import tangents, to_local, to_world

from .bsdf.bsdf_checks import MaterialBSDF
from .tracer_scenes import look_at, make_scene, settings

APEX = np.radians(60.0)


def prism(z_half=1.0):
    """Equilateral prism, side 2 m, apex up (+Y) at (0, sqrt 3), extruded along Z; outward winding."""
    a, b, c = (-1.0, 0.0), (1.0, 0.0), (0.0, np.sqrt(3.0))
    verts = np.array([[*p, z] for z in (-z_half, z_half) for p in (a, b, c)])
    tris = np.array([[0, 2, 1], [3, 4, 5],  # caps
                     [0, 1, 4], [0, 4, 3],  # base AB (y = 0)
                     [1, 2, 5], [1, 5, 4],  # right face BC
                     [2, 0, 3], [2, 3, 5]])  # left face CA
    return verts, tris


def _deviation(theta1, n):
    theta2 = np.arcsin(np.sin(theta1) / n)
    theta4 = np.arcsin(n * np.sin(APEX - theta2))
    return theta1 + theta4 - APEX


def test_rays_through_prism_follow_snell_at_both_faces():
    glass = glass_by_name("N-SF11")
    verts, tris = prism()
    scene = make_scene([(verts, tris, 0)], [Material("prism", kind="dielectric", glass="N-SF11")],
                       Camera("c", np.eye(4), (1, 1)))
    geometry, _, _ = prepare_geometry(scene, np.zeros(3))
    acc = Accel(geometry)
    bsdf = MaterialBSDF(scene.materials[0])
    lam = np.linspace(400.0, 700.0, 31)[:, None]
    n = len(lam)
    left_normal = np.array([-np.sqrt(3) / 2, 0.5, 0.0])
    theta1 = np.radians(60.0)
    # incident direction: -normal rotated by theta1 towards the apex side
    rot = np.array([[np.cos(theta1), -np.sin(theta1), 0], [np.sin(theta1), np.cos(theta1), 0], [0, 0, 1]])
    d_in = rot @ -left_normal
    hit_point = np.array([-0.5, np.sqrt(3) / 2, 0.1])
    o = np.repeat((hit_point - 3 * d_in)[None], n, 0)
    d = np.repeat(d_in[None], n, 0)
    rays = new_ray_queue(n)
    for face in (6, 4):  # enters the left face, leaves the right face
        rays.origin[:], rays.direction[:] = o, d
        tri, t, bu, bv = acc.intersect(rays, n)
        assert set(tri) <= {face, face + 1}
        hits = [surface_at(geometry, int(tri[j]), float(bu[j]), float(bv[j]), 0.5) for j in range(n)]
        frames = [(*tangents(ng), ng) for _, ng, _ in hits]
        wo = np.array([to_local(tuple(-dj), *f) for dj, f in zip(d, frames)])
        u = np.tile([0.99999, 0.5, 0.5], (n, 1))  # choose refraction
        s = bsdf.sample(wo, lam, u, np.zeros(n, int), np.ones(n, bool))
        d = np.array([to_world(tuple(w), *f) for w, f in zip(s.wi, frames)])
        o = np.array([offset_origin(p, ng, tuple(dj)) for (p, ng, _), dj in zip(hits, d)])
    index = glass.index(lam[:, 0])
    expected = _deviation(theta1, index)
    measured = np.arccos(np.clip(d @ d_in, -1, 1))
    assert np.allclose(measured, expected, atol=1e-6)
    assert np.all(np.diff(measured) < 0)  # blue bends more than red
    assert np.allclose(d[:, 2], 0.0, atol=1e-6) and np.all(d[:, 1] < d_in[1])  # bent towards the base


def test_render_through_prism_spreads_a_white_line_into_a_spectrum():
    """A thin emissive slit seen through the prism: each wavelength sees it at its own
    deviation, so red and blue land on different columns, in Snell's order."""
    verts, tris = prism(z_half=2.0)
    glass = glass_by_name("N-SF11")
    theta1 = np.radians(60.0)
    left_normal = np.array([-np.sqrt(3) / 2, 0.5, 0.0])
    rot = np.array([[np.cos(theta1), -np.sin(theta1), 0], [np.sin(theta1), np.cos(theta1), 0], [0, 0, 1]])
    d_in = rot @ -left_normal
    entry = np.array([-0.5, np.sqrt(3) / 2, 0.0])
    out_angle = np.arctan2(d_in[1], d_in[0]) - _deviation(theta1, glass.index(550.0))
    d_out = np.array([np.cos(out_angle), np.sin(out_angle), 0.0])
    # far away (200 m), so the viewing-angle formula below needs no parallax correction
    centre = np.array([0.5, np.sqrt(3) / 2 - 0.1, 0.0]) + 200.0 * d_out
    side = np.cross(d_out, [0, 0, 1.0]) * 0.5
    up = np.array([0, 0, 50.0])
    slit = (np.array([centre - side - up, centre + side - up, centre + side + up, centre - side + up]),
            np.array([[0, 1, 2], [0, 2, 3]]))
    mats = [Material("prism", kind="dielectric", glass="N-SF11"),
            Material("slit", base_color=(0, 0, 0), emission=SpectrumSpec(), emission_strength=5.0)]
    cam = Camera("cam", look_at(entry - 4.0 * d_in, entry, up=(0, 0, 1)), (48, 8), focal_length_mm=50.0,
                 film_width_mm=36.0, film_height_mm=6.0)
    scene = make_scene([(verts, tris, 0), (*slit, 1)], mats, cam, world=World())
    r = Renderer(scene, settings(samples=32, samples_per_pass=32, max_bounces=4, wavelength_mode="gaussian_rgb"))
    r.render_pass()
    assert "hero-wavelength termination" in r.strategy and r.stats["nan_samples"] == 0
    img = r.image_rgb().astype(np.float64).mean(0)  # [W, 3]
    # the direct image of the slit (a fainter ghost, reflected inside the prism, lies further right)
    peak = int(np.argmax(img[:, 1]))
    window = slice(max(peak - 8, 0), peak + 9)
    x = np.arange(img.shape[0])[window]
    red, blue = (img[window, c].clip(0) for c in (0, 2))
    assert red.sum() > 0 and blue.sum() > 0
    centroid_r = (x * red).sum() / red.sum()
    centroid_b = (x * blue).sum() / blue.sum()
    # Seen from the camera the output direction is fixed (towards the slit), so the viewing
    # angle changes by d(theta1) = sin(A) dn / (cos theta1 cos theta3); R ~ 600 nm, B ~ 450 nm.
    n = glass.index(550.0)
    theta3 = APEX - np.arcsin(np.sin(theta1) / n)
    px_per_rad = 48 / 2 / (18.0 / 50.0)
    dn = glass.index(450.0) - glass.index(600.0)
    predicted = px_per_rad * np.sin(APEX) * dn / (np.cos(theta1) * np.cos(theta3))
    assert predicted > 2
    assert centroid_r - centroid_b == pytest.approx(predicted, rel=0.15)
