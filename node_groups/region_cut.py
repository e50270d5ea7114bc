"""Sandscape Region Cut: removes the terrain's faces over the footprint region.

The footprint patch object (adaptive subdivision, true displacement) replaces them, so
the rest of the terrain stays coarse. A face is cut when its centre lies inside the box
Min..Max in the object's X and Y; the patch keeps exactly those faces (same test), so the
two meet without a gap or an overlap. Twin: core.footprints.faces_in_region.
"""

from . import helper as h

NAME = "Sandscape Region Cut"
VERSION = 1
TREE_TYPE = "GeometryNodeTree"


def build(tree):
    tree.description = ("Deletes faces whose centre lies inside Min..Max (object X and Y): the "
                        "footprint patch draws them instead")
    h.add_input(tree, "Geometry", "NodeSocketGeometry", "The terrain")
    h.add_input(tree, "Min", "NodeSocketVector", "Lower corner of the region (object X, Y; Z unused)",
                (0.0, 0.0, 0.0))
    h.add_input(tree, "Max", "NodeSocketVector", "Upper corner of the region (object X, Y; Z unused)",
                (0.0, 0.0, 0.0))
    h.add_output(tree, "Geometry", "NodeSocketGeometry", "The terrain without the region's faces")

    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    position = h.add_node(tree, "GeometryNodeInputPosition", (-700, -200))
    above = h.add_node(tree, "FunctionNodeCompare", (-450, -100), "Above Min", data_type="VECTOR",
                       mode="ELEMENT", operation="GREATER_EQUAL")
    below = h.add_node(tree, "FunctionNodeCompare", (-450, -350), "Below Max", data_type="VECTOR",
                       mode="ELEMENT", operation="LESS_EQUAL")
    h.link(tree, position.outputs[0], above.inputs["A"])
    h.link(tree, inputs["Min"], above.inputs["B"])
    h.link(tree, position.outputs[0], below.inputs["A"])
    h.link(tree, inputs["Max"], below.inputs["B"])
    # ELEMENT mode compares all three components: Z is opened to +-inf by the caller.
    inside = h.add_node(tree, "FunctionNodeBooleanMath", (-200, -200), "Inside", operation="AND")
    h.link(tree, above.outputs[0], inside.inputs[0])
    h.link(tree, below.outputs[0], inside.inputs[1])
    delete = h.add_node(tree, "GeometryNodeDeleteGeometry", (100, 0), domain="FACE")
    h.link(tree, inputs["Geometry"], delete.inputs["Geometry"])
    h.link(tree, inside.outputs[0], delete.inputs["Selection"])
    h.link(tree, delete.outputs[0], group_out.inputs["Geometry"])
