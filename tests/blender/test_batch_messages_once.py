"""What a finished batch render says: each warning once (the status line, which Blender and Prism print
every pass, counts warnings instead of quoting one), and a secondary output that fails after the render
costs neither the main image nor a clear exit status."""

from __future__ import annotations

import importlib

import bpy

from helpers.bpy_scenes import build_lit_card_scene, image_pixels


def _collimated_panel():
    data = bpy.data.lights.new("Panel", "AREA")
    data.energy, data.size, data.spread = 20.0, 0.5, 0.0
    panel = bpy.data.objects.new("Panel", data)
    panel.location = (0.0, 0.0, 1.5)
    bpy.context.scene.collection.objects.link(panel)


def test_each_warning_prints_once(prism_addon, fresh_scene, tmp_path, capfd, bad_input):
    build_lit_card_scene(resolution=(8, 6))
    _collimated_panel()
    render = importlib.import_module("render")
    capfd.readouterr()
    status = render.main(["--samples", "3", "--output", str(tmp_path / "out.png")], in_blender=True)  # 3 passes
    out, err = capfd.readouterr()
    printed = out + err
    warning = "Light 'Panel': Spread 0° makes a collimated beam"
    assert status == 0, printed
    # Was once more per pass: the status line quoted it, and Blender prints that line ("Fra: …") and Prism
    # its "Time: …" copy for render farms.
    assert printed.count(warning) == 1, printed
    assert "1 warning(s)" in err.splitlines()[-2]
    line = next(line for line in err.splitlines() if warning in line)
    assert line.startswith("Prism: warning: ")
    bad_input("an area light of Spread 0 (rendered at the narrowest spread Prism samples, with a warning)", status,
              line)


def test_a_spectral_exr_that_fails_after_the_render_keeps_the_image(prism_addon, fresh_scene, tmp_path, capfd,
                                                                     monkeypatch, bad_input):
    build_lit_card_scene(resolution=(8, 6))
    spectral_exr = importlib.import_module(f"{prism_addon.__name__}.engine.output.spectral_exr")
    errors = importlib.import_module(f"{prism_addon.__name__}.engine.tracer.errors")

    def disk_full(path, *_):
        raise errors.PrismInputError(f"Cannot write '{path}': No space left on device")

    monkeypatch.setattr(spectral_exr, "write_spectral_exr", disk_full)
    render = importlib.import_module("render")
    capfd.readouterr()
    output, bands = tmp_path / "out.exr", tmp_path / "bands.exr"
    status = render.main(["--samples", "1", "--output", str(output), "--spectral-output", str(bands)], in_blender=True)
    out, err = capfd.readouterr()
    lines = [line for line in err.splitlines() if line.strip()]
    assert status == 1
    assert lines[-2:] == [f"Saved: '{output}'", f"Prism: error: The spectral EXR was not written (Cannot write "
                                                f"'{bands}': No space left on device); the rendered image is kept."]
    assert (out + err).count("The spectral EXR was not written") == 1
    assert image_pixels(output)[..., :3].mean() > 0.0 and not bands.exists()
    bad_input("--spectral-output whose writing fails after the render (disk full)", status, lines[-1])
