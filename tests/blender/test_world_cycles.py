"""Worlds against Cycles, the same .blend rendered by both and compared by statistics:

- an equirectangular HDRI with one small hot region lighting a floor and two spheres (light-sampled
  environment): mean luminance, normalised relMSE and the sunlit, shadowed and sphere regions within 2 %;
- the HDRI seen directly through a Mapping node (rotation and scale) and an equirectangular camera;
- the Nishita sky, whose measured differences docs/worlds.md explains (Prism integrates the long paths
  near the horizon more finely, and lets ozone absorb the direct sunlight).
"""

from __future__ import annotations

import math

import bpy
import numpy as np

from helpers.bpy_scenes import add_camera, add_plane
from helpers.bpy_worlds import blender_image, environment_world, hot_spot_hdri, sky_world
from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba


def _lambert(obj):
    """Principled without its specular layer: the Lambertian surface both renderers agree on."""
    obj.data.materials[0].node_tree.nodes["Principled BSDF"].inputs["Specular IOR Level"].default_value = 0.0


def _sphere(name, location, color, radius=0.6):
    bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=location, segments=48, ring_count=24)
    sphere = bpy.context.active_object
    sphere.name = name
    bpy.ops.object.shade_smooth()
    material = bpy.data.materials.new(name)
    material.use_nodes = True
    material.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (*color, 1.0)
    sphere.data.materials.append(material)
    _lambert(sphere)
    return sphere


def _floor_and_spheres():
    floor = add_plane("Floor", 10.0, color=(0.5, 0.5, 0.5))
    _lambert(floor)
    _sphere("Red", (-0.8, 0.0, 0.6), (0.8, 0.3, 0.2))
    _sphere("Blue", (0.8, 0.0, 0.6), (0.2, 0.5, 0.8))


def test_hdri_with_a_hot_spot_matches_cycles(prism_addon, fresh_scene):
    _floor_and_spheres()
    add_camera((0.0, -5.5, 2.8), (math.radians(62), 0.0, 0.0), lens_mm=35.0, resolution=(48, 32))
    environment_world(blender_image("hdri", hot_spot_hdri(sun_texel=(11, 40))))
    cycles = render_cycles_rgba(fresh_scene, samples=256)
    prism = render_prism_rgba(fresh_scene, samples=256)
    lc, lp = luminance(cycles), luminance(prism)
    a, b = lc / lc.mean(), lp / lp.mean()
    rel_mse = np.mean((a - b) ** 2 / (a**2 + 1e-2))
    print(f"MEASURED hot-spot HDRI: mean luminance Prism / Cycles {lp.mean() / lc.mean():.4f}, relMSE {rel_mse:.4f}")
    assert abs(lp.mean() / lc.mean() - 1) < 0.02
    assert rel_mse < 0.01
    near_floor = np.zeros(lc.shape, bool)
    near_floor[16:] = True  # all sunlit
    median = np.median(lc[near_floor])
    seen = lc > 0.05 * median  # not the HDRI's dark ground above the floor's far edge
    regions = {"sunlit floor": near_floor, "shadows": seen & (lc < 0.5 * median), "sunlit spheres": lc > 1.3 * median}
    for name, region in regions.items():
        assert region.sum() >= 20, name
        ratio = lp[region].mean() / lc[region].mean()
        print(f"MEASURED hot-spot HDRI, {name} ({region.sum()} px): Prism / Cycles {ratio:.4f}")
        assert abs(ratio - 1) < 0.02, f"{name}: Prism / Cycles = {ratio:.4f}"
    assert np.all(prism[..., 3] == 1.0)


def test_mapped_hdri_seen_through_an_equirectangular_camera_matches_cycles(prism_addon, fresh_scene):
    """A Mapping node rotating and stretching the HDRI, seen whole: every pixel as Cycles shows it."""
    rng = np.random.default_rng(3)
    image = np.repeat(np.repeat(rng.random((8, 16, 3)).astype(np.float32), 4, 0), 4, 1)  # 32 x 64, blocky
    environment_world(blender_image("blocks", image), strength=1.5, rotation=(0.3, -0.2, 1.1), scale=(1.0, 1.4, 0.8))
    camera = add_camera((0.0, 0.0, 0.0), (math.pi / 2, 0.0, -math.pi / 2), resolution=(64, 32))
    camera.data.type, camera.data.panorama_type = "PANO", "EQUIRECTANGULAR"
    add_plane("Speck", 0.001, location=(0.0, 0.0, -50.0))  # Prism needs some geometry
    cycles = render_cycles_rgba(fresh_scene, samples=16)[..., :3]
    prism = render_prism_rgba(fresh_scene, samples=16)[..., :3]
    difference = np.abs(prism - cycles).max(-1) / (cycles.max(-1) + 0.05)
    print(f"MEASURED mapped HDRI, equirectangular camera: median difference {np.median(difference):.4f}, "
          f"{100 * np.mean(difference < 0.1):.1f} % of pixels within 10 %, mean ratio {prism.mean() / cycles.mean():.4f}")
    assert np.median(difference) < 0.02
    assert np.mean(difference < 0.1) > 0.9  # the rest: block edges, where a pixel mixes two blocks
    assert abs(prism.mean() / cycles.mean() - 1) < 0.01


def test_nishita_sky_compares_with_cycles_as_documented(prism_addon, fresh_scene):
    floor = add_plane("Floor", 30.0, color=(0.5, 0.5, 0.5))
    _lambert(floor)
    _sphere("Ball", (0.0, 0.0, 0.6), (0.8, 0.8, 0.8))
    add_camera((0.0, -6.0, 1.2), (math.radians(88), 0.0, 0.0), lens_mm=28.0, resolution=(64, 40))
    sky_world(strength=0.1, sun_elevation=math.radians(30), sun_rotation=math.radians(200), sun_size=math.radians(1.5))
    cycles = render_cycles_rgba(fresh_scene, samples=64)
    prism = render_prism_rgba(fresh_scene, samples=64)
    lc, lp = luminance(cycles), luminance(prism)
    upper_sky = lp[:8].mean() / lc[:8].mean()  # 12-20° above the horizon
    floor_ratio = lp[28:].mean() / lc[28:].mean()
    horizon = lp[16:20].mean() / lc[16:20].mean()
    # docs/worlds.md: sky within a few percent above 10°, brighter near the horizon (Blender's 32 even
    # steps underestimate long paths), the sunlit floor a few percent darker (ozone absorbs sunlight).
    print(f"MEASURED Nishita Prism / Cycles: sky 12-20° {upper_sky:.4f}, near the horizon {horizon:.4f}, sunlit floor "
          f"{floor_ratio:.4f}, whole image {lp.mean() / lc.mean():.4f}")
    assert 0.97 < upper_sky < 1.06, upper_sky
    assert 0.92 < floor_ratio < 0.995, floor_ratio
    assert 1.1 < horizon < 1.7, horizon
    assert abs(lp.mean() / lc.mean() - 1) < 0.04
