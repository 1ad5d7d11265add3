"""The stages of a bounce, one compiled loop over paths each (see ``renderer`` for their order):

``camera`` (new paths and their first rays) → Embree → ``emission`` (light found by hits and escapes;
which paths hit a surface) → ``shade`` (surface, material, light sampling (``nee``), BSDF sampling,
``roulette``; the next rays and shadow rays) → Embree → ``shadow`` (light that reached its vertex) →
… → ``film`` (spectral radiance to RGB per path).
"""
