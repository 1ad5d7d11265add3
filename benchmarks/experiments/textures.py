"""What texture evaluation costs: the grey Cornell box next to textured twins of it.

The twins keep the geometry, light and camera of ``cornell_grey`` and change only the walls' material,
built as node programs (``engine.tracer.materials``) exactly as the export compiles Blender nodes:

- ``image``: base colour from an 8-bit sRGB image (1024², bilinear) on planar UVs;
- ``noise``: base colour from a 3-D fBM Noise Texture (detail 2) through a Color Ramp;
- ``principled``: an untextured Principled BSDF (diffuse under a GGX specular layer whose weight depends
  on the view: the layering runs as a program at every hit).

Each row: seconds per pass (64 × 64 pixels, 16 spp, 2 threads, best of several), rays per pass, the
ratio to the untextured box, and the extra time per ray cast.
"""

from __future__ import annotations

import time

import numpy as np

TITLE = "Texture evaluation cost (Cornell box, textured twins)"


def _diffuse_program(build):
    """A one-diffuse-closure ``ShaderProgram`` whose tint is the colour ``build(builder)`` computes."""
    from engine.tracer.bsdf.closure import DIFFUSE
    from engine.tracer.materials.folding import fold_evaluator
    from engine.tracer.materials.program_builder import ProgramBuilder
    from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram

    builder = ProgramBuilder(fold_evaluator())
    colour, images = build(builder)
    return ShaderProgram([ClosureSpec(DIFFUSE, tint=Colour(register=colour.register))],
                         builder.instructions(), builder.initial_registers(), builder.register_count, images=images)


def _image_material():
    from engine.tracer.materials import opcodes as op
    from engine.tracer.materials.shader import TextureImage

    rng = np.random.default_rng(1)
    levels = (rng.random((1024, 1024, 4)) * 255).astype(np.uint8)
    levels[..., 3] = 255
    decode = np.repeat(np.where(np.arange(256) / 255 <= 0.04045, np.arange(256) / 255 / 12.92,
                                ((np.arange(256) / 255 + 0.055) / 1.055) ** 2.4)[:, None], 3, axis=1) * 0.8
    image = TextureImage("noise", levels, decode.astype(np.float32), "Linear", "REPEAT")

    def build(b):
        uv = b.emit(op.UV, [0, None, None, None, None, None, 0], width=3)
        rgba = b.emit(op.IMAGE, [uv, 0], width=4)
        return rgba, [image]

    return _diffuse_program(build)


def _noise_material():
    from engine.tracer.materials import opcodes as op

    def build(b):
        p = b.emit(op.OBJECT_COORDINATES, [None, None, None, None, None, None, 0], width=3)
        noise = b.emit(op.NOISE, [p, b.constant(0.0), b.constant(3.0), b.constant(2.0), b.constant(0.5),
                                  b.constant(2.0), b.constant(0.0)], mode=op.NOISE_TYPES.index("FBM") * 8 + 3,
                       width=4, extra=[b.constant(0.0), b.constant(1.0), 1, 0])
        ramp = np.array([[0.2 + 0.6 * t, 0.3 + 0.3 * t, 0.6 - 0.4 * t, 1.0] for t in np.linspace(0, 1, 256)])
        table = b.constant(*ramp.ravel())
        out = b.emit(op.COLOR_RAMP, [noise.component(0), table, 256], width=4, reads=[table])
        return out, []

    return _diffuse_program(build)


def _principled_material():
    from engine.tracer.bsdf.closure import C_TINT_SCALE, CONDUCTOR, DIFFUSE, FRESNEL_DIELECTRIC
    from engine.tracer.materials import opcodes as op
    from engine.tracer.materials.folding import fold_evaluator
    from engine.tracer.materials.program_builder import ProgramBuilder
    from engine.tracer.materials.shader import ClosureSpec, Colour, ShaderProgram

    b = ProgramBuilder(fold_evaluator())
    incoming = b.emit(op.INCOMING, [None, None, None, None, None, None, 0], width=3)
    normal = b.emit(op.NORMAL, [None, None, None, None, None, None, 0], width=3)
    cos = b.emit(op.VECTOR_MATH, [incoming, normal], mode=op.VECTOR_MATH_OPERATIONS.index("DOT_PRODUCT"),
                 width=1)
    s = b.emit(op.LAYER_ALBEDO, [b.constant(0.5), cos, b.constant(1.5)], width=1)
    f0 = 0.04
    albedo = b.emit(op.MATH, [b.constant(f0), s, b.constant(1.0 - f0)], mode=op.MATH_OPERATIONS.index("MULTIPLY_ADD"),
                    width=1)
    weight = b.emit(op.MATH, [b.constant(1.0), albedo], mode=op.MATH_OPERATIONS.index("SUBTRACT"), width=1)
    closures = [ClosureSpec(CONDUCTOR, alpha=0.25, eta=1.5, fresnel=FRESNEL_DIELECTRIC, selection=0.1),
                ClosureSpec(DIFFUSE, tint=Colour(rgb=(0.6, 0.6, 0.6)), bindings=[(C_TINT_SCALE, weight.register, True)])]
    return ShaderProgram(closures, b.instructions(), b.initial_registers(), b.register_count)


def _with_material(scene, shader, uvs=False):
    import copy

    from engine.tracer.scene import SurfaceAttributes

    twin = copy.copy(scene)
    twin.materials = [copy.copy(scene.materials[0])]
    twin.materials[0].shader = shader
    if uvs:
        corners = np.asarray(scene.vertices)[np.asarray(scene.triangles)]
        uv = np.stack([corners[..., 0] + corners[..., 1], corners[..., 2] + corners[..., 1]], -1) * 0.5
        twin.surface = SurfaceAttributes(uvs=uv[None].astype(np.float32))
    return twin


def _pass_seconds(scene, repeats):
    from engine.tracer.renderer import Renderer
    from engine.tracer.settings import RenderSettings

    settings = RenderSettings(samples=10_000, samples_per_pass=16, seed=0, threads=2)
    with Renderer(scene, settings) as renderer:
        renderer.render_pass()  # compiles or loads the kernels
        best = np.inf
        for _ in range(repeats):
            started = time.perf_counter()
            renderer.render_pass()
            best = min(best, time.perf_counter() - started)
        rays = renderer.stats["rays_cast"] / renderer._passes
    return best, rays


def run(quick: bool) -> dict:
    from benchmarks.scenes import cornell_grey

    repeats = 3 if quick else 8
    plain = cornell_grey()
    scenes = [("untextured", plain), ("image", _with_material(plain, _image_material(), uvs=True)),
              ("noise", _with_material(plain, _noise_material())),
              ("principled", _with_material(plain, _principled_material()))]
    rows = []
    base = None
    for name, scene in scenes:
        seconds, rays = _pass_seconds(scene, repeats)
        base = base or (seconds, rays)
        rows.append({"scene": name, "pass_s": round(seconds, 4), "rays_per_pass": int(rays),
                     "vs_untextured": round(seconds / base[0], 3),
                     "extra_ns_per_ray": round(max(seconds - base[0], 0.0) / rays * 1e9, 1)})
    worst = max(rows[1:], key=lambda r: r["vs_untextured"])
    costs = ", ".join(f"{r['scene']} x{r['vs_untextured']}" for r in rows[1:])
    summary = (f"Textured walls cost {costs} of the untextured pass ({rows[0]['pass_s']} s); the most "
               f"expensive ({worst['scene']}) adds {worst['extra_ns_per_ray']} ns per ray cast.")
    return {"rows": rows, "summary": summary}


if __name__ == "__main__":
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
    from benchmarks.experiments import print_run

    print_run(run)
