"""Parity scenes about the film and the output: transparent film (alpha), several view layers, the render
border (cropped or not), resolution percentage, pixel aspect and an animation's frame range."""

from __future__ import annotations

import bpy

from . import building as kit
from .record import ParityScene


def _ball_on_the_stage(**stage):
    kit.stage(**stage)
    kit.sphere("Ball", 0.6, (0.0, 0.0, 0.6), material=kit.diffuse("Red", (0.8, 0.15, 0.1)))


def film_transparent():
    """Film ▸ Transparent under a blue world that lights the scene: the world is alpha 0 (and black in the
    premultiplied RGB), what it lit keeps alpha 1."""
    _ball_on_the_stage(world_strength=0.6)
    bpy.context.scene.world.node_tree.nodes["Background"].inputs["Color"].default_value = (0.3, 0.5, 0.9, 1.0)
    bpy.context.scene.render.film_transparent = True


def view_layers():
    """Two view layers in one render: 'Everything', and 'Without extras', which excludes the collection
    'Extras' (a green box) and has Filter ▸ Environment off. The layers side by side."""
    scene = bpy.context.scene
    _ball_on_the_stage()
    extras = bpy.data.collections.new("Extras")
    scene.collection.children.link(extras)
    kit.cube("Extra box", 0.7, (1.4, 0.5, 0.35), material=kit.diffuse("Green", (0.2, 0.7, 0.2)), collection=extras)
    everything = scene.view_layers[0]
    everything.name = "Everything"
    reduced = scene.view_layers.new("Without extras")
    reduced.layer_collection.children["Extras"].exclude = True
    reduced.use_sky = False


def _border(crop: bool):
    _ball_on_the_stage()
    render = bpy.context.scene.render
    render.use_border, render.use_crop_to_border = True, crop
    render.border_min_x, render.border_max_x = 0.2, 0.7
    render.border_min_y, render.border_max_y = 0.25, 0.8


def render_border():
    """Render Region (border) on, not cropped: the frame at full size, black and transparent outside the
    region."""
    _border(crop=False)


def render_border_cropped():
    """Render Region with Crop to Render Region: the image is the region alone."""
    _border(crop=True)


def resolution_percentage():
    """96 × 64 at 50 %: a 48 × 32 image of the whole frame."""
    _ball_on_the_stage()
    render = bpy.context.scene.render
    render.resolution_x, render.resolution_y, render.resolution_percentage = 96, 64, 50


def pixel_aspect():
    """Pixel aspect 2 : 1 (anamorphic): 48 × 48 pixels, each twice as wide as high, so the frame shows a
    field twice as wide as high and the ball squeezed."""
    _ball_on_the_stage()
    bpy.context.scene.render.pixel_aspect_x, bpy.context.scene.render.pixel_aspect_y = 2.0, 1.0


def frame_range():
    """Frames 2, 4 and 6 of an animation (Frame Start 2, End 6, Step 2): the ball moves, the bulb dims."""
    scene = bpy.context.scene
    _ball_on_the_stage()
    ball, bulb = bpy.data.objects["Ball"], bpy.data.objects["Bulb"].data
    for frame, x, power_w in ((1, -1.5, 500.0), (7, 1.5, 100.0)):
        ball.location.x, bulb.energy = x, power_w
        ball.keyframe_insert("location", index=0, frame=frame)
        bulb.keyframe_insert("energy", frame=frame)
    scene.frame_start, scene.frame_end, scene.frame_step = 2, 6, 2
    scene.frame_set(1)  # the current frame is outside the range: only the range is rendered


def animated_shading():
    """Frames 2, 4 and 6 again, now with keyframed shading: an emissive card's Strength and the world's
    Strength change over the frames (node values, not object or light settings)."""
    scene = bpy.context.scene
    _ball_on_the_stage()
    card = kit.plane("Glowing card", 1.0, location=(1.3, 0.6, 0.6), rotation=(kit.degrees(90.0), 0.0, 0.0),
                     material=kit.emission("Glow", 1.0, (1.0, 0.6, 0.2)))
    glow = card.data.materials[0].node_tree.nodes["Emission"].inputs["Strength"]
    sky = scene.world.node_tree.nodes["Background"].inputs["Strength"]
    for frame, glow_strength, sky_strength in ((1, 0.5, 0.1), (7, 6.0, 0.6)):
        glow.default_value, sky.default_value = glow_strength, sky_strength
        glow.keyframe_insert("default_value", frame=frame)
        sky.keyframe_insert("default_value", frame=frame)
    scene.frame_start, scene.frame_end, scene.frame_step = 2, 6, 2
    scene.frame_set(1)


SCENES = [
    ParityScene("film_transparent", "Film ▸ Transparent (alpha)", film_transparent),
    ParityScene("view_layers", "Two view layers (an excluded collection, a filter)", view_layers, output="layers"),
    ParityScene("render_border", "Output ▸ Render Region", render_border),
    ParityScene("render_border_cropped", "Render Region ▸ Crop to Render Region", render_border_cropped),
    ParityScene("resolution_percentage", "Format ▸ Resolution % (50 %)", resolution_percentage),
    ParityScene("pixel_aspect", "Format ▸ Aspect X : Y = 2 : 1", pixel_aspect),
    ParityScene("frame_range", "Frame Start / End / Step (animation render)", frame_range, output="frames"),
    ParityScene("animated_shading", "Keyframed node values over a frame range", animated_shading, output="frames"),
]
