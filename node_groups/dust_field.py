"""Sandscape Dust Field: where the wind has lifted dust, as a 0..1 density factor.

The seed's open problem: its volumetric light filled all open ground. Here dust is a noise
field carried by the wind (sampled at position - wind x time), thresholded so there are
clear and dusty patches, and thinning with height above the ground: exp(-height / falloff).
Time = Frame / FPS, with Frame driven by the expression `frame` (no Python auto-run).
Twin: core.dust.dust_field.
"""

from . import helper as h

NAME = "Sandscape Dust Field"
VERSION = 2
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = (
    "Wind-lifted dust: thresholded noise moving with the wind, thinning with height; "
    "multiply the volume density by it")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Frame", "NodeSocketFloat", "Current frame (driven by 'frame')", 1.0)
    h.add_input(tree, "FPS", "NodeSocketFloat", "Frames per second of the scene", 24.0, 1e-3, None)
    h.add_input(tree, "Wind", "NodeSocketVector", "Wind velocity, metres per second", (3.0, 1.0, 0.0))
    h.add_input(tree, "Scale", "NodeSocketFloat", "Size of the dust patches, metres", 8.0, 1e-3, None)
    h.add_input(tree, "Coverage", "NodeSocketFloat", "Share of the ground under dust, 0..1", 0.5, 0.0, 1.0,
                "FACTOR")
    h.add_input(tree, "Softness", "NodeSocketFloat", "Width of the patch edges in noise units", 0.08, 1e-4,
                None)
    h.add_input(tree, "Ground", "NodeSocketFloat", "World height of the ground, metres", 0.0)
    h.add_input(tree, "Falloff", "NodeSocketFloat", "Height over which the dust thins by 1/e, metres",
                1.5, 1e-3, None)
    h.add_output(tree, "Factor", "NodeSocketFloat", "Dust density factor, 0 (clear) to 1")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    position = h.add_node(tree, "ShaderNodeNewGeometry", (-900, 200))
    time = h.math(tree, "DIVIDE", inputs["Frame"], inputs["FPS"], (-900, -100), "Time (s)")
    drift = h.add_node(tree, "ShaderNodeVectorMath", (-700, -100), "Wind × Time", operation="SCALE")
    h.link(tree, inputs["Wind"], drift.inputs[0])
    h.link(tree, time.outputs[0], drift.inputs["Scale"])
    carried = h.add_node(tree, "ShaderNodeVectorMath", (-500, 100), "Position − Drift", operation="SUBTRACT")
    h.link(tree, position.outputs["Position"], carried.inputs[0])
    h.link(tree, drift.outputs[0], carried.inputs[1])
    frequency = h.math(tree, "DIVIDE", 1.0, inputs["Scale"], (-500, -100), "1 / Scale")
    # 2D noise over the ground: a patch is a column of dust, not a blob that hides in a projection.
    noise = h.add_node(tree, "ShaderNodeTexNoise", (-300, 100), "Dust Noise", noise_dimensions="2D",
                       inputs={"Detail": 3.0})
    h.link(tree, carried.outputs[0], noise.inputs["Vector"])
    h.link(tree, frequency.outputs[0], noise.inputs["Scale"])
    # Noise above (1 - coverage) is dusty; a smoothstep of +-softness softens the patch edges.
    edge = h.math(tree, "SUBTRACT", 1.0, inputs["Coverage"], (-300, -150), "1 − Coverage")
    low = h.math(tree, "SUBTRACT", edge.outputs[0], inputs["Softness"], (-100, -100))
    high = h.math(tree, "ADD", edge.outputs[0], inputs["Softness"], (-100, -250))
    patches = h.add_node(tree, "ShaderNodeMapRange", (100, 100), "Patches", interpolation_type="SMOOTHSTEP")
    h.link(tree, noise.outputs["Fac"], patches.inputs["Value"])
    h.link(tree, low.outputs[0], patches.inputs["From Min"])
    h.link(tree, high.outputs[0], patches.inputs["From Max"])
    split = h.add_node(tree, "ShaderNodeSeparateXYZ", (-700, 400))
    h.link(tree, position.outputs["Position"], split.inputs[0])
    height = h.math(tree, "SUBTRACT", split.outputs["Z"], inputs["Ground"], (-500, 400), "Height")
    clamped = h.math(tree, "MAXIMUM", height.outputs[0], 0.0, (-300, 400))
    ratio = h.math(tree, "DIVIDE", clamped.outputs[0], inputs["Falloff"], (-100, 400))
    negative = h.math(tree, "MULTIPLY", ratio.outputs[0], -1.0, (100, 400))
    thinning = h.math(tree, "EXPONENT", negative.outputs[0], None, (300, 400), "exp(−h / falloff)")
    factor = h.math(tree, "MULTIPLY", patches.outputs["Result"], thinning.outputs[0], (500, 200), "Factor")
    h.link(tree, factor.outputs[0], group_out.inputs["Factor"])
    h.frame(tree, "Carried by the Wind", (position, time, drift, carried, frequency, noise))
    h.frame(tree, "Patches", (edge, low, high, patches))
    h.frame(tree, "Thinning with Height", (split, height, clamped, ratio, negative, thinning))
    h.frame(tree, "Factor", (factor,))
    h.arrange(tree)
