"""Hair Curves scenes for the Blender tests: strands built with bpy, a groom, and the sun-and-sky lighting the
hair tests share (``test_hair_curves``, ``test_hair_bsdf_cycles``)."""

from __future__ import annotations

import importlib

import bpy
import numpy as np

from helpers.node_scenes import sun_and_sky


def export_scene(prism_addon, warnings=None):
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    return export.export_scene(bpy.context.evaluated_depsgraph_get(), warnings)


def hair_object(name, sizes, positions, radii=None, curve_slots=None):
    """A Curves object of curves with ``sizes`` points at ``positions`` [P, 3], a ``radius`` attribute where
    given and the CURVE-domain ``material_index`` ``curve_slots``."""
    curves = bpy.data.hair_curves.new(name)
    curves.add_curves(list(sizes))
    curves.points.foreach_set("position", np.asarray(positions, np.float32).ravel())
    if radii is not None:
        curves.attributes.new("radius", "FLOAT", "POINT")
        curves.points.foreach_set("radius", np.asarray(radii, np.float32))
    if curve_slots is not None:
        index = curves.attributes.new("material_index", "INT", "CURVE")
        index.data.foreach_set("value", np.asarray(curve_slots, np.int32))
    obj = bpy.data.objects.new(name, curves)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def groom(count=300, points=6, seed=3):
    """``count`` strands of ``points`` points rising from a 1 m disc, bending sideways, tapering from 8 to 3 mm."""
    rng = np.random.default_rng(seed)
    angle, distance = rng.uniform(0, 2 * np.pi, count), 0.5 * np.sqrt(rng.uniform(0, 1, count))
    roots = np.column_stack([distance * np.cos(angle), distance * np.sin(angle), np.zeros(count)])
    s = np.linspace(0.0, 1.0, points)[None, :, None]
    lean = rng.normal(size=(count, 1, 3)) * (0.25, 0.25, 0.0)
    height = rng.uniform(0.6, 1.0, (count, 1, 1))
    positions = roots[:, None, :] + s * height * np.array([0.0, 0.0, 1.0]) + s * s * lean
    radii = np.tile(np.linspace(0.008, 0.003, points), count)
    return [points] * count, positions.reshape(-1, 3), radii


def tint_and_fade(obj, sizes, rng, tint_range=(0.2, 0.9), root_fade=0.3):
    """Give the strands of ``obj`` (``sizes`` points each) a curve-domain colour "tint" (uniform in ``tint_range``
    per channel, from ``rng``) and a point-domain float "fade" rising from ``root_fade`` at the root to 1 at the
    tip; return a material whose Diffuse colour is tint × fade (two Attribute nodes)."""
    from helpers.node_scenes import material, node

    tint = np.column_stack([rng.uniform(*tint_range, (len(sizes), 3)), np.ones(len(sizes))])
    obj.data.attributes.new("tint", "FLOAT_COLOR", "CURVE").data.foreach_set("color", tint.ravel())
    fade = np.concatenate([np.linspace(root_fade, 1.0, n) for n in sizes])
    obj.data.attributes.new("fade", "FLOAT", "POINT").data.foreach_set("value", fade)
    mat, nodes, link = material("Tint x fade")
    bsdf = node(nodes, "ShaderNodeBsdfDiffuse")
    product = node(nodes, "ShaderNodeVectorMath")
    product.operation = "MULTIPLY"
    for index, name in enumerate(("tint", "fade")):
        read = nodes.new("ShaderNodeAttribute")
        read.attribute_name = name
        link(read.outputs["Color"], product.inputs[index])
    link(product.outputs[0], bsdf.inputs["Color"])
    link(bsdf.outputs[0], nodes["Output"].inputs["Surface"])
    return mat


def luminance_and_coverage(scene, label, samples=64):
    """Prism and Cycles render ``scene`` (a transparent film): (Prism / Cycles mean luminance, Prism / Cycles mean
    alpha, Cycles' mean alpha), printed as ``MEASURED label``."""
    from helpers.cycles import luminance, render_cycles_rgba, render_prism_rgba

    cycles = render_cycles_rgba(scene, samples)
    prism = render_prism_rgba(scene, samples)
    light = luminance(prism).mean() / luminance(cycles).mean()
    coverage = prism[..., 3].mean() / cycles[..., 3].mean()
    print(f"MEASURED {label}: luminance Prism {luminance(prism).mean():.5f}, Cycles {luminance(cycles).mean():.5f}, "
          f"ratio {light:.4f}; coverage Prism {prism[..., 3].mean():.4f}, Cycles {cycles[..., 3].mean():.4f}, "
          f"ratio {coverage:.4f}")
    return light, coverage, float(cycles[..., 3].mean())


def assert_matches_cycles(scene, label, covered=(0.1, 0.6), samples=64):
    """Prism's mean luminance and coverage within 2 % of Cycles' (``luminance_and_coverage``), with Cycles' mean
    alpha inside ``covered`` (the strands cover part of the picture; None: not checked)."""
    import pytest

    light, coverage, seen = luminance_and_coverage(scene, label, samples)
    if covered is not None:
        assert covered[0] < seen < covered[1]
    assert light == pytest.approx(1.0, abs=0.02)
    assert coverage == pytest.approx(1.0, abs=0.02)


def lit(scene):
    """A sun and a grey world; Render ▸ Curves ▸ Shape "3D Curves" (a new scene's is "Rounded Ribbons")."""
    scene.cycles_curves.shape = "THICK"
    sun_and_sky(scene, (0.7, 0.2, 0.8))
