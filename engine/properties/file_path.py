"""Options for file-path settings that accept Blender's "//" prefix (the .blend file's folder).

Every Prism path setting resolves "//" with ``bpy.path.abspath``. From Blender 4.5 a FILE_PATH
property must also declare so, or Blender warns 'does not support blend relative "//" prefix' each
time such a path is set; Blender 4.2-4.4 do not know the option and refuse it.
"""

import bpy

BLEND_RELATIVE_PATH_OPTIONS = {"PATH_SUPPORTS_BLEND_RELATIVE"} if bpy.app.version >= (4, 5, 0) else set()
