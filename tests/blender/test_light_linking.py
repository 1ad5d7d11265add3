"""Blender's Light Linking and Shadow Linking against Cycles 4.5, in absolute terms: a point light and an
emissive mesh that each light one floor half only, and an area light whose shadow an excluded card does
not cast."""

from __future__ import annotations

import importlib
import math

import bpy
import numpy as np
import pytest

from helpers.bpy_scenes import add_camera, add_plane, add_point_light, shader_material
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba
from helpers.node_scenes import black_world

SAMPLES = 64
# The camera 5 m above the floor, 50 mm lens on a 36 mm film, 32 × 16 pixels: the frame is 3.6 m × 1.8 m.
ROWS, COLUMNS = np.mgrid[0:16, 0:32]


def _floor_xy(sub=4):
    """Floor coordinates (m) [16, 32, sub², 2] of sub × sub points inside each pixel."""
    offsets = (np.arange(sub) + 0.5) / sub
    oy, ox = np.meshgrid(offsets, offsets, indexing="ij")
    x = (COLUMNS[..., None] + ox.reshape(-1) - 16.0) * 0.1125
    y = (8.0 - ROWS[..., None] - oy.reshape(-1)) * 0.1125
    return np.stack([x, y], -1)


def _linked(collection_name, *objects, state="INCLUDE"):
    collection = bpy.data.collections.new(collection_name)
    for obj in objects:
        collection.objects.link(obj)
    for entry in collection.collection_objects:
        entry.light_linking.link_state = state
    return collection


def _emissive_panel(name, size_m, location, strength):
    """A square facing -Z that emits white light of ``strength`` (Cycles' Emission strength)."""
    bpy.ops.mesh.primitive_plane_add(size=size_m, location=location, rotation=(math.pi, 0.0, 0.0))
    panel = bpy.context.active_object
    panel.name = name
    panel.data.materials.append(shader_material(f"{name} emission", "ShaderNodeEmission", Strength=strength))
    return panel


def _renders(scene, regions):
    cycles = regions(render_cycles_rgba(scene, SAMPLES, max_bounces=1))
    scene.prism.max_bounces = 1
    prism = regions(render_prism_rgba(scene, SAMPLES))
    return prism, cycles


@pytest.fixture
def halves(fresh_scene):
    """Two grey Lambertian floor halves, a 30 W point light 1 m over the left one and an emissive panel
    (0.6 m, strength 40) 1 m up, beside the frame, toward the right one; the light linked to the left half,
    the panel to the right one."""
    black_world()
    left = add_plane("Left", 1.8, color=(0.5, 0.5, 0.5), location=(-0.95, 0.0, 0.0), specular=0.0)
    right = add_plane("Right", 1.8, color=(0.5, 0.5, 0.5), location=(0.95, 0.0, 0.0), specular=0.0)
    bulb = add_point_light("Bulb", 30.0, (-0.95, 0.0, 1.0))
    panel = _emissive_panel("Panel", 0.6, (0.95, 1.2, 1.0), 40.0)
    bulb.light_linking.receiver_collection = _linked("Bulb lights", left)
    panel.light_linking.receiver_collection = _linked("Panel lights", right)
    add_camera((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), resolution=(32, 16))
    return fresh_scene, bulb, panel


def _half_regions(image):
    lum = luminance(image)
    return float(lum[1:15, 1:15].mean()), float(lum[1:15, 17:31].mean())


def _bulb_closed_form():
    """Mean radiance of the left region lit by the bulb alone: ρ/π · I · h / r³ with I = P / 4π."""
    xy = _floor_xy()[1:15, 1:15]
    r2 = (xy[..., 0] + 0.95) ** 2 + xy[..., 1] ** 2 + 1.0
    return float((0.5 / math.pi * 30.0 / (4 * math.pi) / r2 ** 1.5).mean())


def test_each_emitter_lights_only_its_half(prism_addon, halves):
    """Light linking: the left half is lit by the bulb only (its closed form: the panel's light, 16 % of it
    unlinked, is gone), the right half by the panel only, in light sampling and BSDF-sampled hits alike;
    both halves as bright as Cycles renders them (2 %)."""
    scene, bulb, panel = halves
    prism, cycles = _renders(scene, _half_regions)
    print(f"light linking: Prism {prism}, Cycles {cycles}, ratios {[p / c for p, c in zip(prism, cycles)]}, "
          f"left closed form {_bulb_closed_form()}")
    for p, c in zip(prism, cycles):
        assert p == pytest.approx(c, rel=0.02)
    assert prism[0] == pytest.approx(_bulb_closed_form(), rel=0.02)
    bulb.light_linking.receiver_collection = None
    panel.light_linking.receiver_collection = None
    unlinked = _half_regions(render_prism_rgba(scene, SAMPLES))
    assert unlinked[0] > 1.1 * prism[0]  # the panel lights the left half too
    assert unlinked[1] > 1.05 * prism[1]  # and the bulb the right one (measured +10 %)


@pytest.fixture
def card_under_light(fresh_scene):
    """A grey floor, a 100 W area light (0.5 m) 2 m above its centre and a grey card (0.4 m) 1 m above it;
    the light's blocker collection excludes the card."""
    black_world()
    add_plane("Floor", 4.0, color=(0.5, 0.5, 0.5), specular=0.0)
    card = add_plane("Card", 0.4, color=(0.5, 0.5, 0.5), location=(0.0, 0.0, 1.0), specular=0.0)
    data = bpy.data.lights.new("Key", "AREA")
    data.energy, data.size = 100.0, 0.5
    key = bpy.data.objects.new("Key", data)
    key.location = (0.0, 0.0, 2.0)
    bpy.context.scene.collection.objects.link(key)
    key.light_linking.blocker_collection = _linked("Key blockers", card, state="EXCLUDE")
    add_camera((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), resolution=(32, 16))
    return fresh_scene, key


def _card_regions(image):
    """Mean luminance of the card (seen within 0.2 m of the centre at floor scale; it covers 0.25 m), of
    the floor ring its shadow would darken (0.3 m to 0.6 m; the card hides the floor within 0.25 m) and of
    the floor farther out."""
    lum = luminance(image)
    xy = _floor_xy(1)[..., 0, :]
    reach = np.abs(xy).max(-1)
    return (float(lum[reach < 0.2].mean()), float(lum[(reach > 0.3) & (reach < 0.6)].mean()),
            float(lum[reach > 0.7].mean()))


def test_excluded_card_casts_no_shadow_from_the_light(prism_addon, card_under_light):
    """Shadow linking: the card, excluded from the light's blockers, casts no shadow (the ring around it is
    as bright as Cycles renders it, and brighter than Prism without the link); the card itself stays lit."""
    scene, key = card_under_light
    prism, cycles = _renders(scene, _card_regions)
    print(f"shadow linking: Prism {prism}, Cycles {cycles}, ratios {[p / c for p, c in zip(prism, cycles)]}")
    for p, c in zip(prism, cycles):
        assert p == pytest.approx(c, rel=0.02)
    key.light_linking.blocker_collection = None
    unlinked = _card_regions(render_prism_rgba(scene, SAMPLES))
    assert unlinked[1] < 0.8 * prism[1]  # unlinked, the card shades the ring


def test_excluded_card_casts_no_shadow_from_an_emissive_panel(prism_addon, card_under_light):
    """Shadow linking of an emissive mesh: the area light swapped for an emissive panel of the same size and
    radiance (strength 100 / π / 0.25 m²), hidden from the camera (Ray Visibility ▸ Camera off, so Prism
    traces each ray kind against its own scene); the card excluded from its blockers casts no shadow."""
    scene, key = card_under_light
    bpy.data.objects.remove(key)
    panel = _emissive_panel("Panel", 0.5, (0.0, 0.0, 2.0), 100.0 / (math.pi * 0.25))
    panel.visible_camera = False
    panel.light_linking.blocker_collection = _linked("Panel blockers", bpy.data.objects["Card"], state="EXCLUDE")
    prism, cycles = _renders(scene, _card_regions)
    print(f"shadow linking, emissive panel: Prism {prism}, Cycles {cycles}, "
          f"ratios {[p / c for p, c in zip(prism, cycles)]}")
    for p, c in zip(prism, cycles):
        assert p == pytest.approx(c, rel=0.02)
    panel.light_linking.blocker_collection = None
    unlinked = _card_regions(render_prism_rgba(scene, SAMPLES))
    assert unlinked[1] < 0.8 * prism[1]


def test_linking_export_and_no_warning(prism_addon, halves):
    """The export reads one receiver set per floor half and a one-bit mask per emitter (the bulb lights
    the left half's set only, the panel the right half's), leaves shadows unlinked, and no longer warns
    that linking is ignored."""
    warnings = []
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    scene = export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)
    links = scene.light_links
    names = scene.object_names
    left, right, panel = (links.object_receiver_set[names.index(n)] for n in ("Left", "Right", "Panel"))
    assert len({left, right, panel}) == 3 and panel == 0  # the panel is in no collection: set 0
    assert links.light_sets == {"Bulb": 1 << left}
    assert links.object_light_sets[names.index("Panel")] == 1 << right
    assert not links.shadow_linking and links.light_linking
    assert not [w for w in warnings if "linking" in w]


def test_child_collections_and_exclusions(prism_addon, halves):
    """A child collection's state applies to its objects, an excluded object leaves an included child
    collection (included minus excluded), and a collection of exclusions only shadows everything else."""
    _, bulb, panel = halves
    left, right = bpy.data.objects["Left"], bpy.data.objects["Right"]
    floor = bpy.data.collections.new("Floor halves")
    floor.objects.link(left)
    floor.objects.link(right)
    receivers = bpy.data.collections.new("Bulb receivers")
    receivers.children.link(floor)
    receivers.objects.link(right)
    receivers.collection_objects[0].light_linking.link_state = "EXCLUDE"
    bulb.light_linking.receiver_collection = receivers
    panel.light_linking.receiver_collection = None
    panel.light_linking.blocker_collection = _linked("Panel blockers", left, state="EXCLUDE")
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    exported = export.export_scene(bpy.context.evaluated_depsgraph_get(), [])
    links, names = exported.light_links, exported.object_names
    lit = {n for i, n in enumerate(names) if links.light_sets["Bulb"] >> int(links.object_receiver_set[i]) & 1}
    panel_shadows = links.object_shadow_sets[names.index("Panel")]
    shadowing = {n for i, n in enumerate(names) if panel_shadows >> int(links.object_blocker_set[i]) & 1}
    assert lit == {"Left"}
    assert shadowing == {"Right", "Panel"}
    assert links.light_linking and links.shadow_linking


def test_viewport_warns_that_it_ignores_linking(prism_addon, halves):
    """The rendered viewport does not apply linking: its sync says so once per linked emitter."""
    sync_module = importlib.import_module(f"{prism_addon.__name__}.engine.viewport.scene_sync")
    sync = sync_module.SceneSync()
    sync.update(bpy.context.evaluated_depsgraph_get(), sync_module.Updates.everything())
    linking = [w for w in sync.warnings if "Light Linking" in w]
    assert len(linking) == 2 and any("'Bulb'" in w for w in linking) and any("'Panel'" in w for w in linking)
