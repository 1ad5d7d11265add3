"""Registering the add-on: fixed order, repeatable, and nothing heavy imported.

Heavy means the JIT (numba, llvmlite: ~0.3 s to import, more to compile) and the physics and
ray libraries (colour-science, scipy, embreex): all wait for the first render.
"""

import subprocess
import sys
import textwrap
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
HEAVY_MODULES = ("numba", "llvmlite", "colour", "scipy", "embreex")

_PROBE = textwrap.dedent(
    """
    import sys, traceback
    import bpy
    sys.path.insert(0, {root!r})

    def engines():
        try:
            bpy.context.scene.render.engine = "PRISM"
        except TypeError:
            return []
        return ["PRISM"]

    try:
        from render import load_addon_package
        addon = load_addon_package()
        addon.register()
        heavy = sorted(m for m in {heavy!r} if m in sys.modules)
        registered = engines()
        addon.unregister()
        after_unregister = engines()
        addon.register()
        again = engines()
        addon.unregister()
        print("HEAVY", heavy)
        print("ENGINES", "PRISM" in registered, "PRISM" in after_unregister, "PRISM" in again)
        status = 0
    except Exception:
        traceback.print_exc()
        status = 1
    from render import exit_now
    exit_now(status)
    """
)


def test_register_is_light_and_repeatable():
    completed = subprocess.run(
        [sys.executable, "-c", _PROBE.format(root=str(REPO_ROOT), heavy=HEAVY_MODULES)],
        capture_output=True,
        text=True,
        timeout=90,
    )
    assert completed.returncode == 0, completed.stderr
    lines = dict(line.split(" ", 1) for line in completed.stdout.splitlines() if line[:5] in {"HEAVY", "ENGIN"})
    assert lines["HEAVY"] == "[]", f"register imported heavy modules: {lines['HEAVY']}"
    assert lines["ENGINES"] == "True False True"


def test_prism_engine_is_available(fresh_scene):
    assert fresh_scene.render.engine == "PRISM"
