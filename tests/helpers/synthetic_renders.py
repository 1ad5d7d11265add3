"""Synthetic renders for the equal-time experiments' arithmetic: two renderers whose noise and times are known."""

import numpy as np


def two_renderers(seconds_per_spp, noise, spps=(16, 32, 64, 128), shape=(48, 64, 3), seed=0):
    """Two renderers' images [renderer, spp, seed, H, W, 3] of a 0.2-1.0 image with relative noise
    noise[r] / sqrt(spp), and times seconds_per_spp[r] x spp."""
    rng = np.random.default_rng(seed)
    truth = rng.uniform(0.2, 1.0, shape)
    images = np.stack([np.stack([truth * (1 + rng.normal(0.0, n / np.sqrt(spp), (2, *shape))) for spp in spps])
                       for n in noise])
    seconds = np.stack([[[t * spp] * 2 for spp in spps] for t in seconds_per_spp])
    return {"images": images, "seconds": seconds, "spp": np.array(spps), "renderers": np.array(["prism", "cycles"])}
