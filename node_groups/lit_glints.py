"""Sandscape Lit Glints: glinting grains on object-space cells, as mirror facets lit by real light.

The cells are those of Sandscape Glints (Glint Size in the object's own space, Seed), so the
same grains glint; each cell's noise says whether it can, and its noise colour which way its
facet leans (Sandscape Glint Facet). Twin: core.sand.glint_cells and glint_facets.
"""

from . import glint_facet, glints
from . import helper as h

NAME = "Sandscape Lit Glints"
VERSION = 1
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Sparkling sand lit by the sun: object-space cells of Glint Size, a seeded random value "
               "per cell, mirror facets above Threshold that glint only where light reaches them")

INPUTS = {**glint_facet.INPUTS, **glints.CELL_INPUTS}
SOCKETS = ("Base", "Threshold", "Glint Size", "Facing Power", "Color", "Roughness", "Seed", "Normal")


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, SOCKETS, INPUTS, glint_facet.OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    coords = h.add_node(tree, "ShaderNodeTexCoord")
    scaled = h.vector_math(tree, "DIVIDE", coords.outputs["Object"], label="Position / Size")
    h.link(tree, inputs["Glint Size"], scaled.inputs[1])
    # Cells centred on multiples of the size, as Sandscape Glints: the same grains glint.
    centred = h.vector_math(tree, "ADD", scaled.outputs[0], (0.5, 0.5, 0.5), label="Centre Cells")
    cell = h.vector_math(tree, "FLOOR", centred.outputs[0], label="Cell")
    noise = h.add_node(tree, "ShaderNodeTexWhiteNoise", noise_dimensions="4D")
    h.link(tree, cell.outputs[0], noise.inputs["Vector"])
    h.link(tree, inputs["Seed"], noise.inputs["W"])
    facet = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(glint_facet), label="Glint Facet")
    h.link(tree, noise.outputs["Value"], facet.inputs["Noise"])
    h.link(tree, noise.outputs["Color"], facet.inputs["Tilt"])
    for name in ("Base", "Threshold", "Facing Power", "Color", "Roughness", "Normal"):
        h.link(tree, inputs[name], facet.inputs[name])
    for name in glint_facet.OUTPUTS:
        h.link(tree, facet.outputs[name], group_out.inputs[name])
    h.frame(tree, "Object-Space Cells", (coords, scaled, centred, cell))
    h.frame(tree, "Seeded Noise and Tilt per Cell", (noise,))
    h.frame(tree, "Mirror Facet", (facet,))
    h.arrange(tree)
