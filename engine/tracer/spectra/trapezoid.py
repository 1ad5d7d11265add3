"""The trapezoid rule, one name for numpy 1.26 (Blender 4.2-5.0) and numpy 2.x.

numpy 2.0 renamed ``np.trapz`` to ``np.trapezoid``; numpy 2.5 removed ``np.trapz``, and 1.26 has no
``np.trapezoid``. Every integral over wavelength in the engine, the tools, the benchmarks and the tests
goes through this name, so the next rename is a one-line change.
"""

from __future__ import annotations

import numpy as np

#: ``trapezoid(y, x=None, dx=1.0, axis=-1)``: numpy's trapezoid rule, whichever name this numpy has.
trapezoid = getattr(np, "trapezoid", None) or np.trapz
