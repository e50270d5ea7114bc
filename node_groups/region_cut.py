"""Sandscape Region Cut: removes the terrain's faces over the footprint region.

The footprint patch object (adaptive subdivision, true displacement) replaces them, so
the rest of the terrain stays coarse. A face is cut when its centre, in the space of the
Frame object (the print frame: world-aligned and in world units when the prints were
painted), lies inside the box Min..Max in X and Y; the patch keeps exactly those faces (same
test), so the two meet without a gap or an overlap. Without a Frame, the box is in the
terrain's own space. The faces left keep the normals they had: deleting faces would otherwise
turn the border vertices' normals and show a seam. Twin: core.footprints.faces_in_region on
frame-space face centres.
"""

from . import helper as h

NAME = "Sandscape Region Cut"
VERSION = 3
TREE_TYPE = "GeometryNodeTree"
NORMAL_ATTRIBUTE = "sandscape_cut_normal"
DESCRIPTION = (
    "Deletes faces whose centre lies inside Min..Max (X and Y of the Frame object's space): the "
    "footprint patch draws them instead")


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Geometry", "NodeSocketGeometry", "The terrain")
    h.add_input(tree, "Min", "NodeSocketVector", "Lower corner of the region (Frame X, Y; Z unused)",
                (0.0, 0.0, 0.0))
    h.add_input(tree, "Max", "NodeSocketVector", "Upper corner of the region (Frame X, Y; Z unused)",
                (0.0, 0.0, 0.0))
    h.add_input(tree, "Frame", "NodeSocketObject", "The print frame whose X and Y the region is in "
                "(empty: the terrain's own space)")
    h.add_output(tree, "Geometry", "NodeSocketGeometry", "The terrain without the region's faces")

    group_in, group_out = h.group_io(tree)
    inputs = group_in.outputs
    frame = h.add_node(tree, "GeometryNodeObjectInfo", label="Print Frame", transform_space="RELATIVE")
    h.link(tree, inputs["Frame"], frame.inputs["Object"])
    to_frame = h.add_node(tree, "FunctionNodeInvertMatrix", label="Terrain → Frame")
    h.link(tree, frame.outputs["Transform"], to_frame.inputs["Matrix"])
    position = h.add_node(tree, "GeometryNodeInputPosition")
    in_frame = h.add_node(tree, "FunctionNodeTransformPoint", label="Position in Frame")
    h.link(tree, position.outputs[0], in_frame.inputs["Vector"])
    h.link(tree, to_frame.outputs["Matrix"], in_frame.inputs["Transform"])
    above = h.add_node(tree, "FunctionNodeCompare", label="Above Min", data_type="VECTOR", mode="ELEMENT",
                       operation="GREATER_EQUAL")
    below = h.add_node(tree, "FunctionNodeCompare", label="Below Max", data_type="VECTOR", mode="ELEMENT",
                       operation="LESS_EQUAL")
    h.link(tree, in_frame.outputs[0], above.inputs["A"])
    h.link(tree, inputs["Min"], above.inputs["B"])
    h.link(tree, in_frame.outputs[0], below.inputs["A"])
    h.link(tree, inputs["Max"], below.inputs["B"])
    # ELEMENT mode compares all three components: Z is opened to +-inf by the caller.
    inside = h.add_node(tree, "FunctionNodeBooleanMath", label="Inside", operation="AND")
    h.link(tree, above.outputs[0], inside.inputs[0])
    h.link(tree, below.outputs[0], inside.inputs[1])
    normal = h.add_node(tree, "GeometryNodeInputNormal")
    keep = h.add_node(tree, "GeometryNodeStoreNamedAttribute", label="Normals Before the Cut",
                      data_type="FLOAT_VECTOR", domain="CORNER", inputs={"Name": NORMAL_ATTRIBUTE})
    h.link(tree, inputs["Geometry"], keep.inputs["Geometry"])
    h.link(tree, normal.outputs["Normal"], keep.inputs["Value"])
    delete = h.add_node(tree, "GeometryNodeDeleteGeometry", domain="FACE")
    h.link(tree, keep.outputs["Geometry"], delete.inputs["Geometry"])
    h.link(tree, inside.outputs[0], delete.inputs["Selection"])
    kept = h.add_node(tree, "GeometryNodeInputNamedAttribute", data_type="FLOAT_VECTOR",
                      inputs={"Name": NORMAL_ATTRIBUTE})
    restore = h.add_node(tree, "GeometryNodeSetMeshNormal", label="Same Normals After", mode="FREE",
                         domain="CORNER")
    h.link(tree, delete.outputs[0], restore.inputs["Mesh"])
    h.link(tree, kept.outputs["Attribute"], restore.inputs["Custom Normal"])
    tidy = h.add_node(tree, "GeometryNodeRemoveAttribute", inputs={"Name": NORMAL_ATTRIBUTE})
    h.link(tree, restore.outputs[0], tidy.inputs["Geometry"])
    h.link(tree, tidy.outputs[0], group_out.inputs["Geometry"])
    h.frame(tree, "Face Centres in the Print Frame", (frame, to_frame, position, in_frame))
    h.frame(tree, "Inside the Region", (above, below, inside))
    h.frame(tree, "Cut, Normals Kept", (normal, keep, delete, kept, restore, tidy))
    h.arrange(tree)
