"""The installable extension: `tools/build_extension.py` builds a linux-x64 zip that Blender's
own tool validates, that holds the add-on and its runtime wheels (numba and llvmlite included,
never numpy) and nothing of the developer tree, and that installs through
`bpy.ops.extensions.package_install_files` and renders through the compiled core: numba comes
from the extension's site-packages, and the kernels the zip ships (compiled for x86-64-v3 by the build)
are loaded from the extension's user folder without compiling.

Wheels are cached in the repository's `wheels/` (gitignored), so only the first run downloads
(the linux wheels only, from PyPI). Without network the build fails with the tool's message.
The build (which compiles the kernels it ships), and then the install-and-render check (a subprocess with
its own Blender user dirs), start with the test run in a background thread (`helpers/extension_build.py`),
so that the build's kernel compile overlaps the run's first one.
"""

from __future__ import annotations

import importlib.util
import json
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest

from engine.tracer import kernel_folder, kernel_target
from helpers import extension_build

REPO_ROOT = Path(__file__).resolve().parents[2]
BUILD_TOOL = REPO_ROOT / "tools" / "build_extension.py"
PLATFORM = "linux-x64"
RUNTIME_WHEELS = ("colour_science", "embreex", "imageio", "llvmlite", "numba", "pillow", "scipy",
                  "typing_extensions")
COMPILING = "Compiling Prism kernels (first render only)"
SHIPPED_LEVEL = "x86-64-v3"  # the CPU level tools/ship_kernels.py compiles the shipped kernels for
DEV_ONLY_DIRS = ("tests/", "benchmarks/", ".ci/", "docs/", "tools/", ".venv/", ".git/",
                 ".coord/", "build/", "dist/", "demo/")


@pytest.fixture(scope="session")
def linux_zip() -> Path:
    """The linux-x64 zip, built from this tree (wheels from the repository's cache) when the run began
    (``helpers/extension_build.py``)."""
    result, zips = extension_build.start().build()
    if result is None or result.returncode != 0:
        pytest.fail(f"tools/build_extension.py failed:\n{result and result.stdout}\n{result and result.stderr}")
    assert [z.name for z in zips] == ["prism_spectral-0.1.0-linux_x64.zip"], result.stdout
    return zips[0]


def _blender_ext() -> Path:
    """Blender's extension CLI, shipped inside the bpy module."""
    spec = importlib.util.find_spec("bpy")
    found = [p for loc in spec.submodule_search_locations
             for p in Path(loc).glob("*/scripts/addons_core/bl_pkg/cli/blender_ext.py")]
    assert found, "blender_ext.py not found in the bpy module"
    return sorted(found)[-1]


def test_zip_validates_with_blender_tool(linux_zip):
    result = subprocess.run([sys.executable, str(_blender_ext()), "validate", str(linux_zip)],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stdout + result.stderr


def test_zip_holds_the_addon_and_its_wheels_only(linux_zip):
    with zipfile.ZipFile(linux_zip) as zf:
        names = zf.namelist()
        manifest = tomllib.loads(zf.read("blender_manifest.toml").decode("utf-8"))
    assert "__init__.py" in names
    assert any(n.startswith("engine/tracer/") for n in names)
    # Every file of the add-on's own directories is packaged (lens data included).
    for folder in ("engine", "farm", "lenses", "operators", "ui"):
        for path in (REPO_ROOT / folder).rglob("*"):
            rel = path.relative_to(REPO_ROOT).as_posix()
            if path.is_file() and "__pycache__" not in rel and not rel.endswith(".pyc"):
                assert rel in names, f"{rel} is missing from the zip"
    leaked = [n for n in names if n.startswith(DEV_ONLY_DIRS) or "__pycache__" in n]
    assert leaked == []

    wheels = sorted(n for n in names if n.startswith("wheels/"))
    assert all(n.endswith(".whl") for n in wheels)
    bundled = {Path(n).name.split("-")[0].lower() for n in wheels}
    assert bundled == set(RUNTIME_WHEELS)  # never numpy: Blender ships its own
    for wheel in wheels:  # CPython 3.11 Linux x86-64, or pure Python
        tag = Path(wheel).stem.split("-", 2)[2]
        assert tag == "py3-none-any" or (tag.startswith("cp311-cp311-manylinux")
                                         and tag.endswith("x86_64")), wheel
    assert sorted(f"./{w}" for w in wheels) == sorted(manifest["wheels"])
    assert manifest["build"]["generated"]["platforms"] == [PLATFORM]


def test_zip_ships_the_kernels_a_first_render_needs(linux_zip):
    with zipfile.ZipFile(linux_zip) as zf:
        names = zf.namelist()
        shipped = json.loads(zf.read("kernels/manifest.json"))
    # What "Install from Disk" imports, these very sources, this platform and Python, a portable CPU level.
    assert shipped["package"] == "bl_ext.user_default.prism_spectral"
    assert shipped["fingerprint"] == kernel_folder.source_fingerprint()
    assert shipped["machine"] == kernel_target.machine() and shipped["target"] == SHIPPED_LEVEL
    files = [n for n in names if n.startswith("kernels/") and n != "kernels/manifest.json"]
    assert len(files) == shipped["files"] and all(n.startswith(f"kernels/{SHIPPED_LEVEL}/") for n in files)
    assert all(n.endswith((".nbi", ".nbc")) for n in files)
    # the whole bounce loop of a chunk, and the material interpreter it calls, by tracer folder
    assert any(n.startswith(f"kernels/{SHIPPED_LEVEL}/stages/bounce_loop.") for n in files), files[:20]
    assert any(n.startswith(f"kernels/{SHIPPED_LEVEL}/materials/") for n in files)


def test_missing_wheel_error_names_package_and_platform(tmp_path):
    result = subprocess.run(
        [sys.executable, str(BUILD_TOOL), "--platform", "macos-arm64", "--no-download",
         "--wheels-dir", str(tmp_path / "empty"), "--output-dir", str(tmp_path / "dist"),
         "--stage-dir", str(tmp_path / "stage")],
        capture_output=True, text=True, timeout=120,
    )
    assert result.returncode == 1
    for expected in ("macos-arm64", "embreex==", "numba=="):
        assert expected in result.stderr, result.stderr
    assert not (tmp_path / "dist").exists()


def _assert_cached(cache: dict, kernels: list[str]) -> None:
    """Every ``module:function`` of ``kernels`` has a numba index file in the cache folder."""
    for kernel in kernels:
        module, function = kernel.split(":")
        index_prefix = f"{module.rsplit('.', 1)[-1]}.{function}-"  # numba: <file stem>.<qualname>-<line>
        assert any(Path(f).name.startswith(index_prefix) and f.endswith(".nbi")
                   for f in cache["files"]), f"{kernel} is not cached in {cache['directory']}: {cache['files']}"


def _extension_wheels():
    """tools/extension_wheels.py, imported once (dataclasses need it in sys.modules)."""
    name = "prism_tools_extension_wheels"
    if name not in sys.modules:
        spec = importlib.util.spec_from_file_location(name, REPO_ROOT / "tools" / "extension_wheels.py")
        sys.modules[name] = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(sys.modules[name])
    return sys.modules[name]


def test_a_wheel_that_needs_a_newer_numpy_than_blender_42_is_refused():
    ew = _extension_wheels()
    Requirement = ew.requirements.Requirement

    scipy = ew.Pin("scipy", "1.17.1")
    with pytest.raises(ew.WheelError, match=r"scipy==1.17.1 requires numpy>=1.26.4 but Blender 4.2 bundles numpy 1.24.3"):
        ew.check_constraints("linux-x64", {"scipy": "1.17.1"}, [(scipy, Requirement("numpy>=1.26.4"))])
    numba = ew.Pin("numba", "0.62.1")
    with pytest.raises(ew.WheelError, match=r"numba==0.62.1 requires llvmlite<0.46"):
        ew.check_constraints("macos-x64", {"llvmlite": "0.50.0"}, [(numba, Requirement("llvmlite<0.46,>=0.45.0dev0"))])
    ew.check_constraints("macos-x64", {"llvmlite": "0.45.1"}, [(numba, Requirement("numpy<2.4,>=1.22")),
                                                                (numba, Requirement("llvmlite<0.46,>=0.45.0dev0"))])


def test_linux_wheels_run_with_the_numpy_of_blender_42(tmp_path):
    """The oldest numpy the zips meet (the test suite itself runs Blender 4.5's 1.26.4)."""
    oldest = min(_extension_wheels().BLENDER_NUMPY.values(), key=lambda v: tuple(map(int, v.split("."))))
    result = subprocess.run(
        [sys.executable, str(REPO_ROOT / "tools" / "check_blender_numpy.py"), "--numpy", oldest,
         "--work-dir", str(tmp_path)],
        capture_output=True, text=True, timeout=600,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert f'"numpy": "{oldest}", "numba": ' in result.stdout, result.stdout


def test_installed_zip_enables_and_renders(linux_zip):
    build = extension_build.start()  # its install check started with the run, beside the first compile
    result = build.check()
    report_path, user_dir = build.report_path, build.user_dir
    assert result is not None, "the install check did not run"
    log = f"exit {result.returncode}\n{result.stdout[-3000:]}\n{result.stderr[-3000:]}"
    assert report_path.exists(), log
    report = json.loads(report_path.read_text())
    assert "error" not in report, report["error"] + log
    assert result.returncode == 0, f"the check died during its {report['phase']} phase: {log}"

    assert report["extensions_dir"].startswith(str(user_dir))  # the real config is untouched
    assert report["install_result"] == ["FINISHED"]
    assert report["addon_enabled"], "bl_ext.user_default.prism_spectral is not enabled"
    assert "PRISM" in report["engines"]
    assert report["heavy_imported_at_register"] == []
    for package in ("colour", "scipy", "embreex", "PIL", "imageio", "numba", "llvmlite"):
        assert package in report["site_packages_content"]
    # The render used the bundled wheels, not this environment's copies.
    for module in ("embreex", "numba", "llvmlite"):
        assert report["modules_from"][module], f"the render did not use {module}"
    for module, path in report["modules_from"].items():
        assert path is None or path.startswith(report["site_packages"]), (module, path)

    # The zip ships the kernels a first render needs, compiled for x86-64-v3 (tools/ship_kernels.py): on a
    # CPU with that level the first render loads them, compiles nothing and says nothing of compiling.
    # Elsewhere it compiles this CPU's kernels and says so. The second render stays quiet either way.
    cache = report["kernel_cache"]
    assert cache["warm"]
    assert report["shipped_kernels"], "the Linux zip ships no compiled kernels"
    first, second = report["status_bar"]
    level = SHIPPED_LEVEL if kernel_target.host_supports(SHIPPED_LEVEL) else None
    assert report["kernel_target"] == level
    assert report["counter_counts"], "the compile counter does not see the add-on's numba"
    if level is not None:
        assert report["compiled_by_first_render"] == 0, "the first render compiled despite the shipped kernels"
        assert first and not any(COMPILING in line for line in first), first
    else:
        assert any(COMPILING in line for line in first), first
    assert second and not any(COMPILING in line for line in second), second
    # Kernels compile into the extension's user folder, not next to the installed sources.
    assert cache["directory"].startswith(str(user_dir)) and cache["directory"].endswith("kernel_cache")
    assert cache["jit_directory"] == cache["directory"]
    assert cache["numba_cache_dir"] == cache["numba_directory"]
    assert Path(cache["numba_directory"]) == Path(cache["kernel_directory"]) / (level or "")
    # one folder per package name and version of the tracer sources
    assert Path(cache["kernel_directory"]).parent.parent == Path(cache["directory"])
    if report["probe_kernel"]:  # one installed kernel compiled by hand: seen as run, and cached
        assert report["probe_kernel"] in report["kernel_cache_after_probe"]["kernels_run"]
        _assert_cached(report["kernel_cache_after_probe"], [report["probe_kernel"]])
    # The render went through the compiled core: its kernels ran and were cached in the user folder.
    assert cache["kernels_run"], "the installed add-on rendered without running a compiled tracer kernel"
    _assert_cached(cache, cache["kernels_run"])

    image = report["image"]
    assert image["size"] == [16, 16]
    assert image["all_finite"]
    assert image["max"] > 0.05  # the lit cube
    assert image["std"] > 0.01  # cube against the background, not a flat frame
