"""Blender lights → ``tracer.scene.Light`` (power in Blender's watts, as Cycles)."""

import numpy as np

from ..tracer.scene import Light, SpectrumSpec

_AREA_SHAPES = {"SQUARE": "rectangle", "RECTANGLE": "rectangle", "DISK": "disk", "ELLIPSE": "disk"}


def light_spectrum(light_data) -> SpectrumSpec:
    """The light's colour as a spectrum specification."""
    return SpectrumSpec(kind="rgb", rgb=tuple(float(c) for c in light_data.color))


def _export_light(name: str, light_data, matrix_world) -> Light:
    matrix = np.array(matrix_world, dtype=np.float64)
    axes = matrix[:3, :3]
    scale = np.linalg.norm(axes, axis=0)
    safe_scale = np.where(scale > 0, scale, 1.0)
    axis_u, axis_v, axis_z = (axes / safe_scale).T
    light = Light(
        name=name,
        kind=light_data.type.lower(),
        position=matrix[:3, 3].copy(),
        direction=-axis_z,
        axis_u=axis_u,
        axis_v=axis_v,
        spectrum=light_spectrum(light_data),
    )
    if light_data.type == "SUN":
        light.irradiance_w_m2 = float(light_data.energy)
        light.sun_angle_rad = float(light_data.angle)
        return light
    light.power_w = float(light_data.energy)
    if light_data.type in {"POINT", "SPOT"}:
        light.radius_m = float(light_data.shadow_soft_size)
    if light_data.type == "SPOT":
        light.spot_size_rad = float(light_data.spot_size)
        light.spot_blend = float(light_data.spot_blend)
    if light_data.type == "AREA":
        light.area_shape = _AREA_SHAPES[light_data.shape]
        size_v = light_data.size if light_data.shape in {"SQUARE", "DISK"} else light_data.size_y
        light.size_u_m = float(light_data.size * scale[0])
        light.size_v_m = float(size_v * scale[1])
    return light


def export_lights(depsgraph) -> list[Light]:
    """Every visible light instance of the evaluated depsgraph."""
    lights = []
    for instance in depsgraph.object_instances:
        obj = instance.object
        if obj.type != "LIGHT" or obj.data.energy == 0:
            continue
        lights.append(_export_light(obj.name, obj.data, instance.matrix_world))
    return lights
