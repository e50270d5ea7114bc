"""Sandscape Glints: procedural glints on object-space cells.

Each cell of Glint Size (in the object's own space and units, so glints stick to the
surface and do not crawl when the camera moves) gets a white-noise value seeded by
Seed; Sandscape Glint Shade turns it into the glint. Twin: core.glints.glints.
"""

from . import glint_shade
from . import helper as h

NAME = "Sandscape Glints"
VERSION = 3
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = (
    "Sparkling sand grains: object-space cells of Glint Size, a seeded random "
    "value per cell, lit above Threshold and only where the view meets the normal")


# A grain's cell, shared with the lit glints.
CELL_INPUTS = {
    "Glint Size": ("NodeSocketFloat", "Edge of a grain's cell in the object's own units (scaling the "
                   "object scales it)", 0.003, 0.0, None, "DISTANCE"),
    "Seed": ("NodeSocketFloat", "Another seed gives another random set of glinting grains",
             0.0, None, None, None),
}
INPUTS = {**glint_shade.INPUTS, **CELL_INPUTS}


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, ("Threshold", "Glint Size", "Facing Power", "Color", "Strength", "Seed"), INPUTS,
                  glint_shade.OUTPUTS)

    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    coords = h.add_node(tree, "ShaderNodeTexCoord", (-700, 200))
    scaled = h.add_node(tree, "ShaderNodeVectorMath", (-500, 200), "Position / Size", operation="DIVIDE")
    h.link(tree, coords.outputs["Object"], scaled.inputs[0])
    h.link(tree, inputs["Glint Size"], scaled.inputs[1])
    # Cells are centred on multiples of the size: a surface through the origin (z = 0 in
    # object space) lies mid-cell, where transform round-off cannot flip it between two cells.
    centred = h.add_node(tree, "ShaderNodeVectorMath", (-400, 200), "Centre Cells", operation="ADD",
                         inputs={1: (0.5, 0.5, 0.5)})
    h.link(tree, scaled.outputs[0], centred.inputs[0])
    cell = h.add_node(tree, "ShaderNodeVectorMath", (-300, 200), "Cell", operation="FLOOR")
    h.link(tree, centred.outputs[0], cell.inputs[0])
    noise = h.add_node(tree, "ShaderNodeTexWhiteNoise", (-100, 200), noise_dimensions="4D")
    h.link(tree, cell.outputs[0], noise.inputs["Vector"])
    h.link(tree, inputs["Seed"], noise.inputs["W"])

    shade = h.add_node(tree, "ShaderNodeGroup", (150, 0), node_tree=h.ensure_group(glint_shade))
    h.link(tree, noise.outputs["Value"], shade.inputs["Noise"])
    for name in ("Threshold", "Facing Power", "Color", "Strength"):
        h.link(tree, inputs[name], shade.inputs[name])
    for name in glint_shade.OUTPUTS:
        h.link(tree, shade.outputs[name], group_out.inputs[name])
    h.frame(tree, "Object-Space Cells", (coords, scaled, centred, cell))
    h.frame(tree, "Seeded Noise per Cell", (noise,))
    h.frame(tree, "Glint", (shade,))
    h.arrange(tree)
