"""The scalars every stage reads, as one value the kernels take (``KernelSettings``)."""

from __future__ import annotations

from collections import namedtuple

#: max_bounces, roulette_depth (first vertex depth where roulette may end a path, minus one),
#: use_mis, sampler (``sampler.SOBOL`` / ``INDEPENDENT``), seed, light_tracing (caustic paths come from
#: light tracing and path tracing skips them: ``stages.caustic_split``).
KernelSettings = namedtuple("KernelSettings", "max_bounces roulette_depth use_mis sampler seed light_tracing")
