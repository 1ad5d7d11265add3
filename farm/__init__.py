"""Rendering on a Flamenco farm: Prism's job type for the Manager and job submission from Blender.

- ``prism_render.js``: the job type ``prism-render`` (copy it into the ``scripts/`` folder next to the
  ``flamenco-manager`` executable). Every frame's samples are split into chunks rendered by separate
  workers; one merge task per frame combines them, bit-identical to a single render.
- ``manager``: a small client of Flamenco Manager's REST API (standard library only).
- ``submission``: the job a scene's settings describe, as Flamenco's ``SubmittedJob``.

Nothing here imports bpy: the Farm panel and operator hand over plain values. See ``docs/farm.md``.
"""

from pathlib import Path

JOB_TYPE_NAME = "prism-render"
JOB_TYPE_SCRIPT = Path(__file__).with_name("prism_render.js")
