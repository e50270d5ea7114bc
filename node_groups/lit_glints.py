"""Sandscape Lit Glints: glinting grains as mirror facets lit by real light, each sparkle a point
put into the pixel it projects into (Sandscape Glint Splat), so a sparkle covers one pixel and
every sample of that pixel agrees on it.

The splat's four candidate cells each get a facet (Sandscape Glint Facet: its noise says whether
it can glint, its colour which way it leans) over their share of the pixel, on top of the sand.
Without a render camera's pixel (Resolution 0, a panoramic camera) the cells sized to the
pixel's footprint (Sandscape Glint Cells) stand in, found by the samples that land in them; with
Pixel Angle and Pixel Size 0 too, one cell per grain: Sandscape Glints' grains.
Twins: core.glint_splat, core.glints.sparkle_noise and core.sand.glint_facets.
"""

from . import glint_cells, glint_facet, glint_splat
from . import helper as h

NAME = "Sandscape Lit Glints"
VERSION = 8
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Sparkling sand lit by the sun: cells of grains sized to the pixel's footprint, a seeded "
               "random value per cell, mirror facets above Threshold that glint only where light "
               "reaches them")

INPUTS = {**glint_facet.INPUTS, **glint_cells.INPUTS, **glint_splat.INPUTS}
SOCKETS = ("Base", "Threshold", "Glint Size", "Facing Power", "Color", "Roughness", "Seed", "Normal",
           "Pixel Angle", "Pixel Size", "Resolution X", "Resolution Y", "IOR")
CELL_SOCKETS = ("Glint Size", "Seed", "Threshold", "Pixel Angle", "Pixel Size")
FACET_SOCKETS = ("Facing Power", "Color", "Roughness", "Normal", "IOR")


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
    for name in ("Base", "Facing Power", "Roughness", "Normal", "IOR"):
        h.link(tree, inputs[name], facet.inputs[name])
    mask = h.math(tree, "MULTIPLY", facet.outputs["Mask"], cells.outputs["Weight"], label="Mask × Weight")
    h.frame(tree, "Cells Sized to the Pixel (no render camera)", (cells,))
    h.frame(tree, "Mirror Facet", (facet, coverage, boost, color, mask))
    splat, splat_mask, splat_nodes = _splat(tree, inputs)

    # The splat where the render camera's pixel is known; the cells elsewhere (the inactive branch's
    # closures weigh nothing, so Cycles does not evaluate them).
    choose = h.add_node(tree, "ShaderNodeMixShader", label="Cells or Splat")
    h.link(tree, splat.outputs["Active"], choose.inputs["Fac"])
    h.link(tree, facet.outputs["Shader"], choose.inputs[1])
    h.link(tree, splat_mask[0], choose.inputs[2])
    either = h.add_node(tree, "ShaderNodeMix", label="Mask: Cells or Splat")
    h.link(tree, splat.outputs["Active"], h.socket(either.inputs, "Factor"))
    h.link(tree, mask.outputs[0], h.socket(either.inputs, "A"))
    h.link(tree, splat_mask[1], h.socket(either.inputs, "B"))
    shown = h.add_node(tree, "ShaderNodeMix", label="Mirror Shown: Cells or Splat")
    h.link(tree, splat.outputs["Active"], h.socket(shown.inputs, "Factor"))
    h.link(tree, facet.outputs["Mirror"], h.socket(shown.inputs, "A"))
    h.link(tree, splat_mask[2], h.socket(shown.inputs, "B"))
    h.link(tree, h.socket(shown.outputs, "Result"), group_out.inputs["Mirror"])
    facets = h.add_node(tree, "ShaderNodeMixShader", label="Facets: Cells or Splat")
    h.link(tree, splat.outputs["Active"], facets.inputs["Fac"])
    h.link(tree, facet.outputs["Facets"], facets.inputs[1])
    h.link(tree, splat_mask[3], facets.inputs[2])
    h.link(tree, facets.outputs[0], group_out.inputs["Facets"])
    h.link(tree, choose.outputs[0], group_out.inputs["Shader"])
    h.link(tree, h.socket(either.outputs, "Result"), group_out.inputs["Mask"])
    h.link(tree, facet.outputs["Facet Normal"], group_out.inputs["Facet Normal"])
    h.frame(tree, "Sparkles Put into Their Pixels", splat_nodes)
    h.frame(tree, "Which Applies", (choose, either, shown, facets))
    h.arrange(tree)


def _splat(tree, inputs):
    """The base with each candidate's facet over its share of the pixel. Returns (the splat node,
    (shader, mask, mirror shown, facets alone) sockets, the nodes made)."""
    splat = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(glint_splat), label="Glint Splat")
    for name in glint_splat.INPUTS:
        h.link(tree, inputs[name], splat.inputs[name])
    made, total, shown, shader = [splat], None, None, None
    for k in glint_splat.CANDIDATES:
        facet = h.add_node(tree, "ShaderNodeGroup", node_tree=h.ensure_group(glint_facet), label=f"Facet {k}")
        h.link(tree, splat.outputs[f"Noise {k}"], facet.inputs["Noise"])
        h.link(tree, splat.outputs[f"Tilt {k}"], facet.inputs["Tilt"])
        h.link(tree, splat.outputs["Threshold"], facet.inputs["Threshold"])
        h.link(tree, splat.outputs[f"Amount {k}"], facet.inputs["Coverage"])
        for name in FACET_SOCKETS:
            h.link(tree, inputs[name], facet.inputs[name])
        made.append(facet)
        amount, mirror = splat.outputs[f"Amount {k}"], facet.outputs["Mirror"]
        if total is None:
            total, shown, shader = amount, mirror, facet.outputs["Shader"]
            continue
        add = h.math(tree, "ADD", total, amount, label="Can Glint")
        add_shown = h.math(tree, "ADD", shown, mirror, label="Mirror Shown")
        both = h.add_node(tree, "ShaderNodeAddShader", label="+ Facet")
        h.link(tree, shader, both.inputs[0])
        h.link(tree, facet.outputs["Shader"], both.inputs[1])
        made += [add, add_shown, both]
        total, shown, shader = add.outputs[0], add_shown.outputs[0], both.outputs[0]
    # The facets' mirrors on top of the sand (the mask counts every grain that can glint).
    both = h.add_node(tree, "ShaderNodeAddShader", label="Sand + Facets")
    h.link(tree, inputs["Base"], both.inputs[0])
    h.link(tree, shader, both.inputs[1])
    made.append(both)
    return splat, (both.outputs[0], total, shown, shader), made
