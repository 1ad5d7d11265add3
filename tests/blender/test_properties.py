"""Prism's PropertyGroups: names, defaults, descriptions, enum numbers, and .blend round trips."""

from __future__ import annotations

import math

import pytest

EXPECTED_DEFAULTS = {
    "scene": {
        "samples": 64,
        "samples_per_pass": 1,
        "max_bounces": 8,
        "transparent_max_bounces": 8,
        "seed": 0,
        "wavelength_mode": "CIE",
        "wavelengths_per_path": 4,
        "mean_r_nm": 600.0,
        "sigma_r_nm": 25.0,
        "mean_g_nm": 550.0,
        "sigma_g_nm": 25.0,
        "mean_b_nm": 450.0,
        "sigma_b_nm": 15.0,
        "use_mis": True,
        "russian_roulette_depth": 3,
        "threads": 0,
        "use_pass_variance": False,
        "use_pass_sample_count": False,
        "preview_samples": 1024,
        "preview_max_bounces": 4,
        "preview_pause": False,
        "pixel_filter": "BOX",
        "filter_width_px": 1.5,
        "light_tracing": "AUTO",
    },
    "overlay": {
        "enabled": False,
        "wavelength_source": "CHANNELS",
        "rays_per_fan": 9,
        "field_angle_deg": 0.0,
        "source_distance_m": 0.0,
        "show_outlines": True,
        "show_sensor": True,
        "show_spot_diagram": True,
    },
    "camera": {"lens_model": "PINHOLE", "lens_source": "BUNDLED", "lens_file": ""},
    "light": {"color_source": "RGB", "temperature_k": 6500.0, "wavelength_nm": 550.0, "line_width_nm": 10.0},
    "material": {
        "glass_source": "PRINCIPLED_IOR",
        "glass_name": "N-BK7",
        "glass_nd": 1.5168,
        "glass_vd": 64.17,
        "conductor": "FROM_COLOR",
        "coating_thickness_nm": 0.0,
        "coating_ior": 1.38,
        "is_thin_film": False,
        "film_thickness_nm": 500.0,
        "film_ior": 1.33,
    },
}

ENUM_NUMBERS = {
    ("scene", "wavelength_mode"): {"CIE": 0, "GAUSSIAN_RGB": 1},
    ("scene", "pixel_filter"): {"BOX": 0, "GAUSSIAN": 1},
    ("scene", "light_tracing"): {"AUTO": 0, "OFF": 1, "ON": 2},
    ("overlay", "wavelength_source"): {"CHANNELS": 0, "CUSTOM": 1},
    ("camera", "lens_model"): {"PINHOLE": 0, "THIN_LENS": 1, "REAL_LENS": 2},
    ("camera", "lens_source"): {"BUNDLED": 0, "FILE": 1},
    ("light", "color_source"): {"RGB": 0, "BLACKBODY": 1, "MONOCHROMATIC": 2, "ILLUMINANT": 3, "FILE": 4},
    ("material", "glass_source"): {"PRINCIPLED_IOR": 0, "CATALOGUE": 1, "ABBE": 2},
    ("material", "emission_source"): {"COLOR": 0, "BLACKBODY": 1, "MONOCHROMATIC": 2, "ILLUMINANT": 3, "FILE": 4},
    ("material", "reflectance_source"): {"COLOR": 0, "MEASURED": 1, "FILE": 2},
    ("material", "conductor"): {"FROM_COLOR": 0, "AU": 1, "AG": 2, "CU": 3, "AL": 4},
}


@pytest.fixture
def groups(fresh_scene):
    """The five PropertyGroups of a fresh scene, camera, light and material."""
    import bpy

    camera = bpy.data.cameras.new("Cam")
    light = bpy.data.lights.new("Lamp", "SPOT")
    material = bpy.data.materials.new("Mat")
    return {
        "scene": fresh_scene.prism,
        "overlay": fresh_scene.prism.lens_overlay,
        "camera": camera.prism,
        "light": light.prism,
        "material": material.prism,
    }


def _user_properties(group):
    return [p for p in group.bl_rna.properties if p.identifier not in {"rna_type", "name"}]


def _items_callback(group, identifier):
    annotation = type(group).__annotations__[identifier]
    return annotation.keywords["items"]


def test_defaults_are_as_documented(groups):
    for kind, expected in EXPECTED_DEFAULTS.items():
        group = groups[kind]
        for name, value in expected.items():
            actual = getattr(group, name)
            if isinstance(value, float):
                assert actual == pytest.approx(value, rel=1e-6), (kind, name)
            else:
                assert actual == value, (kind, name)


def test_every_property_has_a_description_and_enums_explicit_numbers(groups):
    for kind, group in groups.items():
        for prop in _user_properties(group):
            assert prop.description.strip(), f"{kind}.{prop.identifier} has no description"
            if prop.type == "ENUM" and not prop.is_enum_flag:
                items = _items_callback(group, prop.identifier)
                if callable(items):
                    items = items(group, None)
                assert all(len(item) >= 4 for item in items), f"{kind}.{prop.identifier} items lack numbers"
                numbers = [item[3] for item in items]
                assert len(set(numbers)) == len(numbers), f"{kind}.{prop.identifier} repeats a number"
    for (kind, name), expected in ENUM_NUMBERS.items():
        items = _items_callback(groups[kind], name)
        assert {item[0]: item[3] for item in items} == expected


def test_dynamic_enums_list_catalogue_glasses_and_bundled_lenses(prism_addon, groups):
    material_module = prism_addon.engine.properties.material
    camera_module = prism_addon.engine.properties.camera
    glass_items = _items_callback(groups["material"], "glass_name")(groups["material"], None)
    names = {item[0] for item in glass_items}
    assert {"N-BK7", "SF11"} <= names
    # Numbers depend on the name only, so a saved choice survives a longer catalogue.
    common = prism_addon.engine.properties._common
    assert all(number == common.stable_enum_number(ident, set()) for ident, _, _, number in glass_items)
    # The same list object is returned while nothing changed (Blender only borrows the strings).
    assert _items_callback(groups["material"], "glass_name")(groups["material"], None) is glass_items
    lens_names = {entry[0] for entry in camera_module.bundled_lens_entries()}
    on_disk = {p.stem for p in camera_module.LENS_DIRECTORY.glob("*.lens")}
    assert on_disk <= lens_names
    assert material_module.glass_catalogue_names() == sorted(names)


def _new_value(group, prop):
    """A valid value different from the current one."""
    name = prop.identifier
    current = getattr(group, name)
    if prop.type == "BOOLEAN":
        return not current
    if prop.type == "INT":
        return current + 1 if current + 1 <= prop.hard_max else current - 1
    if prop.type == "FLOAT":
        step = 1.25 if prop.hard_max - prop.hard_min > 3 else 0.25
        return current + step if current + step <= prop.hard_max else current - step
    if prop.type == "ENUM":
        items = _items_callback(group, name)
        if callable(items):
            items = items(group, None)
        others = [item[0] for item in items if item[0] != current]
        return others[-1] if others else None
    if prop.type == "STRING":
        if name == "custom_wavelengths_nm":
            return "420, 520.5, 640"
        if prop.subtype == "FILE_PATH":
            return "//lenses/test_lens.lens"
        return current + "x"
    raise AssertionError(f"no test value for {prop.type} {name}")


def _set_all(group, written, path):
    for prop in _user_properties(group):
        if prop.type == "POINTER":
            _set_all(getattr(group, prop.identifier), written, f"{path}.{prop.identifier}")
            continue
        if prop.is_readonly:
            continue
        value = _new_value(group, prop)
        if value is None:  # a dynamic enum with a single item: nothing else to choose
            continue
        setattr(group, prop.identifier, value)
        assert getattr(group, prop.identifier) != EXPECTED_DEFAULTS.get(path, {}).get(prop.identifier, object())
        written[f"{path}.{prop.identifier}"] = getattr(group, prop.identifier)


def _read(root, dotted):
    value = root
    for part in dotted.split("."):
        value = getattr(value, part)
    return value


def test_every_property_round_trips_through_a_blend_file(groups, tmp_path):
    import bpy

    written = {}
    owners = {
        "scene": bpy.context.scene,
        "camera": bpy.data.cameras["Cam"],
        "light": bpy.data.lights["Lamp"],
        "material": bpy.data.materials["Mat"],
    }
    for kind in ("scene", "camera", "light", "material"):
        _set_all(groups[kind], written, kind)
    for data in (owners["camera"], owners["light"], owners["material"]):
        data.use_fake_user = True
    assert len(written) >= 47
    path = tmp_path / "roundtrip.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path))
    bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    assert bpy.context.scene.prism.samples == 64  # really reset before loading
    bpy.ops.wm.open_mainfile(filepath=str(path))
    reloaded = {
        "scene": bpy.context.scene.prism,
        "camera": bpy.data.cameras["Cam"].prism,
        "light": bpy.data.lights["Lamp"].prism,
        "material": bpy.data.materials["Mat"].prism,
    }
    for dotted, value in written.items():
        kind, rest = dotted.split(".", 1)
        actual = _read(reloaded[kind], rest)
        if isinstance(value, float):
            assert math.isclose(actual, value, rel_tol=1e-6), dotted
        else:
            assert actual == value, dotted


def test_custom_wavelengths_are_validated(prism_addon, groups):
    lens_overlay = prism_addon.engine.properties.lens_overlay
    errors = prism_addon.engine.tracer.errors
    assert lens_overlay.parse_wavelengths_nm("450, 550 650nm;700") == (450.0, 550.0, 650.0, 700.0)
    for bad, words in (("", "at least one"), ("450, green", "'green'"), ("300", "outside the visible range")):
        with pytest.raises(errors.PrismInputError, match=words):
            lens_overlay.parse_wavelengths_nm(bad)
    overlay = groups["overlay"]
    assert overlay.custom_wavelengths_error == ""
    assert overlay.wavelengths_nm(groups["scene"]) == (600.0, 550.0, 450.0)
    overlay.wavelength_source = "CUSTOM"
    overlay.custom_wavelengths_nm = "486.1, 656.3"
    assert overlay.wavelengths_nm(groups["scene"]) == pytest.approx((486.1, 656.3))
    overlay.custom_wavelengths_nm = "486, 9000"
    assert "9000 nm is outside" in overlay.custom_wavelengths_error
    with pytest.raises(errors.PrismInputError):
        overlay.wavelengths_nm(groups["scene"])


def test_light_swatch_follows_the_spectrum(groups):
    light = groups["light"]
    light.id_data.color = (0.2, 0.4, 0.6)
    assert tuple(light.preview_color) == pytest.approx((0.2, 0.4, 0.6))
    light.color_source = "BLACKBODY"
    light.temperature_k = 2000.0
    warm = tuple(light.preview_color)
    light.temperature_k = 12000.0
    cool = tuple(light.preview_color)
    assert warm[0] == pytest.approx(1.0) and warm[2] < 0.2  # candle-like: red, little blue
    assert cool[2] == pytest.approx(1.0) and cool[0] < 0.8  # blue sky-like
    light.color_source = "MONOCHROMATIC"
    for wavelength_nm, brightest in ((450.0, 2), (530.0, 1), (640.0, 0)):
        light.wavelength_nm = wavelength_nm
        assert max(range(3), key=lambda c: light.preview_color[c]) == brightest


def test_unregister_removes_the_pointer_properties(prism_addon):
    import bpy

    properties = prism_addon.engine.properties
    ui = prism_addon.ui
    ui.unregister()
    properties.unregister()
    try:
        for id_type in (bpy.types.Scene, bpy.types.Camera, bpy.types.Light, bpy.types.Material):
            assert not hasattr(id_type, "prism")
    finally:
        properties.register()
        ui.register()
    assert bpy.context.scene.prism.lens_overlay.rays_per_fan == 9


def _file_path_settings(group, path):
    for prop in _user_properties(group):
        if prop.type == "POINTER":
            yield from _file_path_settings(getattr(group, prop.identifier), f"{path}.{prop.identifier}")
        elif prop.type == "STRING" and prop.subtype == "FILE_PATH":
            yield group, prop.identifier, f"{path}.{prop.identifier}"


def test_every_file_path_setting_takes_blend_relative_paths_without_a_warning(groups):
    import warnings

    settings = [s for kind, group in groups.items() for s in _file_path_settings(group, kind)]
    assert len(settings) >= 4, [path for _, _, path in settings]
    for group, identifier, path in settings:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            setattr(group, identifier, "//textures/file.exr")
        assert getattr(group, identifier) == "//textures/file.exr", path
        assert not [str(w.message) for w in caught], path
