"""Errors in the scene a user can act on: each one is a Blender error report naming the object and the fix,
the render stops (no silent wrong image), and the batch script exits non-zero with the message.

Each case breaks the renderable scene of ``helpers.error_scenes`` in one way (camera, lens, world,
material, light, geometry, frame size) and is checked at export, at render and in the batch script.
"""

from __future__ import annotations

import importlib
import math
from pathlib import Path

import bpy
import pytest

from helpers.batch import run_batch
from helpers.error_scenes import base_scene as _base_scene
from helpers.error_scenes import light as _light

REPO_ROOT = Path(__file__).resolve().parents[2]


def _no_camera():
    bpy.context.scene.camera = None


def _empty_as_camera():
    empty = bpy.data.objects.new("Helper", None)
    bpy.context.scene.collection.objects.link(empty)
    bpy.context.scene.camera = empty


def _panorama(kind):
    def mutate():
        data = bpy.context.scene.camera.data
        data.type = "PANO"
        data.panorama_type = kind

    return mutate


def _custom_camera():
    bpy.context.scene.camera.data.type = "CUSTOM"


def _real_lens_ortho(tmp):
    def mutate():
        _real_lens(REPO_ROOT / "lenses" / "double_gauss_50mm.lens")()
        bpy.context.scene.camera.data.type = "ORTHO"

    return mutate


def _world_texture(kind, **settings):
    return lambda tmp: lambda: _add_world_texture(tmp, kind, settings)


def _add_world_texture(tmp, kind, settings):
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    nodes = world.node_tree.nodes
    node = nodes.new(kind)
    for key, value in settings.items():
        if key == "image_path":
            image = bpy.data.images.new("hdri", 4, 2, float_buffer=True)
            image.source, image.filepath = "FILE", str(Path(tmp) / value)
            node.image = image
        else:
            setattr(node, key, value)
    world.node_tree.links.new(node.outputs["Color"], nodes["Background"].inputs["Color"])
    bpy.context.scene.world = world


def _real_lens(path):
    def mutate():
        settings = bpy.context.scene.camera.data.prism
        settings.lens_model = "REAL_LENS"
        settings.lens_source = "FILE"
        settings.lens_file = str(path) if path is not None else ""

    return mutate


def _write(tmp, name, text):
    path = Path(tmp) / name
    path.write_text(text)
    return path


def _bad_toml_lens(tmp):
    return _real_lens(_write(tmp, "bad.lens", 'format = "prism-lens-1"\nname = "bad"\n[[surface]]\nradius_mm = 30.0\nthickness_mm = = 3\n'))


def _unknown_glass_in_lens(tmp):
    text = (
        'format = "prism-lens-1"\nname = "x"\n[[surface]]\nradius_mm = 30.0\nthickness_mm = 3\naperture_mm = 20\n'
        'glass = "UNOBTAINIUM"\n[[surface]]\nradius_mm = -30\nthickness_mm = 40\naperture_mm = 20\n'
    )
    return _real_lens(_write(tmp, "glass.lens", text))


def _floor_material():
    material = bpy.data.materials["Floor material"]
    return material, material.node_tree.nodes["Principled BSDF"]


def _glass(source, **values):
    def mutate():
        material, node = _floor_material()
        node.inputs["Transmission Weight"].default_value = 1.0
        material.prism.glass_source = source
        for key, value in values.items():
            if key == "raw_glass_name":
                material.prism["glass_name"] = value  # a glass saved by a catalogue that no longer has it
            elif key == "ior":
                node.inputs["IOR"].default_value = value
            else:
                setattr(material.prism, key, value)

    return mutate


def _light_stored(**values):
    def mutate():
        settings = bpy.data.lights["Bulb"].prism
        for key, value in values.items():
            if isinstance(value, str):
                setattr(settings, key, value)
            else:
                settings[key] = value  # past the property's limits, as a script or an old file can

    return mutate


def _nan_vertex():
    mesh = bpy.data.objects["Floor"].data
    mesh.vertices[0].co = (math.nan, 0.0, 0.0)


def _nan_light():
    bpy.data.objects["Bulb"].location = (math.nan, 0.0, 2.0)


def _only_camera():
    for name in ("Floor", "Bulb"):
        bpy.data.objects.remove(bpy.data.objects[name])


def _no_light():
    bpy.data.objects.remove(bpy.data.objects["Bulb"])
    bpy.context.scene.world = None


def _thin_lens_focus(distance_m):
    def mutate():
        data = bpy.context.scene.camera.data
        data.prism.lens_model = "THIN_LENS"
        data.dof.focus_distance = distance_m

    return mutate


def _focus_behind():
    data = bpy.context.scene.camera.data
    data.prism.lens_model = "THIN_LENS"
    target = bpy.data.objects.new("Behind", None)
    target.location = (0.0, -10.0, 3.0)
    bpy.context.scene.collection.objects.link(target)
    data.dof.focus_object = target


def _zero_area_light():
    data = bpy.data.lights.new("Panel", "AREA")
    data.energy, data.size = 50.0, 1.0
    obj = bpy.data.objects.new("Panel", data)
    obj.location = (0.0, 0.0, 2.0)
    obj.scale = (0.0, 1.0, 1.0)
    bpy.context.scene.collection.objects.link(obj)


def _set(path, value):
    """``_set("objects['Floor'].location", v)``: set a property of ``bpy.data`` by its path."""

    def mutate():
        owner, _, attribute = path.rpartition(".")
        setattr(eval(f"bpy.data.{owner}"), attribute, value)  # noqa: S307 - test-only paths written above

    return mutate


def _principled(**inputs):
    def mutate():
        _, node = _floor_material()
        for socket, value in inputs.items():
            node.inputs[socket.replace("_", " ")].default_value = value

    return mutate


def _prism_material(**values):
    def mutate():
        material, node = _floor_material()
        node.inputs["Metallic"].default_value = 1.0
        for key, value in values.items():
            material.prism[key] = value  # as a script or an old file can store it, past the UI's limits

    return mutate


def _thin_film_material():
    material, _ = _floor_material()
    material.prism.is_thin_film = True
    material.prism["film_ior"] = 0.5


def _far_vertex():
    bpy.data.objects["Floor"].data.vertices[0].co = (3.4e38, 0.0, 0.0)


def _world_strength_nan():
    world = bpy.data.worlds.new("Sky")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = math.nan
    bpy.context.scene.world = world


def _huge_resolution():
    render = bpy.context.scene.render
    render.resolution_x = render.resolution_y = 65536  # Blender's largest: ~4.3 billion pixels


CASES = {
    "no camera": (_no_camera, "Scene 'Scene' has no active camera"),
    "camera is not a camera": (_empty_as_camera, "The active camera 'Helper' is not a camera object"),
    "mirror ball panorama": (_panorama("MIRRORBALL"), "Camera 'Camera': the Mirrorball panorama is not supported"),
    "custom (OSL) camera": (
        _custom_camera, "Camera 'Camera' is a Custom (OSL script) camera, which Prism cannot run: Prism renders "
        "perspective, orthographic and panoramic"
    ),
    "real lens on an orthographic camera": (
        _real_lens_ortho, "Camera 'Camera' uses a real lens, which forms a perspective image: set Camera ▸ Lens"
    ),
    "environment texture without an image": (
        _world_texture("ShaderNodeTexEnvironment"), "World 'Sky', Environment Texture 'Environment Texture' has no image"
    ),
    "environment image file missing": (
        _world_texture("ShaderNodeTexEnvironment", image_path="gone.exr"),
        "World 'Sky', Environment Texture 'Environment Texture': image 'hdri' has no pixels",
    ),
    "Hosek-Wilkie sky": (
        _world_texture("ShaderNodeTexSky", sky_type="HOSEK_WILKIE"),
        "World 'Sky', Sky Texture 'Sky Texture': sky type Hosek Wilkie is not supported; set Sky Type to Nishita",
    ),
    "no lens chosen": (lambda tmp: _real_lens(None), "Camera 'Camera' uses a real lens but no prescription is chosen"),
    "missing lens file": (lambda tmp: _real_lens(Path(tmp) / "nowhere.lens"), "nowhere.lens' does not exist"),
    "invalid lens file": (_bad_toml_lens, "bad.lens: not valid TOML: Invalid value (at line 5, column 16)"),
    "unknown glass in lens": (_unknown_glass_in_lens, "glass.lens, line 7 (surface 1, 'glass'): unknown glass 'UNOBTAINIUM'"),
    "unknown glass": (_glass("CATALOGUE", raw_glass_name=12345), "Material 'Floor material' uses a catalogue glass that is not in"),
    "invalid Abbe glass": (_glass("ABBE", glass_nd=1.0), "Material 'Floor material': Glass n_d 1 is invalid"),
    "temperature out of range": (
        _light(color_source="BLACKBODY", temperature_k=500.0),
        "Light 'Bulb': blackbody temperature 500 K is outside 1000-40000 K",
    ),
    "negative light power": (_light(energy=-10.0), "Light 'Bulb' has Power -10"),
    "zero-size area light": (_zero_area_light, "Area light 'Panel' has zero size"),
    "NaN vertices": (_nan_vertex, "Object 'Floor' has vertices that are NaN or infinite"),
    "empty scene": (_only_camera, "Scene 'Scene' has no visible geometry"),
    "no light": (_no_light, "Scene 'Scene' has no light"),
    "thin lens focused at 0 m": (_thin_lens_focus(0.0), "Camera 'Camera' focuses at 0 m"),
    "focus object behind camera": (_focus_behind, "focuses on 'Behind', which is behind the camera"),
    "light at NaN location": (_nan_light, "Light 'Bulb' has a non-finite transform"),
    "camera scaled to zero": (
        _set("objects['Camera'].scale", (0.0, 0.0, 0.0)),
        "Camera 'Camera' is scaled to zero (world scale 0, 0, 0), so the direction it looks in is lost",
    ),
    "camera flattened on one axis": (_set("objects['Camera'].scale", (1.0, 1.0, 0.0)), "Camera 'Camera' is scaled to zero"),
    "camera at NaN location": (_set("objects['Camera'].location", (0.0, math.nan, 1.5)), "Camera 'Camera' has a non-finite"),
    "camera 3e38 m away": (
        _set("objects['Camera'].location", (3.0e38, -3.0, 1.5)),
        "Camera 'Camera' is 3e+38 m from the world origin; Prism renders scenes within 1e+15 m of it",
    ),
    "vertex at 3.4e38 m": (
        _far_vertex,
        "Object 'Floor' has vertices 3.4e+38 m from the world origin; Prism renders scenes within 1e+15 m of it",
    ),
    "object scaled to 1e30": (_set("objects['Floor'].scale", (1e30, 1e30, 1e30)), "Object 'Floor' has vertices 2e+30 m"),
    "light 3e38 m away": (
        _set("objects['Bulb'].location", (0.0, 3.0e38, 2.0)),
        "Light 'Bulb' is 3e+38 m from the world origin; Prism renders scenes within 1e+15 m of it",
    ),
    "Principled thin film IOR 0 on metal": (
        _principled(Metallic=1.0, Thin_Film_Thickness=300.0, Thin_Film_IOR=0.0),
        "Material 'Floor material': Principled BSDF ▸ Thin Film IOR is 0; a film's refractive index must be 1 or more",
    ),
    "coating IOR 0 stored past the UI's limit": (
        _prism_material(coating_thickness_nm=120.0, coating_ior=0.0),
        "Material 'Floor material': Material ▸ Prism ▸ Coating IOR is 0; a film's refractive index must be 1",
    ),
    "thin film IOR 0.5": (_thin_film_material, "Material 'Floor material': Material ▸ Prism ▸ Film IOR is 0.5"),
    "NaN roughness": (_principled(Roughness=math.nan), "Material 'Floor material': Principled BSDF ▸ Roughness is nan; enter a finite number."),
    "negative emission strength": (
        _principled(Emission_Strength=-2.0), "Material 'Floor material': Emission Strength -2 is negative."
    ),
    "monochromatic light at 900 nm stored past the UI's limit": (
        _light_stored(color_source="MONOCHROMATIC", wavelength_nm=900.0),
        "Light 'Bulb': wavelength 900 nm is outside 360-830 nm",
    ),
    "world strength NaN": (_world_strength_nan, "World 'Sky': background colour and strength must be finite"),
    "resolution larger than memory": (
        _huge_resolution, "Scene 'Scene': a 65536 x 65536 frame needs about 81.4 GB (80.0 GB for the image Blender"
    ),
}
_NEEDS_TMP = {"no lens chosen", "missing lens file", "invalid lens file", "unknown glass in lens",
              "real lens on an orthographic camera", "environment texture without an image",
              "environment image file missing", "Hosek-Wilkie sky"}


@pytest.mark.parametrize("case", list(CASES))
def test_error_is_reported_and_stops_the_render(prism_addon, fresh_scene, tmp_path, case, capsys, bad_input):
    requests = importlib.import_module(f"{prism_addon.__name__}.engine.render.request")
    export = importlib.import_module(f"{prism_addon.__name__}.engine.export")
    mutate, message = CASES[case]
    _base_scene()
    (mutate(tmp_path) if case in _NEEDS_TMP else mutate)()
    fresh_scene.render.engine = "PRISM"
    with pytest.raises(export.PrismInputError, match="") as exported:
        export.export_scene(bpy.context.evaluated_depsgraph_get())
    assert message in str(exported.value)
    with requests.render_request() as report, pytest.raises(RuntimeError) as raised:
        bpy.ops.render.render()
    if case == "no camera":  # Blender refuses before any engine runs; the batch script names the scene
        assert "no camera" in str(raised.value) and not report.started
    else:
        assert message in str(raised.value)
        assert report.error is not None and message in report.error
        assert "Traceback" not in report.error
    output = tmp_path / "x.png"
    status, line = run_batch(capsys, "--samples", 1, "--output", output)
    assert (status, line) == (1, f"Prism: error: {exported.value}")
    assert not output.exists()
    bad_input(case, status, line)
