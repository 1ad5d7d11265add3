"""Which paths light tracing supplies, so path tracing skips exactly those (no double counting).

Light tracing (``stages.light_paths``) supplies the caustic paths L S+ D E: light, one or more vertices
on purely specular materials (``MAT_DELTA``: smooth glass, mirrors, films), then one non-specular
vertex D that the camera sees directly. A camera path is such a path, read backwards, when

- its first vertex (after the camera, with no film crossed before it) scattered through a non-delta
  lobe (``SEEN_DIFFUSE``),
- every later vertex lies on a purely specular material (``CAUSTIC`` from the first of them on),
- and the next ray finds a light.

The emission found then gets MIS weight 0 (``stages.mis.emitter_weight``). Crossing a free-standing
film straight through is a null event on both sides (it changes neither state); a camera ray that
crosses a film before its first vertex is ``NOT_CAUSTIC``, because the light tracer's connections to
the camera stop at films. Light sampling never produces L S+ D E (it connects a non-specular vertex to
the light directly), and light tracing does not emit from the world, so world-lit caustics stay with
path tracing (escaping rays are never skipped).
"""

from __future__ import annotations

from ..bsdf.closure import SAMPLED_DELTA
from ..jit import inlined
from ..materials.table import MAT_DELTA
from ..state import CAUSTIC, NOT_CAUSTIC, SEEN_DIFFUSE


@inlined
def classify_vertex(state, i, material_flags, sampled, null_crossing):
    """Advance path ``i``'s place in the split after the scattering at its current vertex."""
    flags = state.flags[i]
    if flags & NOT_CAUSTIC:
        return
    if flags & (SEEN_DIFFUSE | CAUSTIC) == 0:  # the camera's own ray
        if null_crossing or material_flags & MAT_DELTA or sampled & SAMPLED_DELTA:
            state.flags[i] = flags | NOT_CAUSTIC
        else:
            state.flags[i] = flags | SEEN_DIFFUSE
        return
    if null_crossing:
        return
    if material_flags & MAT_DELTA:
        state.flags[i] = (flags & ~SEEN_DIFFUSE) | CAUSTIC
    else:
        state.flags[i] = (flags & ~(SEEN_DIFFUSE | CAUSTIC)) | NOT_CAUSTIC
