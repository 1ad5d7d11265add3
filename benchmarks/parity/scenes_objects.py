"""Parity scenes about what is in the scene and how it is seen: camera clipping, view-layer filters, soft
light falloff, light temperature, instancing, linked libraries, materials without an output, holdouts, ray
visibility and motion blur. Each builder fills the emptied current file (see ``building.empty_file``)."""

from __future__ import annotations

import tempfile
from pathlib import Path

import bpy

from . import building as kit
from .record import ParityScene


def clip_range():
    """Camera at the origin looking down -Z, Clip Start 1 m and Clip End 5 m: a bright plane at 0.5 m
    (clipped) before one at 3 m on the left, a plane at 8 m (clipped) on the right, the world around."""
    kit.world(0.25)
    kit.plane("Near", 1.0, location=(-0.5, 0.0, -0.5), material=kit.emission("Near", 4.0))
    kit.plane("Middle", 3.0, location=(-1.5, 0.0, -3.0), material=kit.emission("Middle", 1.0))
    kit.plane("Far", 6.0, location=(3.0, 0.0, -8.0), material=kit.emission("Far", 2.0))
    camera = kit.camera((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), lens_mm=30.0)
    camera.data.clip_start, camera.data.clip_end = 1.0, 5.0


def environment_filter():
    """View Layer ▸ Filter ▸ Environment off under a bright world: Cycles shows black where the world was
    and lets it light nothing; the bulb alone lights the floor and the ball."""
    kit.stage(world_strength=1.0)
    kit.sphere("Ball", 0.6, (0.0, 0.0, 0.6))
    bpy.context.view_layer.use_sky = False


def surfaces_filter():
    """View Layer ▸ Filter ▸ Surfaces off: no surface at all is rendered (neither seen nor casting
    shadows), leaving the world and the bulb."""
    kit.stage(world_strength=0.5)
    kit.sphere("Ball", 0.6, (0.0, 0.0, 0.6))
    bpy.context.view_layer.use_solid = False


def curves_filter():
    """View Layer ▸ Filter ▸ Curves off: a glowing tuft of hair curves (a Curves object) standing on the
    floor is left out (with the filter on it raises the image's mean by 9 %); the floor and
    ball stay."""
    kit.stage()
    kit.sphere("Ball", 0.5, (0.8, 0.0, 0.5))
    curves = bpy.data.hair_curves.new("Tuft")
    curves.add_curves([2] * 36)
    for index, curve in enumerate(curves.curves):
        x, y = -1.0 + 0.1 * (index % 6), -0.3 + 0.1 * (index // 6)
        curve.points[0].position = (x, y, 0.0)
        curve.points[1].position = (x, y, 1.2)
    for point in curves.points:
        point.radius = 0.03
    curves.materials.append(kit.emission("Tuft glow", 2.0, (1.0, 0.5, 0.2)))
    kit.link_object(bpy.data.objects.new("Tuft", curves))
    bpy.context.view_layer.use_strand = False


def soft_falloff():
    """Soft Falloff on (Blender 4.x's default for new lights), seen from above over a grey floor: a point
    light of radius 0.5 m only 0.2 m over the floor (the floor cuts its sphere) and a 40° spot of radius
    0.3 m whose cone edge the radius widens."""
    kit.world(0.0)
    kit.plane("Floor", 8.0, material=kit.diffuse("Floor grey"))
    kit.light("Point", "POINT", 20.0, (-1.0, 0.0, 0.2), radius_m=0.5, soft_falloff=True).visible_camera = False
    kit.light("Spot", "SPOT", 200.0, (1.0, 0.0, 1.0), radius_m=0.3, soft_falloff=True, spot_size=kit.degrees(40.0),
              spot_blend=0.0).visible_camera = False
    kit.camera((0.0, 0.0, 5.0), (0.0, 0.0, 0.0), lens_mm=50.0)


def light_temperature():
    """Light ▸ Temperature (Blender 4.4+) on both lights, seen from above over a grey floor with a white ball:
    a 2700 K area light in white and a 9000 K point light whose Color (0.9, 0.95, 1.0) tints it; Cycles
    multiplies the Color by the temperature's colour, Prism filters Planck's spectrum by the Color."""
    kit.world(0.0)
    kit.plane("Floor", 8.0, material=kit.diffuse("Floor grey"))
    kit.sphere("Ball", 0.5, (0.0, 0.0, 0.5), material=kit.diffuse("Ball white", (0.8, 0.8, 0.8)))
    kit.light("Warm", "AREA", 150.0, (-1.2, 0.0, 2.0), size=1.0, use_temperature=True, temperature=2700.0)
    kit.light("Cool", "POINT", 300.0, (1.5, -0.5, 1.5), use_temperature=True, temperature=9000.0,
              color=(0.9, 0.95, 1.0))
    kit.camera((0.0, -3.0, 4.0), (0.0, 0.0, 0.3), lens_mm=35.0)


def instancing():
    """A collection (a ball and a box, not in the scene itself) instanced twice by empties, rotated and
    scaled, and a small ball instanced on the four vertices of a hidden square (Instancing ▸ Vertices)."""
    kit.stage()
    props = bpy.data.collections.new("Props")
    kit.sphere("Prop ball", 0.35, (0.0, 0.0, 0.35), material=kit.diffuse("Prop red", (0.8, 0.2, 0.1)), collection=props)
    kit.cube("Prop box", 0.5, (0.6, 0.0, 0.25), material=kit.diffuse("Prop blue", (0.1, 0.3, 0.8)), collection=props)
    placements = (("Left set", (-1.2, 0.3, 0.0), 30.0, 1.0), ("Right set", (0.9, -0.2, 0.0), -60.0, 1.4))
    for name, location, turn, scale in placements:
        empty = bpy.data.objects.new(name, None)
        empty.instance_type, empty.instance_collection = "COLLECTION", props
        empty.location, empty.rotation_euler, empty.scale = location, (0.0, 0.0, kit.degrees(turn)), (scale,) * 3
        kit.link_object(empty)
    square = kit.plane("Vertex carrier", 1.6, location=(0.0, 1.6, 0.2))
    square.instance_type = "VERTS"
    pebble = kit.sphere("Pebble", 0.2, (0.0, 0.0, 0.0), material=kit.diffuse("Pebble yellow", (0.8, 0.7, 0.1)))
    pebble.parent = square


def _library_file() -> Path:
    """Where the library .blend is written (a fixed temporary path, rewritten for every build)."""
    folder = Path(tempfile.gettempdir()) / "prism_parity"
    folder.mkdir(exist_ok=True)
    return folder / "library_props.blend"


def linked_library():
    """A red ball and a green box written to a library .blend (``bpy.data.libraries.write``), removed from
    this file and linked back: the ball as a linked object, the collection through an instancing empty."""
    path = _library_file()
    props = bpy.data.collections.new("Library props")
    kit.sphere("Library ball", 0.5, (0.0, 0.0, 0.5), material=kit.diffuse("Library red", (0.8, 0.15, 0.1)),
               collection=props)
    kit.cube("Library box", 0.6, (0.9, 0.3, 0.3), material=kit.diffuse("Library green", (0.2, 0.7, 0.2)),
             collection=props)
    bpy.data.libraries.write(str(path), {props}, fake_user=True)
    for obj in list(props.objects):
        bpy.data.objects.remove(obj)
    bpy.data.collections.remove(props)
    kit.stage()
    with bpy.data.libraries.load(str(path), link=True) as (_, linked):
        linked.collections = ["Library props"]
        linked.objects = ["Library ball"]
    ball = linked.objects[0]
    kit.link_object(ball)  # linked object, placed where the library put it
    empty = bpy.data.objects.new("Library set", None)
    empty.instance_type, empty.instance_collection = "COLLECTION", linked.collections[0]
    empty.location = (-1.5, 0.5, 0.0)
    kit.link_object(empty)


def material_without_output():
    """Two upright cards: a grey control, and one whose node tree lost its Material Output (an add-on's
    tree, the add-on not installed), which Cycles renders black."""
    kit.stage()
    upright = (kit.degrees(90.0), 0.0, 0.0)
    kit.plane("Control card", 1.2, location=(-0.8, 0.0, 0.7), rotation=upright)
    lost = kit.plane("Lost card", 1.2, location=(0.8, 0.0, 0.7), rotation=upright,
                     material=kit.diffuse("Lost material", (0.7, 0.7, 0.7)))
    tree = lost.data.materials[0].node_tree
    tree.nodes.remove(next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial"))


def holdouts():
    """A ball with Object ▸ Visibility ▸ Holdout and an upright card with the Holdout shader, film not
    transparent: both cut alpha-0 black holes in the image."""
    kit.stage()
    kit.sphere("Holdout ball", 0.6, (-0.8, 0.0, 0.6)).is_holdout = True
    hole = bpy.data.materials.new("Hole")
    hole.use_nodes = True
    nodes = hole.node_tree.nodes
    nodes.remove(nodes["Principled BSDF"])
    hole.node_tree.links.new(nodes.new("ShaderNodeHoldout").outputs[0], nodes["Material Output"].inputs["Surface"])
    kit.plane("Holdout card", 1.0, location=(0.9, 0.0, 0.6), rotation=(kit.degrees(90.0), 0.0, 0.0), material=hole)


def visibility_flags():
    """Object ▸ Visibility: a ball hidden from the camera (its shadow stays), a ball that casts no shadow,
    a box disabled in renders (hide_render: neither seen nor shadowing)."""
    kit.stage()
    kit.sphere("Unseen ball", 0.5, (-1.0, 0.0, 0.5)).visible_camera = False
    orange = kit.diffuse("Orange", (0.8, 0.4, 0.1))
    kit.sphere("Shadowless ball", 0.5, (0.4, -0.2, 0.5), material=orange).visible_shadow = False
    kit.cube("Disabled box", 0.8, (1.3, 0.8, 0.4)).hide_render = True


def motion_blur():
    """Render ▸ Motion Blur on, a ball moving 0.5 m while the shutter is open: both renderers blur it
    (``docs/motion_blur.md``)."""
    scene = bpy.context.scene
    kit.stage()
    ball = kit.sphere("Moving ball", 0.5, (-0.5, 0.0, 0.5))
    for frame, x in ((0, -1.5), (2, 0.5)):  # linear: 0.5 m during the half-frame shutter around frame 1
        ball.location.x = x
        ball.keyframe_insert("location", index=0, frame=frame)
    for point in ball.animation_data.action.fcurves[0].keyframe_points:
        point.interpolation = "LINEAR"
    scene.frame_set(1)
    scene.render.use_motion_blur = True


def layer_motion_blur():
    """Render ▸ Motion Blur on but the view layer's Filter ▸ Motion Blur off: the ball of ``motion_blur``
    renders sharp at frame 1 in both engines."""
    motion_blur()
    bpy.context.view_layer.use_motion_blur = False


SCENES = [
    ParityScene("clip_range", "Camera ▸ Clip Start / Clip End", clip_range, samples=8, bounces=1),
    ParityScene("environment_filter", "View Layer ▸ Filter ▸ Environment off", environment_filter),
    ParityScene("surfaces_filter", "View Layer ▸ Filter ▸ Surfaces off", surfaces_filter),
    ParityScene("curves_filter", "View Layer ▸ Filter ▸ Curves off", curves_filter),
    ParityScene("soft_falloff", "Light ▸ Soft Falloff (point, spot)", soft_falloff, samples=256, bounces=1),
    ParityScene("light_temperature", "Light ▸ Temperature (Blender 4.4+)", light_temperature, bounces=2),
    ParityScene("instancing", "Collection instances, Instancing ▸ Vertices", instancing),
    ParityScene("linked_library", "Linked library (object and collection)", linked_library),
    ParityScene("material_without_output", "Material without Material Output", material_without_output),
    ParityScene("holdouts", "Object ▸ Holdout, Holdout shader", holdouts),
    ParityScene("visibility_flags", "Visibility ▸ Camera, Shadow; Disable in Renders", visibility_flags),
    ParityScene("motion_blur", "Render ▸ Motion Blur", motion_blur),
    ParityScene("layer_motion_blur", "View Layer ▸ Filter ▸ Motion Blur off", layer_motion_blur),
]
