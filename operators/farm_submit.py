"""Submit the scene to a Flamenco render farm as a ``prism-render`` job (Render ▸ Farm panel).

The workers render a snapshot: the open file is saved as a copy next to the output, on the shared
storage the workers write to, so later edits never reach a running job (and all chunks of a frame
render the same scene). Frames, samples and seed are the scene's; the rest is ``Scene.prism.farm``.
"""

from __future__ import annotations

import os
import re
import time
from pathlib import Path

import bpy

from ..farm.manager import FlamencoError, FlamencoManager
from ..farm.submission import PrismFarmJob, frame_range_text, samples_per_chunk, submit
from . import online_access

SNAPSHOT_FOLDER = "prism-jobs"


def output_path(scene) -> str:
    """The Farm panel's output as an absolute path; ``ValueError`` when it cannot be one."""
    output = scene.prism.farm.output_path.strip()
    if not output:
        raise ValueError("Farm: set the Output path (on storage the workers share) in the Farm panel.")
    if output.startswith("//") and not bpy.data.filepath:
        raise ValueError(f"Farm: Output '{output}' is relative to the .blend file, which is not saved yet: "
                         "save the file or give an absolute path on shared storage.")
    return os.path.normpath(bpy.path.abspath(output))


def farm_job(scene, blendfile: str) -> PrismFarmJob:
    """The job ``scene``'s settings describe, rendering ``blendfile``; ``ValueError`` naming the fix."""
    settings, farm = scene.prism, scene.prism.farm
    samples_per_chunk(settings.samples, farm.chunks)
    return PrismFarmJob(
        name=job_name(scene),
        blendfile=blendfile,
        frames=frame_range_text(scene.frame_start, scene.frame_end, scene.frame_step),
        samples=settings.samples,
        chunks=farm.chunks,
        seed=settings.seed,
        render_output_path=output_path(scene),
        samples_per_pass=settings.samples_per_pass,
        render_script=farm.render_script.strip(),
        priority=farm.priority,
    )


def job_name(scene) -> str:
    """The Farm panel's job name, else the .blend file's, else the scene's."""
    return scene.prism.farm.job_name.strip() or Path(bpy.data.filepath).stem or scene.name


def job_summary(scene) -> str:
    """``2 frames × 3 chunks of 16 samples: 6 render tasks + 2 merges`` (``ValueError`` like ``farm_job``)."""
    frame_range_text(scene.frame_start, scene.frame_end, scene.frame_step)
    frames = len(range(scene.frame_start, scene.frame_end + 1, scene.frame_step))
    chunks = scene.prism.farm.chunks
    per_chunk = samples_per_chunk(scene.prism.samples, chunks)
    if chunks == 1:
        return f"{frames} frames of {per_chunk} samples: {frames} render tasks"
    return (f"{frames} frames × {chunks} chunks of {per_chunk} samples: "
            f"{frames * chunks} render tasks + {frames} merges")


def save_snapshot(scene) -> str:
    """Save the open file as a copy in ``prism-jobs/`` beside the output; returns its path."""
    name = re.sub(r"[^\w.-]+", "_", job_name(scene))
    folder = Path(output_path(scene)).parent / SNAPSHOT_FOLDER
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as error:
        raise ValueError(f"Farm: cannot create '{folder}' for the job's copy of the .blend file ({error.strerror}): "
                         "check the Output path is on writable shared storage.") from None
    snapshot = folder / f"{name}-{time.strftime('%Y%m%d-%H%M%S')}.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(snapshot), copy=True, relative_remap=True)
    return str(snapshot)


class PRISM_OT_farm_submit(bpy.types.Operator):
    """Submit this scene to the Flamenco Manager: every frame's samples are split into chunks that
    free workers render, then merged. The workers render a copy of the file saved beside the output"""

    bl_idname = "prism.farm_submit"
    bl_label = "Submit to Flamenco"
    bl_options = {"REGISTER"}

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def execute(self, context):
        scene = context.scene
        farm = scene.prism.farm
        if not online_access.online_access_allowed():
            self.report({"ERROR"}, online_access.OFFLINE_MESSAGE)
            return {"CANCELLED"}
        try:
            summary = job_summary(scene)
            manager = FlamencoManager(farm.manager_url)
            job = farm_job(scene, blendfile="")
            manager.version()  # reachable, before writing anything
            job.blendfile = save_snapshot(scene)
            stored = submit(manager, job)
        except (ValueError, FlamencoError) as error:
            self.report({"ERROR"}, str(error))
            return {"CANCELLED"}
        farm.last_job_id = stored.get("id", "")
        per_chunk = job.samples // job.chunks
        if per_chunk % scene.prism.samples_per_pass:
            self.report({"WARNING"}, f"Farm: chunks of {per_chunk} samples are not a multiple of Samples per Pass "
                                     f"({scene.prism.samples_per_pass}): the merged frames are correct but not "
                                     "bit-identical to a single render.")
        self.report({"INFO"}, f"Farm: submitted '{job.name}' to {farm.manager_url} as job {farm.last_job_id}: "
                              f"{summary}; the workers render {job.blendfile}.")
        return {"FINISHED"}


_CLASSES = (PRISM_OT_farm_submit,)


register, unregister = bpy.utils.register_classes_factory(_CLASSES)
