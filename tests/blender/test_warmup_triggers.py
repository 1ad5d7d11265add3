"""When the add-on starts the background kernel warm-up, how many, and what a render does meanwhile.

The warm-up process is replaced by a stand-in that sleeps (the real one compiles for minutes: see
``test_warmup_child.py``), started through the same launcher, lock and pid. Warm-ups are enabled in
background mode with ``PRISM_KERNEL_WARMUP=1``. The bpy module has no event loop, so Blender never
delivers msgbus notifications here: the tests set the engine and then call ``engine_changed``, which is
what Blender calls for the subscription; ``load_post`` and registration run for real.
"""

from __future__ import annotations

import importlib
import os
import subprocess
import sys
import time
from types import SimpleNamespace

import bpy
import pytest

STAND_IN = "import time; time.sleep(60)"


@pytest.fixture
def warmup(prism_addon, tmp_path, monkeypatch):
    """The add-on's warm-up modules over an empty kernel cache, its process a stand-in (killed after)."""
    package = prism_addon.__name__
    modules = SimpleNamespace(**{name: importlib.import_module(f"{package}.engine.{path}") for name, path in (
        ("launch", "warmup.launch"), ("triggers", "warmup.triggers"), ("lock", "warmup.lock"),
        ("kernel_folder", "tracer.kernel_folder"), ("kernel_cache", "warmup.kernel_cache"), ("requests", "render.request"))})
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(tmp_path / "kernels"))
    monkeypatch.setenv("PRISM_KERNEL_WARMUP", "1")
    started = []

    def stand_in(cache, lock_file):
        started.append(lock_file)
        return [sys.executable, "-c", STAND_IN]

    monkeypatch.setattr(modules.launch, "command", stand_in)
    modules.started = started
    yield modules
    for process in modules.launch._started:
        process.kill()
        process.wait()
    modules.launch._started.clear()


def test_setting_the_engine_to_prism_starts_one_warmup_while_the_cache_is_cold(warmup, fresh_scene):
    assert not warmup.kernel_folder.cache_is_warm()
    fresh_scene.render.engine = "BLENDER_WORKBENCH"
    warmup.triggers.engine_changed()
    assert warmup.started == []
    fresh_scene.render.engine = "PRISM"
    warmup.triggers.engine_changed()
    assert len(warmup.started) == 1
    (process,) = warmup.launch._started
    assert warmup.launch.running() == process.pid, "the lock holds the process's pid"
    assert warmup.launch.log_path().exists()
    fresh_scene.render.engine = "CYCLES"
    warmup.triggers.engine_changed()
    fresh_scene.render.engine = "PRISM"
    warmup.triggers.engine_changed()  # one is running: no second one
    assert len(warmup.started) == 1


def test_opening_a_file_that_uses_prism_starts_one_warmup(warmup, fresh_scene, tmp_path):
    path = str(tmp_path / "prism.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    assert warmup.started == []  # saving is no trigger
    bpy.ops.wm.open_mainfile(filepath=path)
    assert len(warmup.started) == 1
    bpy.ops.wm.open_mainfile(filepath=path)
    assert len(warmup.started) == 1


def test_registering_while_the_scene_uses_prism_starts_one_warmup(warmup, fresh_scene):
    warmup.triggers.unregister()
    warmup.triggers.register()
    assert len(warmup.started) == 1


def test_a_warm_cache_starts_no_warmup(warmup, fresh_scene, tmp_path):
    warmup.kernel_folder.mark_cache_warm()
    warmup.triggers.engine_changed()
    path = str(tmp_path / "prism.blend")
    bpy.ops.wm.save_as_mainfile(filepath=path)
    bpy.ops.wm.open_mainfile(filepath=path)
    assert warmup.started == []


def test_without_the_variable_background_blender_starts_no_warmup(warmup, fresh_scene, monkeypatch):
    monkeypatch.delenv("PRISM_KERNEL_WARMUP")  # blender -b, render.py: the render compiles what it needs
    warmup.triggers.engine_changed()
    monkeypatch.setenv("PRISM_KERNEL_WARMUP", "0")
    warmup.triggers.engine_changed()
    assert warmup.started == []


def _dead_pid() -> int:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


@pytest.mark.parametrize("holder", ["dead", "garbage", "old"])
def test_a_stale_lock_is_ignored(warmup, holder):
    lock_file = warmup.launch.lock_path()
    lock_file.parent.mkdir(parents=True, exist_ok=True)
    lock_file.write_text({"dead": f"{_dead_pid()}\n", "garbage": "not a pid\n", "old": f"{os.getpid()}\n"}[holder])
    if holder == "old":  # a live pid, but written long before any warm-up could still run (a reused pid)
        past = time.time() - warmup.lock.STALE_AFTER_S - 60
        os.utime(lock_file, (past, past))
    process = warmup.launch.start()
    assert process is not None
    assert lock_file.read_text().strip() == str(process.pid)


def test_a_live_lock_is_respected(warmup):
    lock_file = warmup.launch.lock_path()
    lock_file.parent.mkdir(parents=True, exist_ok=True)
    lock_file.write_text(f"{os.getpid()}\n")  # another Blender's warm-up, say
    assert warmup.launch.start() is None
    assert warmup.launch.running() == os.getpid()


def test_wait_returns_when_the_warmup_ends_and_stops_on_request(warmup, monkeypatch):
    monkeypatch.setattr(warmup.launch, "command", lambda cache, lock_file: [sys.executable, "-c",
                                                                           "import time; time.sleep(1.5)"])
    assert warmup.launch.wait(lambda: False, print) is True  # none running: at once
    process = warmup.launch.start()
    assert warmup.launch.wait(lambda: True, lambda seconds: None) is False
    waited = []
    assert warmup.launch.wait(lambda: False, waited.append, poll_s=0.1) is True
    assert process.poll() is not None and waited and warmup.launch.running() is None


def test_a_render_during_a_warmup_says_it_waits_for_it(warmup, fresh_scene):
    """Stopped while it waits (as Esc would), so that no kernel compiles here."""
    from helpers.bpy_scenes import build_lit_card_scene

    build_lit_card_scene(resolution=(8, 6))
    warmup.launch.start()
    status = []

    def record(stats, *_):
        status.append(stats)

    bpy.app.handlers.render_stats.append(record)
    try:
        request = warmup.requests.RenderRequest(stop_requested=lambda: len(status) >= 2)
        with warmup.requests.render_request(request) as report:
            bpy.ops.render.render()
    finally:
        bpy.app.handlers.render_stats.remove(record)
    assert report.cancelled and report.error is None
    assert any(warmup.kernel_cache.WAITING_MESSAGE in line for line in status), status
    assert not any(warmup.kernel_cache.COMPILING_MESSAGE in line for line in status), status


_LIGHT_PROBE = """
import importlib, sys
import bpy
sys.path.insert(0, {root!r})
from render import exit_now, load_addon_package
addon = load_addon_package()
addon.register()
launch = importlib.import_module(addon.__name__ + ".engine.warmup.launch")
launch.command = lambda cache, lock_file: [sys.executable, "-c", "pass"]
bpy.context.scene.render.engine = "PRISM"
importlib.import_module(addon.__name__ + ".engine.warmup.triggers").engine_changed()
print("STARTED", len(launch._started))
print("HEAVY", sorted(m for m in ("numba", "llvmlite", "colour", "scipy", "embreex") if m in sys.modules))
exit_now(0)
"""


def test_starting_a_warmup_imports_nothing_heavy_into_blender(tmp_path):
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    environment = dict(os.environ, PRISM_KERNEL_CACHE=str(tmp_path / "kernels"), PRISM_KERNEL_WARMUP="1")
    completed = subprocess.run([sys.executable, "-c", _LIGHT_PROBE.format(root=root)], capture_output=True,
                               text=True, timeout=120, env=environment)
    assert completed.returncode == 0, completed.stderr
    assert "STARTED 1" in completed.stdout.splitlines(), completed.stdout
    assert "HEAVY []" in completed.stdout.splitlines(), completed.stdout


def test_the_real_process_starts_and_a_killed_one_leaves_a_cold_cache_and_a_stale_lock(prism_addon, tmp_path,
                                                                                       monkeypatch):
    """The launcher's own command (no stand-in), stopped as soon as it has logged its start (~1 s)."""
    launch = importlib.import_module(f"{prism_addon.__name__}.engine.warmup.launch")
    kernel_folder = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.kernel_folder")
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(tmp_path / "kernels"))
    process = launch.start()
    try:
        deadline = time.monotonic() + 60
        while process.poll() is None and time.monotonic() < deadline and "pid" not in launch.log_path().read_text():
            time.sleep(0.1)
        assert launch.running() == process.pid
    finally:
        process.kill()  # as a crash or a killed Blender session would
        process.wait()
    log = launch.log_path().read_text()
    assert f"Prism kernel warm-up, pid {process.pid}, package {prism_addon.__name__}" in log, log
    assert not kernel_folder.cache_is_warm()
    assert launch.lock_path().exists() and launch.running() is None, "the dead process's lock is stale"
    again = launch.start()
    assert again is not None
    again.kill()
    again.wait()
    launch._started.clear()
