"""Cycles' shadow catcher in the tracer, against closed forms: a floor marked Shadow Catcher under a point
light, a black card between them. The catcher's copy of each camera path sees the floor without the card,
the path itself sees both, and they share their random numbers (as Cycles' split copies them), so the
Shadow Catcher pass is exactly 0 in the card's umbra and exactly 1 where the light is free; Combined
holds the card over a transparent floor, with the shadow in alpha unless the pass is on."""

from dataclasses import replace

import numpy as np

from engine.tracer.pass_table import PassRequest
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material
from engine.tracer.shadow_catcher_film import WIDTH
from engine.tracer.state import PathState, new_path_state
from engine.tracer.visibility import ALL_RAYS, SHADOW_CATCHER

from .tracer_scenes import look_at, make_scene, quad, settings

SIZE = 32
PIXEL_M = 0.1125  # 50 mm lens on a 36 mm film, 5 m above the floor: 3.6 m across 32 pixels
LIGHT_Z, CARD_Z, CARD_HALF = 3.0, 2.5, 0.2
UMBRA_HALF = CARD_HALF * LIGHT_Z / (LIGHT_Z - CARD_Z)  # 1.2 m: the card's shadow on the floor
CARD_SEEN_HALF = CARD_HALF * 5.0 / (5.0 - CARD_Z)  # 0.4 m: where the camera sees the card over the floor


def _scene(lights=None):
    cam = Camera("cam", look_at((0, 0, 5.0), (0, 0, 0), up=(0, 1, 0)), (SIZE, SIZE), focal_length_mm=50.0,
                 film_width_mm=36.0, film_height_mm=36.0)
    floor = quad((0, 0, 0), (2.0, 0, 0), (0, 2.0, 0))
    card = quad((0, 0, CARD_Z), (CARD_HALF, 0, 0), (0, CARD_HALF, 0))
    lights = lights or [Light("lamp", "point", np.array([0.0, 0.0, LIGHT_Z]), power_w=100.0)]
    scene = make_scene([(*floor, 0), (*card, 1)], [Material("floor", base_color=(0.5, 0.5, 0.5)),
                                                   Material("card", base_color=(0.0, 0.0, 0.0))], cam, lights)
    scene.triangle_object = np.array([0, 0, 1, 1], np.int32)
    scene.object_flags = np.array([ALL_RAYS | SHADOW_CATCHER, ALL_RAYS], np.uint8)
    return scene


def _regions():
    """Masks [32, 32] of whole pixels: the card, the floor in its umbra (beside the card), the lit floor."""
    rows, columns = np.mgrid[0:SIZE, 0:SIZE]
    x = (columns + 0.5 - SIZE / 2) * PIXEL_M
    y = (SIZE / 2 - rows - 0.5) * PIXEL_M
    reach = np.maximum(np.abs(x), np.abs(y))  # square regions: the card and its shadow are squares
    half = PIXEL_M / 2
    card = reach < CARD_SEEN_HALF - half
    umbra = (reach > CARD_SEEN_HALF + half) & (reach < UMBRA_HALF - half)
    lit = reach > UMBRA_HALF + half
    return card, umbra, lit


def _render(scene, passes=(), transparent=True, samples=16):
    st = settings(samples=samples, samples_per_pass=samples, passes=PassRequest(passes=passes))
    st.film_transparent = transparent
    with Renderer(scene, st) as r:
        r.render_pass()
        return r.image_rgb().astype(np.float64), r.image_alpha().astype(np.float64), r.pass_images(), r


def test_pass_is_zero_in_the_umbra_and_one_in_the_light():
    card, umbra, lit = _regions()
    assert card.sum() >= 16 and umbra.sum() >= 100 and lit.sum() >= 40
    rgb, alpha, images, r = _render(_scene(), passes=("Shadow Catcher",))
    assert r.tables.kernel_settings.shadow_catcher and r.tables.ray_classes is not None
    catcher = images["Shadow Catcher"]
    assert catcher.shape == (SIZE, SIZE, 3)
    assert np.abs(catcher[umbra]).max() < 1e-6
    assert np.abs(catcher[lit] - 1.0).max() < 1e-5
    assert np.all(catcher[card] == 1.0)  # no sample split there: no catcher in the pixel
    # With the pass on, Combined is the matte: the card (black, opaque) over a transparent floor.
    assert np.all(alpha[card] == 1.0) and np.abs(alpha[umbra | lit]).max() < 1e-6
    assert np.abs(rgb[umbra | lit]).max() < 1e-6


def test_combined_with_the_pass_off_holds_the_shadow_in_alpha():
    card, umbra, lit = _regions()
    rgb, alpha, _, r = _render(_scene())
    assert "caustics by path tracing (shadow catcher)" in r.strategy  # light paths would have to split too
    assert np.all(alpha[card] == 1.0)
    assert np.abs(alpha[umbra] - 1.0).max() < 1e-6  # a full shadow: opaque black
    assert np.abs(alpha[lit]).max() < 1e-5  # no shadow: transparent
    assert np.abs(rgb[umbra | lit]).max() < 1e-6
    # Underneath, the film keeps the floor as lit with the card: ρ/π · I cosθ / r² at the lit pixels' centres.
    raw = r.film.mean()
    rows, columns = np.mgrid[0:SIZE, 0:SIZE]
    x, y = (columns + 0.5 - SIZE / 2) * PIXEL_M, (SIZE / 2 - rows - 0.5) * PIXEL_M
    r2 = x ** 2 + y ** 2 + LIGHT_Z ** 2
    closed = 0.5 / np.pi * 100.0 / (4 * np.pi) * LIGHT_Z / r2 ** 1.5
    ratio = raw[lit].mean(-1).mean() / closed[lit].mean()
    assert abs(ratio - 1.0) < 0.02, ratio


def test_a_light_that_is_no_catcher_brightens_the_pass():
    """Two equal lights at one place, one not a shadow catcher (Object ▸ Visibility ▸ Shadow Catcher off on
    the light): the copies see only the other, so the lit floor's pass is (I + I) / I = 2."""
    _, _, lit = _regions()
    lamp = Light("lamp", "point", np.array([0.0, 0.0, LIGHT_Z]), power_w=100.0)
    other = replace(lamp, name="other", shadow_catcher=False)
    _, _, images, _ = _render(_scene([lamp, other]), passes=("Shadow Catcher",), samples=64)
    mean = images["Shadow Catcher"][lit].mean()
    assert abs(mean - 2.0) < 0.04, mean


def test_an_emissive_catcher_counts_its_glow_on_both_sides():
    """The floor also glows (radiance E): in the umbra the path brings E and its copy E + the lamp's light, so
    the pass is E / (E + ρ/π · I cosθ / r²) there (the copy shades the catcher with its emission, as Cycles')."""
    from engine.tracer.scene import SpectrumSpec

    _, umbra, lit = _regions()
    glow = 0.05
    scene = _scene()
    scene.materials[0] = Material("floor", base_color=(0.5, 0.5, 0.5), emission=SpectrumSpec(), emission_strength=glow)
    _, _, images, _ = _render(scene, passes=("Shadow Catcher",), samples=64)
    rows, columns = np.mgrid[0:SIZE, 0:SIZE]
    x, y = (columns + 0.5 - SIZE / 2) * PIXEL_M, (SIZE / 2 - rows - 0.5) * PIXEL_M
    lamp = 0.5 / np.pi * 100.0 / (4 * np.pi) * LIGHT_Z / (x ** 2 + y ** 2 + LIGHT_Z ** 2) ** 1.5
    closed = glow / (glow + lamp)
    got = images["Shadow Catcher"].mean(-1)
    assert 0.25 < closed[umbra].mean() < 0.4
    assert abs(got[umbra].mean() / closed[umbra].mean() - 1.0) < 0.02, (got[umbra].mean(), closed[umbra].mean())
    assert abs(got[lit].mean() - 1.0) < 0.01


def test_scenes_without_a_catcher_keep_their_tables():
    scene = _scene()
    scene.object_flags = np.array([ALL_RAYS, ALL_RAYS], np.uint8)
    with Renderer(scene, settings()) as r:
        tables = r.tables
        assert not tables.kernel_settings.shadow_catcher
        assert tables.ray_classes is None and tables.pass_layout.kernel.catcher == -1
        assert tables.light_table.arrays.catcher_excluded.shape == (1,)


def test_the_pass_without_a_catcher_is_one():
    scene = _scene()
    scene.object_flags = np.array([ALL_RAYS, ALL_RAYS], np.uint8)
    rgb, alpha, images, r = _render(scene, passes=("Shadow Catcher",), transparent=False, samples=4)
    assert r.tables.pass_layout.columns["shadow_catcher"][1] == WIDTH
    assert np.all(images["Shadow Catcher"] == 1.0)
    assert np.array_equal(rgb, r.film.mean().astype(np.float32)) and np.all(alpha == 1.0)


def test_what_is_not_as_cycles_is_warned_naming_the_catcher():
    from engine.tracer.shadow_catcher_film import catcher_names, catcher_warnings

    scene = _scene()
    scene.object_names = ["Floor", "Card"]
    assert catcher_names(scene) == ["Floor"]
    plain = settings()
    assert catcher_warnings(plain, ["Floor"]) == []
    grouped = settings(passes=PassRequest(light_groups=("key",)), spectral_band_nm=10.0)
    messages = catcher_warnings(grouped, catcher_names(scene))
    assert len(messages) == 2 and all(m.startswith("Shadow catcher 'Floor':") for m in messages)
    assert "light group passes" in messages[0] and "spectral EXR" in messages[1]
    scene.object_flags = np.array([ALL_RAYS, ALL_RAYS], np.uint8)
    assert catcher_names(scene) == [] and catcher_warnings(grouped, []) == []


def test_copy_path_copies_every_field():
    from engine.tracer.stages.shadow_catcher import copy_path

    rng = np.random.default_rng(3)
    state = new_path_state(2, 4)
    for field in PathState._fields:
        array = getattr(state, field)
        array[...] = rng.integers(1, 1000, array.shape) if array.dtype.kind == "i" else rng.random(array.shape)
    copy_path(state, 0, 1)
    for field in PathState._fields:
        array = getattr(state, field)
        assert np.array_equal(array[0], array[1]), field
