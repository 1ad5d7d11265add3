"""The installable extension: `tools/build_extension.py` builds a linux-x64 zip that Blender's
own tool validates, that holds the add-on and its runtime wheels and nothing of the developer
tree, and that installs through `bpy.ops.extensions.package_install_files` and renders.

Wheels are cached in the repository's `wheels/` (gitignored), so only the first run downloads
(the linux wheels only, from PyPI). Without network the build fails with the tool's message.
The install-and-render check runs in a subprocess with its own Blender user dirs.
"""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[2]
BUILD_TOOL = REPO_ROOT / "tools" / "build_extension.py"
INSTALL_CHECK = REPO_ROOT / "tools" / "check_extension_install.py"
PLATFORM = "linux-x64"
RUNTIME_WHEELS = ("colour_science", "embreex", "imageio", "pillow", "scipy", "typing_extensions")
DEV_ONLY_DIRS = ("tests/", "benchmarks/", ".ci/", "docs/", "tools/", ".venv/", ".git/",
                 ".coord/", "build/", "dist/", "demo/")


@pytest.fixture(scope="session")
def linux_zip(tmp_path_factory) -> Path:
    """The linux-x64 zip, built from this tree (wheels from the repository's cache)."""
    out = tmp_path_factory.mktemp("extension")
    result = subprocess.run(
        [sys.executable, str(BUILD_TOOL), "--platform", PLATFORM,
         "--output-dir", str(out / "dist"), "--stage-dir", str(out / "stage")],
        capture_output=True, text=True, timeout=600,
    )
    if result.returncode != 0:
        pytest.fail(f"tools/build_extension.py failed:\n{result.stdout}\n{result.stderr}")
    zips = sorted((out / "dist").glob("*.zip"))
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


def test_missing_wheel_error_names_package_and_platform(tmp_path):
    result = subprocess.run(
        [sys.executable, str(BUILD_TOOL), "--platform", "macos-arm64", "--no-download",
         "--wheels-dir", str(tmp_path / "empty"), "--output-dir", str(tmp_path / "dist"),
         "--stage-dir", str(tmp_path / "stage")],
        capture_output=True, text=True, timeout=120,
    )
    assert result.returncode == 1
    assert "macos-arm64" in result.stderr and "embreex==" in result.stderr, result.stderr
    assert not (tmp_path / "dist").exists()


def test_installed_zip_enables_and_renders(linux_zip, tmp_path):
    report_path = tmp_path / "report.json"
    user_dir = tmp_path / "blender-user"
    env = dict(os.environ)
    for var, sub in (("BLENDER_USER_RESOURCES", "resources"), ("BLENDER_USER_CONFIG", "config"),
                     ("BLENDER_USER_SCRIPTS", "scripts")):
        env[var] = str(user_dir / sub)
    result = subprocess.run(
        [sys.executable, str(INSTALL_CHECK), str(linux_zip), "--user-dir", str(user_dir),
         "--report", str(report_path)],
        capture_output=True, text=True, timeout=300, env=env, cwd=tmp_path,
    )
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
    for package in ("colour", "scipy", "embreex", "PIL", "imageio"):
        assert package in report["site_packages_content"]
    # The render used the bundled wheels, not this environment's copies.
    assert report["modules_from"]["embreex"], "the render did not use embreex"
    for module, path in report["modules_from"].items():
        assert path is None or path.startswith(report["site_packages"]), (module, path)

    image = report["image"]
    assert image["size"] == [16, 16]
    assert image["all_finite"]
    assert image["max"] > 0.05  # the lit cube
    assert image["std"] > 0.01  # cube against the background, not a flat frame
