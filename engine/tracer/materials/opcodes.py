"""The instruction set of material programs (``materials.program``): numbers shared by the compiler
(``engine/export/nodes``) and the interpreter.

An instruction is a row of ``INSTRUCTION`` int32: ``[op, mode, dst, a, b, c, d, e, f, g]``. ``dst`` and
the operands ``a``-``g`` are register indices (a vector or colour occupies three consecutive registers,
a colour with alpha four); ``mode`` picks a variant (a Math operation, a blend mode, a texture's
dimensions, ...). Where an op needs an integer that is not a register (a texture id, a UV map slot, the
first constant of a colour ramp) it is named in the op's comment. Modes are indices into the lists below,
which hold Blender's own identifiers, so the compiler maps ``node.operation`` with ``.index()``.
"""

from __future__ import annotations

INSTRUCTION = 10
OP, MODE, DST, A, B, C, D, E, F, G = range(INSTRUCTION)

# Hit inputs (write dst).
UV = 1  # a = UV slot → (u, v, 0)
COLOR_ATTRIBUTE = 2  # a = colour slot → (r, g, b, alpha)
POSITION = 3  # world position (m)
NORMAL = 4  # shading normal, facing the incoming ray
TRUE_NORMAL = 5  # geometric normal, facing the incoming ray
INCOMING = 6  # unit vector towards where the ray came from
GENERATED = 7  # object texture-space coordinates (0-1 over the mesh's bounds)
OBJECT_COORDINATES = 8  # object-space position
OBJECT_INFO = 9  # mode: OBJECT_INFO_FIELDS → (location xyz) or a scalar
BACKFACING = 10  # 1 if the ray arrived on the back of the surface
TANGENT = 11  # a = UV slot → unit tangent (xyz) and bitangent sign (+3), world space
PARAMETRIC = 12  # barycentric (1 - u - v, u, 0)
POINT_INFO = 13  # mode: POINT_INFO_FIELDS → the point's centre (world, m), radius (m) or random; 0 off points
HAIR_INFO = 14  # mode: HAIR_INFO_FIELDS → Cycles' Hair Info outputs (``hit_inputs.hair_info``); 0 off curves
LIGHT_PATH = 15  # mode: ``light_path.OUTPUTS`` index → what the ray that reached the point was (written by the caller)
AMBIENT_OCCLUSION = 16  # mode: samples × AO_SAMPLES + AO_* flags; dst (ao, colour c × ao) within distance a
#                         about normal b (-1: the shading normal); traces rays (``shader_rays``)
BEVEL = 17  # mode = samples; dst = the normal averaged over radius a, then moved as normal b is (-1: none)

# Arithmetic.
COPY = 20  # dst[0:mode] = a[0:mode]
MATH = 21  # mode: MATH_OPERATIONS; dst = op(a, b, c)
VECTOR_MATH = 22  # mode: VECTOR_MATH_OPERATIONS; dst (vector, or scalar) = op(a, b, c vectors; d scalar)
MIX_FLOAT = 23  # dst = mix(b, c, a) ; mode 1 clamps the factor
MIX_VECTOR = 24  # dst = mix(b, c, a) (a scalar factor; mode 1: a is a vector factor); e = 1 clamps
MIX_COLOR = 25  # mode: BLEND_MODES; dst = blend(fac a, b, c); d = 1 clamps the factor, e = 1 the result
MAP_RANGE = 26  # mode: MAP_RANGE_MODES; dst = map(value a, from b..c, to d..e, steps f); g = 1 clamps
CLAMP = 27  # mode 0 min-max, 1 range; dst = clamp(a, b, c)
RGB_TO_BW = 28  # dst = luminance of colour a
SEPARATE_COLOR = 29  # mode: 0 RGB, 1 HSV, 2 HSL; dst (3 scalars) from colour a
COMBINE_COLOR = 30  # mode: 0 RGB, 1 HSV, 2 HSL; dst colour from scalars a, b, c
HUE_SATURATION = 31  # dst = hsv adjust(hue a, saturation b, value c, fac d, colour e)
INVERT = 32  # dst = mix(colour b, 1 - colour b, fac a)
BRIGHT_CONTRAST = 33  # dst = colour a with bright b, contrast c
GAMMA = 34  # dst = colour a ^ gamma b
COLOR_RAMP = 35  # mode: RAMP_INTERPOLATIONS; dst (rgba) = ramp(fac a); b = first constant register, c = stops
CURVES = 36  # mode 0 RGB curves, 1 vector curves, 2 float curve; dst = curves(fac a, colour b); c = table, d = size
MAPPING = 38  # mode: MAPPING_TYPES; dst = map(vector a, location b, rotation c, scale d)
VECTOR_ROTATE = 39  # mode: ROTATE_TYPES; dst = rotate(vector a, center b, axis c, angle d, rotation e); f = 1 inverts
COMBINE_XYZ = 41  # dst = (a, b, c)
FLOAT_TO_COLOR = 42  # dst = (a, a, a)
VECTOR_TO_FLOAT = 43  # dst = (x + y + z) / 3 of a

# Shading inputs that need the view direction or the normal.
FRESNEL = 50  # dst = dielectric Fresnel of IOR a for normal b
LAYER_WEIGHT = 51  # dst = (fresnel, facing) of blend a for normal b
NORMAL_MAP = 52  # mode: NORMAL_MAP_SPACES; dst = normal from colour b, strength a; c = UV slot
BUMP = 53  # dst = normal bumped by height a (and its offsets b, c along the tangents); d strength, e distance,
#            f normal; mode 1 inverts
DISPLACEMENT_NORMAL = 54  # reserved

# Textures.
IMAGE = 60  # b = texture id; dst (rgba) = image at vector a
NOISE = 61  # mode: dimensions + 4 × NOISE_TYPES; dst (fac, colour xyz) at vector a, w b, scale c, detail d,
#             roughness e, lacunarity f, distortion g; extras in the next instruction (offset, gain, normalize)
VORONOI = 62  # see ``textures.voronoi``: two instructions
CHECKER = 63  # dst (colour, fac) = checker(vector a, colour1 b, colour2 c, scale d)
GRADIENT = 64  # mode: GRADIENT_TYPES; dst (colour, fac) at vector a
WAVE = 65  # see ``textures.patterns``: two instructions
BRICK = 66  # see ``textures.patterns``: two instructions
MAGIC = 67  # mode = depth; dst (colour, fac) at vector a, scale b, distortion c
WHITE_NOISE = 68  # mode = dimensions; dst (value, colour) at vector a, w b
EXTRA = 69  # operands of the previous instruction that did not fit in one row

# Closure support: layered weights (Principled) and binding results to the closure rows.
LAYER_ALBEDO = 80  # mode: LAYER_ALBEDO_KINDS; dst = albedo factor s(roughness a, cos b, ior c)
BIND = 81  # rows[a, b] = register c (a scalar parameter of closure a, column b); mode 1 multiplies
BIND_RGB = 82  # rows[a, b] = colour at register c (a spectral parameter: resolved per hit)
LAYER_DARKENING = 83  # dst = factor on the albedo of a Multiscatter GGX dielectric layer: roughness a, cos b,
#                       ior c, normal-incidence reflectance d (``layering.dielectric_darkening``)
SHEEN_ALBEDO = 84  # dst = fitted directional albedo of the microfiber sheen: roughness a, cos b (``bsdf.sheen``)
VALID_REFLECTION = 85  # dst = normal a raised so that the view's reflection leaves above the surface (Cycles' Bump
#                        Map Correction, ``closure_normals.valid_specular_normal``): a Principled coat's normal

MATH_OPERATIONS = [
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "POWER", "LOGARITHM", "SQRT", "INVERSE_SQRT",
    "ABSOLUTE", "EXPONENT", "MINIMUM", "MAXIMUM", "LESS_THAN", "GREATER_THAN", "SIGN", "COMPARE", "SMOOTH_MIN",
    "SMOOTH_MAX", "ROUND", "FLOOR", "CEIL", "TRUNC", "FRACT", "MODULO", "FLOORED_MODULO", "WRAP", "SNAP",
    "PINGPONG", "SINE", "COSINE", "TANGENT", "ARCSINE", "ARCCOSINE", "ARCTANGENT", "ARCTAN2", "SINH", "COSH",
    "TANH", "RADIANS", "DEGREES",
]
VECTOR_MATH_OPERATIONS = [
    "ADD", "SUBTRACT", "MULTIPLY", "DIVIDE", "MULTIPLY_ADD", "CROSS_PRODUCT", "PROJECT", "REFLECT", "REFRACT",
    "FACEFORWARD", "DOT_PRODUCT", "DISTANCE", "LENGTH", "SCALE", "NORMALIZE", "ABSOLUTE", "POWER", "SIGN",
    "MINIMUM", "MAXIMUM", "FLOOR", "CEIL", "FRACTION", "MODULO", "WRAP", "SNAP", "SINE", "COSINE", "TANGENT",
]
#: Vector Math operations whose result is a scalar.
VECTOR_MATH_SCALAR = {"DOT_PRODUCT", "DISTANCE", "LENGTH"}
BLEND_MODES = [
    "MIX", "DARKEN", "MULTIPLY", "BURN", "LIGHTEN", "SCREEN", "DODGE", "ADD", "OVERLAY", "SOFT_LIGHT",
    "LINEAR_LIGHT", "DIFFERENCE", "EXCLUSION", "SUBTRACT", "DIVIDE", "HUE", "SATURATION", "COLOR", "VALUE",
]
MAP_RANGE_MODES = ["LINEAR", "STEPPED", "SMOOTHSTEP", "SMOOTHERSTEP"]
RAMP_INTERPOLATIONS = ["LINEAR", "CONSTANT", "EASE", "CARDINAL", "B_SPLINE"]
MAPPING_TYPES = ["POINT", "TEXTURE", "VECTOR", "NORMAL"]
ROTATE_TYPES = ["AXIS_ANGLE", "X_AXIS", "Y_AXIS", "Z_AXIS", "EULER_XYZ"]
NORMAL_MAP_SPACES = ["TANGENT", "OBJECT", "WORLD", "BLENDER_OBJECT", "BLENDER_WORLD"]
GRADIENT_TYPES = ["LINEAR", "QUADRATIC", "EASING", "DIAGONAL", "SPHERICAL", "QUADRATIC_SPHERE", "RADIAL"]
NOISE_TYPES = ["MULTIFRACTAL", "RIDGED_MULTIFRACTAL", "HYBRID_MULTIFRACTAL", "FBM", "HETERO_TERRAIN"]
VORONOI_FEATURES = ["F1", "F2", "SMOOTH_F1", "DISTANCE_TO_EDGE", "N_SPHERE_RADIUS"]
VORONOI_METRICS = ["EUCLIDEAN", "MANHATTAN", "CHEBYCHEV", "MINKOWSKI"]
WAVE_TYPES = ["BANDS", "RINGS"]
WAVE_BANDS_DIRECTIONS = ["X", "Y", "Z", "DIAGONAL"]
WAVE_RINGS_DIRECTIONS = ["X", "Y", "Z", "SPHERICAL"]
WAVE_PROFILES = ["SIN", "SAW", "TRI"]
OBJECT_INFO_FIELDS = ["LOCATION", "COLOR", "ALPHA", "OBJECT_INDEX", "MATERIAL_INDEX", "RANDOM"]
POINT_INFO_FIELDS = ["POSITION", "RADIUS", "RANDOM"]
HAIR_INFO_FIELDS = ["IS_STRAND", "INTERCEPT", "LENGTH", "THICKNESS", "TANGENT_NORMAL", "RANDOM"]
#: AMBIENT_OCCLUSION's mode: the node's Only Local and Inside bits, plus its samples × AO_SAMPLES.
AO_ONLY_LOCAL, AO_INSIDE, AO_SAMPLES = 1, 2, 4
#: LAYER_ALBEDO: the directional albedo factor s of a GGX reflection lobe whose Fresnel F(cos) is
#: remapped from [F0, 1] to [f0, f90]: albedo ≈ mix(f0, f90, s) (``materials.layering``).
LAYER_ALBEDO_KINDS = ["DIELECTRIC", "SCHLICK", "SHEEN"]
