"""Sandscape Journey Sand: the sand model of Journey (seed 004, after John Edwards' GDC talk),
as Cycles closures, each term a framed part to see and tune:

- Sand Normal: the normal nudged per grain (Sandscape Sand Normal), which every term uses.
- Diffuse Contrast: Journey's saturate(4 N'.L), N' the normal with its vertical component
  scaled by 0.3 and not renormalised. On the unit N' that is min(1, 4 |N'| cos angle), a
  function of the angle to one normal, which Toon BSDFs light: two of them, their size and
  smooth driven per point, ramp it in two straight pieces. Each Toon's colour is scaled by
  1 - cos of its cone, which cancels the pdf Cycles multiplies its light by. The material turns
  bump-map correction off for this look: its softening of a closure whose normal is not the
  surface's darkened the slopes the contrast keeps lit.
- Rim: light reflected at grazing angles, a glossy lobe weighted by (1 - N.V)^power, with its
  own colour and strength.
- Ocean Specular: a Blinn-Phong lobe of exponent p, as Beckmann roughness (2 / (p + 2))^1/4
  (the two lobes' widths agree within 7 % at p = 16 and 2 % above 64).
- Glitter: the lit glints (Sandscape Lit Glints), added by the material on top.
- EEVEE Shader: EEVEE lights a Toon BSDF as a diffuse, so the contrast there is one Diffuse BSDF
  on the unit squashed normal whose colour carries min(1/c, k) / 2, c = N'.L on that normal:
  Lambert's c / pi times it is the seed's saturate(4 N'.L) / 2 pi exactly, the Cycles output's
  scale. It needs the sun's direction (Sun Direction, driven by the material); with none the
  factor is k / 2, the contrast of a light straight along the squashed normal.

The talk adds the diffuse term to saturate(max(rim, ocean)). Closures cannot take a maximum of
each other's light, so they are added: the rim lives at grazing angles and the ocean specular
around the mirror direction, and where both are small their sum stays near the maximum.
Twins: core.sand.journey_diffuse, journey_eevee_factor, ocean_roughness, rim, sand_normal.
"""

from ..core import sand
from . import helper as h
from . import sand_normal

NAME = "Sandscape Journey Sand"
VERSION = 3
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Journey's sand (seed 004): diffuse contrast, sand normal, rim, ocean specular as Cycles "
               "closures; add the lit glints for the glitter")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Color", "NodeSocketColor", "Albedo of the sand", sand.SAND_COLOR)
    sand_normal.add_grain_inputs(tree, "Sand normal: how far the grains turn the normal")
    h.add_input(tree, "Diffuse Size", "NodeSocketFloat", "Diffuse contrast: fully lit where the squashed "
                "N.L reaches the cosine of this share of a right angle (0.839: 0.25, Journey's 4 N.L)",
                sand.TOON_SIZE, 0.0, 1.0, "FACTOR")
    unused = h.add_input(tree, "Diffuse Smooth", "NodeSocketFloat", "Not used since version 2 (the "
                         "contrast fades linearly in N.L, as in Journey); kept so materials linking it "
                         "still load", 0.161, 0.0, 1.0, "FACTOR")
    unused.hide_value = True
    h.add_input(tree, "Squash", "NodeSocketFloat", "Diffuse contrast: factor on the normal's vertical "
                "component (Journey: 0.3)", sand.SQUASH, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Rim Color", "NodeSocketColor", "Rim: colour of the grazing reflection",
                (1.0, 0.92, 0.8, 1.0))
    h.add_input(tree, "Rim Power", "NodeSocketFloat", "Rim: exponent on 1 - N.V; higher keeps it to the "
                "silhouettes", 4.0, 0.0, None)
    h.add_input(tree, "Rim Strength", "NodeSocketFloat", "Rim: scale of the grazing reflection", 0.5, 0.0,
                None)
    h.add_input(tree, "Ocean Color", "NodeSocketColor", "Ocean specular: colour of the highlight",
                (1.0, 0.95, 0.9, 1.0))
    h.add_input(tree, "Ocean Exponent", "NodeSocketFloat", "Ocean specular: Blinn-Phong exponent (higher, "
                "narrower)", 64.0, 0.0, None)
    h.add_input(tree, "Ocean Strength", "NodeSocketFloat", "Ocean specular: scale of the highlight", 0.4,
                0.0, None)
    h.add_input(tree, "Sun Direction", "NodeSocketVector", "EEVEE Shader only: towards the sun (the "
                "material drives it from the scene's sun lamp; zero: no sun)", (0.0, 0.0, 0.0))
    h.add_output(tree, "Shader", "NodeSocketShader", "Diffuse contrast + rim + ocean specular")
    h.add_output(tree, "EEVEE Shader", "NodeSocketShader", "The same for EEVEE, which lights Toon BSDFs "
                 "as diffuse: the contrast through one Diffuse BSDF")
    h.add_output(tree, "Normal", "NodeSocketVector", "The sand normal every term uses")
    h.add_output(tree, "Rim Weight", "NodeSocketFloat", "(1 - N.V)^power x strength, for inspection")
    h.add_output(tree, "Ocean Roughness", "NodeSocketFloat", "The Beckmann roughness of the ocean lobe")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs

    grains = sand_normal.grain_node(tree, inputs)
    normal = grains.outputs["Normal"]

    contrast_nodes, contrast, squashed = _diffuse_contrast(tree, inputs, normal)
    eevee_nodes, eevee_contrast = _eevee_contrast(tree, inputs, squashed)

    facing = h.add_node(tree, "ShaderNodeLayerWeight", inputs={"Blend": 0.5})
    h.link(tree, normal, facing.inputs["Normal"])
    power = h.math(tree, "MAXIMUM", inputs["Rim Power"], 0.0, label="Power ≥ 0")
    falloff = h.math(tree, "POWER", facing.outputs["Facing"], power.outputs[0], label="(1 − N·V)^Power")
    weight = h.math(tree, "MULTIPLY", falloff.outputs[0], inputs["Rim Strength"], label="Rim Weight")
    tint = h.vector_math(tree, "SCALE", inputs["Rim Color"], label="Rim Colour × Weight")
    h.link(tree, weight.outputs[0], tint.inputs["Scale"])
    rim = h.add_node(tree, "ShaderNodeBsdfGlossy", label="Rim", distribution="GGX", inputs={"Roughness": 0.5})
    h.link(tree, tint.outputs[0], rim.inputs["Color"])
    h.link(tree, normal, rim.inputs["Normal"])

    plus_two = h.math(tree, "ADD", inputs["Ocean Exponent"], 2.0, label="p + 2")
    ratio = h.math(tree, "DIVIDE", 2.0, plus_two.outputs[0], label="2 / (p + 2)")
    roughness = h.math(tree, "POWER", ratio.outputs[0], 0.25, label="Beckmann Roughness")
    shine = h.vector_math(tree, "SCALE", inputs["Ocean Color"], label="Ocean Colour × Strength")
    h.link(tree, inputs["Ocean Strength"], shine.inputs["Scale"])
    ocean = h.add_node(tree, "ShaderNodeBsdfGlossy", label="Ocean Specular", distribution="BECKMANN")
    h.link(tree, shine.outputs[0], ocean.inputs["Color"])
    h.link(tree, roughness.outputs[0], ocean.inputs["Roughness"])
    h.link(tree, normal, ocean.inputs["Normal"])

    lit, total = _summed(tree, contrast, rim.outputs[0], ocean.outputs[0], "")
    h.link(tree, total.outputs[0], group_out.inputs["Shader"])
    eevee_lit, eevee_total = _summed(tree, eevee_contrast, rim.outputs[0], ocean.outputs[0], "EEVEE: ")
    h.link(tree, eevee_total.outputs[0], group_out.inputs["EEVEE Shader"])
    h.link(tree, normal, group_out.inputs["Normal"])
    h.link(tree, weight.outputs[0], group_out.inputs["Rim Weight"])
    h.link(tree, roughness.outputs[0], group_out.inputs["Ocean Roughness"])
    h.frame(tree, "Sand Normal", (grains,))
    h.frame(tree, "Diffuse Contrast", contrast_nodes)
    h.frame(tree, "Rim", (facing, power, falloff, weight, tint, rim))
    h.frame(tree, "Ocean Specular", (plus_two, ratio, roughness, shine, ocean))
    h.frame(tree, "Combined (added: closures take no maximum)", (lit, total))
    h.frame(tree, "Diffuse Contrast for EEVEE", eevee_nodes)
    h.frame(tree, "EEVEE Combined", (eevee_lit, eevee_total))
    h.arrange(tree)


def _summed(tree, diffuse, rim, ocean, prefix):
    """diffuse + rim + ocean specular, as two Add Shader nodes (returned)."""
    lit = h.add_node(tree, "ShaderNodeAddShader", label=f"{prefix}Diffuse + Rim")
    h.link(tree, diffuse, lit.inputs[0])
    h.link(tree, rim, lit.inputs[1])
    total = h.add_node(tree, "ShaderNodeAddShader", label=f"{prefix}+ Ocean Specular")
    h.link(tree, lit.outputs[0], total.inputs[0])
    h.link(tree, ocean, total.inputs[1])
    return lit, total


def _diffuse_contrast(tree, inputs, normal):
    """Two Toon BSDFs lighting min(1, k cos angle) on the unit squashed normal (twin:
    core.sand.contrast_toons, journey_diffuse). Returns (nodes, shader socket, (unit squashed
    normal, k) sockets)."""
    nodes = []

    def math(operation, a, b=None, label=None):
        nodes.append(h.math(tree, operation, a, b, label=label))
        return nodes[-1].outputs[0]

    split = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, normal, split.inputs[0])
    squashed = h.add_node(tree, "ShaderNodeCombineXYZ", label="N'")
    h.link(tree, split.outputs["X"], squashed.inputs["X"])
    h.link(tree, split.outputs["Y"], squashed.inputs["Y"])
    low = math("MULTIPLY", split.outputs["Z"], inputs["Squash"], label="Z × Squash")
    h.link(tree, low, squashed.inputs["Z"])
    length = h.vector_math(tree, "LENGTH", squashed.outputs[0], label="|N'|")
    unit = h.vector_math(tree, "NORMALIZE", squashed.outputs[0], label="Squashed Normal")
    nodes += [split, squashed, length, unit]
    angle = math("MULTIPLY", inputs["Diffuse Size"], 1.5707963, label="Size × 90°")
    threshold = math("MAXIMUM", math("COSINE", angle), 1e-4, label="Fully Lit N'·L")
    k = math("DIVIDE", length.outputs["Value"], threshold, label="k = |N'| / Fully Lit")
    full = math("ARCCOSINE", math("MINIMUM", math("DIVIDE", 1.0, k), 1.0), label="Fully Lit Angle")
    knee = math("ADD", math("MULTIPLY", full, 0.5), 0.7853982, label="Knee Angle")
    top = math("MINIMUM", k, 1.0, label="Light at Full")
    middle = math("MULTIPLY", k, math("COSINE", knee), label="Light at Knee")
    size_first = math("MULTIPLY", full, 0.6366198, label="Size (Full)")
    smooth_first = math("SUBTRACT", math("MULTIPLY", knee, 0.6366198), size_first, label="Smooth to Knee")
    size_second = math("MULTIPLY", knee, 0.6366198, label="Size (Knee)")
    smooth_second = math("SUBTRACT", 1.0, size_second, label="Smooth to 90°")
    cone = math("SUBTRACT", 1.0, math("COSINE", knee), label="1 − cos Knee")
    weight_first = math("MULTIPLY", math("SUBTRACT", top, middle), cone, label="First Toon Weight")
    shaders = []
    for label, size, smooth, weight in (("Toon to the Knee", size_first, smooth_first, weight_first),
                                        ("Toon to 90°", size_second, smooth_second, middle)):
        colour = h.vector_math(tree, "SCALE", inputs["Color"], label=f"Colour × Weight ({label})")
        h.link(tree, weight, colour.inputs["Scale"])
        toon = h.add_node(tree, "ShaderNodeBsdfToon", label=label, component="DIFFUSE")
        h.link(tree, colour.outputs[0], toon.inputs["Color"])
        h.link(tree, size, toon.inputs["Size"])
        h.link(tree, smooth, toon.inputs["Smooth"])
        h.link(tree, unit.outputs[0], toon.inputs["Normal"])
        nodes += [colour, toon]
        shaders.append(toon.outputs[0])
    both = h.add_node(tree, "ShaderNodeAddShader", label="Diffuse Contrast")
    h.link(tree, shaders[0], both.inputs[0])
    h.link(tree, shaders[1], both.inputs[1])
    nodes.append(both)
    return nodes, both.outputs[0], (unit.outputs[0], k)


def _eevee_contrast(tree, inputs, squashed):
    """One Diffuse BSDF on the unit squashed normal, its colour times min(1/c, k) / 2 (twin:
    core.sand.journey_eevee_factor). Returns (nodes, shader socket)."""
    unit, k = squashed
    sun = h.vector_math(tree, "NORMALIZE", inputs["Sun Direction"], label="Towards the Sun")
    cosine = h.vector_math(tree, "DOT_PRODUCT", unit, sun.outputs[0], label="c = N'·L")
    held = h.math(tree, "MAXIMUM", cosine.outputs["Value"], 1e-4, label="c ≥ 0.0001")
    inverse = h.math(tree, "DIVIDE", 1.0, held.outputs[0], label="1 / c")
    capped = h.math(tree, "MINIMUM", inverse.outputs[0], k, label="min(1 / c, k)")
    half = h.math(tree, "MULTIPLY", capped.outputs[0], 0.5, label="Factor (÷ 2: Cycles' scale)")
    colour = h.vector_math(tree, "SCALE", inputs["Color"], label="Colour × Factor")
    h.link(tree, half.outputs[0], colour.inputs["Scale"])
    diffuse = h.add_node(tree, "ShaderNodeBsdfDiffuse", label="Diffuse Contrast (EEVEE)")
    h.link(tree, colour.outputs[0], diffuse.inputs["Color"])
    h.link(tree, unit, diffuse.inputs["Normal"])
    return (sun, cosine, held, inverse, capped, half, colour, diffuse), diffuse.outputs[0]
