"""Motion blur against its closed form: an emitting square moving sideways at constant speed during the shutter,
seen by an orthographic camera over a black world, smears into the box convolution of its sharp profile (linear
ramps of width speed × shutter) and keeps its energy; so do a glowing hair strand (a round curve as wide as the
square) and a glowing point (a sphere as wide, its disc smeared) moving the same way; a still square seen by a
camera moving the other way gives the same smear; an emitter moving over a floor lights it as the mean of its
still positions over the shutter; a still scene renders bit for bit as without motion."""

import numpy as np
import pytest

from engine.tracer.curves import CurveSegments, padded_strands
from engine.tracer.motion import Motion, shutter_times
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, SpectrumSpec
from engine.tracer.spheres import SpherePoints
from engine.tracer.spectra.rgb_to_spectrum import white_rgb

from .tracer_scenes import look_at, make_scene, quad, settings

WIDTH_M, PIXELS = 4.0, 64  # the orthographic view: 4 m over 64 px, 1/16 m a pixel
SIDE_M = 1.0  # the square's side
TRAVEL_M = 0.5  # how far it moves while the shutter is open (speed × shutter)
STEPS = 3  # Cycles' default: open, middle, close


def _camera(x=0.0):
    return Camera("cam", look_at((x, 0.0, 5.0), (x, 0.0, 0.0), up=(0, 1, 0)), (PIXELS, PIXELS),
                  projection="orthographic", ortho_width_m=WIDTH_M, ortho_height_m=WIDTH_M,
                  clip_start_m=0.1, clip_end_m=100.0)


def _square_scene(camera):
    square = quad((0.0, 0.0, 0.0), (SIDE_M / 2, 0, 0), (0, SIDE_M / 2, 0))
    glow = Material("glow", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=1.0)
    return make_scene([(*square, 0)], [glow], camera)


def _steps(start_m, end_m, count=STEPS):
    return np.linspace(start_m, end_m, count)


def _render(scene, samples=64, says=""):
    r = Renderer(scene, settings(samples=samples, samples_per_pass=samples, max_bounces=1))
    assert says in r.tables.strategy  # the render stats name what motion blur does
    r.render_pass()
    return r.image_rgb().astype(np.float64)[..., 1] / white_rgb()[1]  # green: radiance 1 reads 1


def _box_profile(shift_m, travel_m):
    """The closed form per pixel column: the square's indicator [-side/2, side/2] + ``shift_m`` convolved
    with a box of width ``travel_m`` (uniform motion over the shutter), averaged over each pixel."""
    edges = (np.arange(PIXELS + 1) / PIXELS - 0.5) * WIDTH_M
    fine = (np.arange(400) + 0.5) / 400  # midpoints: the pixel average as a mean
    x = edges[:-1, None] + np.diff(edges)[:, None] * fine[None, :]

    def covered(a):  # length of [a - travel, a] inside the square, over travel: the box convolution
        lo, hi = -SIDE_M / 2 + shift_m, SIDE_M / 2 + shift_m
        if travel_m == 0.0:
            return ((a >= lo) & (a <= hi)).astype(float)
        return np.clip(np.minimum(a, hi) - np.maximum(a - travel_m, lo), 0.0, None) / travel_m

    return covered(x + travel_m / 2).mean(axis=1)


def _middle_rows(image):
    rows = slice(PIXELS // 2 - 6, PIXELS // 2 + 6)  # well inside the square's height (16 px)
    return image[rows].mean(axis=0)


def _moving_square_scene(travel_m):
    scene = _square_scene(_camera())
    scene.camera.shutter_times = shutter_times([1.0, 1.0])
    scene.motion = Motion(np.stack([scene.vertices + [dx, 0.0, 0.0] for dx in _steps(-travel_m / 2, travel_m / 2)]))
    return scene


def test_a_moving_square_smears_into_the_box_convolution_and_keeps_its_energy():
    sharp = _render(_square_scene(_camera()))
    blurred = _render(_moving_square_scene(TRAVEL_M), says="motion blur (2 moving triangles x3 steps)")
    expected = _box_profile(0.0, TRAVEL_M)
    profile = _middle_rows(blurred)
    # the ramps: linear over TRAVEL_M (8 px), the plateau 1, nothing beyond side + travel
    assert np.abs(profile - expected).max() < 0.03, np.round(np.c_[profile, expected][20:44], 3)
    ramp = profile[(expected > 0.1) & (expected < 0.9)]
    assert len(ramp) >= 2 * (TRAVEL_M / WIDTH_M * PIXELS) - 4  # two ramps, each ~travel wide
    width_px = np.sum(profile > 0.01)  # smear extent: side + travel
    assert abs(width_px - (SIDE_M + TRAVEL_M) / WIDTH_M * PIXELS) <= 1
    # energy: the blurred image holds the sharp one's light (and the closed form: side² × radiance 1)
    energy_sharp, energy_blurred = sharp.sum(), blurred.sum()
    pixel_area = (WIDTH_M / PIXELS) ** 2
    assert energy_blurred / energy_sharp == pytest.approx(1.0, abs=0.01)
    assert energy_sharp * pixel_area == pytest.approx(SIDE_M ** 2, rel=0.01)


def _strand_scene(travel_m):
    """A glowing round strand of diameter ``SIDE_M`` along y across the whole view (its ends outside it), moving
    ``travel_m`` along x over the shutter (3 time steps); a black speck far outside the view is the scene's only
    triangle."""
    glow = Material("glow", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=1.0)
    black = Material("black", base_color=(0.0, 0.0, 0.0))
    scene = make_scene([(*quad((100.0, 0.0, 0.0), (0.1, 0, 0), (0, 0.1, 0)), 1)], [glow, black], _camera())
    points, radii, segments = padded_strands(np.linspace([0.0, -3.0, 0.0], [0.0, 3.0, 0.0], 4), np.full(4, SIDE_M / 2),
                                             np.array([0, 4]))
    scene.curves = CurveSegments(points, radii, segments, np.zeros(len(segments), np.int32),
                                 np.zeros(len(segments), np.int32))
    scene.object_names, scene.triangle_object = ["Hair", "Speck"], np.ones(2, np.int32)
    if travel_m > 0.0:
        scene.camera.shutter_times = shutter_times([1.0, 1.0])
        frame = np.column_stack([points, radii])
        scene.motion = Motion(None, None, np.stack([frame + [dx, 0.0, 0.0, 0.0]
                                                    for dx in _steps(-travel_m / 2, travel_m / 2)]))
    return scene


def test_a_moving_strand_smears_into_the_box_convolution_and_keeps_its_energy():
    sharp = _render(_strand_scene(0.0))
    blurred = _render(_strand_scene(TRAVEL_M), says="motion blur (3 moving curve segments x3 steps)")
    profile = _middle_rows(blurred)
    expected = _box_profile(0.0, TRAVEL_M)
    assert np.abs(profile - expected).max() < 0.03, np.round(np.c_[profile, expected][20:44], 3)
    assert abs(np.sum(profile > 0.01) - (SIDE_M + TRAVEL_M) / WIDTH_M * PIXELS) <= 1  # smear: side + travel
    pixel_area = (WIDTH_M / PIXELS) ** 2
    assert blurred.sum() / sharp.sum() == pytest.approx(1.0, abs=0.01)
    assert sharp.sum() * pixel_area == pytest.approx(SIDE_M * WIDTH_M, rel=0.01)  # the strand across the view


def _point_scene(travel_m):
    """A glowing sphere point of diameter ``SIDE_M`` at the origin, moving ``travel_m`` along x over the shutter (3
    time steps); a black speck far outside the view is the scene's only triangle."""
    glow = Material("glow", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=1.0)
    black = Material("black", base_color=(0.0, 0.0, 0.0))
    scene = make_scene([(*quad((100.0, 0.0, 0.0), (0.1, 0, 0), (0, 0.1, 0)), 1)], [glow, black], _camera())
    scene.points = SpherePoints(np.zeros((1, 3)), np.full(1, SIDE_M / 2), np.zeros(1, np.int32), np.zeros(1, np.int32))
    scene.object_names, scene.triangle_object = ["Dust", "Speck"], np.ones(2, np.int32)
    if travel_m > 0.0:
        scene.camera.shutter_times = shutter_times([1.0, 1.0])
        scene.motion = Motion(None, points=np.stack([[[dx, 0.0, 0.0, SIDE_M / 2]]
                                                     for dx in _steps(-travel_m / 2, travel_m / 2)]))
    return scene


def _disc_smear(travel_m, fine=12):
    """The closed form per pixel: the fraction of the shutter for which a disc of radius ``SIDE_M`` / 2 moving
    uniformly from x = -travel/2 to travel/2 covers the point, averaged over ``fine``² points of the pixel."""
    edges = (np.arange(PIXELS + 1) / PIXELS - 0.5) * WIDTH_M
    offsets = (np.arange(fine) + 0.5) / fine * (WIDTH_M / PIXELS)
    x = (edges[:-1, None] + offsets[None]).reshape(-1)
    y = -x  # the image's rows run from +y down; the disc is symmetric
    half = np.sqrt(np.clip((SIDE_M / 2) ** 2 - y[:, None] ** 2, 0.0, None))  # half-chord at each y
    lo, hi = x[None, :] - half - (-travel_m / 2), x[None, :] + half - (-travel_m / 2)  # centre offsets covering x
    covered = np.clip(np.minimum(hi, travel_m) - np.maximum(lo, 0.0), 0.0, None) / travel_m
    return covered.reshape(PIXELS, fine, PIXELS, fine).mean(axis=(1, 3))


def test_a_moving_point_smears_its_disc_into_the_closed_form_and_keeps_its_energy():
    sharp = _render(_point_scene(0.0))
    blurred = _render(_point_scene(TRAVEL_M), says="motion blur (1 moving spheres x3 steps)")
    expected = _disc_smear(TRAVEL_M)
    # each pixel within 5 standard deviations of its 64 samples' coverage fraction (a binomial; the sampler's
    # stratification keeps it well inside: mean |z| 0.35, max error 0.088), plus 0.01 for the closed form's grid
    sigma = np.sqrt(expected * (1.0 - expected) / 64)
    assert (np.abs(blurred - expected) <= 5.0 * sigma + 0.01).all(), np.abs(blurred - expected).max()
    assert np.abs(_middle_rows(blurred) - _middle_rows(expected)).max() < 0.03  # measured 0.014
    assert abs(np.sum(blurred[PIXELS // 2] > 0.01) - (SIDE_M + TRAVEL_M) / WIDTH_M * PIXELS) <= 1  # side + travel
    pixel_area = (WIDTH_M / PIXELS) ** 2
    assert blurred.sum() / sharp.sum() == pytest.approx(1.0, abs=0.01)
    assert sharp.sum() * pixel_area == pytest.approx(np.pi * (SIDE_M / 2) ** 2, rel=0.01)  # the disc


def test_a_moving_camera_smears_a_still_square_the_same_way():
    scene = _square_scene(_camera())
    scene.camera.shutter_times = shutter_times([1.0, 1.0])
    # the camera moves +x by TRAVEL_M: the square moves -x in the image, the same box convolution
    scene.camera.motion_to_world = np.stack([look_at((dx, 0.0, 5.0), (dx, 0.0, 0.0), up=(0, 1, 0))
                                             for dx in _steps(-TRAVEL_M / 2, TRAVEL_M / 2)])
    profile = _middle_rows(_render(scene, says="motion blur (moving camera)"))
    expected = _box_profile(0.0, TRAVEL_M)
    assert np.abs(profile - expected).max() < 0.03, np.round(np.c_[profile, expected][20:44], 3)


def test_a_shutter_curve_weights_the_ray_time():
    # openness rising linearly from 0 to 1: τ has density 2τ, so the square (moving +x) leaves a brighter
    # trail where it ends: the profile is the box convolution with that density
    scene = _moving_square_scene(TRAVEL_M)
    scene.camera.shutter_times = shutter_times(np.linspace(0.0, 1.0, 33))
    profile = _middle_rows(_render(scene))
    edges = (np.arange(PIXELS + 1) / PIXELS - 0.5) * WIDTH_M
    centres = 0.5 * (edges[1:] + edges[:-1])
    tau = (np.arange(2000) + 0.5) / 2000
    density = 2.0 * tau
    fine = (np.arange(40) + 0.5) / 40
    x = edges[:-1, None] + np.diff(edges)[:, None] * fine[None, :]
    position = -TRAVEL_M / 2 + TRAVEL_M * tau  # the square's centre at τ
    inside = np.abs(x[..., None] - position) <= SIDE_M / 2
    expected = (inside * density).mean(axis=(1, 2)) * 1.0  # E over τ (density mean 1) and over the pixel
    assert np.abs(profile - expected).max() < 0.04, np.round(np.c_[centres, profile, expected][20:44], 3)
    # 0.59 m right of centre the square passes for τ > 0.69 (weight 0.53), as far left for τ < 0.31 (0.10)
    assert profile[PIXELS // 2 + 9] > 0.4 > 0.2 > profile[PIXELS // 2 - 10]


def test_a_still_scene_is_unchanged_by_motion_blur_being_on():
    still = _render(_square_scene(_camera()), samples=16)
    scene = _square_scene(_camera())
    scene.camera.shutter_times = shutter_times([1.0, 1.0])
    scene.motion = Motion(np.stack([scene.vertices] * STEPS))  # nothing moves
    assert np.array_equal(_render(scene, samples=16, says="motion blur (nothing moves)"), still)


def _panel_over_floor(x_m):
    """A 0.6 m emitting panel 1 m over a grey floor, its centre at ``x_m``, seen from under it (the camera at
    0.6 m, looking down: the panel is behind it, so only the light it casts is seen)."""
    floor = quad((0.0, 0.0, 0.0), (4.0, 0, 0), (0, 4.0, 0))
    panel = quad((x_m, 0.0, 1.0), (0.3, 0, 0), (0, -0.3, 0))  # facing down
    materials = [Material("floor", base_color=(0.5, 0.5, 0.5)),
                 Material("panel", base_color=(0.0, 0.0, 0.0), emission=SpectrumSpec(), emission_strength=10.0)]
    camera = Camera("cam", look_at((0.0, 0.0, 0.6), (0.0, 0.0, 0.0), up=(0, 1, 0)), (32, 32),
                    projection="orthographic", ortho_width_m=3.2, ortho_height_m=3.2, clip_start_m=0.1,
                    clip_end_m=10.0)
    return make_scene([(*floor, 0), (*panel, 1)], materials, camera)


def _green_and_variance(scene, samples, seed):
    """(green image, variance of each pixel's estimate) of ``scene``, direct light only."""
    r = Renderer(scene, settings(samples=samples, samples_per_pass=samples, max_bounces=1, seed=seed))
    r.render_pass()
    return r.image_rgb().astype(np.float64)[..., 1], r.variance_rgb().astype(np.float64)[..., 1]


def _blocks(image):
    return image.reshape(8, 4, 8, 4).mean(axis=(1, 3))


def test_a_moving_emitter_lights_the_floor_where_it_is_at_each_ray_time():
    """The panel slides 2 m over the shutter. Light sampling draws it where it stands at the path's time and MIS
    weighs its hits there, so the floor's light is the mean of the floor lit by the still panel over its travel (16
    still renders at the midpoints of 16 equal slices of the shutter): block by block within 4.5 standard errors
    and in total within 1 %; the panel held where it stands at the frame lights a narrower patch."""
    slices = [_green_and_variance(_panel_over_floor(x), 64, k + 2)
              for k, x in enumerate(-1.0 + 2.0 * (np.arange(16) + 0.5) / 16)]
    expected = np.mean([image for image, _ in slices], axis=0)
    expected_var = np.sum([variance for _, variance in slices], axis=0) / 16 ** 2
    scene = _panel_over_floor(0.0)
    panel = np.unique(scene.triangles[scene.triangle_material == 1])
    steps = np.repeat(scene.vertices[None], STEPS, axis=0)
    steps[:, panel, 0] += _steps(-1.0, 1.0)[:, None]
    scene.camera.shutter_times = shutter_times([1.0, 1.0])
    scene.motion = Motion(steps)
    blurred, variance = _green_and_variance(scene, 1024, 1)
    z = (_blocks(blurred) - _blocks(expected)) / np.sqrt((_blocks(variance) + _blocks(expected_var)) / 16 + 1e-12)
    assert np.abs(z).max() < 4.5, np.round(z, 1)
    assert blurred.sum() / expected.sum() == pytest.approx(1.0, abs=0.01)
    held, _ = _green_and_variance(_panel_over_floor(0.0), 64, 1)  # the panel where it stands at the frame
    assert np.abs(_blocks(held) - _blocks(expected)).max() > 0.2 * _blocks(expected).max()
