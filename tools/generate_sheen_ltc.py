"""Regenerate ``engine/tracer/bsdf/data/sheen_ltc.npz``: the fitted microfiber-sheen LTC table.

The data are the published fit of Zeltner, Burley & Chiang, "Practical Multiple-Scattering Sheen Using
Linearly Transformed Cosines" (SIGGRAPH 2022 talk, https://tizianzeltner.com/projects/Zeltner2022Practical/),
as Cycles ships them (``src/scene/shader.tables``, ``table_sheen_ltc``, Apache-2.0, Blender Foundation):
three 32 x 32 grids, rows = sheen roughness 0..1, columns = view cosine 0..1, both uniform, holding the
LTC coefficients a and b (the inverse transform [[a, 0, b], [0, a, 0], [0, 0, 1]] in a frame whose x
axis points at the viewer) and the lobe's directional albedo. Only the numbers are taken over.

    python tools/generate_sheen_ltc.py path/to/cycles/src/scene/shader.tables

(``git -C <cycles clone> show HEAD:src/scene/shader.tables > shader.tables`` gives the file.)
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np

OUT = Path(__file__).resolve().parent.parent / "engine" / "tracer" / "bsdf" / "data" / "sheen_ltc.npz"
SIZE = 32  # grid points per axis in the published table


def read_table(text: str, name: str) -> np.ndarray:
    """The float values of the C array ``name`` in ``text``."""
    match = re.search(r"\b" + re.escape(name) + r"\s*\[[^\]]*\]\s*=\s*\{(.*?)\};", text, re.S)
    if match is None:
        raise SystemExit(f"{name} not found")
    return np.array([float(v.rstrip("f")) for v in re.findall(r"[-+0-9.eE]+f?", match.group(1))])


def main(source: str) -> None:
    values = read_table(Path(source).read_text(), "table_sheen_ltc")
    if values.size != 3 * SIZE * SIZE:
        raise SystemExit(f"expected {3 * SIZE * SIZE} values, found {values.size}")
    ltc_a, ltc_b, albedo = values.reshape(3, SIZE, SIZE)  # [quantity, roughness, view cosine]
    np.savez_compressed(OUT, ltc_a=ltc_a, ltc_b=ltc_b, albedo=albedo)
    print(f"wrote {OUT}: albedo {albedo.min():.4f}..{albedo.max():.4f}")


if __name__ == "__main__":
    main(sys.argv[1])
