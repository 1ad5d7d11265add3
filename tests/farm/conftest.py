"""A real Flamenco farm on loopback for the farm tests: the Manager and three Workers from
``../shared/farm`` (next to the repository checkout), run in a temporary directory and stopped after.

Where the Flamenco binaries are: ``$PRISM_FLAMENCO_FARM`` if set, else the first ``shared/farm``
folder beside the repository or one of its parent folders (CI checks the repository out next to
``shared/``). Without them the tests skip, and fail under ``CI``.

The Workers' ``blender`` is ``blender_shim.py`` (Blender's command line over the bpy module). Three
workers, because Flamenco 3.9 retries a failed task on another worker only while at least two
workers besides the one that failed it remain; with fewer it fails the whole job.
"""

from __future__ import annotations

import json
import os
import re
import shlex
import shutil
import signal
import socket
import stat
import subprocess
import sys
import time
import urllib.error
import urllib.request
from pathlib import Path

import pytest

from engine.tracer import jit
from farm import JOB_TYPE_SCRIPT
from farm.manager import FlamencoError, FlamencoManager

REPO_ROOT = Path(__file__).resolve().parents[2]
SHIM = Path(__file__).resolve().with_name("blender_shim.py")
FARM_ENV = "PRISM_FLAMENCO_FARM"
BINARIES = ("flamenco-manager", "flamenco-worker")
WORKER_COUNT = 3
START_TIMEOUT_S = 60.0
#: What a worker logs when a command's output has a line it counts as a step ("Time: …").
STEP_LOG_LINE = "blender-render: frame rendered"
_COLOURS = re.compile(r"\x1b\[[0-9;]*m")


def find_farm_folder() -> Path | None:
    """The folder holding the Flamenco binaries (see the module docstring), or None."""
    if os.environ.get(FARM_ENV):
        return Path(os.environ[FARM_ENV]).expanduser()
    for folder in (REPO_ROOT, *REPO_ROOT.parents):
        candidate = folder / "shared" / "farm"
        if all((candidate / name).is_file() for name in BINARIES):
            return candidate
    return None


def _free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def _copy_executable(source: Path, folder: Path) -> Path:
    """A copy (the Manager reads ``scripts/`` next to its real path, so never a symlink), made executable."""
    folder.mkdir(parents=True, exist_ok=True)
    target = folder / source.name
    shutil.copyfile(source, target)
    target.chmod(target.stat().st_mode | stat.S_IXUSR | stat.S_IXGRP | stat.S_IXOTH)
    return target


MANAGER_CONFIG = """\
_meta:
  version: 3
manager_name: Prism test farm
database: flamenco-manager.sqlite
listen: 127.0.0.1:{port}
autodiscoverable: false
local_manager_storage_path: ./flamenco-manager-storage
shared_storage_path: {shared}
shaman:
  enabled: false
task_timeout: 5m0s
worker_timeout: 1m0s
blocklist_threshold: 3
task_fail_after_softfail_count: 3
variables:
"""
VARIABLE = """\
  {name}:
    values:
    - platform: all
      value: {value}
"""


def _signal_group(process: subprocess.Popen, signal_number: int) -> None:
    """Signal the process group ``process`` leads (started with its own session), if any is left."""
    try:
        os.killpg(process.pid, signal_number)
    except ProcessLookupError:
        pass


class LocalFarm:
    """A Flamenco Manager and Workers started in ``root``; ``stop()`` ends every process it started."""

    def __init__(self, binaries: Path, root: Path):
        self.binaries = binaries
        self.root = root
        self.shared = root / "shared"
        self.fail_once_marker = root / "fail-once.txt"
        self.port = _free_port()
        self.url = f"http://127.0.0.1:{self.port}"
        self.manager = FlamencoManager(self.url, timeout_s=10.0)
        self.processes: list[tuple[str, subprocess.Popen]] = []
        self.variables = {"blender": str(root / "bin" / "blender"), "blenderArgs": "-b -y", "prism": str(REPO_ROOT)}

    def start(self, workers: int = WORKER_COUNT) -> None:
        self.shared.mkdir(parents=True)
        self._write_blender_launcher()
        manager_dir = self.root / "manager"
        manager = _copy_executable(self.binaries / "flamenco-manager", manager_dir)
        (manager_dir / "scripts").mkdir()
        shutil.copyfile(JOB_TYPE_SCRIPT, manager_dir / "scripts" / JOB_TYPE_SCRIPT.name)
        (manager_dir / "flamenco-manager.yaml").write_text(
            MANAGER_CONFIG.format(port=self.port, shared=self.shared)
            + "".join(VARIABLE.format(name=name, value=json.dumps(value)) for name, value in self.variables.items())
        )
        self._launch("manager", [str(manager)], manager_dir, os.environ.copy())
        self._wait(lambda: self.manager.version(), "the Manager to answer on " + self.url)

        worker = _copy_executable(self.binaries / "flamenco-worker", self.root / "bin")
        environment = os.environ.copy()
        environment.update({
            "PRISM_SHIM_FAIL_ONCE": str(self.fail_once_marker),
            # The workers' HOME is temporary: keep compiled kernels where this test run keeps them.
            "PRISM_KERNEL_CACHE": str(jit.cache_directory()),
        })
        for index in range(workers):
            home = self.root / f"worker-{index + 1}"
            home.mkdir()
            self._launch(f"worker-{index + 1}", [str(worker), "-manager", self.url], home, {**environment, "HOME": str(home)})
        self._wait(lambda: self._awake_workers() >= workers or None, f"{workers} workers to sign on")

    def fail_once(self, output_name: str) -> None:
        """Make the first render that writes a file called ``output_name`` fail (see blender_shim.py)."""
        self.fail_once_marker.write_text(output_name)

    def wait_for_job(self, job_id: str, timeout_s: float = 300.0) -> dict:
        """The job once it is completed, failed or canceled (or at the timeout)."""
        deadline = time.monotonic() + timeout_s
        while True:
            job = self.manager.job(job_id)
            if job["status"] in ("completed", "failed", "canceled") or time.monotonic() > deadline:
                return job
            self._check_alive()
            time.sleep(0.5)

    def task_logs(self, job_id: str) -> str:
        """Every task's status and the end of its log: what a failing test prints."""
        lines = []
        for summary in self.manager.job_tasks(job_id):
            lines.append(f"--- {summary['name']}: {summary['status']}")
            lines.append(self._get(f"/tasks/{summary['id']}/logtail").decode("utf-8", "replace"))
        return "\n".join(lines)

    def steps_logged(self, task_id: str) -> int:
        """How many progress steps the workers counted for a task (from their logs): one per "Time: …"
        line the task's command printed, each sent to the Manager as it came."""
        count = 0
        for log in (self.root / "logs").glob("worker-*.log"):
            for line in _COLOURS.sub("", log.read_text(errors="replace")).splitlines():
                count += STEP_LOG_LINE in line and f"task={task_id}" in line
        return count

    def last_rendered(self, job_id: str) -> dict | None:
        """The job's last-rendered image as the Manager has it (a worker uploads the PNG of a
        "Saved: '…'" line), or None."""
        payload = self._get(f"/jobs/{job_id}/last-rendered")
        return json.loads(payload) if payload else None

    def stop(self) -> None:
        """Interrupt every process started here (workers first, with the renders they run), wait,
        then kill whatever of their process groups is left."""
        for _, process in reversed(self.processes):
            _signal_group(process, signal.SIGINT)
        for _, process in reversed(self.processes):
            try:
                process.wait(timeout=15)
            except subprocess.TimeoutExpired:
                _signal_group(process, signal.SIGKILL)
                process.wait(timeout=15)
            _signal_group(process, signal.SIGKILL)  # a render its worker left behind
        self.processes.clear()
        for copy in (self.root / "manager" / "flamenco-manager", self.root / "bin" / "flamenco-worker"):
            copy.unlink(missing_ok=True)  # 47 MB; pytest keeps the logs of the last runs

    def log_tail(self, name: str, lines: int = 30) -> str:
        path = self.root / "logs" / f"{name}.log"
        return "\n".join(path.read_text(errors="replace").splitlines()[-lines:]) if path.exists() else ""

    def _get(self, path: str) -> bytes:
        with urllib.request.urlopen(f"{self.url}/api/v3{path}", timeout=10) as response:
            return response.read()

    def run_blender_command(self, command: dict) -> subprocess.CompletedProcess:
        """Run a task's ``blender-render`` command here, as a worker would: the Manager's variables
        expanded, then ``exe exeArgs argsBefore [blendfile] args``."""
        def expand(text: str) -> str:
            for name, value in self.variables.items():
                text = text.replace("{" + name + "}", value)
            return text

        parameters = command["parameters"]
        argv = [expand(parameters["exe"]), *shlex.split(expand(parameters["exeArgs"]))]
        argv += [expand(a) for a in parameters["argsBefore"]]
        argv += [expand(parameters["blendfile"])] if parameters["blendfile"] else []
        argv += [expand(a) for a in parameters["args"]]
        return subprocess.run(argv, capture_output=True, text=True, timeout=120)

    def _write_blender_launcher(self) -> None:
        launcher = Path(self.variables["blender"])
        launcher.parent.mkdir(parents=True, exist_ok=True)
        launcher.write_text(f'#!/bin/sh\nexec "{sys.executable}" "{SHIM}" "$@"\n')
        launcher.chmod(0o755)

    def _launch(self, name: str, command: list[str], cwd: Path, environment: dict) -> None:
        (self.root / "logs").mkdir(exist_ok=True)
        with open(self.root / "logs" / f"{name}.log", "wb") as log:
            # Its own session, so stop() can interrupt it together with the renders it started.
            process = subprocess.Popen(command, cwd=cwd, env=environment, stdout=log, stderr=subprocess.STDOUT,
                                       stdin=subprocess.DEVNULL, start_new_session=True)
        self.processes.append((name, process))

    def _check_alive(self) -> None:
        for name, process in self.processes:
            if process.poll() is not None:
                raise RuntimeError(f"Flamenco {name} exited with status {process.returncode}:\n{self.log_tail(name)}")

    def _awake_workers(self) -> int:
        workers = json.loads(self._get("/worker-mgt/workers")).get("workers") or []
        return sum(1 for worker in workers if worker.get("status") == "awake")

    def _wait(self, probe, what: str) -> None:
        deadline = time.monotonic() + START_TIMEOUT_S
        while True:
            self._check_alive()
            try:
                if probe():
                    return
            except (FlamencoError, urllib.error.URLError):
                pass
            if time.monotonic() > deadline:
                raise RuntimeError(f"Timed out after {START_TIMEOUT_S:.0f} s waiting for {what}:\n"
                                   + "\n".join(self.log_tail(name) for name, _ in self.processes))
            time.sleep(0.2)


@pytest.fixture
def unreachable_url() -> str:
    """An http URL on loopback where nothing listens."""
    return f"http://127.0.0.1:{_free_port()}"


@pytest.fixture(scope="module")
def flamenco_farm(tmp_path_factory):
    """A running Manager (with the prism-render job type) and three Workers on loopback."""
    binaries = find_farm_folder()
    if binaries is None or not all((binaries / name).is_file() for name in BINARIES):
        where = (f"${FARM_ENV} is {binaries}, which lacks them" if os.environ.get(FARM_ENV)
                 else f"no shared/farm beside {REPO_ROOT} or its parent folders holds them")
        message = (f"Flamenco binaries ({', '.join(BINARIES)}) not found: {where}. Check out the shared folder "
                   f"next to the repository, or set {FARM_ENV} to the folder that holds them.")
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    farm = LocalFarm(binaries, tmp_path_factory.mktemp("flamenco"))
    try:
        farm.start()
        yield farm
    finally:
        farm.stop()


@pytest.fixture(autouse=True)
def online_access_on(request, monkeypatch):
    """The bpy module starts with Blender's Allow Online Access off (``bpy.app.online_access`` False, a
    read-only flag), and Prism then makes no request to a Manager: the farm tests act as a user who allowed
    it. ``test_farm_online_access.py`` turns it off again."""
    if "prism_addon" in request.fixturenames:
        addon = request.getfixturevalue("prism_addon")
        monkeypatch.setattr(addon.operators.online_access, "online_access_allowed", lambda: True)
