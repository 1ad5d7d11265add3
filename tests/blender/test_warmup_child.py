"""The warm-up process fills an empty kernel cache so that the next F12, in a fresh Blender, compiles nothing.

The cold-compile test here runs first in the session (``conftest.pytest_collection_modifyitems``) and
fills the suite's own kernel cache, under the package name every other test uses (``prism_spectral``,
``helpers.one_package``): its compile is the one the whole run needs, so the rest of the suite loads
the render kernels from the cache. On a cold cache (a fresh clone, CI) it proves the warm-up compiles
every kernel an F12 uses; on a warm one (a rerun) it proves the warm-up leaves a warm cache alone. It
runs ``engine/warmup/child.py`` as the add-on would, then renders the lit card in a fresh bpy process
with the add-on imported and registered, recording numba's compile events (a kernel loaded from the
cache sends none). Adoption of an installed extension's package name (``bl_ext.user_default.
prism_spectral``) is checked without compiling, by the last test.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
import time
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
PACKAGE = "prism_spectral"  # the suite's package name: this compile fills the cache the suite uses
EXTENSION_PACKAGE = "bl_ext.user_default.prism_spectral"
CHILD = REPO_ROOT / "engine" / "warmup" / "child.py"

_F12 = textwrap.dedent(
    """
    import importlib, importlib.util, json, sys, time, traceback, types
    root, cache, package = {root!r}, {cache!r}, {package!r}
    import bpy
    import numpy as np
    sys.path[:0] = [root, root + "/tests"]
    from render import exit_now


    def f12():
        parents = package.split(".")[:-1]
        for depth in range(1, len(parents) + 1):  # Blender's extension packages, empty here
            module = types.ModuleType(".".join(parents[:depth]))
            module.__path__ = []
            sys.modules[module.__name__] = module
        spec = importlib.util.spec_from_file_location(package, root + "/__init__.py",
                                                      submodule_search_locations=[root])
        addon = importlib.util.module_from_spec(spec)
        sys.modules[package] = addon
        spec.loader.exec_module(addon)
        addon.register()
        kernel_cache = importlib.import_module(package + ".engine.warmup.kernel_cache")
        kernel_folder = importlib.import_module(package + ".engine.tracer.kernel_folder")
        kernel_folder.configure_cache(cache)  # what the extension's user folder is in Blender
        kernel_cache._configured = True
        warm = kernel_folder.cache_is_warm()
        from numba.core import event
        compiled = []

        class Compiled(event.Listener):
            def on_start(self, data):
                pass

            def on_end(self, data):
                dispatcher = data.data["dispatcher"]
                compiled.append(dispatcher.py_func.__module__.rsplit(".", 1)[-1] + "."
                                + dispatcher.py_func.__qualname__ + str(data.data["args"])[:{args_chars}])

        event.register("numba:compile", Compiled())
        from helpers.bpy_scenes import build_lit_card_scene, render_linear_rgb
        bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
        build_lit_card_scene(resolution=(8, 6))
        status = []
        bpy.app.handlers.render_stats.append(lambda stats, *_: status.append(stats))
        started = time.perf_counter()
        image = render_linear_rgb(bpy.context.scene, samples=2)
        seconds = time.perf_counter() - started
        return dict(warm=warm, compiled=compiled, seconds=seconds, status=status,
                    finite=bool(np.isfinite(image).all()), mean=float(image.mean()),
                    colour=sorted(name for name in sys.modules if name.split(".")[0] == "colour")[:3])


    try:
        print("REPORT", json.dumps(f12()))
        exit_now(0)
    except BaseException:
        traceback.print_exc()
        exit_now(1)  # a bpy process that rendered can hang at a normal exit
    """
)


def test_the_warmup_leaves_the_cache_warm_and_the_next_f12_compiles_nothing(tmp_path):
    """On a cold cache costs the run's one cold compile of the kernels (2-12 minutes here: the process
    runs at low priority on a shared two-core machine), then a warm F12 in a fresh bpy process (~5 s)."""
    from engine.tracer import kernel_folder  # the suite's tracer (helpers.one_package): its cache

    assert kernel_folder.package_name() == PACKAGE
    cache = kernel_folder.cache_directory()
    was_warm = kernel_folder.cache_is_warm()
    lock_file = tmp_path / "warmup.lock"
    started = time.perf_counter()
    process = subprocess.Popen(
        [sys.executable, str(CHILD), "--package", PACKAGE, "--root", str(REPO_ROOT), "--cache", str(cache),
         "--lock", str(lock_file)],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=tmp_path,
    )
    lock_file.write_text(f"{process.pid}\n")  # as the launcher hands its lock over to the process
    output, _ = process.communicate(timeout=1800)  # 12 min measured at nice 10 under load 4
    compile_seconds = time.perf_counter() - started
    assert process.returncode == 0, output
    assert "Prism kernel warm-up done" in output, output
    done = json.loads(output.split("Prism kernel warm-up done: ", 1)[1].splitlines()[0])
    assert done["already_warm"] == was_warm, output  # a cold cache was compiled, not skipped
    assert not lock_file.exists(), "the process removes its lock when it ends"
    assert kernel_folder.cache_is_warm()
    assert kernel_folder.kernel_directory().parent.name.startswith(PACKAGE + "-")

    probe = _F12.format(root=str(REPO_ROOT), cache=str(cache), package=PACKAGE, args_chars=0)
    environment = {key: value for key, value in os.environ.items() if key != "PRISM_KERNEL_CACHE"}
    rendered = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=600,
                              cwd=tmp_path, env=environment)
    assert rendered.returncode == 0, rendered.stderr[-4000:]
    report = json.loads(next(line[7:] for line in rendered.stdout.splitlines() if line.startswith("REPORT ")))
    print(f"warm-up (cold compile) {compile_seconds:.1f} s, then F12 in a fresh process {report['seconds']:.1f} s")
    assert report["warm"], "a fresh process under the same package name finds the cache warm"
    assert report["compiled"] == [], report["compiled"]  # names of the functions compiled
    assert not any("Compiling" in line or "Waiting" in line for line in report["status"]), report["status"]
    assert report["finite"] and report["mean"] > 0
    # Half a second of every fresh process: the add-on and a render of RGB colours read Prism's own tables.
    assert report["colour"] == [], "the F12 imported colour-science"


_ADOPT = textwrap.dedent(
    """
    import importlib, runpy, sys
    child = runpy.run_path({child!r})  # as a script, not through a package
    child["adopt_package"]({package!r}, {root!r})
    folder = importlib.import_module({package!r} + ".engine.tracer.kernel_folder")
    print("PACKAGE", folder.package_name())
    print("BPY", "bpy" in sys.modules, "numba" in sys.modules)
    """
)


def test_the_process_imports_the_tracer_under_the_parents_name_without_the_addon_init():
    completed = subprocess.run(
        [sys.executable, "-c", _ADOPT.format(child=str(CHILD), package=EXTENSION_PACKAGE, root=str(REPO_ROOT))],
        capture_output=True, text=True, timeout=60,
    )
    assert completed.returncode == 0, completed.stderr
    lines = completed.stdout.splitlines()
    assert f"PACKAGE {EXTENSION_PACKAGE}" in lines and "BPY False False" in lines, completed.stdout
