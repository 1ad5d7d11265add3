"""The targets the benchmark report and its findings measure Prism against (one home: the report's
tables, the findings' verdicts and the scaling section read them from here)."""

from __future__ import annotations

TARGET_CEILING = 0.60  # path throughput / embreex ceiling on cornell_glass, 2 threads
TARGET_PEER_RATIO = {"Cycles": 1.0, "Mitsuba": 1.5}  # largest Prism / peer relMSE at equal time
TARGET_SCALING_KEPT = 0.85  # Prism's speed-up over 1 thread / embreex's on the same rays, at every thread count
TARGET_DEMO_SPEEDUP = 5.0  # make render before / now
TARGET_HERO_SPEEDUP = 4.0
HERO_TARGET_RELMSE = 1e-2


def peer_target(peer_name: str) -> float:
    """The largest acceptable Prism / peer relMSE ratio for a peer named ``Cycles ...`` or ``Mitsuba ...``."""
    return next((v for k, v in TARGET_PEER_RATIO.items() if peer_name.startswith(k)), 1.0)
