"""Sandscape Ripple Defects: one lattice of dislocation pairs in the wind ripples.

Real ripple crests split and end: a crest begins at one Y-junction and ends at another. A cell
of the lattice (DEFECT_CELL wavelengths, shifted by Offset cells) whose noise is under Share holds
such a pair: two phase vortices of opposite sign a random length apart along the crests. Their
phase, the angle between the directions to the two cores, jumps by exactly 2 pi between them (the
inserted crest; the sine does not see the jump) and fades to nothing inside the cell, so cells
join without a seam. Keep flattens the ripples toward each core, where the phase has no slope to
give. Outputs the phase, its gradient, Keep and its gradient. Twin: core.sand.ripple_defects.
"""

from ..core import sand as twin
from . import helper as h

NAME = "Sandscape Ripple Defects"
VERSION = 2  # 2: 8-wavelength cells, shorter inserted crests (1: 11)
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Ripple crests that split and end: one lattice of dislocation pairs as a phase to add "
               "to the ripples' and a share of their height kept")
UP = (0.0, 0.0, 1.0)


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Position", "NodeSocketVector", "World position (only its horizontal part counts)",
                (0.0, 0.0, 0.0))
    h.add_input(tree, "Direction", "NodeSocketVector", "Unit horizontal wind direction", (1.0, 0.0, 0.0))
    h.add_input(tree, "Wavelength", "NodeSocketFloat", "Distance from crest to crest", 0.12, 1e-4, None,
                "DISTANCE")
    h.add_input(tree, "Share", "NodeSocketFloat", "Share of the lattice's cells holding a pair", 0.9,
                0.0, 1.0, "FACTOR")
    h.add_input(tree, "Offset", "NodeSocketFloat", "Shift of the lattice, in cells", 0.0)
    h.add_input(tree, "Layer", "NodeSocketFloat", "The noise's layer: another lattice, other pairs", 2.0)
    h.add_output(tree, "Phase", "NodeSocketFloat", "Phase to add to the ripples' (radians)")
    h.add_output(tree, "Phase Gradient", "NodeSocketVector", "The phase's horizontal gradient")
    h.add_output(tree, "Keep", "NodeSocketFloat", "Share of the ripples' height kept (0 at a core)")
    h.add_output(tree, "Keep Gradient", "NodeSocketVector", "Keep's horizontal gradient")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    wavelength = inputs["Wavelength"]

    pair, pair_nodes = _pair(tree, inputs)
    centre, share_cut, sign, half = pair["centre"], pair["present"], pair["sign"], pair["half"]
    position = h.vector_math(tree, "MULTIPLY", inputs["Position"], (1.0, 1.0, 0.0), label="Horizontal")
    e = h.vector_math(tree, "SUBTRACT", position.outputs[0], centre, label="From the Centre")
    along = h.vector_math(tree, "CROSS_PRODUCT", UP, inputs["Direction"], label="Along the Crests")
    reach = h.vector_math(tree, "SCALE", along.outputs[0], label="Half × Along")
    h.link(tree, half, reach.inputs["Scale"])
    u = h.vector_math(tree, "SUBTRACT", e.outputs[0], reach.outputs[0], label="From Core A")
    v = h.vector_math(tree, "ADD", e.outputs[0], reach.outputs[0], label="From Core B")
    cross = h.vector_math(tree, "CROSS_PRODUCT", u.outputs[0], v.outputs[0], label="u × v")
    cross_z = h.add_node(tree, "ShaderNodeSeparateXYZ", label="(u × v).z")
    h.link(tree, cross.outputs[0], cross_z.inputs[0])
    dot = h.vector_math(tree, "DOT_PRODUCT", u.outputs[0], v.outputs[0], label="u . v")
    angle = h.math(tree, "ARCTAN2", cross_z.outputs["Z"], dot.outputs["Value"], label="Angle from u to v")
    geometry = [position, e, along, reach, u, v, cross, cross_z, dot, angle]

    # The pair's phase, whole inside DEFECT_REACH[0] wavelengths, gone at DEFECT_REACH[1].
    low, high = twin.DEFECT_REACH
    distance = h.vector_math(tree, "LENGTH", e.outputs[0], label="|e|")
    in_waves = h.math(tree, "DIVIDE", distance.outputs["Value"], wavelength, label="|e| ÷ Wavelength")
    t = h.add_node(tree, "ShaderNodeMapRange", label="Fading", inputs={"From Min": low, "From Max": high})
    h.link(tree, in_waves.outputs[0], t.inputs["Value"])
    whole = h.add_node(tree, "ShaderNodeMapRange", label="Whole", interpolation_type="SMOOTHSTEP",
                       inputs={"To Min": 1.0, "To Max": 0.0})
    h.link(tree, t.outputs["Result"], whole.inputs["Value"])
    rest = h.math(tree, "SUBTRACT", 1.0, t.outputs["Result"], label="1 − t")
    bell = h.math(tree, "MULTIPLY", t.outputs["Result"], rest.outputs[0], label="t (1 − t)")
    rate = h.math(tree, "MULTIPLY", bell.outputs[0], -6.0 / (high - low), label="dWhole / d(|e| ÷ λ)")
    fading = h.math(tree, "DIVIDE", rate.outputs[0], wavelength, label="dWhole / d|e|")
    faded = h.math(tree, "MULTIPLY", angle.outputs[0], whole.outputs["Result"], label="Angle × Whole")
    phase = h.math(tree, "MULTIPLY", faded.outputs[0], sign, label="Phase")
    fade_nodes = [distance, in_waves, t, whole, rest, bell, rate, fading, faded, phase]

    swirl_u, u_nodes = _swirl(tree, u.outputs[0], "u")
    swirl_v, v_nodes = _swirl(tree, v.outputs[0], "v")
    swirls = h.vector_math(tree, "SUBTRACT", swirl_v, swirl_u, label="∇Angle")
    inside = h.vector_math(tree, "SCALE", swirls.outputs[0], label="× Whole")
    h.link(tree, whole.outputs["Result"], inside.inputs["Scale"])
    radial = h.vector_math(tree, "NORMALIZE", e.outputs[0], label="Outward")
    edge_rate = h.math(tree, "MULTIPLY", angle.outputs[0], fading.outputs[0], label="Angle × dWhole")
    edge = h.vector_math(tree, "SCALE", radial.outputs[0], label="Angle ∇Whole")
    h.link(tree, edge_rate.outputs[0], edge.inputs["Scale"])
    both = h.vector_math(tree, "ADD", inside.outputs[0], edge.outputs[0], label="∇(Angle × Whole)")
    gradient = h.vector_math(tree, "SCALE", both.outputs[0], label="Phase Gradient")
    h.link(tree, sign, gradient.inputs["Scale"])
    gradient_nodes = [*u_nodes, *v_nodes, swirls, inside, radial, edge_rate, edge, both, gradient]

    core_reach = h.math(tree, "MULTIPLY", wavelength, twin.DEFECT_CORE, label="Core Reach")
    kept_u, slope_u, ku_nodes = _flattening(tree, u.outputs[0], core_reach.outputs[0], share_cut, "A")
    kept_v, slope_v, kv_nodes = _flattening(tree, v.outputs[0], core_reach.outputs[0], share_cut, "B")
    keep = h.math(tree, "MULTIPLY", kept_u, kept_v, label="Keep")
    part_u = h.vector_math(tree, "SCALE", slope_u, label="∇Kept A × Kept B")
    h.link(tree, kept_v, part_u.inputs["Scale"])
    part_v = h.vector_math(tree, "SCALE", slope_v, label="∇Kept B × Kept A")
    h.link(tree, kept_u, part_v.inputs["Scale"])
    keep_gradient = h.vector_math(tree, "ADD", part_u.outputs[0], part_v.outputs[0], label="Keep Gradient")
    keep_nodes = [core_reach, *ku_nodes, *kv_nodes, keep, part_u, part_v, keep_gradient]

    h.link(tree, phase.outputs[0], group_out.inputs["Phase"])
    h.link(tree, gradient.outputs[0], group_out.inputs["Phase Gradient"])
    h.link(tree, keep.outputs[0], group_out.inputs["Keep"])
    h.link(tree, keep_gradient.outputs[0], group_out.inputs["Keep Gradient"])
    h.frame(tree, "The Cell's Pair", pair_nodes)
    h.frame(tree, "Angle between the Cores", geometry)
    h.frame(tree, "Faded inside the Cell", fade_nodes)
    h.frame(tree, "Phase Gradient", gradient_nodes)
    h.frame(tree, "Flattened toward the Cores", keep_nodes)
    h.arrange(tree)


def _pair(tree, inputs):
    """The cell's pair: its centre, present (0 or 1), sign (0 or +-1) and half length, as sockets
    in a dict, and the nodes made."""
    wavelength = inputs["Wavelength"]
    size = h.math(tree, "MULTIPLY", wavelength, twin.DEFECT_CELL, label="Cell Size")
    inverse = h.math(tree, "DIVIDE", 1.0, size.outputs[0], label="1 / Cell Size")
    flat = h.vector_math(tree, "MULTIPLY", inputs["Position"], (1.0, 1.0, 0.0), label="Horizontal")
    scaled = h.vector_math(tree, "SCALE", flat.outputs[0], label="In Cells")
    h.link(tree, inverse.outputs[0], scaled.inputs["Scale"])
    offset = h.add_node(tree, "ShaderNodeCombineXYZ", label="Offset")
    h.link(tree, inputs["Offset"], offset.inputs["X"])
    h.link(tree, inputs["Offset"], offset.inputs["Y"])
    shifted = h.vector_math(tree, "ADD", scaled.outputs[0], offset.outputs[0], label="Shifted")
    cell = h.vector_math(tree, "FLOOR", shifted.outputs[0], label="Cell")
    layer = h.add_node(tree, "ShaderNodeCombineXYZ", label="Layer")
    h.link(tree, inputs["Layer"], layer.inputs["Z"])
    key = h.vector_math(tree, "ADD", cell.outputs[0], layer.outputs[0], label="Cell, Layer")
    noise = h.add_node(tree, "ShaderNodeTexWhiteNoise", label="Pair Noise", noise_dimensions="3D")
    h.link(tree, key.outputs[0], noise.inputs["Vector"])
    colour = h.add_node(tree, "ShaderNodeSeparateColor", label="Jitter")
    h.link(tree, noise.outputs["Color"], colour.inputs["Color"])
    jitter = h.add_node(tree, "ShaderNodeCombineXYZ", label="Jitter (G, B)")
    h.link(tree, colour.outputs["Green"], jitter.inputs["X"])
    h.link(tree, colour.outputs["Blue"], jitter.inputs["Y"])
    centred = h.vector_math(tree, "SUBTRACT", jitter.outputs[0], (0.5, 0.5, 0.0), label="Jitter − ½")
    stray = h.math(tree, "MULTIPLY", wavelength, 2.0 * twin.DEFECT_JITTER, label="2 × Jitter × λ")
    moved = h.vector_math(tree, "SCALE", centred.outputs[0], label="Stray")
    h.link(tree, stray.outputs[0], moved.inputs["Scale"])
    unshifted = h.vector_math(tree, "SUBTRACT", cell.outputs[0], offset.outputs[0], label="Cell − Offset")
    middle = h.vector_math(tree, "ADD", unshifted.outputs[0], (0.5, 0.5, 0.0), label="Cell's Middle")
    placed = h.vector_math(tree, "SCALE", middle.outputs[0], label="× Cell Size")
    h.link(tree, size.outputs[0], placed.inputs["Scale"])
    centre = h.vector_math(tree, "ADD", placed.outputs[0], moved.outputs[0], label="Centre")

    value = noise.outputs["Value"]
    present = h.math(tree, "LESS_THAN", value, inputs["Share"], label="Present")
    draw = h.math(tree, "DIVIDE", value, inputs["Share"], label="Draw")
    first_half = h.math(tree, "LESS_THAN", draw.outputs[0], 0.5, label="Draw < ½")
    turn = h.math(tree, "MULTIPLY_ADD", first_half.outputs[0], -2.0, label="±1", c=1.0)
    sign = h.math(tree, "MULTIPLY", turn.outputs[0], present.outputs[0], label="Sign")
    doubled = h.math(tree, "MULTIPLY", draw.outputs[0], 2.0, label="2 Draw")
    fraction = h.math(tree, "FRACT", doubled.outputs[0], label="Length Draw")
    low, high = twin.DEFECT_HALF
    in_waves = h.math(tree, "MULTIPLY_ADD", fraction.outputs[0], high - low, label="Half Length ÷ λ", c=low)
    half = h.math(tree, "MULTIPLY", in_waves.outputs[0], wavelength, label="Half Length")
    nodes = (size, inverse, flat, scaled, offset, shifted, cell, layer, key, noise, colour, jitter, centred,
             stray, moved, unshifted, middle, placed, centre, present, draw, first_half, turn, sign, doubled,
             fraction, in_waves, half)
    return ({"centre": centre.outputs[0], "present": present.outputs[0], "sign": sign.outputs[0],
             "half": half.outputs[0]}, nodes)


def _swirl(tree, w, name):
    """The gradient of w's direction: perp(w) / |w|^2 (a vortex about its core)."""
    perp = h.vector_math(tree, "CROSS_PRODUCT", UP, w, label=f"perp({name})")
    square = h.vector_math(tree, "DOT_PRODUCT", w, w, label=f"|{name}|²")
    inverse = h.math(tree, "DIVIDE", 1.0, square.outputs["Value"], label=f"1 / |{name}|²")
    swirl = h.vector_math(tree, "SCALE", perp.outputs[0], label=f"∇ Direction of {name}")
    h.link(tree, inverse.outputs[0], swirl.inputs["Scale"])
    return swirl.outputs[0], (perp, square, inverse, swirl)


def _flattening(tree, w, reach, present, name):
    """(kept, its gradient, nodes): smoothstep from 0 at the core to 1 at Core Reach; 1 where the
    cell holds no pair."""
    distance = h.vector_math(tree, "LENGTH", w, label=f"To Core {name}")
    t = h.add_node(tree, "ShaderNodeMapRange", label=f"Near Core {name}")
    h.link(tree, distance.outputs["Value"], t.inputs["Value"])
    h.link(tree, reach, t.inputs["From Max"])
    smooth = h.add_node(tree, "ShaderNodeMapRange", label=f"Smoothstep {name}",
                        interpolation_type="SMOOTHSTEP")
    h.link(tree, t.outputs["Result"], smooth.inputs["Value"])
    lost = h.math(tree, "SUBTRACT", smooth.outputs["Result"], 1.0, label=f"Kept {name} − 1")
    kept = h.math(tree, "MULTIPLY_ADD", present, lost.outputs[0], label=f"Kept {name}", c=1.0)
    rest = h.math(tree, "SUBTRACT", 1.0, t.outputs["Result"], label="1 − t")
    bell = h.math(tree, "MULTIPLY", t.outputs["Result"], rest.outputs[0], label="t (1 − t)")
    rate = h.math(tree, "MULTIPLY", bell.outputs[0], 6.0, label="6 t (1 − t)")
    per_length = h.math(tree, "DIVIDE", rate.outputs[0], reach, label="÷ Core Reach")
    slope = h.math(tree, "MULTIPLY", per_length.outputs[0], present, label=f"Slope {name}")
    outward = h.vector_math(tree, "NORMALIZE", w, label=f"Away from Core {name}")
    gradient = h.vector_math(tree, "SCALE", outward.outputs[0], label=f"∇Kept {name}")
    h.link(tree, slope.outputs[0], gradient.inputs["Scale"])
    nodes = (distance, t, smooth, lost, kept, rest, bell, rate, per_length, slope, outward, gradient)
    return kept.outputs[0], gradient.outputs[0], nodes
