"""Sandscape Gated Blur: the seed's 3x3 Gaussian, kept only where it changes the luminance and
not across an outline of the Guide.

Seed 000, section 4.2. Nine one-pixel translations (nearest, edge pixels extended) weighted
by the normalised kernel; a pixel takes the blurred value where |L(blurred) - L(original)|
exceeds Threshold, unless the Guide's luminance over the same nine pixels spans more than Edge
of its largest value. Twin: core.post.gated_blur.
"""

from ..core import post
from . import helper as h

NAME = "Sandscape Gated Blur"
VERSION = 3
TREE_TYPE = "CompositorNodeTree"
DESCRIPTION = (
    "3x3 Gaussian (0.147761 / 0.118318 / 0.0947416, normalised) applied where it "
    "changes the luminance by more than Threshold, and not across an outline of the Guide")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Image", "NodeSocketColor", "Image to blur (the scattered light)", (0.0, 0.0, 0.0, 1.0))
    h.add_input(tree, "Threshold", "NodeSocketFloat", "Luminance change below which a pixel stays sharp",
                0.01, 0.0, None)
    h.add_input(tree, "Guide", "NodeSocketColor", "Where it has an outline the pixels stay sharp (the "
                "environment pass: the outlines of clouds and land against the sky); black: none",
                (0.0, 0.0, 0.0, 1.0))
    h.add_input(tree, "Edge", "NodeSocketFloat", "Share of the Guide's brightest value its 3×3 pixels may "
                "span before they count as an outline", post.EDGE, 0.0, None)
    h.add_output(tree, "Image", "NodeSocketColor", "The gated blur")
    group_in, group_out = h.group_io(tree)
    kernel = post.gaussian_kernel()
    # The centre first: the compositor gives a sum the domain of its first operand, and a
    # translated first operand would shift the whole blur by a pixel.
    offsets = [(1, 1)] + [(row, col) for row in range(3) for col in range(3) if (row, col) != (1, 1)]
    total, taps, sums = None, [], []
    for index, (row, col) in enumerate(offsets):
        y = 300 - 150 * index
        shift = h.add_node(tree, "CompositorNodeTranslate", (-600, y),
                           inputs={"X": float(col - 1), "Y": float(row - 1), "Interpolation": "Nearest",
                                   "Extension X": "Extend", "Extension Y": "Extend"})
        h.link(tree, group_in.outputs["Image"], shift.inputs["Image"])
        weighted = h.add_node(tree, "ShaderNodeVectorMath", (-400, y), operation="SCALE",
                              inputs={"Scale": float(kernel[row, col])})
        h.link(tree, shift.outputs[0], weighted.inputs[0])
        taps += [shift, weighted]
        if total is None:
            total = weighted
        else:
            added = h.add_node(tree, "ShaderNodeVectorMath", (-200, y), operation="ADD")
            h.link(tree, total.outputs[0], added.inputs[0])
            h.link(tree, weighted.outputs[0], added.inputs[1])
            total = added
            sums.append(added)
    blurred_luma = h.add_node(tree, "CompositorNodeRGBToBW", (0, 200))
    original_luma = h.add_node(tree, "CompositorNodeRGBToBW", (0, 0))
    h.link(tree, total.outputs[0], blurred_luma.inputs[0])
    h.link(tree, group_in.outputs["Image"], original_luma.inputs[0])
    difference = h.math(tree, "SUBTRACT", blurred_luma.outputs[0], original_luma.outputs[0], (200, 100))
    change = h.math(tree, "ABSOLUTE", difference.outputs[0], None, (350, 100))
    changed = h.math(tree, "GREATER_THAN", change.outputs[0], group_in.outputs["Threshold"], (500, 100),
                     "Changes the Luminance")
    outline = _outline(tree, group_in, offsets)
    gate = h.math(tree, "SUBTRACT", changed.outputs[0], outline.outputs[0], (600, 100), "Gate")
    gate.use_clamp = True
    choose = h.add_node(tree, "ShaderNodeMix", (700, 0), data_type="RGBA", blend_type="MIX")
    h.link(tree, gate.outputs[0], choose.inputs["Factor"])
    h.link(tree, group_in.outputs["Image"], choose.inputs[6])
    h.link(tree, total.outputs[0], choose.inputs[7])
    h.link(tree, choose.outputs[2], group_out.inputs["Image"])
    h.frame(tree, "3×3 Gaussian: Shifted Copies × Weights", taps)
    h.frame(tree, "Sum", sums)
    h.frame(tree, "Gate on the Luminance Change",
            (blurred_luma, original_luma, difference, change, changed, gate, choose))
    h.arrange(tree)


def _outline(tree, group_in, offsets):
    """1 where the Guide's luminance over the 3x3 pixels spans more than Edge x its largest value."""
    luma = h.add_node(tree, "CompositorNodeRGBToBW", (-800, -1200))
    h.link(tree, group_in.outputs["Guide"], luma.inputs[0])
    high = low = None
    nodes = [luma]
    for index, (row, col) in enumerate(offsets):
        y = -1200 - 150 * index
        shift = h.add_node(tree, "CompositorNodeTranslate", (-600, y),
                           inputs={"X": float(col - 1), "Y": float(row - 1), "Interpolation": "Nearest",
                                   "Extension X": "Extend", "Extension Y": "Extend"})
        h.link(tree, luma.outputs[0], shift.inputs["Image"])
        nodes.append(shift)
        if high is None:
            high = low = shift
            continue
        high = h.math(tree, "MAXIMUM", high.outputs[0], shift.outputs[0], (-400, y))
        low = h.math(tree, "MINIMUM", low.outputs[0], shift.outputs[0], (-200, y))
        nodes += [high, low]
    span = h.math(tree, "SUBTRACT", high.outputs[0], low.outputs[0], (0, -1400), "Guide's Span")
    allowed = h.math(tree, "MULTIPLY", high.outputs[0], group_in.outputs["Edge"], (0, -1600),
                     "Edge × Largest")
    outline = h.math(tree, "GREATER_THAN", span.outputs[0], allowed.outputs[0], (200, -1500), "Outline")
    h.frame(tree, "Outline of the Guide (3×3 Span)", nodes + [span, allowed, outline])
    return outline
