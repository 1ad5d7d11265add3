"""Kernels shipped inside the extension (``engine.warmup.shipped_kernels``) are used only where they fit,
land where numba looks for them on this machine, and leave this CPU's own kernels first.

No compiling here: the build that ships real kernels, and a render that loads them without compiling, are
``test_extension_package``'s."""

from __future__ import annotations

import json

import pytest

from engine.tracer import kernel_folder, kernel_target
from engine.warmup import shipped_kernels

LEVEL = "x86-64-v3"
needs_level = pytest.mark.skipif(not kernel_target.host_supports(LEVEL), reason=f"this CPU cannot run {LEVEL} code")


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """An empty kernel cache, and a process whose numba is not configured yet (restored afterwards)."""
    monkeypatch.setenv("PRISM_KERNEL_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(kernel_target, "_chosen", [kernel_target.HOST])
    monkeypatch.setattr(kernel_target, "_applied", [])
    return tmp_path / "cache"


def _manifest(**changes) -> dict:
    manifest = {"package": kernel_folder.package_name(), "fingerprint": kernel_folder.source_fingerprint(),
                "machine": kernel_target.machine(), "target": LEVEL, "files": 3}
    return {**manifest, **changes}


def _ship(root, manifest: dict) -> None:
    """An add-on folder ``root`` shipping three cache files: two of the tracer's own folder, one of stages/."""
    shipped = root / shipped_kernels.FOLDER
    (shipped / LEVEL / "stages").mkdir(parents=True)
    (shipped / LEVEL / "jit.kernel-10.py311.nbi").write_bytes(b"index")
    (shipped / LEVEL / "jit.kernel-10.py311.0.nbc").write_bytes(b"code")
    (shipped / LEVEL / "stages" / "bounce_loop.run-5.py311.nbi").write_bytes(b"loop")
    (shipped / shipped_kernels.MANIFEST).write_text(json.dumps(manifest))


@needs_level
def test_kernels_that_fit_are_usable():
    assert shipped_kernels.unusable(_manifest()) is None


@pytest.mark.parametrize(("key", "value", "why"), [
    ("package", "bl_ext.blender_org.prism_spectral", "the add-on's package name"),
    ("fingerprint", "0123456789abcdef", "the tracer's sources, numba or llvmlite"),
    ("machine", "win32-amd64-py311", "the platform or Python"),
    ("target", "x86-64-v9", "unknown CPU level 'x86-64-v9'"),
])
def test_kernels_that_do_not_fit_say_why(key, value, why):
    assert shipped_kernels.unusable(_manifest(**{key: value})).startswith(why)


def test_a_cpu_without_the_level_refuses_them(monkeypatch):
    monkeypatch.setattr(kernel_target, "host_supports", lambda target: False)
    assert shipped_kernels.unusable(_manifest()) == f"this CPU lacks features of {LEVEL}"


@needs_level
def test_adopted_kernels_land_where_numba_looks_and_choose_the_level(tmp_path, cache):
    _ship(tmp_path, _manifest())
    assert shipped_kernels.adopt(tmp_path) == LEVEL
    assert kernel_target.current() == LEVEL and kernel_folder.cache_is_warm(LEVEL)
    assert not kernel_folder.cache_is_warm(kernel_target.HOST)  # the warm-up still compiles this CPU's own
    tracer = kernel_folder.tracer_root()
    level_folder = kernel_folder.numba_directory(LEVEL)
    top = level_folder / kernel_folder.numba_subfolder(tracer)
    stages = level_folder / kernel_folder.numba_subfolder(tracer / "stages")
    assert sorted(p.name for p in top.iterdir()) == ["jit.kernel-10.py311.0.nbc", "jit.kernel-10.py311.nbi"]
    assert (stages / "bounce_loop.run-5.py311.nbi").read_bytes() == b"loop"


@needs_level
def test_this_cpus_own_kernels_come_first(tmp_path, cache):
    _ship(tmp_path, _manifest())
    kernel_folder.mark_cache_warm(kernel_target.HOST)
    assert shipped_kernels.adopt(tmp_path) is None
    assert kernel_target.current() is kernel_target.HOST
    assert not kernel_folder.numba_directory(LEVEL).exists()


def test_kernels_that_do_not_fit_are_left_alone(tmp_path, cache):
    _ship(tmp_path, _manifest(fingerprint="0123456789abcdef"))
    assert shipped_kernels.adopt(tmp_path) is None
    assert kernel_target.current() is kernel_target.HOST and not kernel_folder.numba_directory(LEVEL).exists()
    assert shipped_kernels.adopt(tmp_path / "elsewhere") is None  # an extension shipping none
