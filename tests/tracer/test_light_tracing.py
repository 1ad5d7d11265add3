"""Light tracing for caustics: the split with path tracing adds up (a furnace, a long path-traced
render, with motion blur too), caustic lines land where Snell's law puts them, and renders stay deterministic."""

import numpy as np
import pytest

from engine.tracer.motion import Motion, shutter_times
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, SpectrumSpec
from engine.tracer.spectra.rgb_to_spectrum import white_rgb

from .tracer_scenes import look_at, make_scene, quad, settings, uv_sphere


def _blocks(image, size):
    h, w = image.shape[:2]
    return image[:h - h % size, :w - w % size].reshape(h // size, size, w // size, size, -1).mean((1, 3))


def _light_part(renderer):
    """The light-traced share of the image, float64 [H, W, 3]."""
    film = renderer.film
    return (film._light_sum / film.light_paths).reshape(film.height, film.width, 3)


def _render(scene, **kw):
    r = Renderer(scene, settings(**kw))
    while r.samples_done < r.settings.samples:
        r.render_pass()
    return r


def test_furnace_with_a_mirror_ball_stays_uniform():
    """A closed sphere that emits E and reflects a (Lambert) is filled with radiance E / (1 - a)
    everywhere; a mirror ball inside changes nothing. The wall around the ball receives a few per
    cent of it as caustics (light → mirror → wall): with light tracing supplying them and path
    tracing skipping them, every part of the image still sees E / (1 - a)."""
    a = 0.5
    shell = uv_sphere((0, 0, 0), 1.0, rings=24, segments=48, inward=True)
    ball = uv_sphere((0.0, 0.35, -0.1), 0.4, rings=24, segments=48)
    materials = [Material("glow", base_color=(a,) * 3, emission=SpectrumSpec(), emission_strength=1.0),
                 Material("mirror", kind="conductor", base_color=(1.0, 1.0, 1.0))]
    camera = Camera("cam", look_at((0, -0.9, 0.0), (0, 1, -0.3)), (32, 32), film_width_mm=36.0, film_height_mm=36.0)
    r = _render(make_scene([(*shell, 0), (*ball, 1)], materials, camera), samples=128, samples_per_pass=64,
                max_bounces=32, light_tracing="on")
    assert "caustics by light tracing (mirror)" in r.strategy and r.stats["nan_samples"] == 0
    white = np.asarray(white_rgb()) / (1 - a)
    image = _blocks(r.image_rgb().astype(np.float64) / white, 4).mean(-1)
    stderr = np.sqrt(_blocks(r.variance_rgb().astype(np.float64) / white ** 2, 4).mean(-1) / 16)
    caustics = _blocks(_light_part(r) / white, 4).mean(-1)
    assert caustics.max() > 0.04  # what the light tracer contributes is far above the tolerance below
    assert np.all(np.abs(image - 1.0) < 4 * stderr + 1e-3), (image - 1.0) / stderr
    assert image.mean() == pytest.approx(1.0, abs=0.004)


def _ball_on_floor(resolution=(32, 24), **camera):
    floor = quad((0, 0, 0), (2, 0, 0), (0, 2, 0))
    ball = uv_sphere((0, 0, 0.5), 0.5, rings=32, segments=64)
    materials = [Material("floor", base_color=(0.8, 0.8, 0.8)), Material("glass", kind="dielectric", glass="N-BK7")]
    light = Light("key", "area", np.array([0.3, 0.0, 2.5]), direction=np.array([-0.1, 0, -1.0]), power_w=1800.0,
                  size_u_m=2.0, size_v_m=2.0)
    cam = Camera("cam", look_at((0, -3.0, 2.5), (0, 0, 0.3)), resolution, film_width_mm=36, film_height_mm=27,
                 **camera)
    return make_scene([(*floor, 0), (*ball, 1)], materials, cam, [light])


@pytest.mark.parametrize("camera, filter", [({}, "box"),
                                            (dict(model="thin_lens", fstop=0.5, focus_distance_m=3.0), "gaussian"),
                                            (dict(model="thin_lens", fstop=0.5, focus_distance_m=2.5, aperture_blades=5,
                                                  aperture_rotation_rad=0.3, aperture_ratio=1.6), "box")])
def test_caustic_of_a_glass_ball_agrees_with_long_path_tracing(camera, filter):
    """A 2 m area light over a glass ball: path tracing alone converges here, slowly. The split
    (caustics by light tracing, the rest by path tracing) agrees with it block by block, in the
    caustic too, through a pinhole with the box filter, a thin lens with the Gaussian filter and Blender's
    five-bladed, anamorphic aperture."""
    scene = _ball_on_floor(**camera)
    reference = _render(scene, samples=2048, samples_per_pass=512, max_bounces=6, light_tracing="off", seed=7,
                        pixel_filter=filter)
    split = _render(scene, samples=512, samples_per_pass=256, max_bounces=6, light_tracing="on", seed=8,
                    pixel_filter=filter)
    assert reference.stats["light_splats"] == 0 and split.stats["light_splats"] > 10_000
    a, b = (_blocks(r.image_rgb().astype(np.float64), 4).mean(-1) for r in (reference, split))
    var = sum(_blocks(r.variance_rgb().astype(np.float64), 4).mean(-1) / 16 for r in (reference, split))
    z = (a - b) / np.sqrt(var + 1e-12)
    caustic = _blocks(_light_part(split), 4).mean(-1) > 0.25 * b
    assert caustic.sum() >= 2  # blocks where light tracing brings a quarter of the light or more
    assert np.all(np.abs(z) < 4.5), z
    assert np.abs(z[caustic]).max() < 3.5 and abs(z.mean()) < 0.5, (z.mean(), z[caustic])
    assert abs(b[caustic].sum() - a[caustic].sum()) < 3.5 * np.sqrt(var[caustic].sum())


def _z_against(reference, split):
    """Per 4 × 4 block: (split's luminance - reference's) / the standard error of the difference, and split's."""
    a, b = (_blocks(r.image_rgb().astype(np.float64), 4).mean(-1) for r in (reference, split))
    var = sum(_blocks(r.variance_rgb().astype(np.float64), 4).mean(-1) / 16 for r in (reference, split))
    return (a - b) / np.sqrt(var + 1e-12), b


@pytest.mark.parametrize("moves", ["ball", "camera"])
def test_light_traced_caustics_blur_with_the_shutter_as_path_traced_ones(moves):
    """Motion blur: the glass ball slides 0.8 m while the shutter is open, or the camera does. Each light path
    draws its ray time from the shutter, meets the ball where it is then and connects to the camera where it
    stands then, so the split agrees with long path tracing block by block, in the smeared caustic too; the
    still scene's split does not (the test can fail)."""
    scene = _ball_on_floor()
    scene.camera.shutter_times = shutter_times([1.0, 1.0])
    travel = np.array([-0.4, 0.0, 0.4])
    if moves == "ball":
        ball = np.unique(scene.triangles[scene.triangle_material == 1])
        steps = np.repeat(scene.vertices[None], 3, axis=0)
        steps[:, ball, 0] += travel[:, None]
        scene.motion = Motion(steps)
    else:
        scene.camera.motion_to_world = np.stack([look_at((dx, -3.0, 2.5), (dx, 0, 0.3)) for dx in travel])
    reference = _render(scene, samples=2048, samples_per_pass=512, max_bounces=6, light_tracing="off", seed=7)
    split = _render(scene, samples=512, samples_per_pass=256, max_bounces=6, light_tracing="on", seed=8)
    assert "caustics by light tracing (glass)" in split.strategy and split.stats["light_splats"] > 10_000
    z, b = _z_against(reference, split)
    caustic = _blocks(_light_part(split), 4).mean(-1) > 0.25 * b
    assert caustic.sum() >= 2
    assert np.all(np.abs(z) < 4.5), z
    assert np.abs(z[caustic]).max() < 3.5 and abs(z.mean()) < 0.5, (z.mean(), z[caustic])
    still = _render(_ball_on_floor(), samples=512, samples_per_pass=256, max_bounces=6, light_tracing="on", seed=8)
    assert np.abs(_z_against(reference, still)[0]).max() > 6.0


def test_chunks_threads_and_sample_chunks_give_identical_light_traced_images():
    scene = _ball_on_floor(resolution=(64, 64))
    images = []
    for threads in (1, 2):  # 64 x 64 x 4 paths: 2 chunks with one thread, 4 with two
        with Renderer(scene, settings(samples=4, samples_per_pass=4, threads=threads, light_tracing="on")) as r:
            r.render_pass()
            assert r.stats["light_splats"] > 0
            images.append(r.film.mean())
    assert np.array_equal(images[0], images[1])
    with Renderer(scene, settings(samples=4, samples_per_pass=2, light_tracing="on")) as whole, \
            Renderer(scene, settings(samples=2, samples_per_pass=2, light_tracing="on")) as first, \
            Renderer(scene, settings(samples=2, samples_per_pass=2, light_tracing="on")) as second:
        whole.render_pass()
        whole.render_pass()
        first.render_pass()
        second.start_at_sample(2)
        second.render_pass()
        assert first.film.light_paths + second.film.light_paths == whole.film.light_paths
        assert np.array_equal(first.film._light_sum + second.film._light_sum, whole.film._light_sum)


def test_scenes_without_caustics_render_exactly_as_with_light_tracing_off():
    floor = quad((0, 0, 0), (2, 0, 0), (0, 2, 0))
    rough = uv_sphere((0, 0, 0.5), 0.5, rings=8, segments=16)
    materials = [Material("floor", base_color=(0.8, 0.8, 0.8)),
                 Material("frosted", kind="dielectric", glass="N-BK7", roughness=0.4)]
    light = Light("lamp", "point", np.array([0.5, 0.0, 2.0]), power_w=100.0)
    cam = Camera("cam", look_at((0, -3.0, 2.5), (0, 0, 0.3)), (16, 12), film_width_mm=36, film_height_mm=27)
    scene = make_scene([(*floor, 0), (*rough, 1)], materials, cam, [light])
    images = {}
    for mode in ("auto", "off"):
        with Renderer(scene, settings(samples=4, light_tracing=mode)) as r:
            r.render_pass()
            assert not r.tables.analysis.light_tracing and r.film.light_paths == 0
            images[mode] = r.film.mean()
    with Renderer(scene, settings()) as r:
        assert "no caustics to light-trace" in r.strategy
    assert np.array_equal(images["auto"], images["off"])


# N-SF11 in the SCHOTT catalogue: n² = 1 + Σ B λ² / (λ² - C), λ in µm
SELLMEIER_B = (1.73759695, 0.313747346, 1.89878101)
SELLMEIER_C = (0.013188707, 0.0623068142, 155.23629)
LINES_NM = (486.1, 587.6, 656.3)  # Fraunhofer F, d, C


def _n_sf11(wavelength_nm):
    l2 = (wavelength_nm / 1000.0) ** 2
    return np.sqrt(1 + sum(b * l2 / (l2 - c) for b, c in zip(SELLMEIER_B, SELLMEIER_C)))


def _refract(d, n, eta):
    """Snell's law for unit ``d`` hitting a surface of unit normal ``n`` (n · d < 0), eta = n1 / n2."""
    c = -d @ n
    return eta * d + (eta * c - np.sqrt(1 - eta ** 2 * (1 - c * c))) * n


def test_caustic_lines_land_where_snell_and_sellmeier_put_them():
    """Three monochromatic suns (F, d and C lines) shine through a 4 mm slit onto a 60° N-SF11 prism;
    each refracted sheet draws a line on a wall 0.6 m away (F and C 50 px apart). The lines' centres in
    the image are where the slit's rays land after Snell's law at both faces with the catalogue's
    Sellmeier index, projected through the pinhole: within 0.3 px (0.2 mm on the wall, Δn ≈ 2e-4)."""
    side, half_height = 0.2, 0.1
    a, b, c = np.array([-side / 2, 0, 0]), np.array([side / 2, 0, 0]), np.array([0, side * np.sqrt(3) / 2, 0])
    prism = (np.array([[*p[:2], z] for z in (-half_height, half_height) for p in (a, b, c)]),
             np.array([[0, 2, 1], [3, 4, 5], [0, 1, 4], [0, 4, 3], [1, 2, 5], [1, 5, 4], [2, 0, 3], [2, 3, 5]]))
    left, right = np.array([-np.sqrt(3) / 2, 0.5, 0.0]), np.array([np.sqrt(3) / 2, 0.5, 0.0])
    turn = np.radians(60.0)  # incidence on the left face
    d_in = np.array([[np.cos(turn), -np.sin(turn), 0], [np.sin(turn), np.cos(turn), 0], [0, 0, 1]]) @ -left
    entry = 0.5 * (a + c)

    def ray(nm, offset=0.0):
        """Exit point and direction of the sunlight that enters ``offset`` m across the slit's centre."""
        start = entry + offset * across / np.linalg.norm(across)
        start = start + ((entry - start) @ left) / (d_in @ left) * d_in  # back onto the face
        inside = _refract(d_in, left, 1 / _n_sf11(nm))
        exit_point = start + ((b - start) @ right) / (inside @ right) * inside
        return exit_point, _refract(inside, -right, _n_sf11(nm))

    up = np.array([0.0, 0.0, 1.0])
    across = np.cross(d_in, up)
    exit_d, out_d = ray(587.6)
    wall_centre, wall_normal = exit_d + 0.6 * out_d, -out_d
    slit_centre, slit, big = entry - 0.15 * d_in, 0.004, 1.0
    parts = [(*prism, 0), (*quad(wall_centre, np.cross(up, wall_normal) * 0.5, up * 0.5), 2)]
    parts += [(*quad(slit_centre + s * across * (slit + big) / 2, across * big / 2, up * big / 2), 1) for s in (-1, 1)]
    eye = wall_centre + 0.45 * wall_normal + 0.2 * up  # above the beams, looking straight at the wall
    width, height, focal, film = 384, 8, 60.0, 36.0  # 0.7 mm x 30 mm per pixel on the wall: the lines' height
    shift = -0.2 / 0.45 * focal / film  # Blender's lens shift (units of the film width) brings the lines down
    camera = Camera("cam", look_at(eye, eye - wall_normal), (width, height), focal_length_mm=focal,
                    film_width_mm=film, film_height_mm=32.0, shift_y=shift)
    suns = [Light(f"{nm} nm", "sun", np.zeros(3), direction=d_in, irradiance_w_m2=20.0,
                  spectrum=SpectrumSpec(kind="monochromatic", wavelength_nm=nm, width_nm=1.0)) for nm in LINES_NM]
    materials = [Material("N-SF11", kind="dielectric", glass="N-SF11"), Material("black", base_color=(0, 0, 0)),
                 Material("wall", base_color=(0.8, 0.8, 0.8))]
    r = _render(make_scene(parts, materials, camera, suns), samples=128, samples_per_pass=64, max_bounces=4)
    assert "caustics by light tracing (N-SF11)" in r.strategy and "guided by 3 emission line(s)" in r.strategy
    profile = r.image_rgb().astype(np.float64).mean(-1).sum(0)
    lit = np.flatnonzero(profile > 0.02 * profile.max())
    runs = np.split(lit, np.flatnonzero(np.diff(lit) > 1) + 1)
    assert len(runs) == 3, runs
    measured = [(x * profile[x]).sum() / profile[x].sum() + 0.5 for x in runs]  # pixel centres
    right_axis, up_axis, back = (camera.camera_to_world[:3, i] for i in range(3))
    predicted = []
    for nm in LINES_NM:  # the band between the slit's edges, as whole pixels see it
        edges = []
        for offset in (-slit / 2, slit / 2):
            p, d = ray(nm, offset)
            q = p + ((wall_centre - p) @ wall_normal) / (d @ wall_normal) * d - eye
            edges.append(((q @ right_axis) / -(q @ back) / (film / focal) + 0.5) * width)
        lo, hi = sorted(edges)
        pixels = np.arange(int(lo), int(hi) + 1)
        cover = np.clip(np.minimum(pixels + 1, hi) - np.maximum(pixels, lo), 0, None)
        predicted.append((cover * (pixels + 0.5)).sum() / cover.sum())
    assert sorted(predicted, reverse=True) == predicted  # blue bends most: F lands right of d, d of C
    assert np.allclose(sorted(measured, reverse=True), predicted, atol=0.3), (measured, predicted)


def test_spot_light_caustics_follow_the_cone():
    """A spot's falloff belongs to the point it reaches: a cone that holds the glass gives the point
    light's caustic, one turned away gives none."""
    floor = quad((0, 0, 0), (2, 0, 0), (0, 2, 0))
    ball = uv_sphere((0, 0, 0.5), 0.4, rings=16, segments=32)
    materials = [Material("floor"), Material("glass", kind="dielectric", glass="N-BK7")]
    cam = Camera("cam", look_at((0, -3.0, 2.5), (0, 0, 0.3)), (24, 18), film_width_mm=36, film_height_mm=27)
    sums = {}
    for name, kind, direction in (("point", "point", (0, 0, -1)), ("spot", "spot", (0, 0, -1)),
                                  ("away", "spot", (0, 0, 1))):
        light = Light("lamp", kind, np.array([0.1, 0.0, 2.0]), direction=np.array(direction, float), power_w=200.0,
                      spot_size_rad=np.radians(60), spot_blend=0.0)
        with Renderer(make_scene([(*floor, 0), (*ball, 1)], materials, cam, [light]),
                      settings(samples=8, samples_per_pass=8, light_tracing="on")) as r:
            r.render_pass()
            sums[name] = r.film._light_sum.sum()
    assert sums["point"] > 0 and sums["spot"] == sums["point"] and sums["away"] == 0


def test_a_moved_viewport_camera_connects_light_paths_to_where_it_stands():
    """The viewport keeps the render's origin while the camera moves: connections go to the camera's
    position in that space, so the caustic matches a new renderer's at the new place."""
    from dataclasses import replace

    scene = _ball_on_floor(resolution=(24, 18))
    moved = replace(scene.camera, camera_to_world=look_at((0.8, -2.6, 2.2), (0.0, 0.0, 0.3)))
    with Renderer(scene, settings(samples=16, samples_per_pass=16, light_tracing="on")) as r:
        r.render_pass()
        r.set_camera(moved)
        assert np.abs(r.origin - scene.camera.camera_to_world[:3, 3]).max() == 0
        r.render_pass()
        moved_light = _light_part(r)
    with Renderer(replace(scene, camera=moved), settings(samples=16, samples_per_pass=16, light_tracing="on")) as r:
        r.render_pass()
        fresh_light = _light_part(r)
    assert fresh_light.sum() > 0
    assert np.abs(moved_light - fresh_light).sum() < 1e-3 * fresh_light.sum()


def test_a_border_keeps_the_splats_that_land_in_it():
    """A render border (or a tile) has a film of its own: light paths land anywhere in the frame, and
    only the splats inside the border are added."""
    scene = _ball_on_floor(resolution=(32, 24))
    with Renderer(scene, settings(samples=16, samples_per_pass=16, light_tracing="on", border=(8, 12, 24, 24))) as r:
        r.render_pass()
        assert r.film._light_splats.sum() > 0 and r.film.light_paths == 16 * 12 * 16
        image = r.image_rgb()
    assert np.all(image[:12] == 0) and np.all(image[:, :8] == 0) and np.all(np.isfinite(image))
    assert image[12:, 8:24].max() > 0
