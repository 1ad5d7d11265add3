"""Runtime wheels bundled in the Prism extension: which ones, at which versions, and fetching them.

The wheel set of a platform is the runtime dependency closure of ``RUNTIME_ROOTS``, read from the
``Requires-Dist`` of the wheels themselves (markers evaluated for that platform), minus what
Blender ships itself (``PROVIDED_BY_BLENDER``). Versions: ``ZIP_PINS`` for the few packages a zip
must bundle at another version than the development set, else the ``==`` pin of
``requirements.txt``, else the version installed here. Every wheel's numpy requirement is checked
against the numpy of the oldest and newest Blender the extension supports (``BLENDER_NUMPY``).
Wheels are fetched per Blender platform with ``pip download --only-binary=:all: --no-deps`` for
CPython 3.11 (Blender 4.2 to 5.0) into a cache directory, and picked from that cache with the same
tag priority pip uses. Why each pin is what it is: docs/extension.md, "Pinned versions".
"""

from __future__ import annotations

import dataclasses
import email.parser
import importlib.metadata
import subprocess
import sys
import zipfile
from pathlib import Path

try:
    from packaging import markers, requirements, tags, utils, version
except ImportError:  # pip always vendors packaging
    from pip._vendor.packaging import markers, requirements, tags, utils, version

RUNTIME_ROOTS = ("embreex", "colour-science", "numba")  # numba brings llvmlite
# numpy is bundled with Blender: an extension must never ship its own.
PROVIDED_BY_BLENDER = frozenset({"numpy"})

#: The numpy inside the oldest and the newest Blender the extension supports (Blender 4.2 builds
#: with numpy 1.24.3, 4.5 and 5.0 with 1.26.4). Every bundled wheel must accept both.
BLENDER_NUMPY = {"4.2": "1.24.3", "5.0": "1.26.4"}

#: Versions a zip bundles where they differ from requirements.txt (the development set the tests
#: run with), per Blender platform:
#: - scipy 1.16 and later need numpy >= 1.25.2, newer than Blender 4.2's: 1.15.3 is the last
#:   release that accepts numpy 1.24.
#: - numba 0.63 and later, llvmlite 0.46 and later publish no macOS x86-64 wheel: 0.62.1 / 0.45.1.
ZIP_PINS = {
    "linux-x64": {"scipy": "1.15.3"},
    "windows-x64": {"scipy": "1.15.3"},
    "macos-arm64": {"scipy": "1.15.3"},
    "macos-x64": {"scipy": "1.15.3", "numba": "0.62.1", "llvmlite": "0.45.1"},
}

PYTHON_VERSION = (3, 11)
ABI = "cp311"

# The oldest OS each Blender platform's wheels must run on. Blender 4.2 needs glibc 2.28 on Linux;
# embreex ships macOS wheels for macOS 13 only, so Prism on macOS needs macOS 13.
_MANYLINUX_GLIBC_MAX = 28
_MACOS_MIN = (13, 0)

_MARKER_ENV = {
    "windows-x64": {"sys_platform": "win32", "platform_system": "Windows",
                    "os_name": "nt", "platform_machine": "AMD64"},
    "linux-x64": {"sys_platform": "linux", "platform_system": "Linux",
                  "os_name": "posix", "platform_machine": "x86_64"},
    "macos-arm64": {"sys_platform": "darwin", "platform_system": "Darwin",
                    "os_name": "posix", "platform_machine": "arm64"},
    "macos-x64": {"sys_platform": "darwin", "platform_system": "Darwin",
                  "os_name": "posix", "platform_machine": "x86_64"},
}


class WheelError(RuntimeError):
    """A runtime wheel cannot be resolved, found or downloaded; the message names it."""


@dataclasses.dataclass(frozen=True)
class Pin:
    """One runtime package at one exact version."""

    name: str  # canonical (PEP 503) name
    version: str

    def __str__(self) -> str:
        return f"{self.name}=={self.version}"


def _manylinux_platforms(arch: str) -> list[str]:
    legacy = {17: "manylinux2014", 12: "manylinux2010", 5: "manylinux1"}
    out = []
    for minor in range(_MANYLINUX_GLIBC_MAX, 4, -1):
        out.append(f"manylinux_2_{minor}_{arch}")
        if minor in legacy:
            out.append(f"{legacy[minor]}_{arch}")
    return out


def wheel_platform_tags(platform: str) -> list[str]:
    """Wheel platform tags a Blender platform accepts, best first (e.g. ``win_amd64``)."""
    if platform == "windows-x64":
        return ["win_amd64"]
    if platform == "linux-x64":
        return _manylinux_platforms("x86_64")
    if platform == "macos-arm64":
        return list(tags.mac_platforms(_MACOS_MIN, "arm64"))
    if platform == "macos-x64":
        return list(tags.mac_platforms(_MACOS_MIN, "x86_64"))
    raise WheelError(f"platform {platform!r} is not supported by the build tool "
                     f"(known: {', '.join(_MARKER_ENV)})")


def supported_tags(platform: str) -> list[tags.Tag]:
    """Wheel tags CPython 3.11 on ``platform`` accepts, in pip's order of preference."""
    plats = wheel_platform_tags(platform)
    return [*tags.cpython_tags(PYTHON_VERSION, [ABI], plats),
            *tags.compatible_tags(PYTHON_VERSION, ABI, plats)]


def read_requirement_pins(requirements_txt: Path) -> dict[str, str]:
    """``{canonical name: version}`` for every ``name==version`` line of a requirements file."""
    pins = {}
    for line in requirements_txt.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if not line or line.startswith("-"):
            continue
        req = requirements.Requirement(line)
        exact = [s.version for s in req.specifier if s.operator in ("==", "===")]
        if exact:
            pins[utils.canonicalize_name(req.name)] = exact[0]
    return pins


def _installed_version(name: str) -> str | None:
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return None


def pinned_version(name: str, platform: str, requirement_pins: dict[str, str]) -> str:
    """The version of ``name`` the ``platform`` zip bundles (see the module docstring)."""
    name = utils.canonicalize_name(name)
    version_ = ZIP_PINS.get(platform, {}).get(name) or requirement_pins.get(name) or _installed_version(name)
    if version_ is None:
        raise WheelError(f"{name} is needed at runtime on {platform} but has no version: pin it "
                         "in requirements.txt (or in ZIP_PINS of tools/extension_wheels.py)")
    return version_


def _marker_environment(platform: str) -> dict[str, str]:
    return {**_MARKER_ENV[platform], "python_version": "3.11", "python_full_version": "3.11.9",
            "implementation_name": "cpython", "platform_python_implementation": "CPython",
            "extra": ""}


def wheel_requires(wheel: Path, platform: str) -> list[requirements.Requirement]:
    """The ``Requires-Dist`` of a wheel that apply on ``platform`` (no extras)."""
    with zipfile.ZipFile(wheel) as archive:
        metadata = [n for n in archive.namelist()
                    if n.count("/") == 1 and n.endswith(".dist-info/METADATA")]
        if len(metadata) != 1:
            raise WheelError(f"{wheel.name} has no single .dist-info/METADATA")
        message = email.parser.Parser().parsestr(archive.read(metadata[0]).decode("utf-8"))
    env = _marker_environment(platform)
    out = []
    for text in message.get_all("Requires-Dist") or ():
        req = requirements.Requirement(text)
        if req.marker is None or req.marker.evaluate(env):
            out.append(req)
    return out


def check_constraints(platform: str, pins: dict[str, str],
                       constraints: list[tuple[Pin, requirements.Requirement]]) -> None:
    for parent, req in constraints:
        child = utils.canonicalize_name(req.name)
        if child in PROVIDED_BY_BLENDER:
            for blender, numpy_version in BLENDER_NUMPY.items():
                if not req.specifier.contains(numpy_version, prereleases=True):
                    raise WheelError(
                        f"{parent} requires {req} but Blender {blender} bundles {child} "
                        f"{numpy_version}: bundle a {parent.name} release that accepts it "
                        f"(ZIP_PINS in tools/extension_wheels.py)")
        elif child in pins and not req.specifier.contains(pins[child], prereleases=True):
            raise WheelError(f"{parent} requires {req} but {child}=={pins[child]} is pinned for "
                             f"{platform}; fix the pin (requirements.txt or ZIP_PINS)")


def resolve_wheels(platform: str, requirement_pins: dict[str, str], wheels_dir: Path,
                   download: bool = True) -> dict[Pin, Path]:
    """Every runtime wheel of ``platform``, pinned and cached: ``{pin: wheel path}``, by name.

    Walks the dependency closure level by level from the wheels' own metadata, downloading the
    wheels of each level that are not cached yet. Raises ``WheelError`` when a wheel cannot be
    had, or when a pin does not satisfy a dependent wheel or Blender's numpy.
    """
    pins: dict[str, str] = {}
    chosen: dict[Pin, Path] = {}
    constraints: list[tuple[Pin, requirements.Requirement]] = []
    level = [utils.canonicalize_name(name) for name in RUNTIME_ROOTS]
    while level:
        names = [n for n in dict.fromkeys(level) if n not in pins and n not in PROVIDED_BY_BLENDER]
        wanted = [Pin(n, pinned_version(n, platform, requirement_pins)) for n in names]
        level = []
        for pin, path in ensure_wheels(wanted, platform, wheels_dir, download=download).items():
            pins[pin.name] = pin.version
            chosen[pin] = path
            for req in wheel_requires(path, platform):
                constraints.append((pin, req))
                level.append(utils.canonicalize_name(req.name))
    check_constraints(platform, pins, constraints)
    return dict(sorted(chosen.items(), key=lambda item: item[0].name))


def _cached_wheels(wheels_dir: Path) -> list[tuple[Path, str, version.Version, frozenset]]:
    out = []
    for path in sorted(wheels_dir.glob("*.whl")):
        try:
            name, ver, _build, wheel_tags = utils.parse_wheel_filename(path.name)
        except utils.InvalidWheelFilename:
            continue
        out.append((path, name, ver, wheel_tags))
    return out


def pick_cached_wheel(wheels_dir: Path, pin: Pin, platform: str) -> Path | None:
    """The cached wheel pip would choose for ``pin`` on ``platform``, or None if none fits."""
    rank = {tag: i for i, tag in enumerate(supported_tags(platform))}
    wanted = version.Version(pin.version)
    best = None
    for path, name, ver, wheel_tags in _cached_wheels(wheels_dir):
        if name != pin.name or ver != wanted:
            continue
        score = min((rank[t] for t in wheel_tags if t in rank), default=None)
        if score is not None and (best is None or score < best[0]):
            best = (score, path)
    return None if best is None else best[1]


def _pip_download(pins: list[Pin], platform: str, wheels_dir: Path) -> subprocess.CompletedProcess:
    cmd = [sys.executable, "-m", "pip", "download", "--disable-pip-version-check",
           "--progress-bar", "off", "--only-binary=:all:", "--no-deps",
           "--python-version", "3.11", "--implementation", "cp", "--abi", ABI,
           "--dest", str(wheels_dir)]
    for plat in wheel_platform_tags(platform):
        cmd += ["--platform", plat]
    cmd += [str(p) for p in pins]
    return subprocess.run(cmd, capture_output=True, text=True)


def ensure_wheels(pins: list[Pin], platform: str, wheels_dir: Path,
                  download: bool = True) -> dict[Pin, Path]:
    """Cached wheel path for every pin on ``platform``, downloading the missing ones.

    Raises ``WheelError`` naming the package and platform when a wheel is not in the cache
    (``download=False``) or PyPI has none for CPython 3.11 on that platform.
    """
    wheels_dir.mkdir(parents=True, exist_ok=True)
    missing = [p for p in pins if pick_cached_wheel(wheels_dir, p, platform) is None]
    if missing and not download:
        raise WheelError(f"no cached wheel in {wheels_dir} for {platform}: "
                         f"{', '.join(map(str, missing))}; run without --no-download")
    if missing:
        print(f"downloading {platform} wheels: {', '.join(map(str, missing))}", flush=True)
        result = _pip_download(missing, platform, wheels_dir)
        if result.returncode != 0:
            # Retry one by one so the error names exactly the package(s) without a wheel.
            failed = [p for p in missing if _pip_download([p], platform, wheels_dir).returncode]
            detail = result.stderr.strip().splitlines()[-3:]
            names = ", ".join(map(str, failed)) or ", ".join(map(str, missing))
            raise WheelError(
                f"pip could not download a CPython 3.11 wheel for {platform} "
                f"(wheel tag {wheel_platform_tags(platform)[0]} or compatible) of: {names}\n"
                + "\n".join("  pip: " + line for line in detail)
                + "\n(the first build downloads the wheels: is PyPI reachable?)")
    chosen = {}
    for pin in pins:
        path = pick_cached_wheel(wheels_dir, pin, platform)
        if path is None:
            raise WheelError(f"no wheel of {pin} for {platform} in {wheels_dir} after download")
        chosen[pin] = path
    return chosen
