"""Baking with Prism (Render ▸ Bake, ``bpy.ops.object.bake``) against closed forms and against Cycles 4.5
baking the same .blend: a diffuse plane (albedo ρ) in the open under a uniform world of radiance L bakes
Combined ρ·L, Diffuse Color ρ, Diffuse Direct L (Cycles' light passes without Color are divided by it), an
Emission plane its strength × colour, a flat plane's tangent-space Normal (0.5, 0.5, 1); Glossy, AO beside a
wall and the Combined filter against Cycles, absolute means within 2 %; a bake stops when asked."""

from __future__ import annotations

import bpy
import numpy as np
import pytest

from helpers.bake_scenes import bake, node_material, uniform_world, uv_plane

ALBEDO = 0.6
RADIANCE = 1.5
SAMPLES = 64


def _mean(image) -> np.ndarray:
    return image[..., :3].reshape(-1, 3).mean(axis=0)


def _both(scene, obj, bake_type, **options):
    """(Prism's, Cycles') baked pixels of the same scene."""
    prism = bake(scene, "PRISM", obj, bake_type, SAMPLES, **options)
    cycles = bake(scene, "CYCLES", obj, bake_type, SAMPLES, **options)
    return prism, cycles


def _grey_plane():
    uniform_world(strength=RADIANCE)
    material = node_material("Grey", "ShaderNodeBsdfDiffuse", Color=(ALBEDO, ALBEDO, ALBEDO, 1.0))
    return uv_plane("Floor", 2.0, material)


def test_a_diffuse_plane_bakes_its_closed_forms_as_cycles_does(prism_addon, fresh_scene):
    plane = _grey_plane()
    cases = {  # bake type, pass filter → closed form
        "Combined": ("COMBINED", {}, ALBEDO * RADIANCE),
        "Diffuse (Direct, Indirect, Color)": ("DIFFUSE", {}, ALBEDO * RADIANCE),
        "Diffuse Color": ("DIFFUSE", {"pass_filter": {"COLOR"}}, ALBEDO),
        "Diffuse Direct": ("DIFFUSE", {"pass_filter": {"DIRECT"}}, RADIANCE),
    }
    for name, (bake_type, options, expected) in cases.items():
        prism, cycles = _both(fresh_scene, plane, bake_type, **options)
        p, c = _mean(prism), _mean(cycles)
        print(f"MEASURED {name}: Prism {np.round(p, 4)}, Cycles {np.round(c, 4)}, closed form {expected}")
        assert np.allclose(p, expected, rtol=0.02), name
        assert np.allclose(p, c, rtol=0.02), name
        assert np.all(prism[..., 3] == 1.0)


def test_an_emission_plane_bakes_strength_times_colour(prism_addon, fresh_scene):
    uniform_world(strength=RADIANCE)  # lights it, but Emit is emission only
    colour = (0.9, 0.5, 0.2)
    material = node_material("Lamp", "ShaderNodeEmission", Color=(*colour, 1.0), Strength=2.0)
    plane = uv_plane("Lamp", 2.0, material)
    prism, cycles = _both(fresh_scene, plane, "EMIT")
    p, c = _mean(prism), _mean(cycles)
    print(f"MEASURED Emit: Prism {np.round(p, 4)}, Cycles {np.round(c, 4)}, closed form {2.0 * np.array(colour)}")
    assert np.allclose(p, 2.0 * np.array(colour), rtol=0.02)
    assert np.allclose(p, c, rtol=0.02)


def test_a_flat_plane_bakes_the_flat_tangent_space_normal(prism_addon, fresh_scene):
    plane = _grey_plane()
    plane.rotation_euler = (0.4, -0.3, 0.2)  # tangent space follows the surface wherever it faces
    prism, cycles = _both(fresh_scene, plane, "NORMAL")
    print(f"MEASURED Normal (tangent): Prism {np.round(_mean(prism), 4)}, Cycles {np.round(_mean(cycles), 4)}")
    assert np.allclose(prism[..., :3], (0.5, 0.5, 1.0), atol=1e-3)
    assert np.allclose(prism[..., :3], cycles[..., :3], atol=1e-3)
    world = bake(fresh_scene, "PRISM", plane, "NORMAL", 4, normal_space="OBJECT")
    assert np.allclose(world[..., :3], (0.5, 0.5, 1.0), atol=1e-3)  # +Z of the object, compressed


def test_a_normal_map_bakes_into_the_normal_it_gives(prism_addon, fresh_scene):
    """A tangent-space Normal Map node of constant colour c on the plane's material: the baked tangent-space
    Normal is normalize(2c - 1), compressed (as Cycles bakes the shading normal)."""
    plane = _grey_plane()
    material = plane.active_material
    nodes, links = material.node_tree.nodes, material.node_tree.links
    normal_map = nodes.new("ShaderNodeNormalMap")
    colour = np.array([0.7, 0.5, 0.8])
    normal_map.inputs["Color"].default_value = (*colour, 1.0)
    links.new(normal_map.outputs["Normal"], next(n for n in nodes if n.type == "BSDF_DIFFUSE").inputs["Normal"])
    tilted = 2.0 * colour - 1.0
    expected = (tilted / np.linalg.norm(tilted) + 1.0) / 2.0
    prism, cycles = _both(fresh_scene, plane, "NORMAL")
    print(f"MEASURED Normal Map: Prism {np.round(_mean(prism), 4)}, Cycles {np.round(_mean(cycles), 4)}, "
          f"closed form {np.round(expected, 4)}")
    assert np.allclose(prism[..., :3], expected, atol=2e-3)
    assert np.allclose(_mean(prism), _mean(cycles), atol=2e-3)


def test_glossy_and_the_combined_filter_bake_as_cycles_does(prism_addon, fresh_scene):
    uniform_world(strength=RADIANCE)
    material = node_material("Metal", "ShaderNodeBsdfGlossy", Color=(0.9, 0.7, 0.4, 1.0), Roughness=0.4)
    plane = uv_plane("Metal", 2.0, material)
    prism, cycles = _both(fresh_scene, plane, "GLOSSY")
    print(f"MEASURED Glossy: Prism {np.round(_mean(prism), 4)}, Cycles {np.round(_mean(cycles), 4)}")
    assert np.allclose(_mean(prism), _mean(cycles), rtol=0.02)
    # Color alone: Cycles bakes the closure's colour; Prism's GlossCol pass is the lobe's albedo in the view
    # direction (the BSDF sample weight's mean), a few % below the colour for a rough lobe (docs/bake.md)
    prism, cycles = _both(fresh_scene, plane, "GLOSSY", pass_filter={"COLOR"})
    print(f"MEASURED Glossy Color: Prism {np.round(_mean(prism), 4)}, Cycles {np.round(_mean(cycles), 4)}")
    assert np.allclose(_mean(cycles), (0.9, 0.7, 0.4), rtol=1e-3)
    assert np.all(_mean(prism) < _mean(cycles)) and np.allclose(_mean(prism), _mean(cycles), rtol=0.05)
    # View From ▸ Active Camera: the lobe seen from a camera low over the plane (another view, another reflectance)
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.location, camera.rotation_euler = (0.0, -6.0, 1.5), (1.33, 0.0, 0.0)
    fresh_scene.collection.objects.link(camera)
    fresh_scene.camera = camera
    fresh_scene.render.bake.view_from = "ACTIVE_CAMERA"
    prism, cycles = _both(fresh_scene, plane, "GLOSSY")
    print(f"MEASURED Glossy from the camera: Prism {np.round(_mean(prism), 4)}, Cycles {np.round(_mean(cycles), 4)}")
    assert np.allclose(_mean(prism), _mean(cycles), rtol=0.02)
    fresh_scene.render.bake.view_from = "ABOVE_SURFACE"
    # Combined with Glossy switched off: nothing of this material's light is left
    prism, cycles = _both(fresh_scene, plane, "COMBINED", pass_filter={"DIRECT", "INDIRECT", "DIFFUSE", "EMIT"})
    assert np.allclose(prism[..., :3], 0.0) and np.allclose(cycles[..., :3], 0.0, atol=1e-4)


def test_the_combined_filter_without_emit_keeps_the_reflected_light(prism_addon, fresh_scene):
    """A grey plane that also glows: Combined with Emit off bakes ρ·L alone, as Cycles."""
    uniform_world(strength=RADIANCE)
    material = node_material("Glow", "ShaderNodeBsdfDiffuse", Color=(ALBEDO, ALBEDO, ALBEDO, 1.0))
    nodes, links = material.node_tree.nodes, material.node_tree.links
    diffuse = next(n for n in nodes if n.type == "BSDF_DIFFUSE")
    emission, add = nodes.new("ShaderNodeEmission"), nodes.new("ShaderNodeAddShader")
    emission.inputs["Strength"].default_value = 0.7
    links.new(diffuse.outputs[0], add.inputs[0])
    links.new(emission.outputs[0], add.inputs[1])
    links.new(add.outputs[0], nodes["Material Output"].inputs["Surface"])
    plane = uv_plane("Glow", 2.0, material)
    every = _both(fresh_scene, plane, "COMBINED")
    no_emit = _both(fresh_scene, plane, "COMBINED", pass_filter={"DIRECT", "INDIRECT", "DIFFUSE", "GLOSSY",
                                                                 "TRANSMISSION"})
    for name, (prism, cycles), expected in (("all", every, ALBEDO * RADIANCE + 0.7),
                                            ("Emit off", no_emit, ALBEDO * RADIANCE)):
        print(f"MEASURED Combined {name}: Prism {np.round(_mean(prism), 4)}, Cycles {np.round(_mean(cycles), 4)}")
        assert np.allclose(_mean(prism), expected, rtol=0.02), name
        assert np.allclose(_mean(prism), _mean(cycles), rtol=0.02), name


def test_ambient_occlusion_beside_a_wall_bakes_as_cycles_does(prism_addon, fresh_scene):
    """A floor (baked) with a wall standing along one edge; AO within 1 m: darker towards the wall."""
    plane = _grey_plane()
    uv_plane("Wall", 2.0, location=(1.0, 0.0, 1.0), rotation=(0.0, -np.pi / 2, 0.0))
    fresh_scene.world.light_settings.distance = 1.0
    prism, cycles = _both(fresh_scene, plane, "AO")
    p, c = _mean(prism), _mean(cycles)
    near, far = prism[:, -4:, 0].mean(), prism[:, :4, 0].mean()  # columns by the wall (x = +1) and away
    print(f"MEASURED AO: Prism {np.round(p, 4)}, Cycles {np.round(c, 4)}; by the wall {near:.3f}, away {far:.3f}")
    assert np.allclose(p, c, rtol=0.02)
    assert far == pytest.approx(1.0, abs=0.01) and near < 0.8
    assert np.allclose(cycles[:, -4:, 0].mean(), near, rtol=0.03)


def test_selected_to_active_bakes_the_selected_objects_surface(prism_addon, fresh_scene):
    """A glowing plane 5 cm above the active plane, baked onto it with Selected to Active: its Emit and its
    Combined (its glow plus the world its grey reflects) land in the active plane's image."""
    uniform_world(strength=RADIANCE)
    target = uv_plane("Low", 2.0, node_material("Low", "ShaderNodeBsdfDiffuse"))
    glow = bpy.data.materials.new("High")
    glow.use_nodes = True
    principled = glow.node_tree.nodes["Principled BSDF"]
    principled.inputs["Base Color"].default_value = (ALBEDO, ALBEDO, ALBEDO, 1.0)
    principled.inputs["Specular IOR Level"].default_value = 0.0
    principled.inputs["Emission Color"].default_value = (0.2, 0.6, 1.0, 1.0)
    principled.inputs["Emission Strength"].default_value = 1.5
    high = uv_plane("High", 2.5, glow, location=(0.0, 0.0, 0.05))
    options = dict(also_selected=(high,), use_selected_to_active=True, cage_extrusion=0.1)
    for bake_type, expected in (("EMIT", 1.5 * np.array([0.2, 0.6, 1.0])),
                                ("COMBINED", 1.5 * np.array([0.2, 0.6, 1.0]) + ALBEDO * RADIANCE)):
        prism = bake(fresh_scene, "PRISM", target, bake_type, SAMPLES, **options)
        cycles = bake(fresh_scene, "CYCLES", target, bake_type, SAMPLES, **options)
        print(f"MEASURED Selected to Active {bake_type}: Prism {np.round(_mean(prism), 4)}, "
              f"Cycles {np.round(_mean(cycles), 4)}, closed form {np.round(expected, 4)}")
        assert np.allclose(_mean(prism), expected, rtol=0.02), bake_type
        assert np.allclose(_mean(prism), _mean(cycles), rtol=0.02), bake_type


def _ramp_material():
    """An emission whose strength is u + 2 v of the UV map (white), into an image to bake."""
    material = node_material("Ramp", "ShaderNodeEmission")
    nodes, links = material.node_tree.nodes, material.node_tree.links
    emission = next(n for n in nodes if n.type == "EMISSION")
    coordinates, split = nodes.new("ShaderNodeTexCoord"), nodes.new("ShaderNodeSeparateXYZ")
    twice, total = nodes.new("ShaderNodeMath"), nodes.new("ShaderNodeMath")
    twice.operation, twice.inputs[1].default_value = "MULTIPLY", 2.0
    links.new(coordinates.outputs["UV"], split.inputs[0])
    links.new(split.outputs["Y"], twice.inputs[0])
    links.new(split.outputs["X"], total.inputs[0])
    links.new(twice.outputs[0], total.inputs[1])
    links.new(total.outputs[0], emission.inputs["Strength"])
    return material


def _ramp_error(image, size: int, block: int = 10) -> float:
    """The largest relative error of the baked ramp's means over blocks of ``block`` texels a side (the
    spectral noise of single texels averaged out) against each texel centre's u + 2 v."""
    block = min(block, size // 8)
    centre = (np.arange(size) + 0.5) / size
    expected = centre[None, :] + 2.0 * centre[:, None]  # rows from the bottom: v; columns: u

    def blocks(a):
        return a.reshape(size // block, block, size // block, block).mean(axis=(1, 3))

    return float(np.abs(blocks(image[..., 0]) / blocks(expected) - 1.0).max())


def test_an_image_larger_than_a_tile_bakes_every_texel_in_its_place(prism_addon, fresh_scene):
    """300 x 300 texels (tiles of 256: four uneven ones) of an emission whose strength is u + 2 v of the UV map:
    each texel gets its own centre's value, so tiles land where they belong."""
    material = _ramp_material()
    size = 300
    material.node_tree.nodes.active.image.scale(size, size)
    plane = uv_plane("Ramp", 2.0, material)
    image = bake(fresh_scene, "PRISM", plane, "EMIT", 16)
    error = _ramp_error(image, size)
    print(f"MEASURED {size} x {size} Emit ramp: blocks of 10 x 10 texels within {error:.4f} (relative)")
    assert error < 0.03


def test_a_smooth_sphere_bakes_its_interpolated_normals_as_cycles_does(prism_addon, fresh_scene):
    """A smooth UV sphere (512 loop triangles, their corner normals interpolated) baked to an object-space
    Normal map: texel by texel as Cycles bakes it (Cycles jitters within the texel, Prism takes its centre)."""
    uniform_world()
    bpy.ops.mesh.primitive_uv_sphere_add(segments=32, ring_count=16, radius=1.0)
    sphere = bpy.context.active_object
    sphere.data.shade_smooth()
    sphere.rotation_euler = (0.3, 0.2, 0.1)
    sphere.data.materials.append(node_material("Ball", "ShaderNodeBsdfDiffuse"))
    prism, cycles = _both(fresh_scene, sphere, "NORMAL", normal_space="OBJECT")
    covered = np.linalg.norm(prism[..., :3] - 0.5, axis=-1) > 0.4  # texels with a point (the rest stay black)
    error = np.abs(prism[..., :3] - cycles[..., :3])[covered]
    print(f"MEASURED smooth sphere Normal: {covered.sum()} texels, mean |error| {error.mean():.5f}, "
          f"max {error.max():.4f}")
    assert covered.mean() > 0.8
    assert error.mean() < 0.002 and error.max() < 0.02


def test_a_subdivided_mesh_bakes_each_triangle_where_blender_maps_it(prism_addon, fresh_scene):
    """The UV ramp of ``test_an_image_larger_than_a_tile...`` on a plane under a Subdivision Surface modifier
    (level 2, simple: 32 loop triangles of the evaluated mesh): each texel still gets its own UV's value."""
    material = _ramp_material()
    plane = uv_plane("Ramp", 2.0, material)
    modifier = plane.modifiers.new("Subdivision", "SUBSURF")
    modifier.subdivision_type, modifier.levels, modifier.render_levels = "SIMPLE", 2, 2
    image = bake(fresh_scene, "PRISM", plane, "EMIT", 16)
    error = _ramp_error(image, 32)
    print(f"MEASURED subdivided plane Emit ramp: blocks of 4 x 4 texels within {error:.4f} (relative)")
    assert error < 0.03


def test_position_bakes_each_texels_world_point(prism_addon, fresh_scene):
    """A plane moved and turned: Position bakes each texel's world point (closed form: the texel centre's point
    of the plane), as Cycles bakes it at 1 sample (its texel centre; Cycles 4.5 adds this pass up over the
    samples without dividing: at 64 samples it bakes 64 × the point)."""
    plane = _grey_plane()
    plane.location, plane.rotation_euler = (0.3, -0.2, 0.5), (0.4, -0.3, 0.2)
    bpy.context.view_layer.update()
    centre = (np.arange(32) + 0.5) / 32
    u, v = np.meshgrid(centre, centre)  # rows from the bottom: v
    local = np.stack([2.0 * u - 1.0, 2.0 * v - 1.0, np.zeros_like(u), np.ones_like(u)], axis=-1)
    expected = (local @ np.array(plane.matrix_world).T)[..., :3]
    prism = bake(fresh_scene, "PRISM", plane, "POSITION", SAMPLES)
    cycles = bake(fresh_scene, "CYCLES", plane, "POSITION", 1)
    error = np.abs(prism[..., :3] - cycles[..., :3])
    print(f"MEASURED Position: Prism / Cycles (1 sample) texel by texel max |error| {error.max():.2e} m, "
          f"closed form {np.abs(prism[..., :3] - expected).max():.2e} m")
    assert error.max() < 1e-4
    # Blender's rasteriser puts each texel's point 1.25e-4 of the UV square off the texel's centre
    assert np.allclose(prism[..., :3], expected, atol=5e-4)


def test_a_bake_into_vertex_colours(prism_addon, fresh_scene):
    """Output ▸ Target ▸ Active Color Attribute: each corner gets its point's value (an Emission of strength 2)."""
    uniform_world()
    plane = uv_plane("Lamp", 2.0, node_material("Lamp", "ShaderNodeEmission", Strength=2.0))
    colours = plane.data.color_attributes.new("Baked", "FLOAT_COLOR", "CORNER")
    plane.data.color_attributes.active_color = colours
    bake(fresh_scene, "PRISM", plane, "EMIT", SAMPLES, target="VERTEX_COLORS")
    values = np.empty(len(colours.data) * 4, np.float32)
    colours.data.foreach_get("color", values)
    print(f"MEASURED vertex colours: {np.round(values.reshape(-1, 4)[:, :3].mean(axis=0), 4)} (closed form 2)")
    assert np.allclose(values.reshape(-1, 4)[:, :3], 2.0, rtol=0.02)


def test_a_bake_stops_when_asked(prism_addon, fresh_scene, monkeypatch):
    """Esc (``test_break``) after the first pass of samples stops the bake there: Blender gets nothing for the
    unfinished tile (the image stays as cleared) and no further pass runs."""
    import importlib

    plane = _grey_plane()
    session = importlib.import_module(f"{prism_addon.__name__}.engine.render.bake_session")
    renderer = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.renderer")
    passes = []
    original_pass = renderer.Renderer.render_pass

    def counting_pass(self, samples_per_pixel=None):
        original_pass(self, samples_per_pixel)
        passes.append(self.samples_done)

    class EscAfterAPass:
        def __init__(self, engine):
            self._engine = engine

        def test_break(self):
            return len(passes) >= 1

        def __getattr__(self, name):
            return getattr(self._engine, name)

    original_init = session.BakeSession.__init__
    monkeypatch.setattr(renderer.Renderer, "render_pass", counting_pass)
    monkeypatch.setattr(session.BakeSession, "__init__",
                        lambda self, engine, *rest: original_init(self, EscAfterAPass(engine), *rest))
    fresh_scene.prism.samples_per_pass = 1
    image = bake(fresh_scene, "PRISM", plane, "COMBINED", SAMPLES, keep_samples_per_pass=True)
    assert passes == [1]
    assert np.allclose(image[..., :3], 0.0)  # cleared, never written
