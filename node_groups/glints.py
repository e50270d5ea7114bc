"""Sandscape Glints: the URP paper's emission sparkles, in cells sized to the pixel's footprint.

Sandscape Glint Cells picks the cells (Glint Size in the object's own space and units, so
glints stick to the surface and do not crawl when the camera moves; coarser far away, finer
near, so a sparkle covers at most one pixel); Sandscape Glint Shade turns each cell's noise
into the glint, its strength scaled by the cell's weight. Twin: core.glints.glints.
"""

from . import glint_cells, glint_shade
from . import helper as h

NAME = "Sandscape Glints"
VERSION = 4
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = (
    "Sparkling sand grains: cells of grains sized to the pixel's footprint, a seeded random value "
    "per cell, lit above Threshold and only where the view meets the normal")


# A grain's cell, shared with the lit glints.
CELL_INPUTS = {name: glint_cells.INPUTS[name] for name in ("Glint Size", "Seed", "Pixel Angle", "Pixel Size")}
INPUTS = {**glint_shade.INPUTS, **CELL_INPUTS}


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, ("Threshold", "Glint Size", "Facing Power", "Color", "Strength", "Seed",
                         "Pixel Angle", "Pixel Size"), INPUTS, glint_shade.OUTPUTS)

    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    cells = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(glint_cells), label="Glint Cells")
    for name in ("Glint Size", "Seed", "Threshold", "Pixel Angle", "Pixel Size"):
        h.link(tree, inputs[name], cells.inputs[name])
    shade = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(glint_shade))
    h.link(tree, cells.outputs["Noise"], shade.inputs["Noise"])
    h.link(tree, cells.outputs["Threshold"], shade.inputs["Threshold"])
    strength = h.math(tree, "MULTIPLY", inputs["Strength"], cells.outputs["Weight"],
                      label="Strength × Weight")
    h.link(tree, strength.outputs[0], shade.inputs["Strength"])
    for name in ("Facing Power", "Color"):
        h.link(tree, inputs[name], shade.inputs[name])
    mask = h.math(tree, "MULTIPLY", shade.outputs["Mask"], cells.outputs["Weight"], label="Mask × Weight")
    h.link(tree, shade.outputs["Emission"], group_out.inputs["Emission"])
    h.link(tree, mask.outputs[0], group_out.inputs["Mask"])
    h.link(tree, shade.outputs["Glint Color"], group_out.inputs["Glint Color"])
    h.frame(tree, "Cells Sized to the Pixel", (cells,))
    h.frame(tree, "Glint", (shade, strength, mask))
    h.arrange(tree)
