"""Sandscape Glint Shade: turns a 0..1 noise value into a view-dependent glint.

Seed 000, section 2: a grain glints when its noise value exceeds the threshold, and
only where the view lines up with the normal: (N·V)^power. The noise comes from the
procedural cells (glints.py) or from an image texture. Twin: core.glints.glint_shade.
"""

from . import helper as h

NAME = "Sandscape Glint Shade"
VERSION = 2
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = (
    "Glint term of the Sandscape sand: Noise above Threshold lights a grain, "
    "(N·V)^Facing Power keeps it to where the view meets the normal")


# Socket name -> (type, description, default, min, max, subtype); shared with glints.py so
# the two groups describe the same inputs the same way.
INPUTS = {
    "Noise": ("NodeSocketFloat", "Per-grain random value in 0..1 (procedural cells or an image)",
              0.0, 0.0, 1.0, None),
    "Threshold": ("NodeSocketFloat", "Grains whose noise exceeds this glint: 0 lights all, 1 none; "
                  "about (1 - threshold) of the grains glint", 0.97, 0.0, 1.0, "FACTOR"),
    "Facing Power": ("NodeSocketFloat", "Exponent on N·V: higher keeps glints to where the view lines "
                     "up with the normal; 0 shows them at every angle", 8.0, 0.0, None, None),
    "Color": ("NodeSocketColor", "Glint colour", (1.0, 0.95, 0.85, 1.0), None, None, None),
    "Strength": ("NodeSocketFloat", "Emission strength of a fully facing glint", 30.0, 0.0, None, None),
}
OUTPUTS = {
    "Emission": ("NodeSocketShader", "The glints as an emission shader"),
    "Mask": ("NodeSocketFloat", "Glint coverage 0..1: lit grain × (N·V)^power, without colour or strength"),
    "Glint Color": ("NodeSocketColor", "Colour × Strength × Mask, for an Emission Color input"),
}


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, ("Noise", "Threshold", "Facing Power", "Color", "Strength"), INPUTS, OUTPUTS)

    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    lit = h.math(tree, "GREATER_THAN", inputs["Noise"], inputs["Threshold"], (-600, 200), "Lit Grain")
    layer_weight = h.add_node(tree, "ShaderNodeLayerWeight", (-800, -200), inputs={"Blend": 0.5})
    # Facing = 1 - |N·I| at blend 0.5, so N·V = 1 - Facing.
    n_dot_v = h.math(tree, "SUBTRACT", 1.0, layer_weight.outputs["Facing"], (-600, -200), "N·V")
    # A negative power would turn grazing angles into 0^-p = Inf.
    power = h.math(tree, "MAXIMUM", inputs["Facing Power"], 0.0, (-600, -400), "Power ≥ 0")
    falloff = h.math(tree, "POWER", n_dot_v.outputs[0], power.outputs[0], (-400, -200), "Facing Falloff")
    mask = h.math(tree, "MULTIPLY", lit.outputs[0], falloff.outputs[0], (-200, 0), "Mask")
    strength = h.math(tree, "MULTIPLY", mask.outputs[0], inputs["Strength"], (0, -100), "Strength")
    emission = h.add_node(tree, "ShaderNodeEmission", (250, 100))
    h.link(tree, inputs["Color"], emission.inputs["Color"])
    h.link(tree, strength.outputs[0], emission.inputs["Strength"])
    glint_color = h.add_node(tree, "ShaderNodeVectorMath", (250, -200), "Glint Color", operation="SCALE")
    h.link(tree, inputs["Color"], glint_color.inputs[0])
    h.link(tree, strength.outputs[0], glint_color.inputs["Scale"])

    h.link(tree, emission.outputs[0], group_out.inputs["Emission"])
    h.link(tree, mask.outputs[0], group_out.inputs["Mask"])
    h.link(tree, glint_color.outputs[0], group_out.inputs["Glint Color"])
    h.frame(tree, "Lit Grains × Facing", (lit, layer_weight, n_dot_v, power, falloff, mask))
    h.frame(tree, "Glint Output", (strength, emission, glint_color))
    h.arrange(tree)
