"""Sandscape Weather Map: where clouds are, how wet and of which type, over the ground.

Coverage: a 2D fBm noise over the ground (drifting with the wind, looked up at a warped
position so outlines are ragged), 0 below an edge rising to 1 above it; the edge comes from the
Coverage input by a fit to the noise's own quantiles, so that Coverage is the share of the sky
under cloud. Precipitation is passed on; Type is the given type, or with Mixed Types a slower
noise over the ground. The channels are those of a painted weather map (red coverage, green
precipitation, blue type), so an image can replace this group. It builds in geometry nodes too
(GEOMETRY), for the cloud grid. Twin: core.clouds (weather_noise, map_coverage, mixed_type).
"""

import math

from ..core import clouds
from . import helper as h

NAME = "Sandscape Weather Map"
VERSION = 3
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = "Procedural weather map for the cloud layer: coverage, precipitation and cloud type"
# Inputs every cloud group shares: its pattern's seed, and where the wind has carried it by now.
DRIFT_INPUTS = {
    "Seed": ("NodeSocketFloat", "Another seed, another sky", 0.0, None, None, None),
    "Wind": ("NodeSocketVector", "Wind velocity, per second: the clouds drift with it", (3.0, 1.0, 0.0),
             None, None, "VELOCITY"),
    "Frame": ("NodeSocketFloat", "Current frame (driven by 'frame')", 1.0, None, None, None),
    "FPS": ("NodeSocketFloat", "Frames per second of the scene", 24.0, 1e-3, None, None),
}
# Noise Texture inputs that make it the plain Perlin fBm of core.noise_perlin.fbm.
PLAIN_NOISE = {"Scale": 1.0, "Roughness": 0.5, "Lacunarity": 2.0, "Distortion": 0.0}
INPUTS = {
    "Coverage": ("NodeSocketFloat", "Share of the sky under cloud, 0..1", 0.5, 0.0, 1.0, "FACTOR"),
    "Precipitation": ("NodeSocketFloat", "Rain in the clouds, 0..1: denser and darker", 0.0, 0.0, 1.0,
                      "FACTOR"),
    "Type": ("NodeSocketFloat", "Cloud type: 0 stratus, 0.5 cumulus, 1 cumulonimbus", 0.5, 0.0, 1.0,
             "FACTOR"),
    "Mixed Types": ("NodeSocketFloat", "1: the type varies over the ground (Type is ignored); 0: Type "
                    "everywhere", 0.0, 0.0, 1.0, "FACTOR"),
    "Map Scale": ("NodeSocketFloat", "Size of the weather features: one noise cell", 6000.0, 1e-3, None,
                  "DISTANCE"),
    **DRIFT_INPUTS,
}
OUTPUTS = {
    "Coverage": ("NodeSocketFloat", "Cloud here, 0..1 (red of a painted map)"),
    "Precipitation": ("NodeSocketFloat", "Precipitation here, 0..1 (green)"),
    "Type": ("NodeSocketFloat", "Cloud type here, 0..1 (blue)"),
}


def drifted_position(tree, inputs):
    """World position minus wind x time: where the air now here was at frame 0. Returns
    (socket, nodes)."""
    position = h.position(tree)
    time = h.math(tree, "DIVIDE", inputs["Frame"], inputs["FPS"], label="Time (s)")
    carried = h.vector_math(tree, "SCALE", inputs["Wind"], label="Wind × Time")
    h.link(tree, time.outputs[0], carried.inputs["Scale"])
    drifted = h.vector_math(tree, "SUBTRACT", position.outputs["Position"], carried.outputs[0],
                            label="Position − Drift")
    return drifted.outputs[0], (position, time, carried, drifted)


def seeded(tree, point, scale, seed, extra=0.0, label="Noise Space"):
    """point / scale + seed x SEED_STEP (+ extra on every axis): a noise's own space."""
    scaled = h.vector_math(tree, "DIVIDE", point, None, label=f"÷ {label} Scale")
    h.link(tree, scale, scaled.inputs[1])
    offset = h.vector_math(tree, "SCALE", tuple(clouds.SEED_STEP), label="Seed Offset")
    h.link(tree, seed, offset.inputs["Scale"])
    moved = h.vector_math(tree, "ADD", scaled.outputs[0], offset.outputs[0], label=label)
    nodes = [scaled, offset, moved]
    if extra:
        shifted = h.vector_math(tree, "ADD", moved.outputs[0], (extra,) * 3, label=f"{label} + {extra}")
        nodes.append(shifted)
    return nodes[-1].outputs[0], nodes


def _warp(tree, map_space):
    """map_space + WARP x (fBm - 0.5 in x, in y) (core.clouds.weather_noise). Returns (socket, nodes)."""
    shift = h.add_node(tree, "ShaderNodeCombineXYZ", label="Warp")
    nodes = [shift]
    for axis, offset in zip(("X", "Y"), clouds.WARP_OFFSETS, strict=True):
        moved = h.vector_math(tree, "MULTIPLY_ADD", map_space, (clouds.WARP_FREQUENCY,) * 3,
                              label=f"Warp Space {axis}")
        moved.inputs[2].default_value = (offset,) * 3
        warp = h.add_node(tree, "ShaderNodeTexNoise", label=f"Warp {axis}", noise_dimensions="2D",
                          inputs={**PLAIN_NOISE, "Detail": clouds.WARP_DETAIL,
                                  "Roughness": clouds.WARP_ROUGHNESS})
        h.link(tree, moved.outputs[0], warp.inputs["Vector"])
        centred = h.math(tree, "SUBTRACT", warp.outputs["Fac"], 0.5, label=f"{axis} − 0.5")
        h.link(tree, centred.outputs[0], shift.inputs[axis])
        nodes += [moved, warp, centred]
    scaled = h.vector_math(tree, "MULTIPLY_ADD", shift.outputs[0], (clouds.WARP,) * 3, label="Warped Map")
    h.link(tree, map_space, scaled.inputs[2])
    return scaled.outputs[0], nodes + [scaled]


# This group built for geometry nodes (the cloud grid evaluates it per voxel).
GEOMETRY = h.GeometryBuilder(NAME, VERSION, DESCRIPTION, lambda tree: build(tree))


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, INPUTS, INPUTS, OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    drifted, drift_nodes = drifted_position(tree, inputs)

    map_space, map_nodes = seeded(tree, drifted, inputs["Map Scale"], inputs["Seed"], label="Map")
    warped, warp_nodes = _warp(tree, map_space)
    weather = h.add_node(tree, "ShaderNodeTexNoise", label="Weather Noise", noise_dimensions="2D",
                         inputs={**PLAIN_NOISE, "Detail": clouds.MAP_DETAIL})
    h.link(tree, warped, weather.inputs["Vector"])
    # edge = c0 + c1 L + c3 L^3 - shift, L = ln((1 - c) / c), c kept where the fit is monotone;
    # +-10 at coverage 0 and 1 (core.clouds.coverage_edge, map_coverage).
    kept = h.add_node(tree, "ShaderNodeClamp", label="Coverage in Fit Range",
                      inputs={"Min": clouds.EDGE_RANGE[0], "Max": clouds.EDGE_RANGE[1]})
    h.link(tree, inputs["Coverage"], kept.inputs["Value"])
    clear = h.math(tree, "SUBTRACT", 1.0, kept.outputs[0], label="1 − c")
    odds = h.math(tree, "DIVIDE", clear.outputs[0], kept.outputs[0], label="(1 − c) / c")
    log_odds = h.math(tree, "LOGARITHM", odds.outputs[0], math.e, label="L = ln")
    cube = h.math(tree, "POWER", log_odds.outputs[0], 3.0, label="L³")
    cubic = h.math(tree, "MULTIPLY", cube.outputs[0], clouds.EDGE_FIT[2], label="c3 L³")
    linear = h.math(tree, "MULTIPLY_ADD", log_odds.outputs[0], clouds.EDGE_FIT[1], label="c1 L + c0")
    linear.inputs[2].default_value = clouds.EDGE_FIT[0] - clouds.OPAQUE_SHIFT
    fitted = h.math(tree, "ADD", linear.outputs[0], cubic.outputs[0], label="Fitted Edge")
    none = h.math(tree, "LESS_THAN", inputs["Coverage"], 1e-30, label="Coverage 0")
    full = h.math(tree, "GREATER_THAN", inputs["Coverage"], 1.0 - 1e-7, label="Coverage 1")
    extremes = h.math(tree, "SUBTRACT", none.outputs[0], full.outputs[0], label="None − All")
    edge = h.math(tree, "MULTIPLY_ADD", extremes.outputs[0], 10.0, label="Edge")
    h.link(tree, fitted.outputs[0], edge.inputs[2])
    edge_top = h.math(tree, "ADD", edge.outputs[0], clouds.MAP_SOFTNESS, label="Edge + Softness")
    cover = h.add_node(tree, "ShaderNodeMapRange", label="Coverage Ramp", interpolation_type="SMOOTHSTEP")
    h.link(tree, weather.outputs["Fac"], cover.inputs["Value"])
    h.link(tree, edge.outputs[0], cover.inputs["From Min"])
    h.link(tree, edge_top.outputs[0], cover.inputs["From Max"])
    h.link(tree, cover.outputs["Result"], group_out.inputs["Coverage"])
    h.link(tree, inputs["Precipitation"], group_out.inputs["Precipitation"])

    type_scale = h.math(tree, "MULTIPLY", inputs["Map Scale"], clouds.TYPE_MAP_SCALE, label="Type Map Scale")
    type_space, type_nodes = seeded(tree, drifted, type_scale.outputs[0], inputs["Seed"], 5.5, "Type Map")
    type_noise = h.add_node(tree, "ShaderNodeTexNoise", label="Type Noise", noise_dimensions="2D",
                            inputs={**PLAIN_NOISE, "Detail": 1.0})
    h.link(tree, type_space, type_noise.inputs["Vector"])
    stretched = h.add_node(tree, "ShaderNodeMapRange", label="0.3..0.7 → 0..1",
                           inputs={"From Min": 0.3, "From Max": 0.7})
    h.link(tree, type_noise.outputs["Fac"], stretched.inputs["Value"])
    chosen = h.add_node(tree, "ShaderNodeMix", label="Type or Mixed", data_type="FLOAT")
    h.link(tree, inputs["Mixed Types"], h.socket(chosen.inputs, "Factor"))
    h.link(tree, inputs["Type"], h.socket(chosen.inputs, "A"))
    h.link(tree, stretched.outputs["Result"], h.socket(chosen.inputs, "B"))
    h.link(tree, h.socket(chosen.outputs, "Result"), group_out.inputs["Type"])

    h.frame(tree, "Carried by the Wind", drift_nodes)
    h.frame(tree, "Ragged Outlines", warp_nodes)
    h.frame(tree, "Coverage", (*map_nodes, weather, kept, clear, odds, log_odds, cube, cubic, linear, fitted,
                                 none, full, extremes, edge, edge_top, cover))
    h.frame(tree, "Cloud Type", (type_scale, *type_nodes, type_noise, stretched, chosen))
    h.arrange(tree)
