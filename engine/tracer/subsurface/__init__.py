"""Subsurface scattering as Cycles' default random walk (Chiang, Kutz & Burley 2016, "Practical and
Controllable Subsurface Scattering for Production Path Tracing"), per wavelength.

A path that samples a subsurface closure enters the surface (``bsdf.subsurface_entry``), walks through a
homogeneous medium whose coefficients come from the closure's albedo and radius (``coefficients``) until it
leaves the same object (``walk``), and goes on from the exit point as a Lambertian reflection of albedo 1
(``stages.subsurface``). The radius is a spectrum (Blender's RGB Radius upsampled), so the mean free path
is a function of wavelength.
"""
