"""Sandscape Ripples: wind ripples on the sand, as a height and a shading normal.

Crests run across the wind and wander: phase = 2 pi ((p . wind) / Wavelength + Meander (2 m - 1)),
p the world position, wind the horizontal wind direction and m a smooth value noise on a lattice
of Meander Scale (so crests bend, join and split as real ones do, rather than ruling the sand
like corduroy), plus the pairs of Y-junctions of four Ripple Defects lattices in Defects of their
cells (a crest inserted between each pair); height = Amplitude x weight x (1 - Variation g) x
(1 - Flatten) x keep x sin(phase), g a second value of the same noise, Flatten 1 where a foot
trampled them, keep the defects' flattening toward their cores. The weight fades the
ripples on steep slopes (Steep Fraction at the 35 degree angle of repose) and on slopes turned
away from the wind (down to Lee Fraction), as seed 004 blends its ripple textures by slope and
direction. The normal tilts by the height's
gradient through the phase. Twin: core.sand.ripples.
"""

import math

from ..core import sand
from . import helper as h
from . import ripple_defects

NAME = "Sandscape Ripples"
VERSION = 5  # 5: four defect lattices (two left 5 crest ends per 1000 px of crest, the seventh review)
TREE_TYPE = "ShaderNodeTree"
WAVELENGTH, AMPLITUDE = 0.12, 0.004  # metres: ripples of fine sand
MEANDER_SCALE = 0.8  # metres: about 7 wavelengths between one bend of a crest and the next
MEANDER, VARIATION = 0.8, 0.5  # 0.35 ruled the sand like corduroy in the demo (the fourth review)
DEFECTS = 0.9  # share of the defect lattices' cells where a crest splits and ends
DESCRIPTION = ("Wind ripples: crests across the wind, Wavelength apart, fading on steep and lee slopes; "
               "a height and the rippled normal")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Wind", "NodeSocketVector", "Wind velocity (only its horizontal direction counts)",
                (3.0, 1.0, 0.0))
    h.add_input(tree, "Wavelength", "NodeSocketFloat", "Distance from crest to crest (sand: 5 to 20 cm)",
                WAVELENGTH, 1e-4, None, "DISTANCE")
    h.add_input(tree, "Amplitude", "NodeSocketFloat", "Height of a crest above the mean", AMPLITUDE, 0.0,
                None, "DISTANCE")
    h.add_input(tree, "Steep Fraction", "NodeSocketFloat", "Share of the ripples kept on a 35 degree slope",
                0.2, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Lee Fraction", "NodeSocketFloat", "Share kept on a slope turned away from the wind",
                0.3, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Normal", "NodeSocketVector", "Surface normal (unlinked: the shading normal)",
                (0.0, 0.0, 0.0), subtype=h.SURFACE_NORMAL)
    h.add_input(tree, "Meander", "NodeSocketFloat", "How far crests wander, in wavelengths: 0 gives "
                "straight parallel crests", MEANDER, 0.0, 4.0)
    h.add_input(tree, "Meander Scale", "NodeSocketFloat", "Distance over which a crest bends one way and "
                "back", MEANDER_SCALE, 1e-4, None, "DISTANCE")
    h.add_input(tree, "Variation", "NodeSocketFloat", "How much the ripples' height varies from place to "
                "place: 0 keeps Amplitude everywhere", VARIATION, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Defects", "NodeSocketFloat", "Share of places where a crest splits in two and "
                "ends (Y-junctions): 0 gives unbroken crests", DEFECTS, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Flatten", "NodeSocketFloat", "Share of the ripples flattened here: a footprint's "
                "Pressed (a foot tramples the ripples it lands on)", 0.0, 0.0, 1.0, "FACTOR")
    h.add_output(tree, "Height", "NodeSocketFloat", "Ripple height above the surface")
    h.add_output(tree, "Normal", "NodeSocketVector", "The rippled normal")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    normal, normal_nodes = h.normal_or_geometry(tree, inputs["Normal"])

    # No wind: crests along Y, as under a wind along X.
    direction, direction_nodes = h.wind_direction(tree, inputs["Wind"])

    position = h.add_node(tree, "ShaderNodeNewGeometry")
    along = h.vector_math(tree, "DOT_PRODUCT", position.outputs["Position"], direction,
                          label="Distance along the Wind")
    cycles = h.math(tree, "DIVIDE", along.outputs["Value"], inputs["Wavelength"], label="÷ Wavelength")
    straight = h.math(tree, "MULTIPLY", cycles.outputs[0], 2 * math.pi, label="Straight Phase")
    lattice, lattice_nodes = _lattice_noise(tree, position.outputs["Position"], inputs["Meander Scale"])
    meander_radians = h.math(tree, "MULTIPLY", inputs["Meander"], 2 * math.pi, label="Meander × 2π")
    centred = h.math(tree, "MULTIPLY_ADD", lattice["m"], 2.0, label="2 m − 1")
    centred.inputs[2].default_value = -1.0
    shift = h.math(tree, "MULTIPLY", centred.outputs[0], meander_radians.outputs[0], label="Meander Shift")
    meandered = h.math(tree, "ADD", straight.outputs[0], shift.outputs[0], label="Meandering Phase")
    defects, defect_nodes = _defects(tree, position.outputs["Position"], direction, inputs)
    phase = h.math(tree, "ADD", meandered.outputs[0], defects["phase"], label="Phase")
    wave = h.math(tree, "SINE", phase.outputs[0], label="sin")
    wave_slope = h.math(tree, "COSINE", phase.outputs[0], label="cos")

    split = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, normal, split.inputs[0])
    upright = h.math(tree, "ABSOLUTE", split.outputs["Z"], label="|N.z|")
    slope = h.math(tree, "ARCCOSINE", upright.outputs[0], label="Slope")
    steepness = h.add_node(tree, "ShaderNodeMapRange", label="Towards 35°", interpolation_type="SMOOTHSTEP",
                           inputs={"From Min": 0.0, "From Max": sand.REPOSE, "To Min": 0.0, "To Max": 1.0})
    h.link(tree, slope.outputs[0], steepness.inputs["Value"])
    steep_loss = h.math(tree, "SUBTRACT", inputs["Steep Fraction"], 1.0, label="Fraction − 1")
    steep = h.add_node(tree, "ShaderNodeMath", label="Steep Weight", operation="MULTIPLY_ADD",
                       inputs={2: 1.0})
    h.link(tree, steep_loss.outputs[0], steep.inputs[0])
    h.link(tree, steepness.outputs["Result"], steep.inputs[1])
    downwind = h.vector_math(tree, "DOT_PRODUCT", normal, direction, label="Faces Downwind")
    leeness = h.add_node(tree, "ShaderNodeMapRange", label="Lee Side", interpolation_type="SMOOTHSTEP",
                         inputs={"From Min": 0.0, "From Max": math.sin(sand.REPOSE), "To Min": 0.0,
                                 "To Max": 1.0})
    h.link(tree, downwind.outputs["Value"], leeness.inputs["Value"])
    lee_loss = h.math(tree, "SUBTRACT", inputs["Lee Fraction"], 1.0, label="Fraction − 1")
    lee = h.add_node(tree, "ShaderNodeMath", label="Lee Weight", operation="MULTIPLY_ADD", inputs={2: 1.0})
    h.link(tree, lee_loss.outputs[0], lee.inputs[0])
    h.link(tree, leeness.outputs["Result"], lee.inputs[1])
    weight = h.math(tree, "MULTIPLY", steep.outputs[0], lee.outputs[0], label="Weight")
    weighted = h.math(tree, "MULTIPLY", inputs["Amplitude"], weight.outputs[0], label="Amplitude × Weight")
    varied = h.math(tree, "MULTIPLY", inputs["Variation"], lattice["g"], label="Variation × g")
    keep = h.math(tree, "SUBTRACT", 1.0, varied.outputs[0], label="1 − Variation g")
    varied_size = h.math(tree, "MULTIPLY", weighted.outputs[0], keep.outputs[0], label="Varied Size")
    unflattened = h.math(tree, "SUBTRACT", 1.0, inputs["Flatten"], label="1 − Flatten")
    scale = h.math(tree, "MULTIPLY", varied_size.outputs[0], unflattened.outputs[0], label="Size")

    kept = h.math(tree, "MULTIPLY", scale.outputs[0], defects["keep"], label="Size × Keep")
    height = h.math(tree, "MULTIPLY", kept.outputs[0], wave.outputs[0], label="Height")
    k = h.math(tree, "DIVIDE", 2 * math.pi, inputs["Wavelength"], label="2π / Wavelength")
    across = h.vector_math(tree, "SCALE", direction, label="k × Wind Direction")
    h.link(tree, k.outputs[0], across.inputs["Scale"])
    bend_rate = h.math(tree, "MULTIPLY", meander_radians.outputs[0], 2.0, label="2 × Meander × 2π")
    bend = h.vector_math(tree, "SCALE", lattice["gradient"], label="× ∇m")
    h.link(tree, bend_rate.outputs[0], bend.inputs["Scale"])
    meander_gradient = h.vector_math(tree, "ADD", across.outputs[0], bend.outputs[0],
                                     label="∇Meandering Phase")
    phase_gradient = h.vector_math(tree, "ADD", meander_gradient.outputs[0], defects["phase gradient"],
                                   label="∇Phase")
    rate = h.math(tree, "MULTIPLY", kept.outputs[0], wave_slope.outputs[0], label="Size × Keep × cos")
    through_phase = h.vector_math(tree, "SCALE", phase_gradient.outputs[0], label="Through the Phase")
    h.link(tree, rate.outputs[0], through_phase.inputs["Scale"])
    size_sine = h.math(tree, "MULTIPLY", scale.outputs[0], wave.outputs[0], label="Size × sin")
    through_keep = h.vector_math(tree, "SCALE", defects["keep gradient"], label="Through Keep")
    h.link(tree, size_sine.outputs[0], through_keep.inputs["Scale"])
    gradient = h.vector_math(tree, "ADD", through_phase.outputs[0], through_keep.outputs[0], label="Gradient")
    normal_part = h.vector_math(tree, "DOT_PRODUCT", gradient.outputs[0], normal, label="Along the Normal")
    back = h.vector_math(tree, "SCALE", normal, label="× Normal")
    h.link(tree, normal_part.outputs["Value"], back.inputs["Scale"])
    tangential = h.vector_math(tree, "SUBTRACT", gradient.outputs[0], back.outputs[0], label="In the Surface")
    tilted = h.vector_math(tree, "SUBTRACT", normal, tangential.outputs[0], label="Normal − Gradient")
    rippled = h.vector_math(tree, "NORMALIZE", tilted.outputs[0], label="Rippled Normal")
    h.link(tree, height.outputs[0], group_out.inputs["Height"])
    h.link(tree, rippled.outputs[0], group_out.inputs["Normal"])
    h.frame(tree, "Surface Normal", normal_nodes)
    h.frame(tree, "Wind Direction", direction_nodes)
    h.frame(tree, "Lattice Noise (m, g)", lattice_nodes)
    h.frame(tree, "Crests across the Wind, Meandering", (position, along, cycles, straight, meander_radians,
                                                          centred, shift, meandered, phase, wave,
                                                          wave_slope))
    h.frame(tree, "Crests that Split and End", defect_nodes)
    h.frame(tree, "Fading on Steep and Lee Slopes", (split, upright, slope, steepness, steep_loss, steep,
                                                     downwind, leeness, lee_loss, lee, weight, weighted,
                                                     varied, keep, varied_size, unflattened, scale))
    h.frame(tree, "Height and Normal", (kept, height, k, across, bend_rate, bend, meander_gradient,
                                        phase_gradient, rate, through_phase, size_sine, through_keep,
                                        gradient, normal_part, back, tangential, tilted, rippled))
    h.arrange(tree)


def _defects(tree, position, direction, inputs):
    """The Ripple Defects lattices summed: phase, phase gradient, keep and its gradient as sockets
    in a dict, and the nodes made (keep multiplies, so its gradient by the product rule)."""
    lattices, nodes = [], []
    for offset, layer in sand.DEFECT_LAYERS:
        node = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(ripple_defects),
                          label=f"Ripple Defects {len(lattices) + 1}",
                          inputs={"Offset": offset, "Layer": layer})
        h.link(tree, position, node.inputs["Position"])
        h.link(tree, direction, node.inputs["Direction"])
        h.link(tree, inputs["Wavelength"], node.inputs["Wavelength"])
        h.link(tree, inputs["Defects"], node.inputs["Share"])
        lattices.append(node)
    first = lattices[0].outputs
    phase, phase_gradient = first["Phase"], first["Phase Gradient"]
    keep, keep_gradient = first["Keep"], first["Keep Gradient"]
    for number, lattice in enumerate(lattices[1:], start=2):
        out, so_far = lattice.outputs, f"1-{number}"
        summed = h.math(tree, "ADD", phase, out["Phase"], label=f"Defect Phase {so_far}")
        bent = h.vector_math(tree, "ADD", phase_gradient, out["Phase Gradient"], label=f"∇Phase {so_far}")
        part_before = h.vector_math(tree, "SCALE", keep_gradient, label=f"∇Keep before × Keep {number}")
        h.link(tree, out["Keep"], part_before.inputs["Scale"])
        part_this = h.vector_math(tree, "SCALE", out["Keep Gradient"], label=f"∇Keep {number} × Keep before")
        h.link(tree, keep, part_this.inputs["Scale"])
        both = h.vector_math(tree, "ADD", part_before.outputs[0], part_this.outputs[0], label="∇Keep so far")
        kept = h.math(tree, "MULTIPLY", keep, out["Keep"], label=f"Keep {so_far}")
        phase, phase_gradient = summed.outputs[0], bent.outputs[0]
        keep, keep_gradient = kept.outputs[0], both.outputs[0]
        nodes += [summed, bent, part_before, part_this, both, kept]
    return ({"phase": phase, "phase gradient": phase_gradient, "keep": keep, "keep gradient": keep_gradient},
            (*lattices, *nodes))


def _lattice_noise(tree, position, lattice_scale):
    """Value noise m and g and m's horizontal gradient (sockets in a dict; twin:
    core.sand.ripple_lattice), and the nodes made."""
    inverse = h.math(tree, "DIVIDE", 1.0, lattice_scale, label="1 / Meander Scale")
    scaled = h.vector_math(tree, "SCALE", position, label="Position / Scale")
    h.link(tree, inverse.outputs[0], scaled.inputs["Scale"])
    flat = h.vector_math(tree, "MULTIPLY", scaled.outputs[0], (1.0, 1.0, 0.0), label="Horizontal")
    cell = h.vector_math(tree, "FLOOR", flat.outputs[0], label="Cell")
    inside = h.vector_math(tree, "SUBTRACT", flat.outputs[0], cell.outputs[0], label="Inside the Cell")
    split = h.add_node(tree, "ShaderNodeSeparateXYZ", label="f")
    h.link(tree, inside.outputs[0], split.inputs[0])
    nodes = [inverse, scaled, flat, cell, inside, split]
    weights, rates = [], []
    for axis in ("X", "Y"):
        f = split.outputs[axis]
        smooth = h.add_node(tree, "ShaderNodeMapRange", label=f"Smoothstep {axis}",
                            interpolation_type="SMOOTHSTEP",
                            inputs={"From Min": 0.0, "From Max": 1.0, "To Min": 0.0, "To Max": 1.0})
        h.link(tree, f, smooth.inputs["Value"])
        rest = h.math(tree, "SUBTRACT", 1.0, f, label=f"1 − f{axis.lower()}")
        product = h.math(tree, "MULTIPLY", f, rest.outputs[0], label=f"f{axis.lower()} (1 − f)")
        rate = h.math(tree, "MULTIPLY", product.outputs[0], 6.0, label=f"Smoothstep' {axis}")
        weights.append(smooth.outputs["Result"])
        rates.append(rate.outputs[0])
        nodes += [smooth, rest, product, rate]
    value, green = {}, {}
    for dx in (0, 1):
        for dy in (0, 1):
            corner = h.vector_math(tree, "ADD", cell.outputs[0], (float(dx), float(dy), 0.0),
                                   label=f"Corner {dx}{dy}")
            noise = h.add_node(tree, "ShaderNodeTexWhiteNoise", label=f"Noise {dx}{dy}",
                               noise_dimensions="3D")
            h.link(tree, corner.outputs[0], noise.inputs["Vector"])
            colour = h.add_node(tree, "ShaderNodeSeparateColor", label=f"Green {dx}{dy}")
            h.link(tree, noise.outputs["Color"], colour.inputs["Color"])
            value[dx, dy], green[dx, dy] = noise.outputs["Value"], colour.outputs["Green"]
            nodes += [corner, noise, colour]

    def lerp(a, b, t, label):
        difference = h.math(tree, "SUBTRACT", b, a, label=f"{label}: b − a")
        mixed = h.add_node(tree, "ShaderNodeMath", label=label, operation="MULTIPLY_ADD")
        h.link(tree, difference.outputs[0], mixed.inputs[0])
        h.link(tree, t, mixed.inputs[1])
        h.link(tree, a, mixed.inputs[2])
        nodes.extend((difference, mixed))
        return mixed.outputs[0], difference.outputs[0]

    sx, sy = weights
    out = {}
    for key, c in (("m", value), ("g", green)):
        low, low_dx = lerp(c[0, 0], c[1, 0], sx, f"{key} at y0")
        high, high_dx = lerp(c[0, 1], c[1, 1], sx, f"{key} at y1")
        out[key], _ = lerp(low, high, sy, key)
        if key == "m":
            along_x, _ = lerp(low_dx, high_dx, sy, "∂m/∂x ÷ s'")
    left = h.math(tree, "SUBTRACT", value[0, 1], value[0, 0], label="m: left edge")
    right = h.math(tree, "SUBTRACT", value[1, 1], value[1, 0], label="m: right edge")
    nodes += [left, right]
    along_y, _ = lerp(left.outputs[0], right.outputs[0], sx, "∂m/∂y ÷ s'")
    dx = h.math(tree, "MULTIPLY", along_x, rates[0], label="∂m/∂x")
    dy = h.math(tree, "MULTIPLY", along_y, rates[1], label="∂m/∂y")
    combine = h.add_node(tree, "ShaderNodeCombineXYZ", label="∇m per Cell")
    h.link(tree, dx.outputs[0], combine.inputs["X"])
    h.link(tree, dy.outputs[0], combine.inputs["Y"])
    gradient = h.vector_math(tree, "SCALE", combine.outputs[0], label="∇m")
    h.link(tree, inverse.outputs[0], gradient.inputs["Scale"])
    nodes += [dx, dy, combine, gradient]
    out["gradient"] = gradient.outputs[0]
    return out, nodes
