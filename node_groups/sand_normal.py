"""Sandscape Sand Normal: the surface normal nudged towards a random direction per sand grain
(Journey's sand normal: nlerp of the normal and a grain's direction, by Strength).

Grains are object-space cells of Grain Size; each gets a random direction (its noise colour
as a vector in -1..1, turned to the normal's side). Twin: core.sand.sand_normal.
"""

import sys

from . import helper as h

NAME = "Sandscape Sand Normal"
VERSION = 1
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = "The normal nudged towards a random direction per grain (nlerp by Strength)"
SEED_OFFSET = 0.5  # the grains' directions do not repeat the glints' tilts on the same cells


GRAIN_SIZE = 0.002  # metres: medium sand; a scene in other units gets it converted on build


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Normal", "NodeSocketVector", "Surface normal (unlinked: the shading normal)",
                (0.0, 0.0, 0.0), subtype=h.SURFACE_NORMAL)
    h.add_input(tree, "Grain Size", "NodeSocketFloat", "Edge of a grain's cell in the object's own units",
                GRAIN_SIZE, 0.0, None, "DISTANCE")
    h.add_input(tree, "Strength", "NodeSocketFloat", "0 keeps the normal, 1 turns it to the grain's "
                "direction", 0.2, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Seed", "NodeSocketFloat", "Another seed gives other grains", 0.0)
    h.add_output(tree, "Normal", "NodeSocketVector", "The grainy normal")
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    normal, normal_nodes = h.normal_or_geometry(tree, inputs["Normal"])
    coords = h.add_node(tree, "ShaderNodeTexCoord")
    scaled = h.vector_math(tree, "DIVIDE", coords.outputs["Object"], label="Position / Size")
    h.link(tree, inputs["Grain Size"], scaled.inputs[1])
    centred = h.vector_math(tree, "ADD", scaled.outputs[0], (0.5, 0.5, 0.5), label="Centre Cells")
    cell = h.vector_math(tree, "FLOOR", centred.outputs[0], label="Cell")
    seed = h.math(tree, "ADD", inputs["Seed"], SEED_OFFSET, label="Seed + ½")
    noise = h.add_node(tree, "ShaderNodeTexWhiteNoise", noise_dimensions="4D")
    h.link(tree, cell.outputs[0], noise.inputs["Vector"])
    h.link(tree, seed.outputs[0], noise.inputs["W"])
    direction = h.vector_math(tree, "MULTIPLY_ADD", noise.outputs["Color"], (2.0, 2.0, 2.0),
                              label="2 Colour − 1")
    direction.inputs[2].default_value = (-1.0, -1.0, -1.0)
    side = h.vector_math(tree, "DOT_PRODUCT", direction.outputs[0], normal, label="Which Side")
    sign = h.math(tree, "SIGN", side.outputs["Value"], label="Sign")
    turned = h.vector_math(tree, "SCALE", direction.outputs[0], label="To the Normal's Side")
    h.link(tree, sign.outputs[0], turned.inputs["Scale"])
    grain = h.vector_math(tree, "NORMALIZE", turned.outputs[0], label="Grain Direction")
    keep = h.math(tree, "SUBTRACT", 1.0, inputs["Strength"], label="1 − Strength")
    kept = h.vector_math(tree, "SCALE", normal, label="Normal × (1 − s)")
    h.link(tree, keep.outputs[0], kept.inputs["Scale"])
    towards = h.vector_math(tree, "SCALE", grain.outputs[0], label="Grain × s")
    h.link(tree, inputs["Strength"], towards.inputs["Scale"])
    blend = h.vector_math(tree, "ADD", kept.outputs[0], towards.outputs[0], label="Blend")
    nlerp = h.vector_math(tree, "NORMALIZE", blend.outputs[0], label="nlerp")
    h.link(tree, nlerp.outputs[0], group_out.inputs["Normal"])
    h.frame(tree, "Surface Normal", normal_nodes)
    h.frame(tree, "A Direction per Grain", (coords, scaled, centred, cell, seed, noise, direction, side, sign,
                                            turned, grain))
    h.frame(tree, "nlerp(Normal, Grain, Strength)", (keep, kept, towards, blend, nlerp))
    h.arrange(tree)


def add_grain_inputs(tree, strength_description="How far the grains turn the normal"):
    """The inputs a look passes on to its Sand Normal: Grain Size, Grain Strength, Seed, Normal."""
    h.add_input(tree, "Grain Size", "NodeSocketFloat", "Edge of a grain in the object's own units",
                GRAIN_SIZE, 0.0, None, "DISTANCE")
    h.add_input(tree, "Grain Strength", "NodeSocketFloat", strength_description, 0.15, 0.0, 1.0, "FACTOR")
    h.add_input(tree, "Seed", "NodeSocketFloat", "Another seed gives other grains", 0.0)
    h.add_input(tree, "Normal", "NodeSocketVector", "Surface normal, e.g. the ripples' (unlinked: the "
                "shading normal)", (0.0, 0.0, 0.0), subtype=h.SURFACE_NORMAL)


def grain_node(tree, inputs):
    """A Sand Normal group node fed by the look's add_grain_inputs."""
    this = sys.modules[__name__]
    grains = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(this), label="Sand Normal")
    for name, to in (("Normal", "Normal"), ("Grain Size", "Grain Size"), ("Grain Strength", "Strength"),
                     ("Seed", "Seed")):
        h.link(tree, inputs[name], grains.inputs[to])
    return grains
