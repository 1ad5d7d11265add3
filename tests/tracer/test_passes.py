"""Render passes: each checked against what it means, and Combined-only renders untouched by them."""

import numpy as np
import pytest

from engine.tracer.errors import PrismInputError
from engine.tracer.pass_table import BACKGROUND_DEPTH_M, PASSES, FilmLayout, PassRequest, blender_passes
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, World
from tracer.tracer_scenes import look_at, make_scene, quad, settings

ALL = tuple(PASSES)


def _render(scene, **kw):
    with Renderer(scene, settings(**kw)) as r:
        while not r.finished:
            r.render_pass()
        return r.image_rgb().astype(np.float64), {k: v.astype(np.float64) for k, v in r.pass_images().items()}


def _facing_wall(distance=3.0, colours=((0.8, 0.2, 0.1), (0.1, 0.5, 0.9)), size=16, world=None, lights=None):
    """A wall at ``distance`` m straight in front of the camera (looking along +Y), its left half one
    colour and its right half another, lit by a point light at the camera."""
    camera = Camera("cam", look_at((0, 0, 0), (0, 1, 0)), (size, size), focal_length_mm=50.0, film_width_mm=18.0,
                    film_height_mm=18.0)
    left = quad((-1.0, distance, 0.0), (1.0, 0, 0), (0, 0, 2.0))
    right = quad((1.0, distance, 0.0), (1.0, 0, 0), (0, 0, 2.0))
    materials = [Material(f"m{i}", "diffuse", base_color=c) for i, c in enumerate(colours)]
    if lights is None:
        lights = [Light("bulb", "point", np.array([0.0, 0.2, 0.0]), power_w=200.0)]
    return make_scene([(*left, 0), (*right, 1)], materials, camera, lights, world)


def _wide_view(scene):
    """``scene`` seen through a 15 mm lens on a 36 mm film: the wall of ``_facing_wall`` (4 m wide at 3 m) covers
    the middle of a 7.2 m wide view only."""
    scene.camera.focal_length_mm = 15.0
    scene.camera.film_width_mm = scene.camera.film_height_mm = 36.0
    return scene


def test_depth_position_and_normal_of_a_wall_facing_the_camera():
    scene = _wide_view(_facing_wall(distance=3.0, world=World((0.2, 0.2, 0.2), 1.0)))
    _, p = _render(scene, samples=4, passes=PassRequest(("Depth", "Position", "Normal", "Denoising Normal")))
    depth, position, normal = p["Depth"][..., 0], p["Position"], p["Normal"]
    covered = depth < 100
    assert 0.2 < covered.mean() < 0.9
    assert np.allclose(depth[covered], 3.0, atol=1e-4)  # along the view axis, not the ray: flat across the frame
    assert np.all(depth[covered] == depth[covered][0])
    assert np.all(depth[~covered] == BACKGROUND_DEPTH_M)
    full = np.linalg.norm(normal, axis=-1) > 0.999  # every sample on the wall (Position and Normal are means)
    assert full.sum() > 0.8 * covered.sum() - 4 * 16
    assert np.allclose(position[full][:, 1], 3.0, atol=1e-4)
    pixel_m = 2 * 3.0 * 18.0 / 15.0 / 16  # pixel footprint on the wall
    centre = (np.arange(16) + 0.5 - 8) * pixel_m
    assert np.allclose(position[..., 0][full], np.broadcast_to(centre, (16, 16))[full], atol=0.15 * pixel_m)
    assert np.allclose(position[..., 2][full], np.broadcast_to(-centre[:, None], (16, 16))[full], atol=0.15 * pixel_m)
    assert np.allclose(normal[full], [0, -1, 0], atol=1e-6)  # towards the camera
    assert np.allclose(p["Denoising Normal"][full], [0, 0, -1], atol=1e-6)  # camera space, z forward
    assert np.all(normal[~covered] == 0) and np.all(p["Denoising Normal"][~covered] == 0)


def test_albedo_and_diffuse_colour_are_the_surface_colours():
    colours = ((0.8, 0.2, 0.1), (0.1, 0.5, 0.9))
    _, p = _render(_facing_wall(colours=colours), samples=4,
                   passes=PassRequest(("Denoising Albedo", "DiffCol", "GlossCol", "TransCol")))
    for image in (p["Denoising Albedo"], p["DiffCol"]):
        assert np.allclose(image[:, :7].mean((0, 1)), colours[0], rtol=0.03, atol=0.01)
        assert np.allclose(image[:, 9:].mean((0, 1)), colours[1], rtol=0.03, atol=0.01)
    assert not p["GlossCol"].any() and not p["TransCol"].any()


def _box_with_glass(world=None):
    from benchmarks import scenes

    scene = scenes.cornell_glass((20, 20))
    if world is not None:
        scene.world = world
    return scene


LIGHT = ("Emit", "Env", "DiffDir", "DiffInd", "DiffCol", "GlossDir", "GlossInd", "GlossCol", "TransDir", "TransInd",
         "TransCol")


def _light_total(p):
    """Combined as the light passes add up: Emit + Env + (Dir + Ind) × Col of the three lobes."""
    total = p["Emit"] + p["Env"]
    for lobe in ("Diff", "Gloss", "Trans"):
        total += (p[lobe + "Dir"] + p[lobe + "Ind"]) * p[lobe + "Col"]
    return total


def test_light_passes_add_up_to_combined():
    scene = _box_with_glass(World((0.3, 0.4, 0.5), 1.0))
    image, p = _render(scene, samples=8, samples_per_pass=8, passes=PassRequest(LIGHT))
    assert np.allclose(_light_total(p), image, rtol=1e-4, atol=1e-5)
    assert p["Env"].max() > 0 and p["TransInd"].max() > 0 and p["TransCol"].max() > 0  # through the glass ball
    assert p["DiffInd"].mean() > 0.1 * p["DiffDir"].mean()  # the box bounces light around
    # The camera sees no emitter (the area light is invisible to it) and sees the world through the mouth.
    assert not p["Emit"].any()


@pytest.mark.parametrize("alpha", [0.0, 0.4])
def test_light_seen_through_a_cut_out_is_split_as_the_surface_behind_it(alpha):
    """Cycles' passes see through cut-outs: a surface behind a leaf of alpha α is the camera's, its light Direct
    after one scattering and its albedo in its Color pass × (1 - α); the world behind it Environment × (1 - α)."""
    from engine.tracer.bsdf.closure import DIFFUSE, TRANSPARENT
    from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram

    leaf_colour = np.array([0.2, 0.7, 0.3])
    leaf = Material("leaf", shader=ShaderProgram([ClosureSpec(DIFFUSE, tint=Colour(rgb=tuple(alpha * leaf_colour))),
                                                  ClosureSpec(TRANSPARENT, tint=Colour(rgb=(1.0 - alpha,) * 3))]))
    scene = _wide_view(_facing_wall(world=World((0.2, 0.2, 0.2), 1.0)))
    scene.materials.append(leaf)
    quad_vertices, quad_triangles = quad((0.0, 1.5, 0.0), (4.0, 0, 0), (0, 0, 4.0))  # the leaf fills the view
    scene.triangles = np.concatenate([scene.triangles, quad_triangles + len(scene.vertices)])
    scene.vertices = np.concatenate([scene.vertices, quad_vertices])
    scene.triangle_material = np.concatenate([scene.triangle_material, np.full(len(quad_triangles), 2)])
    image, p = _render(scene, samples=64, samples_per_pass=64, passes=PassRequest(LIGHT))
    assert np.allclose(_light_total(p), image, rtol=1e-4, atol=1e-5)
    assert not any(p[name].any() for name in ("TransDir", "TransInd", "TransCol", "GlossCol", "Emit"))
    wall, sky = (slice(5, 11), slice(4, 7)), (slice(0, 16), slice(0, 3))  # the left (red) wall, the world beside
    colour = alpha * leaf_colour + (1.0 - alpha) * np.array([0.8, 0.2, 0.1])
    assert np.allclose(p["DiffCol"][wall].mean((0, 1)), colour, rtol=0.05), p["DiffCol"][wall].mean((0, 1))
    assert abs(p["Env"][sky].mean() - 0.2 * (1.0 - alpha)) < 0.006, p["Env"][sky].mean()
    if alpha == 0.0:  # nothing scatters twice: the wall's light is all Direct, as without the leaf
        assert not p["DiffInd"].any()
        bare, q = _render(_wide_view(_facing_wall(world=World((0.2, 0.2, 0.2), 1.0))), samples=64,
                          samples_per_pass=64, passes=PassRequest(LIGHT))
        for name in ("DiffDir", "DiffCol", "Env"):
            assert abs(p[name].mean() - q[name].mean()) < 0.01 * q[name].mean(), (name, p[name].mean(), q[name].mean())


def test_a_single_bounce_is_all_direct_light():
    scene = _facing_wall()
    image, p = _render(scene, samples=8, max_bounces=1,
                       passes=PassRequest(("DiffDir", "DiffInd", "DiffCol")))
    assert np.all(p["DiffInd"] == 0)
    assert np.allclose(p["DiffDir"] * p["DiffCol"], image, rtol=1e-5, atol=1e-7)


def test_light_groups_sum_to_combined_and_hold_their_own_light():
    lights = [Light("key", "point", np.array([-0.5, 0.5, 0.5]), power_w=300.0, light_group="key"),
              Light("fill", "point", np.array([0.5, 0.5, -0.5]), power_w=100.0, light_group="fill")]
    scene = _facing_wall(lights=lights, world=World((0.5, 0.5, 0.5), 0.5))
    scene.world.light_group = "sky"
    groups = ("key", "fill", "sky")
    image, p = _render(scene, samples=16, samples_per_pass=16, passes=PassRequest(light_groups=groups))
    parts = [p["Combined_" + g] for g in groups]
    assert np.allclose(sum(parts), image, rtol=1e-6, atol=1e-7)
    alone = _render(_facing_wall(lights=lights[:1]), samples=64, samples_per_pass=16)[0]
    assert p["Combined_key"].mean() == pytest.approx(alone.mean(), rel=0.03)
    assert all(part.mean() > 0.05 * image.mean() for part in parts)


def test_an_unassigned_light_is_in_no_group():
    lights = [Light("key", "point", np.array([0.0, 0.5, 0.0]), power_w=300.0, light_group="key"),
              Light("other", "point", np.array([0.5, 0.5, 0.0]), power_w=300.0)]
    image, p = _render(_facing_wall(lights=lights), samples=8, passes=PassRequest(light_groups=("key",)))
    assert 0.3 < p["Combined_key"].mean() / image.mean() < 0.7


def test_passes_do_not_change_combined():
    scene = _box_with_glass()
    plain, _ = _render(scene, samples=4)
    with_passes, _ = _render(scene, samples=4, passes=PassRequest(ALL, ("g",), {"id": "VALUE"}))
    assert np.array_equal(plain, with_passes)


def test_shader_aovs_write_each_materials_values():
    scene = _facing_wall()
    scene.materials[0].aovs = {"mask": (0.25, 0.5, 0.75, 3.0)}
    _, p = _render(scene, samples=2, passes=PassRequest(aovs={"mask": "COLOR", "mask_value": "VALUE"}))
    assert np.allclose(p["mask"][:, :7], (0.25, 0.5, 0.75, 1.0))
    assert np.all(p["mask"][:, 9:] == 0) and np.all(p["mask_value"] == 0)
    scene.materials[0].aovs = {"mask_value": (0, 0, 0, 3.0)}
    _, p = _render(scene, samples=2, passes=PassRequest(aovs={"mask_value": "VALUE"}))
    assert p["mask_value"].shape[-1] == 1 and np.allclose(p["mask_value"][:, :7], 3.0)


def test_blender_names_and_bad_requests():
    request = PassRequest(("Normal", "Depth"), ("key",), {"id": "COLOR"})
    assert blender_passes(request) == [("Depth", "Z", "VALUE"), ("Normal", "XYZ", "VECTOR"), ("id", "RGBA", "COLOR"),
                                       ("Combined_key", "RGB", "COLOR")]
    assert FilmLayout(PassRequest()).width == 0
    with pytest.raises(PrismInputError, match="'Bogus' is unknown"):
        PassRequest(("Bogus",)).validate()
    with pytest.raises(PrismInputError, match="same name"):
        PassRequest(light_groups=("a", "a")).validate()
