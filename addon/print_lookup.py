"""The print map read in our sand material: four Closest lookups of the image at the texel centres
round the point, blended bilinearly (node groups Sandscape Texel Corners and Texel Blend). It is
the image's Linear value, and EEVEE evaluates it in the vertex stage where software OpenGL's
Linear lookup of a float image made a frame with prints never finish."""

from ..node_groups import helper as h
from ..node_groups import texel_blend, texel_corners
from . import ownership as own

PRINT_MAP = "Sandscape Print Map"  # the first lookup; the others are numbered
PRINT_TEXELS = [PRINT_MAP, *(f"{PRINT_MAP} {k}" for k in texel_corners.CORNERS[1:])]
PRINT_CORNERS, PRINT_BLEND = "Sandscape Print Corners", "Sandscape Print Blend"


def build(tree, mapping, node):
    """The print map read as four Closest lookups blended bilinearly (replacing one Linear lookup)."""
    old = own.node(tree, PRINT_MAP)
    if old is not None:
        tree.nodes.remove(old)
    corners = h.add_node(tree, "ShaderNodeGroup", name=PRINT_CORNERS, label="Print Texels",
                         node_tree=h.ensure_group(texel_corners))
    blend = h.add_node(tree, "ShaderNodeGroup", name=PRINT_BLEND, label="Print Blend",
                       node_tree=h.ensure_group(texel_blend))
    h.link(tree, mapping.outputs["Vector"], corners.inputs["Vector"])
    for k, name in zip(texel_corners.CORNERS, PRINT_TEXELS, strict=True):
        texture = h.add_node(tree, "ShaderNodeTexImage", name=name, label=f"Print Map {k}",
                             interpolation="Closest", extension="CLIP")
        h.link(tree, corners.outputs[f"Corner {k}"], texture.inputs["Vector"])
        h.link(tree, texture.outputs["Color"], blend.inputs[f"Color {k}"])
    for weight in ("Weight X", "Weight Y"):
        h.link(tree, corners.outputs[weight], blend.inputs[weight])
    h.link(tree, blend.outputs["Color"], node.inputs["Print Map"])
