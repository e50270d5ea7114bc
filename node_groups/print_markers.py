"""Sandscape Print Markers: shows the footprint points in the viewport as small dots.

The footprints object is a mesh of loose vertices (editable in Edit Mode); loose vertices
do not draw in Object Mode, so this modifier turns them into points of Radius.
"""

from . import helper as h

NAME = "Sandscape Print Markers"
VERSION = 2
TREE_TYPE = "GeometryNodeTree"
DESCRIPTION = "Footprint points as viewport dots; the object is hidden from renders"


def build(tree):
    tree.description = DESCRIPTION
    h.add_input(tree, "Geometry", "NodeSocketGeometry", "The footprint points (loose vertices)")
    h.add_input(tree, "Radius", "NodeSocketFloat", "Dot radius in metres", 0.03, 0.0, None, "DISTANCE")
    h.add_output(tree, "Geometry", "NodeSocketGeometry", "One point per print, attributes kept")
    group_in, group_out = h.group_io(tree)
    points = h.add_node(tree, "GeometryNodeMeshToPoints", (0, 0), mode="VERTICES")
    h.link(tree, group_in.outputs["Geometry"], points.inputs["Mesh"])
    h.link(tree, group_in.outputs["Radius"], points.inputs["Radius"])
    h.link(tree, points.outputs["Points"], group_out.inputs["Geometry"])
    h.arrange(tree)
