"""Sandscape Cloud Density: the density of a cloud layer at the shading point (seed 001's model).

Height fraction h in the layer; the cloud type's height gradient (smoothstep(a, b, h) -
smoothstep(c, d, h), the four numbers blended from stratus to cumulus to cumulonimbus); a
Perlin-Worley shape noise times the gradient, remapped by the weather map's coverage; edges
eroded by a Worley fBm on a curl-like distorted position, wispy low and billowy at the top but
not at the base itself (flat bases), then sharpened so edges are crisp; precipitation makes it
denser; it fades out at the sides of the Region box. Every noise drifts with the wind, and the
shape leans downwind by Skew at the top. The same group builds in geometry nodes (GEOMETRY), where
the cloud grid evaluates it once per voxel. Twin: core.clouds.density.
"""

from ..core import clouds
from . import helper as h
from .weather_map import DRIFT_INPUTS, PLAIN_NOISE, drifted_position, seeded

NAME = "Sandscape Cloud Density"
VERSION = 3
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = "Density of a cloud layer from a weather map: height gradient by type, shape, erosion, wind"
INPUTS = {
    "Coverage": ("NodeSocketFloat", "The weather map's coverage here, 0..1", 1.0, 0.0, 1.0, "FACTOR"),
    "Precipitation": ("NodeSocketFloat", "The weather map's precipitation here, 0..1", 0.0, 0.0, 1.0,
                      "FACTOR"),
    "Type": ("NodeSocketFloat", "The weather map's cloud type here: 0 stratus, 0.5 cumulus, 1 cumulonimbus",
             0.5, 0.0, 1.0, "FACTOR"),
    "Base": ("NodeSocketFloat", "Altitude of the layer's bottom", 1500.0, None, None, "DISTANCE"),
    "Thickness": ("NodeSocketFloat", "Height of the layer", 2500.0, 1e-6, None, "DISTANCE"),
    "Density": ("NodeSocketFloat", "Extinction of the densest cloud, per unit length", 0.02, 0.0, None, None),
    "Shape Scale": ("NodeSocketFloat", "Size of the cloud shapes", 1200.0, 1e-3, None, "DISTANCE"),
    "Detail Scale": ("NodeSocketFloat", "Size of the eroded detail at the edges", 200.0, 1e-3, None,
                     "DISTANCE"),
    "Erosion": ("NodeSocketFloat", "How much the detail eats into the edges, 0..0.99", 0.35, 0.0, 0.99,
                "FACTOR"),
    "Curl": ("NodeSocketFloat", "Distortion of the detail, in detail cells at the top of the layer", 0.5,
             0.0, None, None),
    "Skew": ("NodeSocketFloat", "How far the tops lean downwind", 300.0, None, None, "DISTANCE"),
    "Region Min": ("NodeSocketVector", "Corner of the box the layer fills (x and y)", (-1e9, -1e9, 0.0),
                   None, None, "TRANSLATION"),
    "Region Max": ("NodeSocketVector", "Opposite corner of the box (x and y)", (1e9, 1e9, 0.0), None, None,
                   "TRANSLATION"),
    "Region Fade": ("NodeSocketFloat", "The density falls to zero over this distance inside the box's sides",
                    1.0, 1e-6, None, "DISTANCE"),
    **DRIFT_INPUTS,
}
OUTPUTS = {
    "Density": ("NodeSocketFloat", "Extinction per unit length: the Density of a Volume Scatter"),
    "Height Fraction": ("NodeSocketFloat", "0 at the layer's bottom, 1 at its top"),
    "Cloudiness": ("NodeSocketFloat", "Density over Density where positive (up to the wet factor), how far "
                   "from cloud where not: smooth across edges, what the cloud grid stores"),
}


def _smoothstep(tree, a, b, value, label):
    node = h.add_node(tree, "ShaderNodeMapRange", label=label, interpolation_type="SMOOTHSTEP")
    h.link(tree, value, node.inputs["Value"])
    for end, name in ((a, "From Min"), (b, "From Max")):
        if isinstance(end, float):
            node.inputs[name].default_value = end
        else:
            h.link(tree, end, node.inputs[name])
    return node


def _remap(tree, value, low, label):
    """Map Range low..1 -> 0..1, clamped (0 where low is 1)."""
    node = h.add_node(tree, "ShaderNodeMapRange", label=label)
    h.link(tree, value, node.inputs["Value"])
    if isinstance(low, float):
        node.inputs["From Min"].default_value = low
    else:
        h.link(tree, low, node.inputs["From Min"])
    return node


def _gradient(tree, cloud_type, height):
    """The type's (a, b, c, d), blended, and smoothstep(a, b, h) - smoothstep(c, d, h)."""
    names = ("STRATUS", "CUMULUS", "CUMULONIMBUS")
    first = h.math(tree, "MULTIPLY", cloud_type, 2.0, label="2 t")
    first.use_clamp = True
    second = h.math(tree, "MULTIPLY_ADD", cloud_type, 2.0, label="2 t − 1")
    second.inputs[2].default_value = -1.0
    second.use_clamp = True
    nodes = [first, second]
    numbers = []
    for index in range(4):
        values = [clouds.GRADIENTS[name][index] for name in names]
        low = h.add_node(tree, "ShaderNodeMix", label=f"Stratus → Cumulus {'abcd'[index]}", data_type="FLOAT")
        h.link(tree, first.outputs[0], h.socket(low.inputs, "Factor"))
        h.socket(low.inputs, "A").default_value = values[0]
        h.socket(low.inputs, "B").default_value = values[1]
        high = h.add_node(tree, "ShaderNodeMix", label=f"→ Cumulonimbus {'abcd'[index]}", data_type="FLOAT")
        h.link(tree, second.outputs[0], h.socket(high.inputs, "Factor"))
        h.link(tree, h.socket(low.outputs, "Result"), h.socket(high.inputs, "A"))
        h.socket(high.inputs, "B").default_value = values[2]
        numbers.append(h.socket(high.outputs, "Result"))
        nodes += [low, high]
    rise = _smoothstep(tree, numbers[0], numbers[1], height, "Rise: smoothstep(a, b, h)")
    fall = _smoothstep(tree, numbers[2], numbers[3], height, "Fall: smoothstep(c, d, h)")
    profile = h.math(tree, "SUBTRACT", rise.outputs["Result"], fall.outputs["Result"], label="Gradient")
    profile.use_clamp = True
    return profile.outputs[0], nodes + [rise, fall, profile]


def _region_window(tree, split, inputs):
    """smoothstep(0, fade, x - xmin) smoothstep(0, fade, xmax - x), the same in y (core.clouds.
    region_window). Returns (the window socket, the nodes made)."""
    low = h.add_node(tree, "ShaderNodeSeparateXYZ", label="Region Min")
    high = h.add_node(tree, "ShaderNodeSeparateXYZ", label="Region Max")
    h.link(tree, inputs["Region Min"], low.inputs[0])
    h.link(tree, inputs["Region Max"], high.inputs[0])
    nodes, window = [low, high], None
    for axis in ("X", "Y"):
        inside = h.math(tree, "SUBTRACT", split.outputs[axis], low.outputs[axis], label=f"{axis} − Min")
        before = h.math(tree, "SUBTRACT", high.outputs[axis], split.outputs[axis], label=f"Max − {axis}")
        nodes += [inside, before]
        for distance in (inside, before):
            ramp = _smoothstep(tree, 0.0, inputs["Region Fade"], distance.outputs[0], f"Fade at {axis}")
            nodes.append(ramp)
            if window is None:
                window = ramp.outputs["Result"]
            else:
                product = h.math(tree, "MULTIPLY", window, ramp.outputs["Result"], label="Window")
                nodes.append(product)
                window = product.outputs[0]
    return window, nodes


# This group built for geometry nodes (the cloud grid evaluates it per voxel).
GEOMETRY = h.GeometryBuilder(NAME, VERSION, DESCRIPTION, lambda tree: build(tree))


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, INPUTS, INPUTS, OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    drifted, drift_nodes = drifted_position(tree, inputs)

    position = h.position(tree)
    split = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, position.outputs["Position"], split.inputs[0])
    above = h.math(tree, "SUBTRACT", split.outputs["Z"], inputs["Base"], label="z − Base")
    fraction = h.math(tree, "DIVIDE", above.outputs[0], inputs["Thickness"], label="Height Fraction")
    fraction.use_clamp = True
    height = fraction.outputs[0]
    h.link(tree, height, group_out.inputs["Height Fraction"])
    profile, gradient_nodes = _gradient(tree, inputs["Type"], height)

    # Tops lean downwind: the noises are sampled Skew x h upwind (core.clouds.wind_direction).
    direction, direction_nodes = h.wind_direction(tree, inputs["Wind"])
    lean = h.math(tree, "MULTIPLY", inputs["Skew"], height, label="Skew × h")
    offset = h.vector_math(tree, "SCALE", direction, label="Lean")
    h.link(tree, lean.outputs[0], offset.inputs["Scale"])
    skewed = h.vector_math(tree, "SUBTRACT", drifted, offset.outputs[0], label="Skewed Position")
    skew_nodes = (*direction_nodes, lean, offset, skewed)

    shape_space, shape_space_nodes = seeded(tree, skewed.outputs[0], inputs["Shape Scale"], inputs["Seed"],
                                            label="Shape")
    perlin = h.add_node(tree, "ShaderNodeTexNoise", label="Perlin fBm", noise_dimensions="3D",
                        inputs={**PLAIN_NOISE, "Detail": clouds.SHAPE_DETAIL,
                                "Roughness": clouds.SHAPE_ROUGHNESS})
    h.link(tree, shape_space, perlin.inputs["Vector"])
    worley = h.add_node(tree, "ShaderNodeTexVoronoi", label="Worley", voronoi_dimensions="3D",
                        feature="F1", distance="EUCLIDEAN", inputs={"Scale": 2.0, "Detail": 0.0,
                                                                    "Randomness": 1.0})
    h.link(tree, shape_space, worley.inputs["Vector"])
    # remap(perlin, worley - 1, 1, 0, 1) with worley = 1 - F1: the low end is -F1.
    dilate_low = h.math(tree, "MULTIPLY", worley.outputs["Distance"], -1.0, label="Inverted Worley − 1")
    perlin_worley = _remap(tree, perlin.outputs["Fac"], dilate_low.outputs[0], "Perlin-Worley")
    shaped = h.math(tree, "MULTIPLY", perlin_worley.outputs["Result"], profile, label="Shape × Gradient")
    uncovered = h.math(tree, "SUBTRACT", 1.0, inputs["Coverage"], label="1 − Coverage")
    covered = _remap(tree, shaped.outputs[0], uncovered.outputs[0], "Remap by Coverage")
    with_cover = h.math(tree, "MULTIPLY", covered.outputs["Result"], inputs["Coverage"], label="× Coverage")

    detail_space, detail_space_nodes = seeded(tree, skewed.outputs[0], inputs["Detail Scale"], inputs["Seed"],
                                              label="Detail")
    quarter = h.vector_math(tree, "SCALE", detail_space, label="Detail / 4", Scale=0.25)
    moved = h.vector_math(tree, "ADD", quarter.outputs[0], tuple(clouds.CURL_OFFSET), label="+ Curl Offset")
    curl_a = h.add_node(tree, "ShaderNodeTexNoise", label="Curl X", noise_dimensions="3D",
                        inputs={**PLAIN_NOISE, "Detail": 0.0})
    curl_b = h.add_node(tree, "ShaderNodeTexNoise", label="Curl Y", noise_dimensions="3D",
                        inputs={**PLAIN_NOISE, "Detail": 0.0})
    h.link(tree, quarter.outputs[0], curl_a.inputs["Vector"])
    h.link(tree, moved.outputs[0], curl_b.inputs["Vector"])
    curl_vector = h.add_node(tree, "ShaderNodeCombineXYZ", label="Curl Offset")
    centred = []
    for noise_node, axis in ((curl_a, "X"), (curl_b, "Y")):
        centred.append(h.math(tree, "SUBTRACT", noise_node.outputs["Fac"], 0.5, label=f"{axis} − 0.5"))
        h.link(tree, centred[-1].outputs[0], curl_vector.inputs[axis])
    curl_amount = h.math(tree, "MULTIPLY", inputs["Curl"], height, label="Curl × h")
    curl_double = h.math(tree, "MULTIPLY", curl_amount.outputs[0], 2.0, label="× 2")
    curl_shift = h.vector_math(tree, "SCALE", curl_vector.outputs[0], label="Curl Shift")
    h.link(tree, curl_double.outputs[0], curl_shift.inputs["Scale"])
    distorted = h.vector_math(tree, "ADD", detail_space, curl_shift.outputs[0], label="Distorted")
    detail_nodes = [quarter, moved, curl_a, curl_b, *centred, curl_vector, curl_amount, curl_double,
                    curl_shift, distorted]
    detail = None
    for octave, weight in enumerate(clouds.DETAIL_WEIGHTS):
        cells = h.add_node(tree, "ShaderNodeTexVoronoi", label=f"Worley Octave {octave + 1}",
                           voronoi_dimensions="3D", feature="F1", distance="EUCLIDEAN",
                           inputs={"Scale": 2.0 ** octave, "Detail": 0.0, "Randomness": 1.0})
        h.link(tree, distorted.outputs[0], cells.inputs["Vector"])
        # weight x (1 - F1) = weight - weight x F1
        term = h.math(tree, "MULTIPLY_ADD", cells.outputs["Distance"], -weight, label=f"{weight} (1 − F1)")
        term.inputs[2].default_value = weight
        detail_nodes += [cells, term]
        if detail is None:
            detail = term.outputs[0]
        else:
            total = h.math(tree, "ADD", detail, term.outputs[0], label="Worley fBm")
            detail_nodes.append(total)
            detail = total.outputs[0]
    # Wispy low (1 - detail), billowy at the top (detail): mix by sat(10 h), which also lets the
    # erosion in from none at the base.
    top_share = h.math(tree, "MULTIPLY", height, clouds.BASE_CALM, label="sat(10 h)")
    top_share.use_clamp = True
    inverted = h.math(tree, "SUBTRACT", 1.0, detail, label="1 − Detail")
    modifier = h.add_node(tree, "ShaderNodeMix", label="Wispy → Billowy", data_type="FLOAT")
    h.link(tree, top_share.outputs[0], h.socket(modifier.inputs, "Factor"))
    h.link(tree, inverted.outputs[0], h.socket(modifier.inputs, "A"))
    h.link(tree, detail, h.socket(modifier.inputs, "B"))
    eroding = h.math(tree, "MULTIPLY", h.socket(modifier.outputs, "Result"), inputs["Erosion"],
                     label="Modifier × Erosion")
    erosion_low = h.math(tree, "MULTIPLY", eroding.outputs[0], top_share.outputs[0], label="None at the Base")
    eroded = _remap(tree, with_cover.outputs[0], erosion_low.outputs[0], "Erode Edges")
    eroded.clamp = False  # signed: how far from cloud, so a grid of it interpolates smoothly
    window, window_nodes = _region_window(tree, split, inputs)
    faded = h.math(tree, "MULTIPLY", eroded.outputs["Result"], window, label="Within the Region")
    crisp = h.add_node(tree, "ShaderNodeClamp", label="Crisp Edges: Gain, Clamped Far Out",
                       inputs={"Min": -clouds.CLOUDINESS_RANGE, "Max": clouds.CLOUDINESS_RANGE})
    gained = h.math(tree, "MULTIPLY", faded.outputs[0], clouds.EDGE_GAIN, label="× Edge Gain")
    h.link(tree, gained.outputs[0], crisp.inputs["Value"])
    wet = h.math(tree, "MULTIPLY_ADD", inputs["Precipitation"], clouds.PRECIPITATION_GAIN,
                 label="1 + Gain × Precipitation")
    wet.inputs[2].default_value = 1.0
    cloudiness = h.math(tree, "MULTIPLY", crisp.outputs[0], wet.outputs[0], label="Cloudiness")
    h.link(tree, cloudiness.outputs[0], group_out.inputs["Cloudiness"])
    positive = h.add_node(tree, "ShaderNodeClamp", label="Where Cloud: 0..Wet")
    h.link(tree, cloudiness.outputs[0], positive.inputs["Value"])
    h.link(tree, wet.outputs[0], positive.inputs["Max"])
    result = h.math(tree, "MULTIPLY", positive.outputs[0], inputs["Density"], label="Density")
    h.link(tree, result.outputs[0], group_out.inputs["Density"])

    h.frame(tree, "Carried by the Wind", drift_nodes)
    h.frame(tree, "Height in the Layer", (position, split, above, fraction))
    h.frame(tree, "Type's Height Gradient", gradient_nodes)
    h.frame(tree, "Tops Lean Downwind", skew_nodes)
    h.frame(tree, "Shape", (*shape_space_nodes, perlin, worley, dilate_low, perlin_worley, shaped, uncovered,
                            covered, with_cover))
    h.frame(tree, "Eroded Edges", (*detail_space_nodes, *detail_nodes, top_share, inverted, modifier,
                                   eroding, erosion_low, eroded))
    h.frame(tree, "Fades Out in Its Box", (*window_nodes, faded))
    h.frame(tree, "Density", (gained, crisp, wet, cloudiness, positive, result))
    h.arrange(tree)
