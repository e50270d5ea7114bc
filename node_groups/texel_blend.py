"""Sandscape Texel Blend: four texels' colours blended by Sandscape Texel Corners' weights, as an
image node's Linear interpolation blends them (bottom pair, top pair, then between the two).
Twin: core.texels.blend.
"""

from . import helper as h
from .texel_corners import CORNERS

NAME = "Sandscape Texel Blend"
VERSION = 1
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = "Four texels' colours blended bilinearly by the weights of Sandscape Texel Corners"

INPUTS = {  # name -> (type, description, default, min, max, subtype); append only
    **{f"Color {k}": ("NodeSocketColor", f"Texel {k}'s colour (a Closest lookup at Corner {k})",
                      (0.0, 0.0, 0.0, 0.0), None, None, None) for k in CORNERS},
    "Weight X": ("NodeSocketFloat", "Texel Corners' Weight X", 0.0, 0.0, 1.0, "FACTOR"),
    "Weight Y": ("NodeSocketFloat", "Texel Corners' Weight Y", 0.0, 0.0, 1.0, "FACTOR"),
}
OUTPUTS = {"Color": ("NodeSocketColor", "The bilinear colour")}


def _mix(tree, factor, a, b, label):
    node = h.add_node(tree, "ShaderNodeMix", label=label, data_type="RGBA", blend_type="MIX",
                      clamp_factor=False)
    h.link(tree, factor, node.inputs["Factor"])
    h.link(tree, a, h.socket(node.inputs, "A"))
    h.link(tree, b, h.socket(node.inputs, "B"))
    return node


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, INPUTS, INPUTS, OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    bottom = _mix(tree, inputs["Weight X"], inputs["Color 1"], inputs["Color 2"], "Bottom Pair")
    top = _mix(tree, inputs["Weight X"], inputs["Color 3"], inputs["Color 4"], "Top Pair")
    pairs = [h.socket(node.outputs, "Result") for node in (bottom, top)]
    between = _mix(tree, inputs["Weight Y"], *pairs, "Between")
    h.link(tree, h.socket(between.outputs, "Result"), group_out.inputs["Color"])
    h.frame(tree, "Bilinear", (bottom, top, between))
    h.arrange(tree)
