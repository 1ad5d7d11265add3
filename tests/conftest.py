"""Shared fixtures: the add-on registered in the bpy module, a fresh scene per test,
an initialised GPU for overlay tests, and the bpy exit workaround.

Pure tracer tests import ``engine.tracer...`` directly (pytest.ini puts the
repository root on sys.path); Blender tests use the add-on as the package
``prism_spectral`` returned by the ``prism_addon`` fixture. Both are one package
(``helpers.one_package``), so kernels compile once per run.
"""

from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

import pytest

from helpers import extension_build, one_package
from render import exit_now, load_addon_package

one_package.install()

REPO_ROOT = Path(__file__).resolve().parents[1]

_exit_status = {"code": None}
#: Bad inputs the tests met (``bad_input`` fixture), for ``tools/bad_input_inventory.py``.
_bad_inputs: list[dict] = []
INVENTORY_ENVIRONMENT = "PRISM_BAD_INPUT_INVENTORY"


@pytest.fixture
def bad_input(request):
    """``bad_input(input, status, message)``: note a bad input a test just fed to Prism, with the
    exit status and the message it observed, for the inventory in ``docs/bad_input.md``."""

    def record(description: str, status: int, message: str) -> None:
        assert message.strip(), "a bad input must produce a message"
        _bad_inputs.append(
            {"test": request.node.nodeid, "input": description, "status": int(status), "message": message.strip()}
        )

    return record


@pytest.fixture(scope="session")
def prism_addon():
    """The add-on package, registered in the bpy module for the whole session."""
    import bpy  # noqa: F401  (imported before the add-on, as Blender would)

    addon = load_addon_package()
    addon.register()
    yield addon
    addon.unregister()


@pytest.fixture
def fresh_scene(prism_addon):
    """An empty factory scene with Prism as its render engine."""
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    scene = bpy.context.scene
    scene.render.engine = "PRISM"
    return scene


def _initialise_gpu():
    """Render one tiny Workbench frame: that brings up Blender's GPU backend
    (Mesa EGL, llvmpipe, when headless) so offscreen drawing works."""
    import bpy

    scene = bpy.context.scene
    previous = scene.render.engine, scene.render.resolution_x, scene.render.resolution_y
    scene.render.engine = "BLENDER_WORKBENCH"
    scene.render.resolution_x = scene.render.resolution_y = 4
    if scene.camera is None:
        data = bpy.data.cameras.new("gpu_init_camera")
        camera = bpy.data.objects.new("gpu_init_camera", data)
        scene.collection.objects.link(camera)
        scene.camera = camera
    bpy.ops.render.render()
    scene.render.engine, scene.render.resolution_x, scene.render.resolution_y = previous
    import gpu

    gpu.types.GPUOffScreen(4, 4).free()


@pytest.fixture(scope="session")
def gpu_ready(prism_addon):
    """The GPU initialised for offscreen drawing; in CI a failure fails the test."""
    try:
        _initialise_gpu()
    except Exception as error:  # noqa: BLE001 - any failure means no GPU here
        message = (
            f"Could not initialise Blender's GPU backend headless ({error}). "
            "Install Mesa EGL: apt-get install -y libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1"
        )
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    return True


#: Runs first: on a cold cache it is the run's one compile of the render kernels (see its docstring).
FIRST_TEST = "test_warmup_child.py::test_the_warmup_leaves_the_cache_warm_and_the_next_f12_compiles_nothing"


def pytest_collection_modifyitems(session, config, items):
    items.sort(key=lambda item: not item.nodeid.endswith(FIRST_TEST))  # stable: the rest keep their order
    if any("linux_zip" in getattr(item, "fixturenames", ()) for item in items):
        extension_build.start()  # its compile overlaps the first test's (helpers/extension_build.py)


def pytest_sessionfinish(session, exitstatus):
    _exit_status["code"] = int(exitstatus)
    extension_build.finish()
    target = os.environ.get(INVENTORY_ENVIRONMENT)
    if target:
        Path(target).write_text(json.dumps(_bad_inputs, indent=1, ensure_ascii=False))


@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config):
    """The bpy module can hang for ever in a global destructor at interpreter exit.

    Once pytest has printed its summary, leave at once with the real exit status.
    """
    if "bpy" in sys.modules and _exit_status["code"] is not None:
        _tidy_temporary_folders(config)
        exit_now(_exit_status["code"])


def _tidy_temporary_folders(config) -> None:
    """What pytest does for its numbered temporary folders in exit handlers, which ``exit_now`` skips:
    unlock this run's folder and remove all but the newest ``tmp_path_retention_count``. Skipped, every
    run's folder stayed locked and was kept for three days (1.4 GB per full run)."""
    factory = getattr(config, "_tmp_path_factory", None)
    basetemp = getattr(factory, "_basetemp", None)
    if basetemp is None or getattr(factory, "_given_basetemp", None) is not None:
        return
    (Path(basetemp) / ".lock").unlink(missing_ok=True)
    try:
        from _pytest.pathlib import LOCK_TIMEOUT, cleanup_numbered_dir
    except ImportError:  # a pytest that moved them: its next run's own clean-up still sees this run unlocked
        return
    keep = 0 if factory._retention_policy == "none" else factory._retention_count
    cleanup_numbered_dir(Path(basetemp).parent, "pytest-", keep, time.time() - LOCK_TIMEOUT)
