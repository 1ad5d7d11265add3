"""Which handler compiles which Blender node (by ``bl_idname``)."""

from __future__ import annotations

from . import converters, inputs, light_path, shader_rays, shaders, textures, vectors, wavelength

NODE_HANDLERS = {**inputs.HANDLERS, **converters.HANDLERS, **textures.HANDLERS, **vectors.HANDLERS,
                 **wavelength.HANDLERS, **light_path.HANDLERS, **shader_rays.HANDLERS}
SHADER_HANDLERS = dict(shaders.SHADER_HANDLERS)
