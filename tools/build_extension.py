"""Build the installable Prism extension zips (one per platform) and validate them.

    python tools/build_extension.py [--platform linux-x64 ...] [--no-download]

Steps: resolve the pinned runtime wheels per platform (``extension_wheels``: numba and llvmlite,
embreex, colour-science and their dependencies, never numpy), fetching the missing ones into the
wheel cache (``wheels/``), stage a copy of the add-on into ``build/extension/`` with those wheels
listed in its manifest (the committed manifest stays clean), build with Blender's own extension
tool (``blender_ext.py build --split-platforms``), add the kernels a first render needs, compiled for a
portable CPU level, to the zip of the platform the build runs on (``ship_kernels``; ``--no-kernels``
skips it), then validate every zip and check it holds exactly one wheel per runtime package. Prints each
zip with its size.
"""

from __future__ import annotations

import argparse
import fnmatch
import importlib.util
import re
import shutil
import subprocess
import sys
import tomllib
import zipfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import extension_wheels as ew  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MANIFEST = "blender_manifest.toml"


class BuildError(RuntimeError):
    """The extension cannot be built; the message says why and what to do."""


def find_blender_ext() -> Path:
    """Path of Blender's extension CLI shipped inside the ``bpy`` module (not imported)."""
    spec = importlib.util.find_spec("bpy")
    if spec is None or not spec.submodule_search_locations:
        raise BuildError("the bpy module is not installed in this Python: run `make venv`")
    for location in spec.submodule_search_locations:
        found = sorted(Path(location).glob("*/scripts/addons_core/bl_pkg/cli/blender_ext.py"))
        if found:
            return found[-1]
    raise BuildError("blender_ext.py not found inside the bpy module")


def read_manifest(source_dir: Path) -> tuple[str, dict]:
    text = (source_dir / MANIFEST).read_text(encoding="utf-8")
    return text, tomllib.loads(text)


def _excluded(rel: str, is_dir: bool, patterns: list[str]) -> bool:
    """A conservative reading of the manifest's gitignore-style ``paths_exclude_pattern``.

    Staging only needs to skip the bulky paths (``.venv``, ``.git``, ...); Blender's build tool
    applies the patterns authoritatively to the staged copy.
    """
    name = rel.rsplit("/", 1)[-1]
    for pattern in patterns:
        dir_only = pattern.endswith("/")
        pat = pattern.rstrip("/")
        if dir_only and not is_dir:
            continue
        if pat.startswith("/"):
            if fnmatch.fnmatchcase(rel, pat[1:]):
                return True
        elif "/" not in pat and fnmatch.fnmatchcase(name, pat):
            return True
    return False


def stage_source(source_dir: Path, stage_dir: Path, patterns: list[str]) -> None:
    """Copy the add-on into ``stage_dir`` minus excluded paths and the wheel cache."""
    if stage_dir.exists():
        shutil.rmtree(stage_dir)
    stage_resolved = stage_dir.resolve()

    def ignore(directory: str, names: list[str]) -> list[str]:
        base = Path(directory)
        rel_dir = base.resolve().relative_to(source_dir.resolve()).as_posix()
        skipped = []
        for name in names:
            path = base / name
            rel = name if rel_dir == "." else f"{rel_dir}/{name}"
            is_dir = path.is_dir()
            if (rel == "wheels" or _excluded(rel, is_dir, patterns)
                    or path.resolve() == stage_resolved
                    or stage_resolved.is_relative_to(path.resolve()) and is_dir):
                skipped.append(name)
        return skipped

    shutil.copytree(source_dir, stage_dir, ignore=ignore, symlinks=False)


def staged_manifest_text(text: str, platforms: list[str], wheels: list[str]) -> str:
    """The manifest text with ``platforms`` narrowed and the ``wheels`` list written."""
    plat_line = "platforms = [" + ", ".join(f'"{p}"' for p in platforms) + "]"
    text, count = re.subn(r"(?ms)^platforms\s*=\s*\[.*?\]", plat_line, text, count=1)
    if count != 1:
        raise BuildError(f"{MANIFEST} has no `platforms = [...]` line to narrow")
    text = re.sub(r"(?ms)^wheels\s*=\s*\[.*?\]\n?", "", text)
    wheel_lines = "wheels = [\n" + "".join(f'  "{w}",\n' for w in wheels) + "]\n\n"
    table = re.search(r"(?m)^\[", text)
    at = table.start() if table else len(text)
    return text[:at] + wheel_lines + text[at:]


def run_blender_ext(blender_ext: Path, *args: str) -> str:
    result = subprocess.run([sys.executable, str(blender_ext), *args],
                            capture_output=True, text=True)
    if result.returncode != 0:
        raise BuildError(f"blender_ext.py {args[0]} failed:\n{result.stdout}{result.stderr}")
    return result.stdout


def check_zip(zip_path: Path, expected_wheels: set[str]) -> None:
    """The zip holds the manifest, ``__init__.py`` and exactly ``expected_wheels``."""
    with zipfile.ZipFile(zip_path) as zf:
        names = set(zf.namelist())
    for required in (MANIFEST, "__init__.py"):
        if required not in names:
            raise BuildError(f"{zip_path.name} is missing {required}")
    wheels = {n.rsplit("/", 1)[-1] for n in names if n.startswith("wheels/") and n.endswith(".whl")}
    if wheels != expected_wheels:
        raise BuildError(f"{zip_path.name} wheels differ from the resolved set: "
                         f"extra {sorted(wheels - expected_wheels)}, "
                         f"missing {sorted(expected_wheels - wheels)}")


#: Blender's platform names by (sys.platform, machine), and the Python Blender 4.2-5.0 run: kernels can be
#: compiled into the zip of the platform the build runs on, with Blender's Python (``ship_kernels``).
BLENDER_PLATFORMS = {("linux", "x86_64"): "linux-x64", ("win32", "amd64"): "windows-x64",
                     ("darwin", "x86_64"): "macos-x64", ("darwin", "arm64"): "macos-arm64"}
BLENDER_PYTHON = (3, 11)
PORTABLE_MACHINES = ("x86_64", "amd64")  # the shipped kernels' CPU level (x86-64-v3) is an x86-64 one


def kernels_refused(platform: str, wheels: dict) -> str | None:
    """Why ``platform``'s zip cannot carry kernels compiled by this Python, or None when it can."""
    import platform as host

    machine = host.machine().lower()
    here = BLENDER_PLATFORMS.get((sys.platform, machine))
    if here != platform:
        return f"they are compiled on the platform itself (this is {here or sys.platform + ' ' + machine})"
    if sys.version_info[:2] != BLENDER_PYTHON:
        return f"this is Python {sys.version_info[0]}.{sys.version_info[1]}, Blender runs {BLENDER_PYTHON[0]}.{BLENDER_PYTHON[1]}"
    if machine not in PORTABLE_MACHINES:
        return f"no portable CPU level is defined for {machine}"
    from importlib import metadata

    for package in ("numba", "llvmlite"):
        bundled = next((pin.version for pin in wheels if pin.name == package), None)
        if bundled != metadata.version(package):
            return f"the zip bundles {package} {bundled}, this Python has {metadata.version(package)}"
    return None


def build(platforms: list[str] | None, output_dir: Path, stage_dir: Path, wheels_dir: Path,
          download: bool = True, source_dir: Path = ROOT, kernels: bool = True) -> list[Path]:
    """Build and validate one zip per platform (with compiled kernels where ``kernels_refused`` allows
    and ``kernels`` is True); returns the zip paths."""
    text, manifest = read_manifest(source_dir)
    declared = list(manifest.get("platforms", []))
    platforms = platforms or declared
    unknown = [p for p in platforms if p not in declared]
    if unknown:
        raise BuildError(f"platform(s) {unknown} are not in {MANIFEST} platforms {declared}")

    requirement_pins = ew.read_requirement_pins(source_dir / "requirements.txt")
    chosen: dict[str, dict[ew.Pin, Path]] = {}
    for platform in platforms:
        chosen[platform] = ew.resolve_wheels(platform, requirement_pins, wheels_dir, download=download)
    all_wheels = sorted({p for per in chosen.values() for p in per.values()}, key=lambda p: p.name)
    for platform, per in chosen.items():
        print(f"{platform}: " + ", ".join(path.name for path in per.values()), flush=True)

    patterns = list(manifest.get("build", {}).get("paths_exclude_pattern", []))
    stage_source(source_dir, stage_dir, patterns)
    (stage_dir / "wheels").mkdir()
    for wheel in all_wheels:
        shutil.copy2(wheel, stage_dir / "wheels" / wheel.name)
    staged = staged_manifest_text(text, platforms, [f"./wheels/{w.name}" for w in all_wheels])
    (stage_dir / MANIFEST).write_text(staged, encoding="utf-8")

    blender_ext = find_blender_ext()
    output_dir.mkdir(parents=True, exist_ok=True)
    run_blender_ext(blender_ext, "build", "--source-dir", str(stage_dir),
                    "--output-dir", str(output_dir), "--split-platforms")
    zips = []
    for platform in platforms:
        zip_path = output_dir / f"{manifest['id']}-{manifest['version']}-{platform.replace('-', '_')}.zip"
        if not zip_path.exists():
            raise BuildError(f"Blender's build tool did not write {zip_path}")
        if kernels:
            _ship_kernels(platform, chosen[platform], stage_dir, zip_path, manifest["id"])
        run_blender_ext(blender_ext, "validate", str(zip_path))
        check_zip(zip_path, {w.name for w in chosen[platform].values()})
        zips.append(zip_path)
    return zips


def _ship_kernels(platform: str, wheels: dict, stage_dir: Path, zip_path: Path, addon_id: str) -> None:
    refused = kernels_refused(platform, wheels)
    if refused is not None:
        print(f"{platform}: no compiled kernels in the zip ({refused}); the first render compiles them", flush=True)
        return
    import ship_kernels

    print(f"{platform}: compiling the kernels a first render needs ({ship_kernels.TARGET}, one core, minutes)",
          flush=True)
    try:
        shipped = ship_kernels.ship(stage_dir, zip_path, addon_id, work_dir=stage_dir.parent)
    except (ship_kernels.ShipError, subprocess.TimeoutExpired) as error:
        raise BuildError(f"compiling the kernels to ship failed: {error}") from error
    print(f"{platform}: {shipped['files']} kernel cache files ({shipped['functions_compiled']} functions, "
          f"{shipped['target']}) added in {shipped['compile_seconds']} s", flush=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--platform", action="append", dest="platforms", metavar="PLATFORM",
                        help="build only this Blender platform (repeatable), e.g. linux-x64")
    parser.add_argument("--no-download", action="store_true",
                        help="use only wheels already in the cache")
    parser.add_argument("--source-dir", type=Path, default=ROOT,
                        help="the add-on to package (default: this repository)")
    parser.add_argument("--output-dir", type=Path, default=ROOT / "dist")
    parser.add_argument("--stage-dir", type=Path, default=ROOT / "build" / "extension")
    parser.add_argument("--wheels-dir", type=Path, default=ROOT / "wheels",
                        help="wheel cache (default: wheels/ in the repository)")
    parser.add_argument("--no-kernels", action="store_true",
                        help="ship no compiled kernels (faster build; the first render compiles them)")
    args = parser.parse_args(argv)
    try:
        zips = build(args.platforms, args.output_dir, args.stage_dir, args.wheels_dir,
                     download=not args.no_download, source_dir=args.source_dir, kernels=not args.no_kernels)
    except (BuildError, ew.WheelError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 1
    print("built and validated:")
    for zip_path in zips:
        print(f"  {zip_path}  {zip_path.stat().st_size / 1e6:.1f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
