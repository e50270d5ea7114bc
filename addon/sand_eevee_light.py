"""The light at the sand's normal in EEVEE, from white diffuse probes read by Shader to RGB: the
sun's light alone (shadow and all) and the ambient light (the sky's, the haze's, the ground's), and
from the ambient EEVEE's own sand under it (its colour plus what its sheen and specular add).
Node builders for the sand's EEVEE output (sand_eevee.py); twin: core.eevee_balance.sand_ambient.
"""

from ..core import eevee_balance as twin
from ..node_groups import helper as h

# The sun's light alone on a white Lambert surface here (shadow and all): EEVEE's lighting of a
# diffuse at the normal, less the ambient light there (below).
SUN_LIGHT_PREFIX = "Sandscape EEVEE Sun Light "
# The ambient light at the normal comes from four diffuse probes the lamp does not reach (two
# across the sun's azimuth, one square to it in its vertical plane, one straight away from it):
# EEVEE's world light is two spherical-harmonic bands, R0 + R1·N, which they give exactly.
PROBES = ("Across", "Across Back", "Square Up", "Away")
SUN_LIGHT = tuple(f"{SUN_LIGHT_PREFIX}{part}" for part in (
    "Geometry", "Sun", "N·L", "Across Axis", "Across Unit", "Square Up Axis", "Back", "Away Axis", "Lit",
    "Lit RGB", *PROBES, *(f"{probe} RGB" for probe in PROBES), "R0", "R0 Half", "Rb", "Rb Half", "Rm", "RL",
    "N·b", "N·m", "Ambient b", "Ambient m", "Ambient L", "Ambient 1", "Ambient 2", "Ambient", "Difference",
    "Held"))
AMBIENT = f"{SUN_LIGHT_PREFIX}Ambient"
SAND_AMBIENT_PREFIX = "Sandscape EEVEE Sand Ambient "
SAND_AMBIENT = tuple(f"{SAND_AMBIENT_PREFIX}{part}" for part in (
    "Geometry", "N·V", "N·V ≥ Limit", *(f"W {k}" for k in range(len(twin.SHEEN_AMBIENT) - 1)), "Colour + W",
    "Light"))


def sun_light(tree, normal, sun):
    """The sun's light on a white Lambert surface at the shading normal (`normal`, None: the
    geometry's), shadowed as EEVEE shadows it: Shader to RGB of a diffuse there, less the ambient
    light at that normal (AMBIENT: R0 + R1·N from the four unlit PROBES). Returns (the colour
    socket, the nodes made)."""
    made = []

    def named(node, part):
        node.name = f"{SUN_LIGHT_PREFIX}{part}"
        made.append(node)
        return node

    def vector(operation, a, b, part, label=None):
        return named(h.vector_math(tree, operation, a, b, label=label or part), part).outputs

    def probe(facing, part):
        diffuse = named(h.add_node(tree, "ShaderNodeBsdfDiffuse", label=f"White Diffuse ({part})",
                                   inputs={"Color": (1.0, 1.0, 1.0, 1.0)}), part)
        h.link(tree, facing, diffuse.inputs["Normal"])
        rgb = named(h.add_node(tree, "ShaderNodeShaderToRGB", label=f"{part} Light"), f"{part} RGB")
        h.link(tree, diffuse.outputs[0], rgb.inputs["Shader"])
        return rgb.outputs["Color"]

    if normal is None:
        normal = named(h.add_node(tree, "ShaderNodeNewGeometry"), "Geometry").outputs["Normal"]
    to_sun = named(h.vector_math(tree, "NORMALIZE", sun, label="Sun"), "Sun").outputs[0]
    cosine = named(h.vector_math(tree, "DOT_PRODUCT", normal, to_sun, label="N·L"), "N·L")
    # b: level, square to the sun (a hair off +x keeps it defined under a zenith sun); m = b × L.
    across = vector("CROSS_PRODUCT", to_sun, (1e-4, 0.0, 1.0), "Across Axis", "L × Up")
    b = vector("NORMALIZE", across[0], None, "Across Unit", "b")[0]
    m = vector("CROSS_PRODUCT", b, to_sun, "Square Up Axis", "m = b × L")[0]
    back = vector("SCALE", b, None, "Back", "−b")
    made[-1].inputs["Scale"].default_value = -1.0
    away = vector("SCALE", to_sun, None, "Away Axis", "−L")
    made[-1].inputs["Scale"].default_value = -1.0
    lit = probe(normal, "Lit")
    plus_b, minus_b, up_m, minus_l = (probe(facing, part) for facing, part in
                                      zip((b, back[0], m, away[0]), PROBES, strict=True))
    r0 = vector("ADD", plus_b, minus_b, "R0", "W(b) + W(−b)")
    r0 = vector("SCALE", r0[0], None, "R0 Half", "R0")
    made[-1].inputs["Scale"].default_value = 0.5
    rb = vector("SUBTRACT", plus_b, minus_b, "Rb", "W(b) − W(−b)")
    rb = vector("SCALE", rb[0], None, "Rb Half", "R1·b")
    made[-1].inputs["Scale"].default_value = 0.5
    rm = vector("SUBTRACT", up_m, r0[0], "Rm", "R1·m")
    rl = vector("SUBTRACT", r0[0], minus_l, "RL", "R1·L")
    nb = vector("DOT_PRODUCT", normal, b, "N·b")
    nm = vector("DOT_PRODUCT", normal, m, "N·m")
    parts = []
    for band, along, part in ((rb, nb["Value"], "Ambient b"), (rm, nm["Value"], "Ambient m"),
                              (rl, cosine.outputs["Value"], "Ambient L")):
        scaled = vector("SCALE", band[0], None, part)
        h.link(tree, along, made[-1].inputs["Scale"])
        parts.append(scaled[0])
    total = vector("ADD", r0[0], parts[0], "Ambient 1")
    total = vector("ADD", total[0], parts[1], "Ambient 2")
    ambient = vector("ADD", total[0], parts[2], "Ambient", "Ambient Light at N (R0 + R1·N)")
    difference = vector("SUBTRACT", lit, ambient[0], "Difference", "The Sun's Light")
    held = named(h.vector_math(tree, "MAXIMUM", difference[0], (0.0, 0.0, 0.0), label="≥ 0"), "Held")
    return held.outputs[0], made


def sand_ambient(tree, normal, ambient, colour):
    """EEVEE's own sand under the light less the sun's: the ambient light at the normal (`ambient`,
    a white Lambert surface's) times the sand's `colour` plus W(N·V), the sheen's and specular's
    share (core.eevee_balance.sheen_ambient). Returns (the colour socket, the nodes made)."""
    parts = iter(SAND_AMBIENT)
    made = []

    def named(node):
        node.name = next(parts)
        made.append(node)
        return node

    geometry = named(h.add_node(tree, "ShaderNodeNewGeometry"))
    if normal is None:
        normal = geometry.outputs["Normal"]
    facing = named(h.vector_math(tree, "DOT_PRODUCT", normal, geometry.outputs["Incoming"], label="N·V"))
    held = named(h.math(tree, "MAXIMUM", facing.outputs["Value"], twin.MIN_COSINE, label="N·V ≥ Limit"))
    v = held.outputs[0]
    # Horner: W(v) = ((c3 v + c2) v + c1) v + c0, per channel.
    *higher, lowest = twin.SHEEN_AMBIENT[::-1]
    total = higher[0]
    for coefficient in (*higher[1:], lowest):
        node = named(h.vector_math(tree, "MULTIPLY_ADD", total, v, label="W(N·V)", c=coefficient))
        total = node.outputs[0]
    tinted = named(h.vector_math(tree, "ADD", colour, total, label="Colour + W"))
    light = named(h.vector_math(tree, "MULTIPLY", ambient, tinted.outputs[0], label="EEVEE's Sand, Ambient"))
    return light.outputs[0], made
