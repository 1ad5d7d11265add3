"""Mitsuba 3 (spectral) on a benchmark scene, as a peer of Prism.

Variant ``llvm_ad_spectral`` (JIT-compiled, vectorised, multi-threaded) when a
libLLVM that Dr.Jit can drive is found (LLVM 15 aborts on x86 ``fminimum``;
Debian's ``libllvm19`` works: ``apt-get install libllvm19``), else
``scalar_spectral``. ``DRJIT_LIBLLVM_PATH`` overrides the search.

Conventions matched to Prism: the same triangles (Mitsuba meshes built in memory
from the Scene's arrays; the timed ``load_dict`` builds the BVH), two-sided
Lambertian grey, a Blender area light as a one-sided ``rectangle`` area emitter
of radiance P / (pi A), RGB white upsampled with Mitsuba's illuminant (D65-white)
convention, pinhole camera with the same horizontal field of view, box pixel
filter, independent sampler, emitters hidden from camera rays (as Prism's and
Cycles' Blender lights), ``max_depth = max_bounces + 1`` (Mitsuba counts the
camera segment), Mitsuba's default Russian roulette (from depth 5).

Run: ``python -m benchmarks.peers.mitsuba --scene cornell_grey --spp 1 4 16 --out x.npz``
"""

from __future__ import annotations

import glob
import os
import re
import sys
import time

import numpy as np

MIN_LLVM_MAJOR = 19


def find_libllvm():
    """Path of the newest libLLVM with major version >= MIN_LLVM_MAJOR, or None."""
    found = []
    for path in glob.glob("/usr/lib/x86_64-linux-gnu/libLLVM*.so*") + glob.glob("/usr/lib/llvm-*/lib/libLLVM*.so*"):
        m = re.search(r"LLVM-?(\d+)", os.path.basename(path))
        if m and int(m.group(1)) >= MIN_LLVM_MAJOR:
            found.append((int(m.group(1)), path))
    return max(found)[1] if found else None


def choose_variant():
    """Set DRJIT_LIBLLVM_PATH if needed and return the variant to use."""
    if os.environ.get("DRJIT_LIBLLVM_PATH"):
        return "llvm_ad_spectral"
    lib = find_libllvm()
    if lib:
        os.environ["DRJIT_LIBLLVM_PATH"] = lib
        return "llvm_ad_spectral"
    return "scalar_spectral"


def make_mesh(name, vertices, triangles, normals, bsdf, emitter=None):
    """A Mitsuba mesh built in memory from numpy arrays (no file round trip)."""
    import mitsuba as mi

    props = mi.Properties()
    props["bsdf"] = mi.load_dict(bsdf)
    if emitter is not None:
        props["emitter"] = mi.load_dict(emitter)
    mesh = mi.Mesh(name, len(vertices), len(triangles), props, has_vertex_normals=normals is not None)
    params = mi.traverse(mesh)
    params["vertex_positions"] = mi.Float(np.ascontiguousarray(vertices, np.float32).ravel())
    params["faces"] = mi.UInt32(np.ascontiguousarray(triangles, np.uint32).ravel())
    if normals is not None:
        params["vertex_normals"] = mi.Float(np.ascontiguousarray(normals, np.float32).ravel())
    params.update()
    return mesh


def _matrix(m):
    import mitsuba as mi

    return mi.ScalarTransform4f(np.asarray(m, dtype=np.float64).tolist())


def scene_dict(scene, max_bounces=8):
    """A Mitsuba 3 scene dict of a Prism ``Scene`` (diffuse/emissive materials, area
    lights, pinhole camera); meshes are Mitsuba meshes built from the same arrays."""
    import mitsuba as mi

    cam = scene.camera
    if cam.model != "pinhole":
        raise ValueError(f"Mitsuba peer: camera model '{cam.model}' has no Mitsuba equivalent here")
    width, height = cam.resolution
    c2w = np.asarray(cam.camera_to_world, dtype=np.float64)
    eye, forward, up = c2w[:3, 3], -c2w[:3, 2], c2w[:3, 1]
    fov_x = np.degrees(2.0 * np.arctan(cam.film_width_mm / (2.0 * cam.focal_length_mm)))
    out = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": max_bounces + 1, "hide_emitters": True},
        "sensor": {
            "type": "perspective",
            "fov": float(fov_x),
            "fov_axis": "x",
            "to_world": mi.ScalarTransform4f().look_at(origin=eye.tolist(), target=(eye + forward).tolist(), up=up.tolist()),
            "sampler": {"type": "independent", "sample_count": 1},
            "film": {"type": "hdrfilm", "width": int(width), "height": int(height),
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"},
        },
    }
    for index, material in enumerate(scene.materials):
        chosen = scene.triangle_material == index
        if not chosen.any():
            continue
        if material.kind != "diffuse":
            raise ValueError(f"Mitsuba peer: material '{material.name}' ({material.kind}) is not compared")
        tris = scene.triangles[chosen]
        if scene.corner_normals is not None:
            vertices = scene.vertices[tris].reshape(-1, 3)
            normals = scene.corner_normals[chosen].reshape(-1, 3)
            tris = np.arange(len(vertices)).reshape(-1, 3)
        else:
            used, tris = np.unique(tris, return_inverse=True)
            vertices, normals, tris = scene.vertices[used], None, tris.reshape(-1, 3)
        bsdf = {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": {
            "type": "rgb", "value": [float(c) for c in material.base_color]}}}
        emitter = None
        if material.emission_strength > 0:
            emitter = {"type": "area", "radiance": {"type": "rgb", "value": [
                float(c) * material.emission_strength for c in material.emission.rgb]}}
        shape = make_mesh(f"material_{index}", vertices, tris, normals, bsdf, emitter)
        out[f"mesh_{index}"] = shape
    for k, light in enumerate(scene.lights):
        if light.kind != "area" or light.area_shape != "rectangle" or light.spectrum.kind != "rgb":
            raise ValueError(f"Mitsuba peer: light '{light.name}' is not a white rectangular area light")
        area = light.size_u_m * light.size_v_m
        radiance = light.power_w / (np.pi * area)
        m = np.eye(4)
        m[:3, 0] = np.asarray(light.axis_u) * light.size_u_m / 2
        m[:3, 1] = -np.asarray(light.axis_v) * light.size_v_m / 2
        m[:3, 2] = light.direction
        m[:3, 3] = light.position
        out[f"light_{k}"] = {
            "type": "rectangle", "to_world": _matrix(m),
            "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.0, 0.0, 0.0]}},
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [
                float(c) * radiance for c in light.spectrum.rgb]}},
        }
    if any(c * scene.world.strength > 0 for c in scene.world.color):
        out["world"] = {"type": "constant", "radiance": {"type": "rgb", "value": [
            float(c) * scene.world.strength for c in scene.world.color]}}
    return out


def main():
    from . import common

    args = common.parse_args("Render a benchmark scene with Mitsuba 3")
    variant = choose_variant()
    import drjit as dr
    import mitsuba as mi

    mi.set_variant(variant)
    dr.set_thread_count(args.threads)
    from benchmarks.scenes import build

    scene = build(args.scene, (args.resolution, args.resolution))
    description = scene_dict(scene, args.max_bounces)
    start = time.perf_counter()
    mi_scene = mi.load_dict(description)  # BVH build and scene set-up
    load_seconds = time.perf_counter() - start

    def render(spp, seed):
        start = time.perf_counter()
        image = np.array(mi.render(mi_scene, spp=int(spp), seed=int(seed)), dtype=np.float32)
        return image, time.perf_counter() - start + load_seconds

    for spp in args.spp:  # compile and cache every kernel once, untimed
        render(spp, 1)
    seconds, images = common.sweep(render, args.spp, args.repeats, args.first_repeat)
    ref = common.reference(render, args.reference_spp, args.reference_chunks) if args.reference_spp else None
    info = {"renderer": f"Mitsuba {mi.__version__}", "variant": variant, "threads": args.threads,
            "load_seconds": load_seconds, "llvm": os.environ.get("DRJIT_LIBLLVM_PATH", "")}
    common.save(args.out, args, args.spp, seconds, images, info, ref)
    print(f"mitsuba {variant}: {args.scene} done", file=sys.stderr)


if __name__ == "__main__":
    main()
