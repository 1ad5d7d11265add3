"""Images out of a render: PNG through the scene's view transform (``png``), the multispectral EXR
(``spectral_exr``), OpenImageIO as Blender bundles it (``openimageio``), OpenImageDenoise (``denoise``)
and the spectrum plots of the Light and Material panels (``spectrum_preview``)."""
