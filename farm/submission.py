"""The Flamenco job a scene's farm settings describe, and its submission.

``PrismFarmJob`` holds plain values (the operator reads them from the scene); ``submit`` sends it to
a Manager as a ``prism-render`` job (see ``prism_render.js`` for the tasks it becomes).
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass

from . import JOB_TYPE_NAME
from .manager import FlamencoError, FlamencoManager

DEFAULT_RENDER_SCRIPT = "{prism}/render.py"
WORKER_PLATFORMS = ("linux", "windows", "darwin")


@dataclass
class PrismFarmJob:
    """One ``prism-render`` job: what to render, how to split it and where the frames go."""

    name: str
    blendfile: str  # absolute, as the workers see it (shared storage)
    frames: str  # Flamenco frame range: "1..24", "7", "1,3,5"
    samples: int  # per finished frame
    chunks: int  # sample chunks per frame; 1 = plain frames
    seed: int
    render_output_path: str  # absolute, .exr or .png; the last run of # becomes the frame number
    samples_per_pass: int = 1  # the scene's: one pass is one step of a task's progress
    render_script: str = DEFAULT_RENDER_SCRIPT
    priority: int = 50

    def settings(self) -> dict:
        """The job's settings, keyed as ``prism_render.js`` declares them."""
        return {
            "blendfile": self.blendfile,
            "frames": self.frames,
            "samples": self.samples,
            "chunks": self.chunks,
            "samples_per_pass": self.samples_per_pass,
            "seed": self.seed,
            "render_output_path": self.render_output_path,
            "render_script": self.render_script,
        }

    def submitted_job(self, type_etag: str = "", platform: str = "") -> dict:
        """Flamenco's ``SubmittedJob`` document for this job."""
        document = {
            "name": self.name,
            "type": JOB_TYPE_NAME,
            "priority": self.priority,
            "settings": self.settings(),
            "submitter_platform": platform or submitter_platform(),
        }
        if type_etag:
            document["type_etag"] = type_etag
        return document


def samples_per_chunk(samples: int, chunks: int) -> int:
    """Samples each chunk renders; ``ValueError`` naming the fix when they do not divide evenly."""
    if chunks < 1 or samples < 1:
        raise ValueError(f"Farm: samples ({samples}) and chunks ({chunks}) must both be at least 1.")
    if samples % chunks:
        lower = samples - samples % chunks
        choices = f"{lower} or {lower + chunks}" if lower else f"{lower + chunks}"
        raise ValueError(
            f"Farm: {samples} samples do not split into {chunks} equal chunks: set Samples to {choices}, "
            f"or choose a number of chunks that divides {samples}."
        )
    return samples // chunks


def frame_range_text(start: int, end: int, step: int = 1) -> str:
    """Blender's frame range in Flamenco's notation: ``1..24``, or the frames listed when step > 1."""
    if end < start:
        raise ValueError(f"Farm: the frame range ends ({end}) before it starts ({start}).")
    if start < 0:
        raise ValueError(f"Farm: Flamenco's frame ranges have no negative frames (the range starts at {start}): "
                         "set the scene's Frame Start to 0 or later.")
    if step == 1:
        return f"{start}..{end}"
    return ",".join(str(frame) for frame in range(start, end + 1, step))


def submitter_platform() -> str:
    """This machine's platform as Flamenco names it (Go's ``GOOS``): linux, windows, darwin."""
    if sys.platform.startswith("linux"):
        return "linux"
    return {"win32": "windows", "cygwin": "windows"}.get(sys.platform, sys.platform)


def submit(manager: FlamencoManager, job: PrismFarmJob) -> dict:
    """Queue ``job`` on ``manager``; returns the stored job (its ``id`` and ``status``).

    Checks first that the Manager has the ``prism-render`` job type with every setting this Prism
    sends, and the variables the render script's path uses, so an outdated script or a missing
    variable is named here instead of failing on the workers.
    """
    job_type = manager.job_type(JOB_TYPE_NAME)
    known = {setting.get("key") for setting in job_type.get("settings") or []}
    missing = sorted(set(job.settings()) - known)
    if missing:
        raise FlamencoError(
            f"The '{JOB_TYPE_NAME}' job type on {manager.url} is older than this Prism (no {', '.join(missing)} "
            "setting): copy this Prism's farm/prism_render.js into the Manager's scripts/ folder and restart it."
        )
    _check_variables(manager, job.render_script)
    return manager.submit_job(job.submitted_job(type_etag=job_type.get("etag", "")))


def _check_variables(manager: FlamencoManager, text: str) -> None:
    """Every ``{name}`` in ``text`` must be a Manager variable for at least one worker platform."""
    for name in sorted(set(re.findall(r"\{(\w+)\}", text))):
        if not any(name in manager.variables(platform) for platform in WORKER_PLATFORMS):
            raise FlamencoError(
                f"Flamenco Manager {manager.url} has no '{name}' variable, which Render Script '{text}' uses: add "
                f"it to flamenco-manager.yaml with the folder Prism is installed in on each worker platform "
                "(see docs/farm.md), or give Render Script as the full path of render.py on the workers."
            )
