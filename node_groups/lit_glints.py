"""Sandscape Lit Glints: glinting grains as mirror facets lit by real light, in cells sized to the
pixel's footprint (Sandscape Glint Cells), so a sparkle covers at most one pixel.

Each cell's noise says whether it can glint, its noise colour which way its facet leans
(Sandscape Glint Facet), and its weight how much of a mirror it is: a far cell stands for many
grains and is mirror over their share of it, sand elsewhere; a near cell is all mirror, as
bright as its grain's light in one pixel. With Pixel Angle and Pixel Size 0 there is one cell
per grain: Sandscape Glints' grains. Twin: core.glints.sparkle_noise and core.sand.glint_facets.
"""

from . import glint_cells, glint_facet
from . import helper as h

NAME = "Sandscape Lit Glints"
VERSION = 3
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Sparkling sand lit by the sun: cells of grains sized to the pixel's footprint, a seeded "
               "random value per cell, mirror facets above Threshold that glint only where light "
               "reaches them")

INPUTS = {**glint_facet.INPUTS, **glint_cells.INPUTS}
SOCKETS = ("Base", "Threshold", "Glint Size", "Facing Power", "Color", "Roughness", "Seed", "Normal",
           "Pixel Angle", "Pixel Size")
CELL_SOCKETS = ("Glint Size", "Seed", "Threshold", "Pixel Angle", "Pixel Size")


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, SOCKETS, INPUTS, glint_facet.OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    cells = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(glint_cells), label="Glint Cells")
    for name in CELL_SOCKETS:
        h.link(tree, inputs[name], cells.inputs[name])
    facet = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(glint_facet), label="Glint Facet")
    h.link(tree, cells.outputs["Noise"], facet.inputs["Noise"])
    h.link(tree, cells.outputs["Tilt"], facet.inputs["Tilt"])
    h.link(tree, cells.outputs["Threshold"], facet.inputs["Threshold"])
    # A coarse cell (weight < 1) is mostly sand: a weight's share of it is mirror. A fine cell
    # (weight > 1) is all mirror, brighter by its weight: its grain's light in one pixel.
    coverage = h.math(tree, "MINIMUM", cells.outputs["Weight"], 1.0, label="Mirror Share")
    h.link(tree, coverage.outputs[0], facet.inputs["Coverage"])
    boost = h.math(tree, "MAXIMUM", cells.outputs["Weight"], 1.0, label="Mirror Boost")
    color = h.vector_math(tree, "SCALE", inputs["Color"], label="Color × Boost")
    h.link(tree, boost.outputs[0], color.inputs["Scale"])
    h.link(tree, color.outputs[0], facet.inputs["Color"])
    for name in ("Base", "Facing Power", "Roughness", "Normal"):
        h.link(tree, inputs[name], facet.inputs[name])
    mask = h.math(tree, "MULTIPLY", facet.outputs["Mask"], cells.outputs["Weight"], label="Mask × Weight")
    h.link(tree, facet.outputs["Shader"], group_out.inputs["Shader"])
    h.link(tree, mask.outputs[0], group_out.inputs["Mask"])
    h.link(tree, facet.outputs["Facet Normal"], group_out.inputs["Facet Normal"])
    h.frame(tree, "Cells Sized to the Pixel", (cells,))
    h.frame(tree, "Mirror Facet", (facet, coverage, boost, color, mask))
    h.arrange(tree)
