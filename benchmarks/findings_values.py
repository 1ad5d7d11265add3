"""Values the document reads out of one run's results, shared by its prose (``findings.py``) and its
tables (``findings_tables.py``): a target met or not, a fraction as a percentage, the cornell_glass ceiling, a peer comparison's
ratio, and a scene's stage split with Embree's share and its largest kernel.
"""

from __future__ import annotations

import numpy as np


def _status(ok):
    return "**met**" if ok else "**not met**"


def _pct(x):
    return "n/a" if x is None or not np.isfinite(x) else f"{100 * x:.0f} %"


def _glass_ceiling(results):
    return next((c for c in results.get("ceiling", []) if c["scene"] == "cornell_glass"), None)


def _peer_ratio(c):
    """(ratio, note, measured) of a peer comparison: at equal total time, or at equal render time when
    the total-time curves do not overlap; ``measured`` is False when only an extrapolation exists."""
    ratio, note = c["ratio"], f" at {c['seconds']:.2f} s"
    if c["extrapolated"] and np.isfinite(c.get("ratio_render_only", float("nan"))):
        return c["ratio_render_only"], " at equal render time, set-up excluded (total times do not overlap)", True
    if c["extrapolated"]:
        return ratio, note + " (extrapolated: the curves do not overlap in time)", False
    return ratio, note, True


def _stage_rows(results, scene, threads):
    entry = next((s for s in results.get("stages", []) if s["scene"] == scene), None)
    return None if entry is None else entry.get(str(threads))


def _embree_share(split):
    return sum(r["share"] for r in split["rows"] if r["stage"].startswith("Embree"))


def _largest_stage(split):
    return max((r for r in split["rows"] if not r["stage"].startswith("Embree") and np.isfinite(r["share"])),
               key=lambda r: r["cpu"])
