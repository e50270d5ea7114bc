"""Sandscape Ripples: wind ripples on the sand, as a height and a shading normal.

Crests run across the wind: height = Amplitude x weight x sin(2 pi (p . wind) / Wavelength), p the
world position and wind the horizontal wind direction. The weight fades the ripples on steep
slopes (Steep Fraction at the 35 degree angle of repose) and on slopes turned away from the wind
(down to Lee Fraction), as seed 004 blends its ripple textures by slope and direction. The
normal tilts by the height's gradient along the wind. Twin: core.sand.ripples.
"""

import math

from ..core import sand
from . import helper as h

NAME = "Sandscape Ripples"
VERSION = 1
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Wind ripples: crests across the wind, Wavelength apart, fading on steep and lee slopes; "
               "a height and the rippled normal")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Wind", "NodeSocketVector", "Wind velocity (only its horizontal direction counts)",
                (3.0, 1.0, 0.0))
    h.add_input(tree, "Wavelength", "NodeSocketFloat", "Distance from crest to crest (sand: 5 to 20 cm)",
                0.12, 1e-4, None, "DISTANCE")
    h.add_input(tree, "Amplitude", "NodeSocketFloat", "Height of a crest above the mean", 0.004, 0.0, None,
                "DISTANCE")
    h.add_input(tree, "Steep Fraction", "NodeSocketFloat", "Share of the ripples kept on a 35 degree slope",
                0.2, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Lee Fraction", "NodeSocketFloat", "Share kept on a slope turned away from the wind",
                0.3, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Normal", "NodeSocketVector", "Surface normal (unlinked: the shading normal)",
                (0.0, 0.0, 0.0), subtype=h.SURFACE_NORMAL)
    h.add_output(tree, "Height", "NodeSocketFloat", "Ripple height above the surface")
    h.add_output(tree, "Normal", "NodeSocketVector", "The rippled normal")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    normal, normal_nodes = h.normal_or_geometry(tree, inputs["Normal"])

    flat = h.vector_math(tree, "MULTIPLY", inputs["Wind"], (1.0, 1.0, 0.0), label="Horizontal Wind")
    length = h.vector_math(tree, "LENGTH", flat.outputs[0], label="|Wind|")
    calm = h.math(tree, "LESS_THAN", length.outputs["Value"], 1e-9, label="Calm")
    # No wind: crests along Y, as under a wind along X.
    fallback = h.vector_math(tree, "SCALE", (1.0, 0.0, 0.0), label="Calm: along X")
    h.link(tree, calm.outputs[0], fallback.inputs["Scale"])
    wind = h.vector_math(tree, "ADD", flat.outputs[0], fallback.outputs[0], label="Wind or X")
    direction = h.vector_math(tree, "NORMALIZE", wind.outputs[0], label="Wind Direction")

    position = h.add_node(tree, "ShaderNodeNewGeometry")
    along = h.vector_math(tree, "DOT_PRODUCT", position.outputs["Position"], direction.outputs[0],
                          label="Distance along the Wind")
    cycles = h.math(tree, "DIVIDE", along.outputs["Value"], inputs["Wavelength"], label="÷ Wavelength")
    phase = h.math(tree, "MULTIPLY", cycles.outputs[0], 2 * math.pi, label="Phase")
    wave = h.math(tree, "SINE", phase.outputs[0], label="sin")
    wave_slope = h.math(tree, "COSINE", phase.outputs[0], label="cos")

    split = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, normal, split.inputs[0])
    upright = h.math(tree, "ABSOLUTE", split.outputs["Z"], label="|N.z|")
    slope = h.math(tree, "ARCCOSINE", upright.outputs[0], label="Slope")
    steepness = h.add_node(tree, "ShaderNodeMapRange", label="Towards 35°", interpolation_type="SMOOTHSTEP",
                           inputs={"From Min": 0.0, "From Max": sand.REPOSE, "To Min": 0.0, "To Max": 1.0})
    h.link(tree, slope.outputs[0], steepness.inputs["Value"])
    steep_loss = h.math(tree, "SUBTRACT", inputs["Steep Fraction"], 1.0, label="Fraction − 1")
    steep = h.add_node(tree, "ShaderNodeMath", label="Steep Weight", operation="MULTIPLY_ADD",
                       inputs={2: 1.0})
    h.link(tree, steep_loss.outputs[0], steep.inputs[0])
    h.link(tree, steepness.outputs["Result"], steep.inputs[1])
    downwind = h.vector_math(tree, "DOT_PRODUCT", normal, direction.outputs[0], label="Faces Downwind")
    leeness = h.add_node(tree, "ShaderNodeMapRange", label="Lee Side", interpolation_type="SMOOTHSTEP",
                         inputs={"From Min": 0.0, "From Max": math.sin(sand.REPOSE), "To Min": 0.0,
                                 "To Max": 1.0})
    h.link(tree, downwind.outputs["Value"], leeness.inputs["Value"])
    lee_loss = h.math(tree, "SUBTRACT", inputs["Lee Fraction"], 1.0, label="Fraction − 1")
    lee = h.add_node(tree, "ShaderNodeMath", label="Lee Weight", operation="MULTIPLY_ADD", inputs={2: 1.0})
    h.link(tree, lee_loss.outputs[0], lee.inputs[0])
    h.link(tree, leeness.outputs["Result"], lee.inputs[1])
    weight = h.math(tree, "MULTIPLY", steep.outputs[0], lee.outputs[0], label="Weight")
    scale = h.math(tree, "MULTIPLY", inputs["Amplitude"], weight.outputs[0], label="Amplitude × Weight")

    height = h.math(tree, "MULTIPLY", scale.outputs[0], wave.outputs[0], label="Height")
    k = h.math(tree, "DIVIDE", 2 * math.pi, inputs["Wavelength"], label="2π / Wavelength")
    rate = h.math(tree, "MULTIPLY", scale.outputs[0], wave_slope.outputs[0], label="× cos")
    gradient_size = h.math(tree, "MULTIPLY", rate.outputs[0], k.outputs[0], label="Slope of the Height")
    gradient = h.vector_math(tree, "SCALE", direction.outputs[0], label="Gradient")
    h.link(tree, gradient_size.outputs[0], gradient.inputs["Scale"])
    normal_part = h.vector_math(tree, "DOT_PRODUCT", gradient.outputs[0], normal, label="Along the Normal")
    back = h.vector_math(tree, "SCALE", normal, label="× Normal")
    h.link(tree, normal_part.outputs["Value"], back.inputs["Scale"])
    tangential = h.vector_math(tree, "SUBTRACT", gradient.outputs[0], back.outputs[0], label="In the Surface")
    tilted = h.vector_math(tree, "SUBTRACT", normal, tangential.outputs[0], label="Normal − Gradient")
    rippled = h.vector_math(tree, "NORMALIZE", tilted.outputs[0], label="Rippled Normal")
    h.link(tree, height.outputs[0], group_out.inputs["Height"])
    h.link(tree, rippled.outputs[0], group_out.inputs["Normal"])
    h.frame(tree, "Surface Normal", normal_nodes)
    h.frame(tree, "Wind Direction", (flat, length, calm, fallback, wind, direction))
    h.frame(tree, "Crests across the Wind", (position, along, cycles, phase, wave, wave_slope))
    h.frame(tree, "Fading on Steep and Lee Slopes", (split, upright, slope, steepness, steep_loss, steep,
                                                     downwind, leeness, lee_loss, lee, weight, scale))
    h.frame(tree, "Height and Normal", (height, k, rate, gradient_size, gradient, normal_part, back,
                                        tangential, tilted, rippled))
    h.arrange(tree)
