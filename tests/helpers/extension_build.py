"""The installable extension's build and install-and-render check, started when the test run begins.

The build compiles the kernels the zip ships under the installed package's own name (``tools/
ship_kernels.py``), and the run's first test compiles them under the suite's name (``conftest.
FIRST_TEST``). numba compiles on one core, so the two compiles overlap instead of following each other;
``test_extension_package`` waits for the results and asserts on them as if it had run them itself.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import threading
from dataclasses import dataclass
from pathlib import Path

REPO_ROOT = Path(__file__).resolve().parents[2]
BUILD_TOOL = REPO_ROOT / "tools" / "build_extension.py"
INSTALL_CHECK = REPO_ROOT / "tools" / "check_extension_install.py"
PLATFORM = "linux-x64"
# The build compiles the kernels the zip ships (9 min alone on one core here), sharing two cores with the
# rest of the suite; the check's render then loads them (it compiles only on a CPU without x86-64-v3).
BUILD_TIMEOUT_S = 1800
CHECK_TIMEOUT_S = 1200


@dataclass
class Outcome:
    """A finished subprocess: ``returncode`` (None if it timed out), ``stdout``, ``stderr``."""

    returncode: int | None
    stdout: str
    stderr: str


class ExtensionBuild:
    """Builds the zip into ``folder``, then installs and renders it in a subprocess with its own Blender
    user folders, in a background thread. ``build()`` and ``check()`` wait for their step."""

    def __init__(self, folder: Path):
        self.folder = folder
        self.user_dir = folder / "blender-user"
        self.report_path = folder / "report.json"
        self._built = threading.Event()
        self._checked = threading.Event()
        self._build: Outcome | None = None
        self._check: Outcome | None = None
        self.zip: Path | None = None
        self._process: subprocess.Popen | None = None
        self._stopped = False
        threading.Thread(target=self._work, name="extension build", daemon=True).start()

    def _work(self) -> None:
        try:
            self._build = self._run([sys.executable, str(BUILD_TOOL), "--platform", PLATFORM,
                                "--output-dir", str(self.folder / "dist"), "--stage-dir", str(self.folder / "stage")],
                               BUILD_TIMEOUT_S)
            zips = sorted((self.folder / "dist").glob("*.zip"))
            self.zip = zips[0] if self._build is not None and self._build.returncode == 0 and len(zips) == 1 else None
        finally:
            self._built.set()
        try:
            if self.zip is not None:
                env = dict(os.environ)
                for var, sub in (("BLENDER_USER_RESOURCES", "resources"), ("BLENDER_USER_CONFIG", "config"),
                                 ("BLENDER_USER_SCRIPTS", "scripts")):
                    env[var] = str(self.user_dir / sub)
                self._check = self._run([sys.executable, str(INSTALL_CHECK), str(self.zip), "--user-dir",
                                    str(self.user_dir), "--report", str(self.report_path)],
                                   CHECK_TIMEOUT_S, env=env, cwd=self.folder)
        finally:
            self._checked.set()

    def _run(self, command, timeout, **kwargs) -> Outcome | None:
        if self._stopped:
            return None
        self._process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kwargs)
        try:
            stdout, stderr = self._process.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            self._process.kill()
            stdout, stderr = self._process.communicate()
            return Outcome(None, stdout, f"timed out after {timeout} s\n{stderr}")
        return Outcome(self._process.returncode, stdout, stderr)

    def stop(self) -> None:
        """End the subprocess still running (a run that stops early leaves no Blender compiling behind)."""
        self._stopped = True
        if self._process is not None and self._process.poll() is None:
            self._process.kill()

    def build(self) -> tuple[Outcome, list[Path]]:
        """The build tool's outcome and the zips it wrote."""
        self._built.wait(BUILD_TIMEOUT_S + 60)
        return self._build, sorted((self.folder / "dist").glob("*.zip"))

    def check(self) -> Outcome | None:
        """The install check's outcome (None when the build failed)."""
        self._checked.wait(BUILD_TIMEOUT_S + CHECK_TIMEOUT_S + 60)
        return self._check


_started: dict[str, ExtensionBuild] = {}


def start() -> ExtensionBuild:
    """The run's build, started on the first call."""
    if "build" not in _started:
        _started["build"] = ExtensionBuild(Path(tempfile.mkdtemp(prefix="prism-extension-")))
    return _started["build"]


def finish() -> None:
    """Stop what is still running and remove the run's folder."""
    build = _started.pop("build", None)
    if build is not None:
        build.stop()
        shutil.rmtree(build.folder, ignore_errors=True)
