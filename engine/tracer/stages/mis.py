"""Multiple importance sampling weights of emission found by BSDF-sampled rays."""

from __future__ import annotations

from ..jit import inlined
from ..state import CAUSTIC, PREV_DELTA
from ..warps import power_heuristic


@inlined
def emitter_weight(state, i, light_pdf, use_mis):
    """Weight of emission that path ``i``'s last BSDF sample found, against light sampling with density
    ``light_pdf``: 1 after a delta lobe (or on camera rays); with MIS the power heuristic; without MIS 0
    (light sampling alone counts that light); 0 on caustic paths light tracing supplies
    (``stages.caustic_split``: the flag is only ever set when light tracing is on)."""
    if state.flags[i] & CAUSTIC:
        return 0.0
    if state.flags[i] & PREV_DELTA:
        return 1.0
    if use_mis:
        return power_heuristic(state.prev_pdf[i], light_pdf)
    return 0.0
