"""Sandscape Glint Cells: which grains can sparkle, in cells sized to the pixel's footprint.

A grain of Glint Size near the camera spans several pixels, and far away a pixel holds
thousands. Either way a sparkle should be a point of light: the cells here are Glint Size x
2^level, the level chosen so a cell spans half to one pixel's footprint on the surface (View
Distance x Pixel Angle + Pixel Size, in the object's units). A fine cell sparkles as often per
area as the grains did and carries its grain's light into its pixel (Weight above 1, at most a
pixel of mirror); a coarse one stands for the grains it holds, dimmer by Weight, so the sand's
mean glint light does not change with distance and a pixel needs few samples to find it.
Pixel Angle and Pixel Size 0 (unlinked): one cell per grain. Twin: core.glints.sparkle_noise.
"""

from ..core import glints as twin
from . import glint_facet
from . import helper as h

NAME = "Sandscape Glint Cells"
VERSION = 2
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Cells of glinting grains sized to the pixel's footprint: a sparkle covers at most one "
               "pixel, near or far; per cell a seeded noise, a tilt, the level's threshold and weight")

MAX_PIXEL_ANGLE = 1.0  # bounds for the driven inputs typed by hand (radians; the object's units)
MAX_PIXEL_SIZE = 1e6
INPUTS = {  # name -> (type, description, default, min, max, subtype); append only
    "Glint Size": ("NodeSocketFloat", "Edge of a grain's cell in the object's own units (scaling the "
                   "object scales it)", 0.003, 0.0, None, "DISTANCE"),
    "Seed": ("NodeSocketFloat", "Another seed gives another random set of glinting grains",
             0.0, None, None, None),
    "Threshold": glint_facet.INPUTS["Threshold"],
    "Pixel Angle": ("NodeSocketFloat", "Angle one pixel spans (radians), from the render camera: "
                    "0 keeps one cell per grain at any distance", 0.0, 0.0, None, "ANGLE"),
    "Pixel Size": ("NodeSocketFloat", "Width of a pixel on an orthographic camera's image plane",
                   0.0, 0.0, None, "DISTANCE"),
}
OUTPUTS = {
    "Noise": ("NodeSocketFloat", "The cell's random value in 0..1"),
    "Tilt": ("NodeSocketColor", "The cell's random colour in 0..1: which way its facet leans"),
    "Threshold": ("NodeSocketFloat", "Noise above this sparkles: Threshold^(grains in the cell)"),
    "Weight": ("NodeSocketFloat", "A sparkle's brightness against a grain's mirror: a fine cell "
               "carries its grain's light into one pixel, a coarse one its grains' share"),
    "Cell Size": ("NodeSocketFloat", "Edge of the cell in the object's units"),
}


def _footprint(tree, inputs):
    """The pixel's footprint at the shaded point, in the object's units."""
    camera = h.add_node(tree, "ShaderNodeCameraData")
    angle, angle_nodes = h.finite(tree, inputs["Pixel Angle"], MAX_PIXEL_ANGLE, label="Pixel Angle, Finite")
    size, size_nodes = h.finite(tree, inputs["Pixel Size"], MAX_PIXEL_SIZE, label="Pixel Size, Finite")
    world = h.math(tree, "MULTIPLY_ADD", camera.outputs["View Distance"], angle, c=size,
                   label="Footprint (world)")
    # The object's scale: a diagonal unit vector carried to world space (exact for uniform scale).
    diagonal = h.add_node(tree, "ShaderNodeVectorTransform", label="Object Scale", vector_type="VECTOR",
                          convert_from="OBJECT", convert_to="WORLD", inputs={"Vector": (0.57735027,) * 3})
    scale = h.vector_math(tree, "LENGTH", diagonal.outputs[0], label="|Scale|")
    footprint = h.math(tree, "DIVIDE", world.outputs[0], scale.outputs["Value"], label="Footprint")
    return footprint.outputs[0], (camera, *angle_nodes, *size_nodes, world, diagonal, scale, footprint)


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, INPUTS, INPUTS, OUTPUTS)
    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    footprint, footprint_nodes = _footprint(tree, inputs)

    # level = ceil(log2(SPARKLE_CELL x footprint / size)); Cycles' log of 0 is 0: no footprint, level 0.
    half = h.math(tree, "MULTIPLY", footprint, twin.SPARKLE_CELL, label="× Cell Share")
    ratio = h.math(tree, "DIVIDE", half.outputs[0], inputs["Glint Size"], label="Footprint / Size")
    log = h.math(tree, "LOGARITHM", ratio.outputs[0], 2.0, label="log2")
    ceil = h.math(tree, "CEIL", log.outputs[0], label="Level")
    low = h.math(tree, "MAXIMUM", ceil.outputs[0], float(twin.LEVELS[0]), label="Finest Level")
    level = h.math(tree, "MINIMUM", low.outputs[0], float(twin.LEVELS[1]), label="Coarsest Level")
    edge = h.math(tree, "POWER", 2.0, level.outputs[0], label="2^Level")
    size = h.math(tree, "MULTIPLY", edge.outputs[0], inputs["Glint Size"], label="Cell Size")
    grains = h.math(tree, "POWER", 4.0, level.outputs[0], label="Grains per Cell")
    # Coarse: one of its grains sparkles (Threshold^Grains); fine: as many per area as grains
    # (1 - Grains x (1 - Threshold)). The larger is the level's threshold: they meet at level 0.
    coarse = h.math(tree, "POWER", inputs["Threshold"], grains.outputs[0], label="Threshold^Grains")
    below = h.math(tree, "SUBTRACT", inputs["Threshold"], 1.0, label="Threshold - 1")
    fine = h.math(tree, "MULTIPLY_ADD", grains.outputs[0], below.outputs[0], label="1 - Grains × Share")
    fine.inputs[2].default_value = 1.0
    threshold = h.math(tree, "MAXIMUM", coarse.outputs[0], fine.outputs[0], label="Threshold of the Level")
    share = h.math(tree, "SUBTRACT", 1.0, inputs["Threshold"], label="Grain Share")
    cell_share = h.math(tree, "SUBTRACT", 1.0, threshold.outputs[0], label="Cell Share")
    ratio_share = h.math(tree, "DIVIDE", share.outputs[0], cell_share.outputs[0], label="Grains' Share")
    # A fine cell carries its grain's light into one pixel, but no more than a whole pixel of mirror:
    # the pixel's area on the surface (footprint² / N·V) over the cell's.
    geometry = h.add_node(tree, "ShaderNodeNewGeometry")
    facing = h.vector_math(tree, "DOT_PRODUCT", geometry.outputs["Normal"], geometry.outputs["Incoming"],
                           label="N·V")
    facing_abs = h.math(tree, "ABSOLUTE", facing.outputs["Value"], label="|N·V|")
    facing_min = h.math(tree, "MAXIMUM", facing_abs.outputs[0], twin.MIN_FACING, label="Grazing Limit")
    pixel_area = h.math(tree, "MULTIPLY", footprint, footprint, label="Footprint²")
    cell_area = h.math(tree, "MULTIPLY", size.outputs[0], size.outputs[0], label="Cell²")
    cell_view = h.math(tree, "MULTIPLY", cell_area.outputs[0], facing_min.outputs[0], label="Cell² × N·V")
    pixel_cells = h.math(tree, "DIVIDE", pixel_area.outputs[0], cell_view.outputs[0], label="Pixel / Cell")
    coarse_level = h.math(tree, "GREATER_THAN", level.outputs[0], -0.5, label="Coarse Level")
    bound = h.math(tree, "MAXIMUM", pixel_cells.outputs[0], coarse_level.outputs[0], label="Pixel Bound")
    weight = h.math(tree, "MINIMUM", ratio_share.outputs[0], bound.outputs[0], label="Weight")

    coords = h.add_node(tree, "ShaderNodeTexCoord")
    scaled = h.vector_math(tree, "DIVIDE", coords.outputs["Object"], label="Position / Cell")
    h.link(tree, size.outputs[0], scaled.inputs[1])
    # Cells centred on multiples of the size, as before: a surface at z = 0 lies mid-cell.
    centred = h.vector_math(tree, "ADD", scaled.outputs[0], (0.5, 0.5, 0.5), label="Centre Cells")
    cell = h.vector_math(tree, "FLOOR", centred.outputs[0], label="Cell")
    seed = h.math(tree, "MULTIPLY_ADD", level.outputs[0], twin.LEVEL_SEED, label="Seed of the Level")
    h.link(tree, inputs["Seed"], seed.inputs[2])
    noise = h.add_node(tree, "ShaderNodeTexWhiteNoise", noise_dimensions="4D")
    h.link(tree, cell.outputs[0], noise.inputs["Vector"])
    h.link(tree, seed.outputs[0], noise.inputs["W"])

    h.link(tree, noise.outputs["Value"], group_out.inputs["Noise"])
    h.link(tree, noise.outputs["Color"], group_out.inputs["Tilt"])
    h.link(tree, threshold.outputs[0], group_out.inputs["Threshold"])
    h.link(tree, weight.outputs[0], group_out.inputs["Weight"])
    h.link(tree, size.outputs[0], group_out.inputs["Cell Size"])
    h.frame(tree, "Pixel Footprint", footprint_nodes)
    h.frame(tree, "Level: Half to One Pixel", (half, ratio, log, ceil, low, level, edge, size))
    h.frame(tree, "Threshold", (grains, coarse, below, fine, threshold))
    h.frame(tree, "Weight", (share, cell_share, ratio_share, geometry, facing, facing_abs, facing_min,
                             pixel_area, cell_area, cell_view, pixel_cells, coarse_level, bound, weight))
    h.frame(tree, "Seeded Noise per Cell", (coords, scaled, centred, cell, seed, noise))
    h.arrange(tree)
