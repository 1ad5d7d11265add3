"""Install a built Prism extension zip into a throw-away Blender user dir and render with it.

    python tools/check_extension_install.py dist/prism_spectral-0.1.0-linux_x64.zip \
        --user-dir /tmp/prism-user --report report.json

Runs with the ``bpy`` module. The user resources, config and scripts dirs all point into
``--user-dir`` (set before ``bpy`` starts), so a developer's real Blender setup is untouched.
The zip goes through ``bpy.ops.extensions.package_install_files`` exactly as "Install from Disk"
does; then a 16x16 cube lit by a point light is rendered twice with the installed engine,
importing the bundled wheels (not this environment's copies). The report says where numba and
the other heavy modules were imported from, where the kernel cache is and which files the first
render compiled into it (none where the zip ships kernels for this CPU's level: it loads them), the
CPU level the kernels were made for, and each render's status bar lines (the first one says it
compiles unless kernels were shipped, the second one finds the cache warm). Writes a JSON report and
ends with ``os._exit`` because the bpy module can hang at interpreter exit after a render.
"""

from __future__ import annotations

import argparse
import importlib
import json
import os
import sys
import traceback
from pathlib import Path

ADDON_ID = "prism_spectral"
MODULE = f"bl_ext.user_default.{ADDON_ID}"
HEAVY_MODULES = ("numba", "llvmlite", "colour", "scipy", "embreex")
KERNEL_CACHE_FILES = ("*.nbi", "*.nbc")  # numba's cache index and compiled code


def _isolate_user_dirs(user_dir: Path) -> None:
    # TMPDIR too: Blender's session folder goes there, and leaving with os._exit skips its removal.
    for var, sub in (("BLENDER_USER_RESOURCES", "resources"), ("BLENDER_USER_CONFIG", "config"),
                     ("BLENDER_USER_SCRIPTS", "scripts"), ("TMPDIR", "tmp")):
        os.environ[var] = str(user_dir / sub)
        (user_dir / sub).mkdir(parents=True, exist_ok=True)


def _install(bpy, zip_path: Path, report: dict) -> None:
    result = bpy.ops.extensions.package_install_files(
        repo="user_default", filepath=str(zip_path), enable_on_install=True)
    report["install_result"] = sorted(result)
    report["addon_enabled"] = MODULE in bpy.context.preferences.addons
    report["engines"] = sorted(getattr(cls, "bl_idname", "") for cls in
                               bpy.types.RenderEngine.__subclasses__())
    report["heavy_imported_at_register"] = [m for m in HEAVY_MODULES if m in sys.modules]
    extensions_dir = Path(bpy.utils.user_resource("EXTENSIONS"))
    report["extensions_dir"] = str(extensions_dir)
    site = extensions_dir / ".local" / "lib" / "python3.11" / "site-packages"
    report["site_packages"] = str(site)
    report["site_packages_content"] = sorted(p.name for p in site.iterdir()) if site.is_dir() else []
    # Import the bundled wheels, not this environment's copies of the same packages.
    if str(site) in sys.path:
        sys.path.remove(str(site))
    sys.path.insert(0, str(site))


def _build_scene(bpy, samples: int):
    scene = bpy.context.scene
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    mesh = bpy.data.meshes.new("cube")
    corners = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    mesh.from_pydata(corners, [], faces)
    mesh.update()
    scene.collection.objects.link(bpy.data.objects.new("cube", mesh))
    light = bpy.data.objects.new("key", bpy.data.lights.new("key", type="POINT"))
    light.data.energy = 1000.0
    light.location = (2.0, -2.0, 4.0)
    scene.collection.objects.link(light)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.location = (0.0, 0.0, 5.0)  # looking down -Z at the cube's top face
    scene.collection.objects.link(camera)
    scene.camera = camera
    if scene.world is None:
        scene.world = bpy.data.worlds.new("world")
    scene.render.engine = "PRISM"
    scene.render.resolution_x = scene.render.resolution_y = 16
    scene.render.resolution_percentage = 100
    scene.prism.samples = samples
    scene.render.image_settings.file_format = "OPEN_EXR"
    return scene


def _render_once(bpy) -> list[str]:
    """Render the scene through the installed engine; returns its status bar lines."""
    lines: list[str] = []

    def record(stats, *_):
        lines.append(stats)

    bpy.app.handlers.render_stats.append(record)
    try:
        bpy.ops.render.render(write_still=True)
    finally:
        bpy.app.handlers.render_stats.remove(record)
    return lines


def _kernels_run() -> list[str]:
    """``module:function`` of every tracer kernel that has been compiled in this process."""
    from numba.core.dispatcher import Dispatcher

    prefix = f"{MODULE}.engine.tracer."
    found = set()
    for name, module in list(sys.modules.items()):
        if not name.startswith(prefix):
            continue
        for value in vars(module).values():
            if isinstance(value, Dispatcher) and value.signatures:
                found.add(f"{value.py_func.__module__.removeprefix(prefix)}:{value.py_func.__qualname__}")
    return sorted(found)


def _compile_a_tracer_kernel() -> str | None:
    """Compile one installed tracer kernel (N-BK7's index at the d line); its ``module:function``.

    Shows where a kernel of the installed sources caches even if the render ran none; None if
    the tracer has no such kernel module.
    """
    import numpy as np

    try:
        dispersion = importlib.import_module(f"{MODULE}.engine.tracer.spectra.dispersion")
    except ImportError:
        return None
    row = np.array([1.0, 300.0, 2500.0, 1.03961212, 0.231792344, 1.01046945,
                    0.00600069867, 0.0200179144, 103.560653])
    index, _ = dispersion.refractive_index(row, 587.56)
    if abs(index - 1.5168) > 1e-4:
        raise RuntimeError(f"the compiled N-BK7 index is {index}, not 1.5168")
    return "spectra.dispersion:refractive_index"


def _kernel_cache_facts(bpy) -> dict:
    jit = importlib.import_module(f"{MODULE}.engine.tracer.jit")
    expected = Path(bpy.utils.extension_path_user(MODULE, path="kernel_cache"))
    files = sorted(p.relative_to(expected).as_posix() for pattern in KERNEL_CACHE_FILES
                   for p in expected.rglob(pattern))
    return {"directory": str(expected), "jit_directory": str(jit.cache_directory()),
            "kernel_directory": str(jit.kernel_directory()),
            "numba_cache_dir": sys.modules["numba"].config.CACHE_DIR,
            "numba_directory": str(jit.numba_directory()),
            "warm": jit.cache_is_warm(), "kernels_run": _kernels_run(), "files": files}


def _render(bpy, image_path: Path, report: dict) -> None:
    import numpy as np

    scene = _build_scene(bpy, samples=2)
    scene.render.filepath = str(image_path)
    # numba's compile events, counted by the warm-up's counter (the bundled numba: importing it makes no code
    # generator yet, so the render still picks the CPU its kernels are made for)
    compiled = importlib.import_module(f"{MODULE}.engine.warmup.child").compile_counter()
    report["status_bar"] = [_render_once(bpy)]
    report["compiled_by_first_render"] = len(compiled)
    before = len(compiled)  # the counter sees the numba the add-on uses: one function compiled here counts
    sys.modules["numba"].njit(lambda x: x + 1)(1)
    report["counter_counts"] = len(compiled) > before
    target = importlib.import_module(f"{MODULE}.engine.tracer.kernel_target")
    report["kernel_target"] = target.current()
    shipped = importlib.import_module(f"{MODULE}.engine.warmup.shipped_kernels")
    report["shipped_kernels"] = shipped.read_manifest() is not None
    report["rendered"] = image_path.exists()
    report["modules_from"] = {m: getattr(sys.modules.get(m), "__file__", None) for m in HEAVY_MODULES}
    report["kernel_cache"] = _kernel_cache_facts(bpy)
    report["status_bar"].append(_render_once(bpy))  # the cache is warm now: no compile notice
    report["probe_kernel"] = _compile_a_tracer_kernel()
    report["kernel_cache_after_probe"] = _kernel_cache_facts(bpy)
    if not image_path.exists():
        return
    image = bpy.data.images.load(str(image_path))
    pixels = np.empty(image.size[0] * image.size[1] * image.channels, dtype=np.float32)
    image.pixels.foreach_get(pixels)
    rgb = pixels.reshape(-1, image.channels)[:, :3]
    report["image"] = {"size": list(image.size), "all_finite": bool(np.isfinite(rgb).all()),
                       "max": float(np.nanmax(rgb)), "mean": float(np.nanmean(rgb)),
                       "std": float(np.nanstd(rgb))}


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("zip", type=Path)
    parser.add_argument("--user-dir", type=Path, required=True)
    parser.add_argument("--report", type=Path, required=True)
    parser.add_argument("--no-render", action="store_true", help="install and enable only")
    args = parser.parse_args()
    _isolate_user_dirs(args.user_dir)
    report: dict = {"zip": str(args.zip), "phase": "import bpy"}
    code = 1
    try:
        import bpy

        report["phase"] = "install"
        _install(bpy, args.zip.resolve(), report)
        if not args.no_render:
            report["phase"] = "render"
            # Written now as well, so a crash inside the render still leaves the install facts.
            args.report.write_text(json.dumps(report, indent=2))
            _render(bpy, args.user_dir / "render.exr", report)
        report["phase"] = "done"
        code = 0
    except Exception:  # noqa: BLE001 - reported to the caller in the JSON report
        report["error"] = traceback.format_exc()
    args.report.write_text(json.dumps(report, indent=2))
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(code)


if __name__ == "__main__":
    main()
