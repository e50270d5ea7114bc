"""Sandscape Texel Corners: the centres of the four texels round a point of an image, and how far
the point lies between them, so four Closest lookups blended by Sandscape Texel Blend give the
image's bilinear (Linear) value.

Why not the image node's Linear: EEVEE samples displacement in the vertex stage, and software
OpenGL's linear filtering of a float image there is so slow that a frame with prints never
finished; Closest lookups are fast in both stages and in Cycles. Twin: core.texels.corners.
"""

from . import helper as h

NAME = "Sandscape Texel Corners"
VERSION = 1
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = "The four texel centres round a point of an image and the blend weights between them"
CORNERS = (1, 2, 3, 4)  # (left, bottom), (right, bottom), (left, top), (right, top)

INPUTS = {  # name -> (type, description, default, min, max, subtype); append only
    "Vector": ("NodeSocketVector", "The point in the image's 0..1 coordinates", (0.0, 0.0, 0.0), None, None,
               None),
    "Width": ("NodeSocketFloat", "The image's width in texels", 1.0, 1.0, None, None),
    "Height": ("NodeSocketFloat", "The image's height in texels", 1.0, 1.0, None, None),
}
OUTPUTS = {
    **{f"Corner {k}": ("NodeSocketVector", f"Centre of texel {k} (left-bottom, right-bottom, left-top, "
                       "right-top)") for k in CORNERS},
    "Weight X": ("NodeSocketFloat", "How far right of the left texels' centres the point is (0..1)"),
    "Weight Y": ("NodeSocketFloat", "How far up from the bottom texels' centres the point is (0..1)"),
}


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, INPUTS, INPUTS, OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    split = h.add_node(tree, "ShaderNodeSeparateXYZ", label="Point")
    h.link(tree, inputs["Vector"], split.inputs[0])
    low, high = [], []
    for axis, size in ((0, inputs["Width"]), (1, inputs["Height"])):
        texels = h.math(tree, "MULTIPLY_ADD", split.outputs[axis], size, c=-0.5, label="In Texels − ½")
        first = h.math(tree, "FLOOR", texels.outputs[0], label="First Texel")
        weight = h.math(tree, "SUBTRACT", texels.outputs[0], first.outputs[0], label="Weight")
        near_texel = h.math(tree, "ADD", first.outputs[0], 0.5)
        far_texel = h.math(tree, "ADD", first.outputs[0], 1.5)
        near = h.math(tree, "DIVIDE", near_texel.outputs[0], size, label="First Centre")
        far = h.math(tree, "DIVIDE", far_texel.outputs[0], size, label="Next Centre")
        h.link(tree, weight.outputs[0], group_out.inputs["Weight X" if axis == 0 else "Weight Y"])
        low.append(near.outputs[0])
        high.append(far.outputs[0])
        stage = [texels, first, weight, near_texel, far_texel, near, far] + ([split] if axis == 0 else [])
        h.frame(tree, "Across" if axis == 0 else "Up", stage)
    corners = []
    for k, (x, y) in zip(CORNERS, ((low[0], low[1]), (high[0], low[1]), (low[0], high[1]),
                                   (high[0], high[1])), strict=True):
        corner = h.add_node(tree, "ShaderNodeCombineXYZ", label=f"Corner {k}")
        h.link(tree, x, corner.inputs[0])
        h.link(tree, y, corner.inputs[1])
        h.link(tree, corner.outputs[0], group_out.inputs[f"Corner {k}"])
        corners.append(corner)
    h.frame(tree, "Texel Centres", corners)
    h.arrange(tree)
