"""Runtime wheels bundled in the Prism extension: which ones, and fetching them.

The wheel set is the runtime dependency closure of ``RUNTIME_ROOTS``, read from the installed
metadata of this environment (``importlib.metadata``), minus what Blender ships itself
(``PROVIDED_BY_BLENDER``). Each package is pinned to the version in ``requirements.txt`` when
pinned there, otherwise to the installed version. Wheels are fetched per Blender platform with
``pip download --only-binary=:all: --no-deps`` for CPython 3.11 (Blender 4.2 to 4.5) into a
cache directory, and picked from that cache with the same tag priority pip uses.
"""

from __future__ import annotations

import dataclasses
import importlib.metadata
import subprocess
import sys
from pathlib import Path

try:
    from packaging import markers, requirements, tags, utils, version
except ImportError:  # pip always vendors packaging
    from pip._vendor.packaging import markers, requirements, tags, utils, version

RUNTIME_ROOTS = ("embreex", "colour-science")
# numpy is bundled with Blender: an extension must never ship its own.
PROVIDED_BY_BLENDER = frozenset({"numpy"})

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


def _runtime_requires(name: str, platform: str) -> list[requirements.Requirement]:
    env = {**_MARKER_ENV[platform], "python_version": "3.11", "python_full_version": "3.11.9",
           "implementation_name": "cpython", "platform_python_implementation": "CPython",
           "extra": ""}
    out = []
    for text in importlib.metadata.requires(name) or ():
        req = requirements.Requirement(text)
        if req.marker is None or req.marker.evaluate(env):
            out.append(req)
    return out


def resolve_pins(platform: str, requirement_pins: dict[str, str]) -> list[Pin]:
    """The runtime closure of ``RUNTIME_ROOTS`` on ``platform``, pinned, sorted by name.

    Raises ``WheelError`` if a needed package is not installed here (its dependencies could not
    be read) or if a pin does not satisfy what a dependent package requires.
    """
    pins: dict[str, str] = {}
    constraints: list[tuple[str, requirements.Requirement]] = []
    todo = list(RUNTIME_ROOTS)
    while todo:
        name = utils.canonicalize_name(todo.pop())
        if name in pins or name in PROVIDED_BY_BLENDER:
            continue
        installed = _installed_version(name)
        if installed is None:
            raise WheelError(
                f"{name} is needed at runtime on {platform} but is not installed in "
                f"{sys.prefix}, so its dependencies cannot be read: add it to requirements.txt "
                "and run `make venv`")
        pins[name] = requirement_pins.get(name, installed)
        if pins[name] != installed:
            print(f"warning: {name} {installed} is installed but requirements.txt pins "
                  f"{pins[name]}; bundling {pins[name]} (run `make venv`)", file=sys.stderr)
        for req in _runtime_requires(name, platform):
            constraints.append((name, req))
            todo.append(req.name)
    for parent, req in constraints:
        child = utils.canonicalize_name(req.name)
        if child in pins and not req.specifier.contains(pins[child], prereleases=True):
            raise WheelError(f"{parent} requires {req} but {child}=={pins[child]} is pinned; "
                             "fix the pin in requirements.txt")
    return [Pin(n, v) for n, v in sorted(pins.items())]


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
