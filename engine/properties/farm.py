"""``Scene.prism.farm``: where and how the Farm panel submits the scene to a Flamenco Manager
(nested in ``scene.py``'s group). The frames, samples and seed are the scene's own settings."""

import bpy
from bpy.props import IntProperty, StringProperty

from .file_path import BLEND_RELATIVE_PATH_OPTIONS


class PrismFarmSettings(bpy.types.PropertyGroup):
    """Render-farm submission settings of a scene."""

    manager_url: StringProperty(
        name="Manager URL",
        description="Address of the Flamenco Manager, as it prints at start-up (e.g. http://flamenco.local:8080)",
        default="http://localhost:8080",
    )
    job_name: StringProperty(
        name="Job Name",
        description="Name of the job in Flamenco (empty: the .blend file's name)",
        default="",
    )
    priority: IntProperty(
        name="Priority",
        description="Flamenco job priority: higher runs first",
        default=50,
        min=0,
        max=100,
    )
    chunks: IntProperty(
        name="Chunks per Frame",
        description="Split every frame's samples into this many chunks, each rendered by any free worker and "
        "merged afterwards (bit-identical to one render); 1 renders plain frames",
        default=1,
        min=1,
        soft_max=64,
        max=1024,
    )
    output_path: StringProperty(
        name="Output",
        description="Finished frames on shared storage, .exr (scene-linear) or .png (the scene's view transform); "
        "the last run of # becomes the frame number",
        default="//render/prism_####.exr",
        subtype="FILE_PATH",
        options=BLEND_RELATIVE_PATH_OPTIONS,
    )
    render_script: StringProperty(
        name="Render Script",
        description="Prism's render.py as the workers see it; {prism} is a Manager variable holding the folder "
        "Prism is installed in on each worker platform",
        default="{prism}/render.py",
    )
    last_job_id: StringProperty(
        name="Last Job",
        description="ID of the job this scene was last submitted as",
        default="",
    )


def register():
    bpy.utils.register_class(PrismFarmSettings)


def unregister():
    bpy.utils.unregister_class(PrismFarmSettings)
