"""Light linking and shadow linking (``light_linking``), in the tracer: each light lights only its objects,
an object outside a light's blocker sets casts none of its shadows, and a scene without linking renders
bit for bit as before."""

import numpy as np

from engine.tracer.light_linking import ALL_SETS, LightLinks
from engine.tracer.renderer import Renderer
from engine.tracer.scene import Camera, Light, Material, World
from tracer.tracer_scenes import look_at, make_scene, quad, settings

# Objects: 0 the floor's left half, 1 its right half, 2 a small card 0.5 m under the left light (above the
# camera, so the camera does not see it; its shadow on the left half is about 1.2 m wide).
LEFT, RIGHT, CARD = 0, 1, 2


def _two_halves(card=True):
    """Two grey floor halves seen from 2 m above (the frame: x in [-1.8, 1.8] m, y in [-0.9, 0.9] m), a point
    light 3 m over the middle of each."""
    camera = Camera("cam", look_at((0, 0, 2.0), (0, 0, 0), up=(0, 1, 0)), (32, 16), focal_length_mm=20.0,
                    film_width_mm=36.0, film_height_mm=18.0)
    parts = [(*quad((-1.0, 0, 0), (1.0, 0, 0), (0, 2.0, 0)), 0), (*quad((1.0, 0, 0), (1.0, 0, 0), (0, 2.0, 0)), 0)]
    if card:
        parts.append((*quad((-1.0, 0, 2.5), (0.1, 0, 0), (0, 0.1, 0)), 0))
    lights = [Light("left", "point", np.array([-1.0, 0.0, 3.0]), power_w=300.0),
              Light("right", "point", np.array([1.0, 0.0, 3.0]), power_w=300.0)]
    scene = make_scene(parts, [Material("grey", base_color=(0.5, 0.5, 0.5))], camera, lights, World((0, 0, 0), 0.0))
    scene.triangle_object = np.repeat(np.arange(len(parts), dtype=np.int32), 2)
    scene.object_names = ["Left", "Right", "Card"][:len(parts)]
    return scene


def _links(n, receivers=(), blockers=(), light_sets=None, shadow_sets=None):
    receiver = np.zeros(n, np.int64)
    blocker = np.zeros(n, np.int64)
    for obj, s in receivers:
        receiver[obj] = s
    for obj, s in blockers:
        blocker[obj] = s
    return LightLinks(receiver, blocker, np.full(n, ALL_SETS, np.int64), np.full(n, ALL_SETS, np.int64),
                      light_sets or {}, shadow_sets or {})


def _render(scene, **kw):
    with Renderer(scene, settings(samples=16, samples_per_pass=16, max_bounces=0, **kw)) as r:
        while not r.finished:
            r.render_pass()
        return r.image_rgb().astype(np.float64).mean(-1), r


def test_each_light_lights_only_its_half():
    """The left light lights only the left half (receiver set 1), the right one only the right half (set 2):
    each half is as bright as with its own light alone, and the other light adds nothing."""
    scene = _two_halves(card=False)
    scene.light_links = _links(2, receivers=[(LEFT, 1), (RIGHT, 2)], light_sets={"left": 0b10, "right": 0b100})
    linked, r = _render(scene)
    assert r.tables.kernel_settings.light_linking and not r.tables.kernel_settings.shadow_linking
    assert not r.tables.analysis.light_tracing
    alone = []
    for keep in (0, 1):
        single = _two_halves(card=False)
        single.lights = [single.lights[keep]]
        alone.append(_render(single)[0])
    left, right = linked[:, :16], linked[:, 16:]
    np.testing.assert_allclose(left.mean(), alone[0][:, :16].mean(), rtol=0.01)
    np.testing.assert_allclose(right.mean(), alone[1][:, 16:].mean(), rtol=0.01)
    assert alone[1][:, :16].mean() > 0.2 * alone[0][:, :16].mean()  # unlinked, the right light reaches the left


def test_excluded_card_casts_no_shadow_from_its_light():
    """The card (blocker set 1) is outside the left light's blocker sets (set 0 only): the left half is lit
    as if the card were not there; the right light's shadows (every set) are unchanged."""
    shadowed, _ = _render(_two_halves())
    free, _ = _render(_two_halves(card=False))
    scene = _two_halves()
    scene.light_links = _links(3, blockers=[(CARD, 1)], shadow_sets={"left": 0b1})
    linked, r = _render(scene)
    assert r.tables.kernel_settings.shadow_linking and not r.tables.kernel_settings.light_linking
    spot = shadowed[6:10, 6:10]
    assert spot.mean() < 0.7 * free[6:10, 6:10].mean()  # without linking, the card shades the left half
    np.testing.assert_allclose(linked[6:10, 6:10].mean(), free[6:10, 6:10].mean(), rtol=0.01)
    np.testing.assert_allclose(linked.mean(), free.mean(), rtol=0.01)


def test_unlinked_links_render_bit_for_bit():
    """Links that single nothing out switch the linking code off: the image is the one without them."""
    plain, _ = _render(_two_halves())
    scene = _two_halves()
    scene.light_links = _links(3)
    same, r = _render(scene)
    assert not (r.tables.kernel_settings.light_linking or r.tables.kernel_settings.shadow_linking)
    assert np.array_equal(plain, same)


def test_light_tracing_is_off_with_linking():
    """Light paths do not test light or shadow sets: with linking the analysis leaves caustics to path
    tracing (which uses Cycles' receiver, the last specular vertex) and says why."""
    from tracer.tracer_scenes import uv_sphere

    scene = _two_halves(card=False)
    ball = uv_sphere((0.0, 0.0, 0.5), 0.3, rings=8, segments=16)
    scene.vertices = np.concatenate([scene.vertices, ball[0]])
    scene.triangles = np.concatenate([scene.triangles, ball[1] + 8]).astype(np.int32)
    scene.materials.append(Material("glass", kind="dielectric", glass="N-BK7"))
    scene.triangle_material = np.concatenate([scene.triangle_material, np.full(len(ball[1]), 1, np.int32)])
    scene.triangle_object = np.concatenate([scene.triangle_object, np.full(len(ball[1]), 2, np.int32)])
    scene.object_names = ["Left", "Right", "Ball"]
    with Renderer(scene, settings(light_tracing="on")) as r:
        assert r.tables.analysis.light_tracing
    scene.light_links = _links(3, receivers=[(LEFT, 1)], light_sets={"left": 0b10})
    with Renderer(scene, settings(light_tracing="on")) as r:
        assert not r.tables.analysis.light_tracing
        assert "light linking" in r.tables.analysis.light_tracing_note


def test_linking_code_with_nothing_singled_out_changes_nothing():
    """The linking code switched on (both flags, every emitter lighting and shadowed by set 0, every object
    in set 0) renders bit for bit the image of the code switched off: it only gates, and shadow rays traced
    layer by layer find what the occlusion query found."""
    from engine.tracer.light_linking import LinkTables
    from tracer.media.no_media_scene import no_media_scene

    def render(linking_code):
        r = Renderer(no_media_scene(), settings(samples=8, samples_per_pass=8, max_bounces=6))
        if linking_code:
            tables = r.tables
            lights = tables.light_table.arrays
            t, rows = len(tables.geometry.triangles), lights.rows.shape[0]
            zeros, everything = np.zeros(t, np.int64), np.full(t, ALL_SETS, np.int64)
            lights = lights._replace(links=LinkTables(zeros, zeros, everything, everything,
                                                      np.full(rows, ALL_SETS, np.int64),
                                                      np.full(rows, ALL_SETS, np.int64)))
            tables.light_table.arrays = lights
            tables.kernel_settings = tables.kernel_settings._replace(light_linking=True, shadow_linking=True)
            tables.arrays = tables.arrays._replace(settings=tables.kernel_settings, lights=lights)
        r.render_pass()
        return np.asarray(r.image_rgb(), np.float64)

    assert np.array_equal(render(False), render(True))
