"""A board of emissive tiles, each showing one texture or colour node chain, seen straight on: what the
tiles show is the nodes' output itself (emission, no lighting), so Prism and Cycles must agree pixel by
pixel."""

from __future__ import annotations

from .node_scenes import black_world, camera, checker_image, emission_material, node, plane, socket


def _tile_materials():
    def checker(nodes, link):
        return node(nodes, "ShaderNodeTexChecker", Scale=3.0, Color1=(0.8, 0.2, 0.1), Color2=(0.1, 0.3, 0.7)
                    ).outputs["Color"]

    def noise_fbm(nodes, link):
        return node(nodes, "ShaderNodeTexNoise", Scale=4.0, Detail=3.0, Distortion=0.3).outputs["Color"]

    def noise_ridged(nodes, link):
        noise = node(nodes, "ShaderNodeTexNoise", Scale=3.0, Detail=2.5)
        noise.noise_type = "RIDGED_MULTIFRACTAL"
        ramp = nodes.new("ShaderNodeValToRGB")
        ramp.color_ramp.elements[0].color = (0.05, 0.1, 0.4, 1.0)
        ramp.color_ramp.elements[1].color = (0.9, 0.8, 0.3, 1.0)
        math = node(nodes, "ShaderNodeMath", Value_001=0.6)
        math.operation = "MULTIPLY"
        link(noise.outputs["Fac"], math.inputs[0])
        link(math.outputs[0], ramp.inputs["Fac"])
        return ramp.outputs["Color"]

    def voronoi_colour(nodes, link):
        return node(nodes, "ShaderNodeTexVoronoi", Scale=5.0).outputs["Color"]

    def voronoi_distance(nodes, link):
        voronoi = node(nodes, "ShaderNodeTexVoronoi", Scale=4.0, Smoothness=0.5, Detail=1.5)
        voronoi.feature, voronoi.distance = "SMOOTH_F1", "MANHATTAN"
        map_range = node(nodes, "ShaderNodeMapRange", From_Max=1.2, To_Min=0.1, To_Max=0.9)
        link(voronoi.outputs["Distance"], map_range.inputs["Value"])
        return map_range.outputs["Result"]

    def wave(nodes, link):
        w = node(nodes, "ShaderNodeTexWave", Scale=2.0, Distortion=3.0, Detail=2.0)
        w.wave_type, w.rings_direction = "RINGS", "SPHERICAL"
        return w.outputs["Color"]

    def brick(nodes, link):
        return node(nodes, "ShaderNodeTexBrick", Scale=3.0, Color1=(0.7, 0.3, 0.2), Color2=(0.5, 0.4, 0.3),
                    Mortar=(0.9, 0.9, 0.85)).outputs["Color"]

    def magic(nodes, link):
        m = node(nodes, "ShaderNodeTexMagic", Scale=2.0, Distortion=1.5)
        m.turbulence_depth = 3
        return m.outputs["Color"]

    def gradient_hsv(nodes, link):
        g = nodes.new("ShaderNodeTexGradient")
        g.gradient_type = "RADIAL"
        ramp = nodes.new("ShaderNodeValToRGB")
        ramp.color_ramp.elements[0].color = (1.0, 0.1, 0.1, 1.0)
        ramp.color_ramp.elements[1].color = (0.1, 0.2, 1.0, 1.0)
        hsv = node(nodes, "ShaderNodeHueSaturation", Hue=0.6, Saturation=0.8, Value=0.9)
        link(g.outputs["Fac"], ramp.inputs["Fac"])
        link(ramp.outputs["Color"], hsv.inputs["Color"])
        return hsv.outputs["Color"]

    def white_noise(nodes, link):
        coords = nodes.new("ShaderNodeTexCoord")
        mapping = node(nodes, "ShaderNodeMapping", Scale=(6.0, 6.0, 1.0))
        snap = nodes.new("ShaderNodeVectorMath")
        snap.operation = "FLOOR"
        noise = nodes.new("ShaderNodeTexWhiteNoise")
        link(coords.outputs["UV"], mapping.inputs["Vector"])
        link(mapping.outputs["Vector"], snap.inputs[0])
        link(snap.outputs["Vector"], noise.inputs["Vector"])
        return noise.outputs["Color"]

    def mix_overlay(nodes, link):
        mix = nodes.new("ShaderNodeMix")
        mix.data_type, mix.blend_type = "RGBA", "OVERLAY"
        socket(mix, "Factor_Float").default_value = 0.7
        noise = node(nodes, "ShaderNodeTexNoise", Scale=6.0)
        chk = node(nodes, "ShaderNodeTexChecker", Scale=2.0)
        link(chk.outputs["Color"], socket(mix, "A_Color"))
        link(noise.outputs["Color"], socket(mix, "B_Color"))
        invert = node(nodes, "ShaderNodeInvert", Fac=0.3)
        bright = node(nodes, "ShaderNodeBrightContrast", Bright=0.05, Contrast=0.2)
        link(socket(mix, "Result_Color", output=True), invert.inputs["Color"])
        link(invert.outputs["Color"], bright.inputs["Color"])
        return bright.outputs["Color"]

    def image_srgb(nodes, link):
        image = checker_image("srgb checker", 8, [(0.9, 0.5, 0.1), (0.2, 0.6, 0.3)], "sRGB")
        tex = nodes.new("ShaderNodeTexImage")
        tex.image, tex.interpolation = image, "Closest"
        return tex.outputs["Color"]

    def curves_of_separated_hsv(nodes, link):
        """Checker → Separate Color (HSV) → hue shifted by Math → Combine Color (HSV) → RGB Curves."""
        chk = node(nodes, "ShaderNodeTexChecker", Scale=4.0, Color1=(0.8, 0.3, 0.1), Color2=(0.2, 0.5, 0.3))
        separate = nodes.new("ShaderNodeSeparateColor")
        combine = nodes.new("ShaderNodeCombineColor")
        separate.mode = combine.mode = "HSV"
        shift = node(nodes, "ShaderNodeMath", Value_001=0.15)
        shift.operation = "ADD"
        link(chk.outputs["Color"], separate.inputs["Color"])
        link(separate.outputs[0], shift.inputs[0])
        link(shift.outputs[0], combine.inputs[0])
        link(separate.outputs[1], combine.inputs[1])
        link(separate.outputs[2], combine.inputs[2])
        curves = nodes.new("ShaderNodeRGBCurve")
        curve = curves.mapping.curves[3]  # the combined curve
        curve.points.new(0.4, 0.6)
        curves.mapping.update()
        link(combine.outputs["Color"], curves.inputs["Color"])
        return curves.outputs["Color"]

    def object_info(nodes, link):
        """The object's colour, scaled by its random number (Cycles' hash of the object's name)."""
        info = nodes.new("ShaderNodeObjectInfo")
        scale = nodes.new("ShaderNodeVectorMath")
        scale.operation = "SCALE"
        link(info.outputs["Color"], scale.inputs[0])
        link(info.outputs["Random"], socket(scale, "Scale"))
        return scale.outputs["Vector"]

    def colour_attribute(nodes, link):
        attribute = nodes.new("ShaderNodeAttribute")
        attribute.attribute_name = "Col"
        return attribute.outputs["Color"]

    def uv_map_xyz(nodes, link):
        """The UV map by name through Separate/Combine XYZ (U to red, V to blue) and a Mapping rotation (kept
        non-negative: Cycles emits negative colours, Prism's spectra cannot be negative)."""
        uv = nodes.new("ShaderNodeUVMap")
        uv.uv_map = "UVMap"
        mapping = node(nodes, "ShaderNodeMapping", Location=(0.3, 0.0, 0.0), Rotation=(0.0, 0.0, 0.3))
        separate = nodes.new("ShaderNodeSeparateXYZ")
        combine = node(nodes, "ShaderNodeCombineXYZ", Y=0.2)
        link(uv.outputs["UV"], mapping.inputs["Vector"])
        link(mapping.outputs["Vector"], separate.inputs["Vector"])
        link(separate.outputs["X"], combine.inputs["X"])
        link(separate.outputs["Y"], combine.inputs["Z"])
        return combine.outputs["Vector"]

    return [("checker", checker), ("noise fBM", noise_fbm), ("noise ridged + ramp", noise_ridged),
            ("voronoi colour", voronoi_colour), ("voronoi smooth distance", voronoi_distance), ("wave", wave),
            ("brick", brick), ("magic", magic), ("gradient + ramp + HSV", gradient_hsv),
            ("white noise", white_noise), ("mix overlay + invert + bright", mix_overlay),
            ("image sRGB", image_srgb), ("separate/combine HSV + RGB curves", curves_of_separated_hsv),
            ("object info colour x random", object_info), ("colour attribute", colour_attribute),
            ("UV map + mapping + separate/combine XYZ", uv_map_xyz)]


def _colour_attribute(obj, index):
    """A corner colour attribute 'Col': a different colour at each corner of the tile."""
    mesh = obj.data
    colours = mesh.color_attributes.new("Col", "FLOAT_COLOR", "CORNER")
    corners = [(0.9, 0.2, 0.1, 1.0), (0.1, 0.8, 0.2, 1.0), (0.2, 0.3, 0.9, 1.0), (0.9, 0.9, 0.2, 1.0)]
    for i, data in enumerate(colours.data):
        data.color = corners[(i + index) % 4]


def build_texture_board(resolution=(96, 72)):
    """Tiles in a 4 x 4 grid facing a camera straight on; returns (tile names, tile objects)."""
    black_world()
    names, tiles = [], []
    for index, (name, build) in enumerate(_tile_materials()):
        row, column = divmod(index, 4)
        obj = plane(f"tile {index}", 0.95, location=(column - 1.5, 0.0, 1.5 - row), rotation=(1.5707963, 0.0, 0.0),
                    mat=emission_material(name, build))
        obj.color = (0.3 + 0.05 * index, 0.9 - 0.04 * index, 0.5, 1.0)
        _colour_attribute(obj, index)
        names.append(name)
        tiles.append(obj)
    camera((0.0, -8.0, 0.0), (0.0, 0.0, 0.0), lens_mm=50.0, resolution=resolution)
    return names, tiles
