"""Reading a spectral EXR with colour-science's own reader, in a fresh process.

colour-science decides at import whether OpenImageIO exists; in the bpy module OpenImageIO (Blender's
copy) is only importable once ``engine.output.openimageio`` has put it on ``sys.path``, which is after the
tests imported colour. A fresh process imports OpenImageIO first, as a user's script would."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np

_SCRIPT = r"""
import json, sys, warnings
sys.path.append(sys.argv[3])
import OpenImageIO
warnings.simplefilter("ignore")
import colour
import numpy as np
components, specification = colour.io.read_spectral_image_Fichet2021(sys.argv[1], additional_data=True)
wavelengths, values = components["S0"]
image = OpenImageIO.ImageInput.open(sys.argv[1])
spec = image.spec()
rgb = image.read_image(OpenImageIO.FLOAT)[..., [spec.channelnames.index(c) for c in "RGB"]]
attributes = {a.name: a.value for a in spec.extra_attribs if isinstance(a.value, str)}
np.savez(sys.argv[2], wavelengths=wavelengths, values=values, rgb=rgb)
print(json.dumps({"emissive": specification.is_emissive, "polarised": specification.is_polarised,
                  "components": list(components), "attributes": attributes}))
"""


def read_with_colour(path, scratch: Path):
    """(info dict, wavelengths [B], values [H, W, B], rgb [H, W, 3]) as colour-science reads ``path``."""
    import bpy

    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    site = Path(bpy.utils.system_resource("PYTHON")) / "lib" / version / "site-packages"
    arrays = Path(scratch) / "read.npz"
    completed = subprocess.run([sys.executable, "-c", _SCRIPT, str(path), str(arrays), str(site)],
                               capture_output=True, text=True, timeout=120)
    assert completed.returncode == 0, completed.stderr
    data = np.load(arrays)
    return json.loads(completed.stdout.strip().splitlines()[-1]), data["wavelengths"], data["values"], data["rgb"]
