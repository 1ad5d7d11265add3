"""The first render on a machine says it is compiling the kernels; a warm cache stays quiet.

The add-on runs as a plain module here (no extension folder), so the kernel cache is the tracer's
default, pointed at a fresh temporary folder through ``$PRISM_KERNEL_CACHE``. The status bar is
read through Blender's ``render_stats`` handler (each ``update_stats`` line), the batch progress
stream from ``render.py``'s stderr. The installed-extension case (the extension's user folder,
compiled files in it) is covered by ``test_extension_package.py``.
"""

from __future__ import annotations

import importlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import bpy
import pytest

from helpers.bpy_scenes import build_lit_card_scene, render_linear_rgb

REPO_ROOT = Path(__file__).resolve().parents[2]
MESSAGE = "Compiling Prism kernels (first render only)"


@pytest.fixture
def lit_plane(fresh_scene):
    build_lit_card_scene(resolution=(8, 6))
    return fresh_scene


@pytest.fixture
def status_bar():
    """The status bar lines (``update_stats``) Blender reports while the fixture is active."""
    lines: list[str] = []

    def record(stats, *_):
        lines.append(stats)

    bpy.app.handlers.render_stats.append(record)
    yield lines
    bpy.app.handlers.render_stats.remove(record)


def _modules(prism_addon):
    package = prism_addon.__name__
    return (importlib.import_module(f"{package}.engine.warmup.kernel_cache"),
            importlib.import_module(f"{package}.engine.tracer.jit"))


def test_first_render_says_it_compiles_then_a_warm_cache_stays_quiet(
    prism_addon, lit_plane, status_bar, tmp_path, monkeypatch
):
    kernel_cache, jit = _modules(prism_addon)
    cache = tmp_path / "kernels"
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(cache))
    assert jit.cache_directory() == cache  # no extension folder: the tracer's default applies
    assert kernel_cache.COMPILING_MESSAGE == MESSAGE

    render_linear_rgb(lit_plane, samples=2)
    assert any(MESSAGE in line for line in status_bar), status_bar
    assert jit.cache_is_warm(), "a finished cold render marks the cache warm"
    assert any(cache.rglob("prism-kernels-*.ok"))

    status_bar.clear()
    render_linear_rgb(lit_plane, samples=2)
    assert any("2/2 spp" in line for line in status_bar), status_bar  # the render did report
    assert not any(MESSAGE in line for line in status_bar), status_bar


def test_a_cancelled_first_render_does_not_mark_the_cache_warm(
    prism_addon, lit_plane, status_bar, tmp_path, monkeypatch
):
    _, jit = _modules(prism_addon)
    session = importlib.import_module(f"{prism_addon.__name__}.engine.render.session")
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(tmp_path / "kernels"))
    original_passes = session.RenderSession._passes

    def cancel_after_passes(self, *args):
        original_passes(self, *args)
        self.cancelled = True  # as if Esc was pressed during the last pass

    monkeypatch.setattr(session.RenderSession, "_passes", cancel_after_passes)
    render_linear_rgb(lit_plane, samples=2)
    assert any(MESSAGE in line for line in status_bar)
    assert not jit.cache_is_warm()


def test_without_an_extension_there_is_no_extension_cache_folder(prism_addon):
    kernel_cache, _ = _modules(prism_addon)
    assert kernel_cache.ADDON_PACKAGE == prism_addon.__name__
    assert kernel_cache.extension_cache_directory() is None
    assert kernel_cache.extension_cache_directory("some_legacy_addon") is None


def _kernels_without_the_warm_stamp(prism_addon, cache: Path) -> None:
    """Copy the suite's cached kernels into ``cache`` less the stamp that marks them warm: to Prism it
    is a first render (the message is about the stamp), and the run's one cold compile (the warm-up
    test's) is not paid a second time. Nothing is copied if the suite's cache is not warm."""
    _, jit = _modules(prism_addon)
    if not jit.cache_is_warm():
        return
    source = jit.kernel_directory()
    target = cache / source.relative_to(jit.cache_directory())
    shutil.copytree(source, target, ignore=shutil.ignore_patterns("prism-kernels-*.ok"))


def test_batch_progress_says_it_compiles_on_the_first_render_only(prism_addon, fresh_scene, tmp_path):
    build_lit_card_scene(resolution=(8, 6))
    scene_file = tmp_path / "card.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(scene_file))
    cache = tmp_path / "kernels"
    _kernels_without_the_warm_stamp(prism_addon, cache)
    env = {**os.environ, "PRISM_KERNEL_CACHE": str(cache)}

    def batch_render() -> str:
        completed = subprocess.run(
            [sys.executable, str(REPO_ROOT / "render.py"), str(scene_file), "--samples", "1",
             "--output", str(tmp_path / "out.png")],
            capture_output=True, text=True, timeout=300, env=env,
        )
        assert completed.returncode == 0, completed.stderr
        return completed.stderr

    first = batch_render()
    assert f"Prism: {MESSAGE}" in first.splitlines(), first
    assert any(cache.rglob("prism-kernels-*.ok")), sorted(p.name for p in cache.rglob("*"))
    second = batch_render()
    assert "1/1 spp" in second and MESSAGE not in second, second
