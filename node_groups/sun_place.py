"""Sandscape Sun Place: the sun's place on screen and how strongly the god rays shine for it.

From the sun's direction in camera space (the camera looks down -Z), the lens' scale and shift
in screen units, and whether the camera is a perspective one: the place u, v (0.5, 0.5 where the
sun is not in front), and 1 with the sun in the frame, easing (smoothstep) to 0 at Fade screen
widths outside it, 0 behind the camera. The post tree drives the inputs from the scene's camera
and sun (addon/sun_screen.py), so it runs per frame in the compositor without Python.
Twin: core.post.sun_on_screen.
"""

from ..core import post
from . import helper as h

NAME = "Sandscape Sun Place"
VERSION = 1
TREE_TYPE = "CompositorNodeTree"
DESCRIPTION = ("The sun's place on screen from its camera-space direction and the lens, and the rays' "
               "strength: 1 in the frame, easing to 0 at Fade screen widths outside it, 0 behind the camera")
FADE_FLOOR = 1e-6  # Fade 0: a step at the frame's edge (Map Range of an empty span gives its To Min)


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Direction", "NodeSocketVector", "The sun's direction in camera space (the camera "
                "looks down -Z)", (0.0, 0.0, -1.0))
    h.add_input(tree, "Scale", "NodeSocketVector", "Screen widths (x) and heights (y) that one unit of "
                "x / -z and y / -z spans", (1.0, 1.0, 0.0))
    h.add_input(tree, "Shift", "NodeSocketVector", "The camera's shift in screen widths and heights",
                (0.0, 0.0, 0.0))
    h.add_input(tree, "Perspective", "NodeSocketFloat", "1 for a perspective camera; else no rays",
                1.0, 0.0, 1.0)
    h.add_input(tree, "Fade", "NodeSocketFloat", "Screen widths outside the frame over which the rays fade",
                0.25, 0.0, None)
    h.add_output(tree, "Sun", "NodeSocketVector", "The sun's place on screen, 0..1 in x and y")
    h.add_output(tree, "Intensity", "NodeSocketFloat", "The rays' strength, 0..1")
    group_in, group_out = h.group_io(tree)
    made = len(tree.nodes)
    direction = h.add_node(tree, "ShaderNodeSeparateXYZ", label="Direction")
    h.link(tree, group_in.outputs["Direction"], direction.inputs[0])
    ahead = h.math(tree, "LESS_THAN", direction.outputs["Z"], -post.FRONT_EPSILON, label="Ahead")
    perspective = h.math(tree, "GREATER_THAN", group_in.outputs["Perspective"], 0.5)
    front = h.math(tree, "MULTIPLY", ahead.outputs[0], perspective.outputs[0], label="In Front")
    made = _stage(tree, "In Front of a Perspective Camera", made)
    scale = h.add_node(tree, "ShaderNodeSeparateXYZ", label="Scale")
    h.link(tree, group_in.outputs["Scale"], scale.inputs[0])
    shift = h.add_node(tree, "ShaderNodeSeparateXYZ", label="Shift")
    h.link(tree, group_in.outputs["Shift"], shift.inputs[0])
    # -z kept away from 0: a sun beside the camera's plane gives a far but finite place.
    depth = h.math(tree, "MULTIPLY", h.math(tree, "MINIMUM", direction.outputs["Z"],
                                            -post.FRONT_EPSILON).outputs[0], -1.0, label="Depth")
    place = h.add_node(tree, "ShaderNodeCombineXYZ", label="Sun Place")
    for axis in "XY":
        tangent = h.math(tree, "DIVIDE", direction.outputs[axis], depth.outputs[0])
        on_screen = h.add_node(tree, "ShaderNodeMath", operation="MULTIPLY_ADD",
                               inputs={2: 0.5})
        h.link(tree, tangent.outputs[0], on_screen.inputs[0])
        h.link(tree, scale.outputs[axis], on_screen.inputs[1])
        shifted = h.math(tree, "SUBTRACT", on_screen.outputs[0], shift.outputs[axis])
        # 0.5 + front × (place − 0.5): the centre where the sun is not in front.
        centred = h.math(tree, "SUBTRACT", shifted.outputs[0], 0.5)
        kept = h.add_node(tree, "ShaderNodeMath", operation="MULTIPLY_ADD", inputs={2: 0.5})
        h.link(tree, centred.outputs[0], kept.inputs[0])
        h.link(tree, front.outputs[0], kept.inputs[1])
        h.link(tree, kept.outputs[0], place.inputs[axis])
    h.link(tree, place.outputs[0], group_out.inputs["Sun"])
    made = _stage(tree, "Place on Screen (the Centre When Not in Front)", made)
    # How far outside the frame: max(0, -u, u - 1, -v, v - 1) = max(|u - ½|, |v - ½|) - ½.
    across = h.math(tree, "ABSOLUTE", h.math(tree, "SUBTRACT", place.inputs["X"].links[0].from_socket,
                                             0.5).outputs[0])
    up = h.math(tree, "ABSOLUTE", h.math(tree, "SUBTRACT", place.inputs["Y"].links[0].from_socket,
                                         0.5).outputs[0])
    farthest = h.math(tree, "MAXIMUM", across.outputs[0], up.outputs[0])
    outside = h.math(tree, "SUBTRACT", farthest.outputs[0], 0.5, label="Outside the Frame")
    span = h.math(tree, "MAXIMUM", group_in.outputs["Fade"], FADE_FLOOR, label="Fade Span")
    fade = h.add_node(tree, "ShaderNodeMapRange", label="Fade", interpolation_type="SMOOTHSTEP",
                      inputs={"From Min": 0.0, "To Min": 1.0, "To Max": 0.0})
    h.link(tree, outside.outputs[0], fade.inputs["Value"])
    h.link(tree, span.outputs[0], fade.inputs["From Max"])
    shown = h.math(tree, "MULTIPLY", fade.outputs["Result"], front.outputs[0], label="× In Front")
    h.link(tree, shown.outputs[0], group_out.inputs["Intensity"])
    _stage(tree, "Fade Outside the Frame", made)
    h.arrange(tree)


def _stage(tree, label, first):
    """Frame the nodes made since the first-th; the node count now."""
    h.frame(tree, label, list(tree.nodes)[first:])
    return len(tree.nodes)
