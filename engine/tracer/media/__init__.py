"""Participating media inside closed meshes: spectral (extinction, albedo and emission per wavelength), as
Blender's Volume Absorption, Volume Scatter and Principled Volume define them; homogeneous, or scaled point by
point by a voxel grid of density (a grid medium: Blender's Volume objects, and a Density driven by nodes).

- ``spec.py``: ``MediumSpec``, a medium as the export layer describes it (Blender's settings, RGB);
- ``table.py``: ``MediaArrays``, the media of a render as spectra per metre (built with the materials);
- ``coefficients.py``: σ_s, σ_t at a path's wavelengths, and transmittance;
- ``phase.py``: the Henyey-Greenstein phase function (evaluate, sample), and a medium's phase function;
- ``phase_functions.py``, ``tabulated_phase.py``: Volume Scatter's other phase functions (Fournier-Forand,
  Draine, Rayleigh, Mie) and mixtures, tabulated and sampled from their table;
- ``baked_density.py``: a Density driven by nodes, baked onto a grid over the meshes that hold it;
- ``segment.py``: a ray segment inside a medium (emission, distance sampling with spectral MIS);
- ``scatter.py``: a scattering vertex in a medium (light sampling through media, phase sampling);
- ``density_grid.py``: ``DensityGrid`` (voxels and their transform) and ``GridArrays`` (the render's grids);
- ``grid_lookup.py``: a ray against a grid's bounds, trilinear density in compiled code;
- ``delta_tracking.py``: a ray segment inside a grid medium (delta tracking with spectral MIS);
- ``ratio_tracking.py``, ``transmittance.py``: a shadow ray's transmittance (ratio tracking in a grid medium,
  Beer-Lambert in a homogeneous one);
- ``nesting.py``, ``boundary.py``: media inside media and the World's fog, added as Cycles adds the volumes on
  its stack; the row a ray crossing a medium's surface travels in.

A path carries the row of the media it is in (``PathState.medium``, -1 outside every medium): it enters a
medium by crossing a surface whose material has one against its geometric normal (inward), and leaves it by
crossing such a surface along the normal; inside several at once it travels in their sum (``nesting``).
Scenes without media skip all of this (``KernelSettings.has_media``).
"""
