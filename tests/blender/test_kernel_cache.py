"""The first render on a machine says it is compiling the kernels; a warm cache stays quiet.

Renders go through ``bpy.ops.render.render`` with the add-on as a plain module (no extension
folder), so the kernel cache is the tracer's default, here pointed at a fresh temporary folder
through ``$PRISM_KERNEL_CACHE``. The installed-extension case (the extension's user folder) is
covered by ``test_extension_package.py``.
"""

from __future__ import annotations

import importlib
import io

import pytest

from helpers.bpy_scenes import add_camera, add_plane, add_point_light, render_linear_rgb


@pytest.fixture
def lit_plane(fresh_scene):
    add_plane("Floor", 4.0, color=(0.8, 0.8, 0.8))
    add_point_light("Bulb", 200.0, (0.0, 0.0, 2.0))
    add_camera((0.0, 0.0, 3.0), (0.0, 0.0, 0.0), lens_mm=35.0, resolution=(8, 8))
    fresh_scene.world = None
    return fresh_scene


@pytest.fixture
def recorded_render(prism_addon, monkeypatch):
    """Render a scene; returns (status bar lines, progress stream text) of that render."""
    session = importlib.import_module(f"{prism_addon.__name__}.engine.session")

    class RecordingEngine:
        """The real engine, with its status bar lines recorded."""

        def __init__(self, engine, lines):
            self._engine, self._lines = engine, lines

        def update_stats(self, stats, info):
            self._lines.append(info)
            self._engine.update_stats(stats, info)

        def __getattr__(self, name):
            return getattr(self._engine, name)

    def render(scene):
        lines, stream = [], io.StringIO()
        original_init = session.RenderSession.__init__

        def init(self, engine, depsgraph, render_request=None):
            original_init(self, RecordingEngine(engine, lines), depsgraph, render_request)
            self.request.progress_stream = stream

        with monkeypatch.context() as patch:
            patch.setattr(session.RenderSession, "__init__", init)
            patch.setattr(session, "request", session.RenderRequest())
            render_linear_rgb(scene, samples=2)
        assert session.last_error is None
        return lines, stream.getvalue()

    return render


def test_first_render_says_it_compiles_then_a_warm_cache_stays_quiet(
    prism_addon, lit_plane, recorded_render, tmp_path, monkeypatch
):
    kernel_cache = importlib.import_module(f"{prism_addon.__name__}.engine.kernel_cache")
    jit = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.jit")
    cache = tmp_path / "kernels"
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(cache))
    assert jit.cache_directory() == cache  # no extension folder: the tracer's default applies
    message = kernel_cache.COMPILING_MESSAGE
    assert message == "Compiling Prism kernels (first render only)"

    lines, progress = recorded_render(lit_plane)
    assert any(message in line for line in lines), lines
    assert f"Prism: {message}" in progress.splitlines(), progress
    assert jit.cache_is_warm(), "a finished cold render marks the cache warm"
    assert any(cache.glob("prism-kernels-*.ok"))

    lines, progress = recorded_render(lit_plane)
    assert lines and not any(message in line for line in lines), lines
    assert message not in progress
    assert "2/2 spp" in progress  # the render did run and report


def test_a_cancelled_first_render_does_not_mark_the_cache_warm(
    prism_addon, lit_plane, recorded_render, tmp_path, monkeypatch
):
    session = importlib.import_module(f"{prism_addon.__name__}.engine.session")
    jit = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.jit")
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(tmp_path / "kernels"))
    original_passes = session.RenderSession._passes

    def cancel_after_passes(self, *args):
        original_passes(self, *args)
        self.cancelled = True  # as if Esc was pressed during the last pass

    monkeypatch.setattr(session.RenderSession, "_passes", cancel_after_passes)
    recorded_render(lit_plane)
    assert not jit.cache_is_warm()


def test_without_an_extension_there_is_no_extension_cache_folder(prism_addon):
    kernel_cache = importlib.import_module(f"{prism_addon.__name__}.engine.kernel_cache")
    assert kernel_cache.ADDON_PACKAGE == prism_addon.__name__
    assert kernel_cache.extension_cache_directory() is None
    assert kernel_cache.extension_cache_directory("some_legacy_addon") is None
