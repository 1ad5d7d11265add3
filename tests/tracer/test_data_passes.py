"""Data passes as Cycles writes them (Mist, UV, IndexOB, IndexMA, AO), each against its closed form, also behind
cut-outs."""

import numpy as np

from engine.tracer.bsdf.closure import DIFFUSE, TRANSPARENT
from engine.tracer.data_passes import DataPassInputs
from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram
from engine.tracer.pass_table import PassRequest
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Material, World
from tracer.tracer_scenes import look_at, make_scene, quad, settings
from tracer.test_passes import _facing_wall


def _passes(scene, names, **kw):
    with Renderer(scene, settings(passes=PassRequest(tuple(names)), **kw)) as r:
        while not r.finished:
            r.render_pass()
        return {k: v.astype(np.float64) for k, v in r.pass_images().items()}


def _wide_wall(distance=3.0):
    """The wall of ``test_passes`` filling the middle of a wide view (4 m of 7.2 m), background around."""
    scene = _facing_wall(distance=distance, world=World((0.2, 0.2, 0.2), 1.0))
    scene.camera.focal_length_mm = 15.0
    scene.camera.film_width_mm = scene.camera.film_height_mm = 36.0
    return scene


def _pixel_mean(f, size=16, tan_half=1.2, sub=32):
    """The mean of f(tan_x, tan_z) over each pixel of a square pinhole view (rows top down), by a sub x
    sub grid."""
    t = (np.arange(size * sub) + 0.5) / (size * sub) * 2.0 - 1.0
    tx, tz = np.meshgrid(t * tan_half, -t * tan_half)
    return f(tx, tz).reshape(size, sub, size, sub).mean((1, 3))


def test_mist_follows_cycles_falloffs_of_the_distance_from_the_camera():
    for falloff, power in (("LINEAR", 1.0), ("QUADRATIC", 2.0), ("INVERSE_QUADRATIC", 0.5)):
        scene = _wide_wall(3.0)
        scene.data_passes = DataPassInputs(mist_start_m=2.0, mist_depth_m=3.0, mist_falloff=falloff)
        mist = _passes(scene, ["Mist", "Depth"], samples=64, samples_per_pass=64)
        depth = mist["Depth"][..., 0]

        def cycles_mist(tx, tz):  # the wall spans ±2 m at 3 m: ±2/3 in tan; no surface: mist 1
            on_wall = (np.abs(tx) < 2.0 / 3.0) & (np.abs(tz) < 2.0 / 3.0)
            distance = 3.0 * np.sqrt(1.0 + tx * tx + tz * tz)
            return np.where(on_wall, np.clip((distance - 2.0) / 3.0, 0.0, 1.0) ** power, 1.0)

        error = np.abs(mist["Mist"][..., 0] - _pixel_mean(cycles_mist))
        assert error[4:12, 4:12].max() < 0.005, (falloff, error[4:12, 4:12].max())  # pixels all on the wall
        assert error.max() < 0.02, (falloff, error.max())  # the wall's edges: sampling noise of the coverage
        assert (depth > 1e9).sum() > 60 and np.all(mist["Mist"][depth > 1e9] == 1.0)


def test_object_and_material_index_are_sample_zeros_ids_never_blended():
    scene = _wide_wall()
    scene.data_passes = DataPassInputs(object_pass_index=np.array([3, 3, 7, 7], np.float32),
                                       material_pass_index=(11, 13))
    p = _passes(scene, ["IndexOB", "IndexMA", "Depth"], samples=16, samples_per_pass=16)
    ob, ma = p["IndexOB"][..., 0], p["IndexMA"][..., 0]
    assert set(np.unique(ob).tolist()) == {0.0, 3.0, 7.0}  # integers: the id of sample 0, never a mean
    assert set(np.unique(ma).tolist()) == {0.0, 11.0, 13.0}
    # columns 0-2 see the background only, 4-7 the left object, 8-11 the right one (3 and 12: edges)
    assert np.all(ob[:, :3] == 0) and np.all(ob[4:12, 4:8] == 3) and np.all(ob[4:12, 8:12] == 7)
    assert np.all(ma[4:12, 4:8] == 11) and np.all(ma[4:12, 8:12] == 13)
    assert np.all((ob == 0) == (ma == 0))


def test_uv_pass_interpolates_the_render_uv_map():
    scene = _facing_wall(distance=3.0)  # the wall fills the view (±0.54 m of its ±2 m)
    corners = scene.vertices[scene.triangles]  # [T, 3, 3]
    scene.data_passes = DataPassInputs(uv=np.stack([(corners[..., 0] + 2.0) / 4.0, (corners[..., 2] + 2.0) / 4.0,
                                                    np.ones(corners.shape[:2])], -1))
    uv = _passes(scene, ["UV"], samples=64, samples_per_pass=64)["UV"]
    half = 3.0 * 0.18  # half the view's width on the wall (50 mm lens, 18 mm film)
    centre = (np.arange(16) + 0.5) / 16 * 2 * half - half
    assert np.allclose(uv[..., 2], 1.0)
    assert np.abs(uv[..., 0] - (centre[None, :] + 2.0) / 4.0).max() < 0.004
    assert np.abs(uv[..., 1] - (-centre[:, None] + 2.0) / 4.0).max() < 0.004


def _ao_closed_form(h, distance):
    """AO at a floor point ``h`` m from an infinite wall, rays as far as ``distance``: the cosine-weighted
    directions that reach the wall within it are those whose horizontal component toward it exceeds
    a = h / distance, a segment of the projected unit disc of area acos(a) - a √(1 - a²)."""
    a = np.clip(h / distance, 0.0, 1.0)
    return 1.0 - (np.arccos(a) - a * np.sqrt(1.0 - a * a)) / np.pi


def test_ambient_occlusion_of_an_open_floor_and_beside_a_wall():
    camera = Camera("cam", look_at((-1.0, 0.0, 2.0), (-1.0, 0.0, 0.0), up=(0, 1, 0)), (16, 16),
                    focal_length_mm=50.0, film_width_mm=18.0, film_height_mm=18.0)
    floor = quad((-5.0, 0.0, 0.0), (5.0, 0, 0), (0, 10.0, 0))
    wall = quad((0.0, 0.0, 10.0), (0, 10.0, 0), (0, 0, 10.0))  # the plane x = 0, facing -x
    grey = [Material("grey", base_color=(0.5, 0.5, 0.5))]
    open_floor = make_scene([(*floor, 0)], grey, camera, world=World((1.0, 1.0, 1.0), 1.0))
    open_floor.data_passes = DataPassInputs(ao_distance_m=2.0)
    assert np.all(_passes(open_floor, ["AO"], samples=16, samples_per_pass=16)["AO"] == 1.0)

    scene = make_scene([(*floor, 0), (*wall, 0)], grey, camera,
                       world=World((1.0, 1.0, 1.0), 1.0))
    scene.data_passes = DataPassInputs(ao_distance_m=2.0)
    p = _passes(scene, ["AO", "Position"], samples=256, samples_per_pass=256)
    h = -p["Position"][..., 0]
    assert 0.6 < h.min() and h.max() < 1.4
    expected = _ao_closed_form(h, 2.0)
    ao = p["AO"]
    assert np.allclose(ao[..., 0], ao[..., 2])
    for low, high in ((0.6, 0.8), (0.8, 1.0), (1.0, 1.2), (1.2, 1.4)):  # 4 bands of distance to the wall
        band = (h >= low) & (h < high)
        assert abs(ao[..., 0][band].mean() - expected[band].mean()) < 0.03, (low, ao[..., 0][band].mean(),
                                                                              expected[band].mean())


def _pinhole_world_to_raster(camera_to_world, focal_mm, film_mm, size):
    """[4, 4] world → pixels (x right, y up from the lower left corner) of a square pinhole camera, written
    from the pinhole model (not from the tracer's camera code)."""
    scale = focal_mm / film_mm * size
    camera_to_raster = np.array([[scale, 0.0, -0.5 * size, 0.0], [0.0, scale, -0.5 * size, 0.0],
                                 [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, -1.0, 0.0]])  # w = depth d = -z: x / d · scale + size / 2
    return camera_to_raster @ np.linalg.inv(camera_to_world)


def test_vector_pass_is_the_screen_motion_to_the_previous_and_from_the_next_frame():
    """The wall moves -0.1 m in x from the previous frame and will be 0.3 m up in the next, while the camera
    (at rest, then) steps 0.2 m back by the next frame: previous - now and now - next in pixels, exactly the
    pinhole projection of those positions; pixels seeing nothing hold 0."""
    scene = _wide_wall(3.0)
    triangles = len(scene.triangles)
    motion = np.zeros((triangles, 2, 3, 3), np.float32)
    motion[:, 0, :, 0] = -0.1  # where each corner was at the previous frame, relative to now
    motion[:, 1, :, 2] = 0.3  # and where it will be at the next
    now = _pinhole_world_to_raster(scene.camera.camera_to_world, 15.0, 36.0, 16)
    moved_camera = scene.camera.camera_to_world.copy()
    moved_camera[1, 3] -= 0.2  # the camera backs away along -y by the next frame
    after = _pinhole_world_to_raster(moved_camera, 15.0, 36.0, 16)
    scene.data_passes = DataPassInputs(triangle_motion=motion, world_to_raster=np.stack([now, now, after]))
    p = _passes(scene, ["Vector", "Depth"], samples=16, samples_per_pass=16)
    vector, depth = p["Vector"], p["Depth"][..., 0]
    assert vector.shape == (16, 16, 4)
    per_metre = 15.0 / 36.0 * 16 / 3.0  # pixels per metre on the wall, 3 m away
    full = np.zeros((16, 16), bool)
    full[5:11, 5:11] = True  # pixels wholly on the wall (it covers pixels 3.6 to 12.4)
    assert np.allclose(vector[full, 0], -0.1 * per_metre, atol=1e-4)
    assert np.allclose(vector[full, 1], 0.0, atol=1e-4)
    # Next frame: the point 0.3 m higher, seen 3.2 m away: now - next per pixel from its centre's offset.
    ys, xs = np.nonzero(full)
    on_wall_x = ((xs + 0.5) - 8.0) / (15.0 / 36.0 * 16) * 3.0  # each pixel's mean wall point (m)
    on_wall_z = (8.0 - (ys + 0.5)) / (15.0 / 36.0 * 16) * 3.0
    next_x = 8.0 + on_wall_x * 15.0 / 36.0 * 16 / 3.2
    next_y = 8.0 + (on_wall_z + 0.3) * 15.0 / 36.0 * 16 / 3.2
    now_y = 8.0 + on_wall_z * 15.0 / 36.0 * 16 / 3.0
    assert np.allclose(vector[full, 2], (8.0 + on_wall_x * per_metre) - next_x, atol=2e-3)
    assert np.allclose(vector[full, 3], now_y - next_y, atol=2e-3)
    background = depth > 1e9
    assert background.sum() > 60 and np.all(vector[background] == 0.0)


def _leaf_before_wall(alpha, threshold):
    """A white diffuse leaf of alpha ``alpha`` (Diffuse × alpha + Transparent × (1 - alpha), so sampling goes through
    it with probability 1 - alpha) filling the view 2 m in front of the camera, and a grey wall at 3 m; Mist from
    0 over 10 m (linear), AO within 0.5 m (so neither surface's rays reach the other)."""
    camera = Camera("cam", look_at((0, 0, 0), (0, 1, 0)), (16, 16), focal_length_mm=50.0, film_width_mm=18.0,
                    film_height_mm=18.0)
    leaf = Material("leaf", shader=ShaderProgram([
        ClosureSpec(DIFFUSE, tint=Colour(rgb=(alpha,) * 3), selection=alpha),
        ClosureSpec(TRANSPARENT, tint=Colour(rgb=(1.0 - alpha,) * 3), selection=1.0 - alpha)]))
    wall = Material("wall", base_color=(0.5, 0.5, 0.5))
    scene = make_scene([(*quad((0.0, 3.0, 0.0), (3.0, 0, 0), (0, 0, 3.0)), 0),
                        (*quad((0.0, 2.0, 0.0), (3.0, 0, 0), (0, 0, 3.0)), 1)], [wall, leaf], camera,
                       world=World((0.2, 0.2, 0.2), 1.0))
    corners = scene.vertices[scene.triangles]  # the leaf's UV map only: (x, z) of the leaf
    uv = np.stack([corners[..., 0], corners[..., 2], np.ones(corners.shape[:2])], -1)
    uv[:2] = 0.0
    scene.data_passes = DataPassInputs(mist_start_m=0.0, mist_depth_m=10.0, mist_falloff="LINEAR",
                                       ao_distance_m=0.5, alpha_threshold=threshold,
                                       object_pass_index=np.array([3, 3, 7, 7], np.float32), uv=uv.astype(np.float32))
    return scene


def test_cut_outs_below_the_alpha_threshold_show_the_surface_behind():
    """Cycles' film_write_data_passes: Depth, Normal, UV and Object Index are those of the first surface whose alpha
    reaches View Layer ▸ Alpha Threshold, Mist and AO blend the surfaces before the first scattering by alpha."""
    names = ["Depth", "Normal", "UV", "IndexOB", "Mist", "AO"]
    distance = _pixel_mean(lambda tx, tz: np.sqrt(1.0 + tx * tx + tz * tz), tan_half=0.18)  # per metre ahead
    for alpha, threshold in ((0.0, 0.5), (0.3, 0.5), (0.3, 0.2), (0.3, 0.0), (0.7, 0.5)):
        p = _passes(_leaf_before_wall(alpha, threshold), names, samples=64, samples_per_pass=64)
        done_at_leaf = threshold == 0.0 or alpha >= threshold
        # Mist: α (1 - m(leaf)) + (1 - α)(1 - m(wall)), m = distance / 10 (an expectation: 64 samples a pixel)
        mist = 1.0 - (alpha * (1.0 - 0.2 * distance) + (1.0 - alpha) * (1.0 - 0.3 * distance))
        error = p["Mist"][..., 0] - mist
        assert abs(error.mean()) < 0.01 and abs(error).max() < 0.2, (alpha, threshold, error.mean(), abs(error).max())
        assert abs(p["AO"][..., 0].mean() - 1.0) < 0.02, (alpha, threshold, p["AO"][..., 0].mean())  # α + (1 - α)
        through = p["Normal"][..., 1].mean() * -1.0  # the samples whose Normal was written: all, or those through
        if done_at_leaf:
            assert np.allclose(p["Depth"], 2.0, atol=1e-4) and np.all(p["IndexOB"] == 7.0)
            assert np.all(p["UV"][..., 2] == 1.0)
            assert np.allclose(p["Normal"], [0.0, -1.0, 0.0])
        elif alpha == 0.0:
            assert np.allclose(p["Depth"], 3.0, atol=1e-4) and np.all(p["IndexOB"] == 3.0) and np.all(p["UV"] == 0.0)
            assert np.allclose(p["Normal"], [0.0, -1.0, 0.0])
        else:  # a sample that reflects off the leaf keeps the leaf's Depth and writes no Normal or UV
            assert abs(p["Depth"].mean() - (alpha * 2.0 + (1.0 - alpha) * 3.0)) < 0.02, p["Depth"].mean()
            assert abs(through - (1.0 - alpha)) < 0.02, through
            assert np.all(p["UV"] == 0.0) and set(np.unique(p["IndexOB"]).tolist()) == {3.0, 7.0}
