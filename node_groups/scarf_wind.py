"""Sandscape Scarf Wind: turns the walker's scarf tail to the wind it feels, every frame.

A geometry-nodes modifier on the walker's body: it reads the object's own world transform (Self
Object), so the tail follows the walker's turns along any path with no keys and no Python on a
farm. The felt wind is the scene's wind less the walk (Walk Speed along the object's +X from Walk
Start to Walk End, easing to none over Settle Frames after it, by the scene's frame), taken
into the object's space; the tail turns about the upright axis through the Nape to that wind's
heading reflected into the walker's back half (the nearer straight back the more that wind blows
forward), its root least. Points are picked and weighted by
the figure's flutter attribute. Twin: core.scarf.
"""

import math

from ..core import scarf
from . import helper as h

NAME = "Sandscape Scarf Wind"
VERSION = 3
TREE_TYPE = "GeometryNodeTree"
DESCRIPTION = "Turns the scarf's tail about the nape to the wind the walker feels (the wind less its walk)"


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Geometry", "NodeSocketGeometry", "The walker's body")
    h.add_input(tree, "Wind", "NodeSocketVector", "The scene's wind (world, units a second)", (3.0, 1.0, 0.0))
    h.add_input(tree, "Walk Speed", "NodeSocketFloat", "How fast the walker walks along its +X (units a "
                "second)", 1.4, 0.0)
    h.add_input(tree, "Walk Start", "NodeSocketFloat", "The walk's first frame (before it, no walk is "
                "felt)", -1e6)
    h.add_input(tree, "Walk End", "NodeSocketFloat", "The walk's last frame (after it the walk is felt "
                "less and less)", 1e6)
    h.add_input(tree, "Settle Frames", "NodeSocketFloat", "Frames after the walk's end over which the "
                "tail stops feeling it", 24.0, 1e-6)
    h.add_input(tree, "Nape", "NodeSocketVector", "Where the tail leaves the neck (the object's space)")
    h.add_input(tree, "Built Heading", "NodeSocketFloat", "The tail's heading as built (radians from +X "
                "toward +Y)", math.pi, subtype="ANGLE")
    h.add_input(tree, "Calm Speed", "NodeSocketFloat", "Felt wind (units a second) under which the tail "
                "eases to straight back", scarf.CALM_SPEED, 1e-6)
    h.add_output(tree, "Geometry", "NodeSocketGeometry", "The body, its tail turned")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs

    me = h.add_node(tree, "GeometryNodeSelfObject")
    info = h.add_node(tree, "GeometryNodeObjectInfo", label="Walker", transform_space="ORIGINAL")
    h.link(tree, me.outputs[0], info.inputs["Object"])
    forward = h.add_node(tree, "FunctionNodeTransformDirection", label="Forward (World)",
                         inputs={"Direction": (1.0, 0.0, 0.0)})
    h.link(tree, info.outputs["Transform"], forward.inputs["Transform"])
    ahead = h.vector_math(tree, "NORMALIZE", forward.outputs[0], label="Forward")
    # The walk's speed by the frame (core.scarf.walk_speed_at): none before the walk, all of it to
    # its end, easing to none over the settle after it.
    time = h.add_node(tree, "GeometryNodeInputSceneTime")
    settled = h.math(tree, "ADD", inputs["Walk End"], inputs["Settle Frames"], label="Settled Frame")
    left = h.math(tree, "SUBTRACT", settled.outputs[0], time.outputs["Frame"], label="Frames Left")
    easing = h.math(tree, "DIVIDE", left.outputs[0], inputs["Settle Frames"], label="Walk Felt")
    easing.use_clamp = True
    early = h.math(tree, "LESS_THAN", time.outputs["Frame"], inputs["Walk Start"], label="Before the Walk")
    started = h.math(tree, "SUBTRACT", 1.0, early.outputs[0], label="Walking or After")
    share = h.math(tree, "MULTIPLY", easing.outputs[0], started.outputs[0])
    speed = h.math(tree, "MULTIPLY", inputs["Walk Speed"], share.outputs[0], label="Walk Speed Now")
    walk = h.vector_math(tree, "SCALE", ahead.outputs[0], label="Walk")
    h.link(tree, speed.outputs[0], walk.inputs["Scale"])
    felt = h.vector_math(tree, "SUBTRACT", inputs["Wind"], walk.outputs[0], label="Felt Wind")
    felt_speed = h.vector_math(tree, "LENGTH", felt.outputs[0], label="|Felt Wind|")
    to_local = h.add_node(tree, "FunctionNodeInvertMatrix", label="World → Walker")
    h.link(tree, info.outputs["Transform"], to_local.inputs["Matrix"])
    local = h.add_node(tree, "FunctionNodeTransformDirection", label="Felt Wind (Walker)")
    h.link(tree, felt.outputs[0], local.inputs["Direction"])
    h.link(tree, to_local.outputs["Matrix"], local.inputs["Transform"])
    h.frame(tree, "The Wind the Walker Feels",
            (me, info, forward, ahead, time, settled, left, easing, early, started, share, speed, walk, felt,
             felt_speed, to_local, local))

    xyz = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, local.outputs[0], xyz.inputs[0])
    heading = h.math(tree, "ARCTAN2", xyz.outputs["Y"], xyz.outputs["X"], label="Felt Heading")
    behind = h.math(tree, "SUBTRACT", heading.outputs[0], math.pi, label="From Straight Back")
    sine = h.math(tree, "SINE", behind.outputs[0])
    back_half = h.math(tree, "ARCSINE", sine.outputs[0], label="Into the Back Half")
    cosine = h.math(tree, "COSINE", heading.outputs[0])
    forward = h.math(tree, "MAXIMUM", cosine.outputs[0], 0.0, label="Blowing Forward")
    keep = h.math(tree, "SUBTRACT", 1.0, forward.outputs[0], label="Swing Kept")
    fade = h.math(tree, "DIVIDE", felt_speed.outputs["Value"], inputs["Calm Speed"], label="Calm Fade")
    fade.use_clamp = True
    swing = h.math(tree, "MULTIPLY", back_half.outputs[0], keep.outputs[0], label="Swing")
    faded = h.math(tree, "MULTIPLY", swing.outputs[0], fade.outputs[0], label="Swing, Faded")
    turn = h.math(tree, "ADD", faded.outputs[0], math.pi, label="Tail Heading")
    angle = h.math(tree, "SUBTRACT", turn.outputs[0], inputs["Built Heading"], label="Tail Turn")
    h.frame(tree, "Heading Downwind, Behind",
            (xyz, heading, behind, sine, back_half, cosine, forward, keep, fade, swing, faded, turn, angle))

    flutter = h.add_node(tree, "GeometryNodeInputNamedAttribute", data_type="FLOAT",
                         inputs={"Name": scarf.FLUTTER_ATTRIBUTE})
    along = h.math(tree, "POWER", flutter.outputs["Attribute"], 1.0 / scarf.FLUTTER_GROWTH,
                   label="Along the Tail")
    root = h.add_node(tree, "ShaderNodeMapRange", label="Root Turns Least", interpolation_type="SMOOTHSTEP",
                      inputs={"From Min": 0.0, "From Max": scarf.ROOT_SHARE, "To Min": 0.0, "To Max": 1.0})
    h.link(tree, along.outputs[0], root.inputs["Value"])
    share = h.math(tree, "MULTIPLY", angle.outputs[0], root.outputs["Result"], label="Point's Turn")
    on_tail = h.math(tree, "GREATER_THAN", flutter.outputs["Attribute"], 0.0, label="On the Tail")
    position = h.add_node(tree, "GeometryNodeInputPosition")
    rotate = h.add_node(tree, "ShaderNodeVectorRotate", label="About the Nape", rotation_type="Z_AXIS")
    h.link(tree, position.outputs[0], rotate.inputs["Vector"])
    h.link(tree, inputs["Nape"], rotate.inputs["Center"])
    h.link(tree, share.outputs[0], rotate.inputs["Angle"])
    place = h.add_node(tree, "GeometryNodeSetPosition")
    h.link(tree, inputs["Geometry"], place.inputs["Geometry"])
    h.link(tree, on_tail.outputs[0], place.inputs["Selection"])
    h.link(tree, rotate.outputs[0], place.inputs["Position"])
    h.link(tree, place.outputs[0], group_out.inputs["Geometry"])
    h.frame(tree, "Turn the Tail", (flutter, along, root, share, on_tail, position, rotate, place))
    h.arrange(tree)
