"""Sandscape Footprint Height: the painted footprint image as a displacement.

Seed 000, section 3.2: red records depressions, green raised rims, and a noise texture
adds subtle variation. Blue holds each texel's birth frame, so one image reveals the prints
as the feet land: a texel counts once Frame has reached its birth frame. Frame is
driven by the expression `frame`, which runs without Python auto-run. With a Refill Time the
wind fills a print in: its depth and rim ease towards the surface as exp(−age × rate / Refill
Time), rate 1 on flat ground and in the lee and (1 + 2 g)³ where the ground rises into the Wind
at gradient g (core.footprints.windward_refill_rate says why).
Pressed is the revealed share of R alone (none at Depth 0: no print): the ripples' Flatten, as a
foot tramples them.
Twin: core.footprints.revealed_height (with Noise Amount 0) and revealed_pressed.
"""

import math

from ..core.footprints import WINDWARD_SPEEDUP
from ..core.sole import REPOSE
from . import helper as h

NAME = "Sandscape Footprint Height"
VERSION = 5
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = (
    "Footprint displacement from a Sandscape print map: Rim × G − Depth × R, revealed where "
    "the texel's birth frame (B) has been reached, varied by a noise texture")
REVEAL_MARGIN = 1e-3  # frames: a print born at frame 12 shows at frame 12 despite float round-off

# Socket name -> (type, description, default, min, max, subtype). Append only.
INPUTS = {
    "Print Map": ("NodeSocketColor", "The painted footprint image: R depression (1 = Depth), "
                  "G raised rim (1 = Rim), B birth frame normalised to Frame Start..End",
                  (0.0, 0.0, 0.0, 0.0), None, None, None),
    "Depth": ("NodeSocketFloat", "How far a print presses into the sand where R is 1, in metres",
              0.03, 0.0, None, "DISTANCE"),
    "Rim": ("NodeSocketFloat", "Height of the sand pushed up around a print where G is 1, in metres",
            0.008, 0.0, None, "DISTANCE"),
    "Frame": ("NodeSocketFloat", "Current frame (driven by the expression 'frame'); texels born later "
              "stay flat", 0.0, None, None, None),
    "Frame Start": ("NodeSocketFloat", "Frame that blue 0 stands for", 1.0, None, None, None),
    "Frame End": ("NodeSocketFloat", "Frame that blue 1 stands for", 250.0, None, None, None),
    "Vector": ("NodeSocketVector", "Where to sample the variation noise (object coordinates)",
               (0.0, 0.0, 0.0), None, None, None),
    "Noise Amount": ("NodeSocketFloat", "Relative variation of print depth and rim: 0.1 is +-10 %",
                     0.15, 0.0, 1.0, "FACTOR"),
    "Noise Scale": ("NodeSocketFloat", "Scale of the variation noise (features per metre)",
                    40.0, 0.0, None, None),
    "Refill Time": ("NodeSocketFloat", "Frames in which the wind fills a print to 1/e of its depth and "
                    "rim (exp(−age / Refill Time)); 0: prints stay as pressed", 0.0, 0.0, None, None),
    "Wind": ("NodeSocketVector", "The scene's wind (world velocity): prints on slopes facing it fill "
             "faster", (0.0, 0.0, 0.0), None, None, "VELOCITY"),
}
OUTPUTS = {
    "Height": ("NodeSocketFloat", "Height of the revealed prints in metres: Rim G - Depth R, varied"),
    "Displacement": ("NodeSocketVector", "Height along the normal, in world units, for the material's "
                     "Displacement output"),
    "Pressed": ("NodeSocketFloat", "Share of the sand pressed down here, 0..1 (R where revealed and not "
                "yet refilled; none at Depth 0): a foot tramples the ripples it lands on"),
}


def build(tree):
    tree.description = DESCRIPTION
    for name, spec in INPUTS.items():
        h.add_input(tree, name, *spec)
    for name, (socket_type, description) in OUTPUTS.items():
        h.add_output(tree, name, socket_type, description)

    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    channels = h.add_node(tree, "ShaderNodeSeparateColor", (-700, 200))
    h.link(tree, inputs["Print Map"], channels.inputs[0])

    # Born where B * span + start < frame + margin; span is at least one frame, as in the painter.
    span = h.math(tree, "SUBTRACT", inputs["Frame End"], inputs["Frame Start"], (-700, -100), "Span")
    span_floor = h.math(tree, "MAXIMUM", span.outputs[0], 1.0, (-500, -100), "Span ≥ 1")
    birth = h.add_node(tree, "ShaderNodeMath", (-300, -100), "Birth Frame", operation="MULTIPLY_ADD")
    h.link(tree, channels.outputs["Blue"], birth.inputs[0])
    h.link(tree, span_floor.outputs[0], birth.inputs[1])
    h.link(tree, inputs["Frame Start"], birth.inputs[2])
    now = h.math(tree, "ADD", inputs["Frame"], REVEAL_MARGIN, (-300, -300), "Frame + Margin")
    born = h.math(tree, "LESS_THAN", birth.outputs[0], now.outputs[0], (-100, -150), "Born")

    rim = h.math(tree, "MULTIPLY", channels.outputs["Green"], inputs["Rim"], (-400, 300), "Rim Height")
    depth = h.math(tree, "MULTIPLY", channels.outputs["Red"], inputs["Depth"], (-400, 150), "Depth")
    base = h.math(tree, "SUBTRACT", rim.outputs[0], depth.outputs[0], (-200, 250), "Rim − Depth")
    shown = h.math(tree, "MULTIPLY", base.outputs[0], born.outputs[0], (0, 150), "Revealed")
    # Refill: exp(−age / T) of the print left, all of it with T = 0 (no wind refill).
    age = h.math(tree, "SUBTRACT", inputs["Frame"], birth.outputs[0], label="Age (frames)")
    age_floor = h.math(tree, "MAXIMUM", age.outputs[0], 0.0, label="Age ≥ 0")
    time = h.math(tree, "MAXIMUM", inputs["Refill Time"], 1e-6, label="Refill Time > 0")
    rate, rate_nodes = _windward_rate(tree, inputs["Wind"])
    windward_age = h.math(tree, "MULTIPLY", age_floor.outputs[0], rate, label="Age × Windward Rate")
    ratio = h.math(tree, "DIVIDE", windward_age.outputs[0], time.outputs[0], label="Age / Refill Time")
    negative = h.math(tree, "MULTIPLY", ratio.outputs[0], -1.0, label="−Age / Refill Time")
    left = h.math(tree, "EXPONENT", negative.outputs[0], label="Left")
    refills = h.math(tree, "GREATER_THAN", inputs["Refill Time"], 0.0, label="Refills")
    kept = h.add_node(tree, "ShaderNodeMix", label="Left (1 without refill)", data_type="FLOAT")
    h.link(tree, refills.outputs[0], kept.inputs["Factor"])
    h.socket(kept.inputs, "A").default_value = 1.0
    h.link(tree, left.outputs[0], h.socket(kept.inputs, "B"))
    revealed = h.math(tree, "MULTIPLY", shown.outputs[0], kept.outputs["Result"], label="Revealed × Left")
    pressed_born = h.math(tree, "MULTIPLY", channels.outputs["Red"], born.outputs[0], label="R × Born")
    pressed_left = h.math(tree, "MULTIPLY", pressed_born.outputs[0], kept.outputs["Result"], label="× Left")
    has_depth = h.math(tree, "GREATER_THAN", inputs["Depth"], 0.0, label="Depth > 0")
    pressed = h.math(tree, "MULTIPLY", pressed_left.outputs[0], has_depth.outputs[0], label="Pressed")
    h.link(tree, pressed.outputs[0], group_out.inputs["Pressed"])

    noise = h.add_node(tree, "ShaderNodeTexNoise", (-400, -500), "Variation", noise_dimensions="3D",
                       inputs={"Detail": 2.0})
    h.link(tree, inputs["Vector"], noise.inputs["Vector"])
    h.link(tree, inputs["Noise Scale"], noise.inputs["Scale"])
    centred = h.add_node(tree, "ShaderNodeMath", (-200, -500), "Noise −1..1", operation="MULTIPLY_ADD",
                         inputs={1: 2.0, 2: -1.0})
    h.link(tree, noise.outputs["Fac"], centred.inputs[0])
    variation = h.add_node(tree, "ShaderNodeMath", (0, -500), "1 + Amount × Noise",
                           operation="MULTIPLY_ADD", inputs={2: 1.0})
    h.link(tree, centred.outputs[0], variation.inputs[0])
    h.link(tree, inputs["Noise Amount"], variation.inputs[1])
    height = h.math(tree, "MULTIPLY", revealed.outputs[0], variation.outputs[0], (200, 0), "Height")

    displacement = h.add_node(tree, "ShaderNodeDisplacement", (450, -100), space="WORLD",
                              inputs={"Midlevel": 0.0, "Scale": 1.0})
    h.link(tree, height.outputs[0], displacement.inputs["Height"])
    h.link(tree, height.outputs[0], group_out.inputs["Height"])
    h.link(tree, displacement.outputs[0], group_out.inputs["Displacement"])
    h.frame(tree, "Channels", (channels,))
    h.frame(tree, "Reveal at the Birth Frame", (span, span_floor, birth, now, born))
    h.frame(tree, "Rim − Depth", (rim, depth, base, shown))
    h.frame(tree, "Wind Refill", (age, age_floor, windward_age, time, ratio, negative, left, refills, kept,
                                  revealed, pressed_born, pressed_left, has_depth, pressed))
    h.frame(tree, "Windward Rate", rate_nodes)
    h.frame(tree, "Variation", (noise, centred, variation, height))
    h.frame(tree, "Displacement", (displacement,))
    h.arrange(tree)


def _windward_rate(tree, wind):
    """(1 + 2 g)³, g = clamp(−N·wind / N_z, 0, tan repose), 0 in a calm: the twin's rate."""
    direction, wind_nodes = h.wind_direction(tree, wind)
    calm = wind_nodes[2]
    geometry = h.add_node(tree, "ShaderNodeNewGeometry", label="Ground Normal")
    facing = h.vector_math(tree, "DOT_PRODUCT", geometry.outputs["Normal"], direction, label="N · Wind")
    normal_parts = h.add_node(tree, "ShaderNodeSeparateXYZ", label="Normal Parts")
    h.link(tree, geometry.outputs["Normal"], normal_parts.inputs[0])
    up = h.math(tree, "MAXIMUM", normal_parts.outputs["Z"], 1e-3, label="N_z > 0")
    into = h.math(tree, "DIVIDE", facing.outputs["Value"], up.outputs[0], label="−Gradient Into Wind")
    rise = h.math(tree, "MULTIPLY", into.outputs[0], -1.0, label="Gradient Into Wind")
    windward = h.math(tree, "MAXIMUM", rise.outputs[0], 0.0, label="Windward Only")
    steepest = h.math(tree, "MINIMUM", windward.outputs[0], float(math.tan(REPOSE)), label="≤ Repose")
    windy = h.math(tree, "SUBTRACT", 1.0, calm.outputs[0], label="Windy")
    gradient = h.math(tree, "MULTIPLY", steepest.outputs[0], windy.outputs[0], label="Gradient (0 Calm)")
    speedup = h.add_node(tree, "ShaderNodeMath", label="1 + 2 g", operation="MULTIPLY_ADD",
                         inputs={1: WINDWARD_SPEEDUP, 2: 1.0})
    h.link(tree, gradient.outputs[0], speedup.inputs[0])
    cubed = h.math(tree, "POWER", speedup.outputs[0], 3.0, label="Rate = Speed-Up³")
    return cubed.outputs[0], (*wind_nodes, geometry, facing, normal_parts, up, into, rise, windward,
                              steepest, windy, gradient, speedup, cubed)
