"""Every node group against its snapshot (tests/snapshots/), and laid out to be read.

A builder that changes what it builds must bump VERSION, or files made by the old builder would
keep the old group: the snapshot test fails when the group changed and VERSION did not.
"""

import importlib
import itertools
import json

import bpy
import pytest

from devtools import session, snapshots

catalog = importlib.import_module(f"{session.MODULE}.node_groups.catalog")
helper = importlib.import_module(f"{session.MODULE}.node_groups.helper")
NAMES = [builder.NAME for builder in catalog.builders()]


@pytest.mark.parametrize("name", NAMES)
def test_group_is_its_snapshot_at_its_version(name):
    builder = catalog.builder_named(name)
    path = snapshots.path_for(builder)
    assert path.is_file(), f"no snapshot for {name}: run devtools/snapshots.py"
    stored = json.loads(path.read_text())
    fresh = snapshots.serialize(snapshots.build_fresh(bpy, builder))
    assert stored["version"] == builder.VERSION, (
        f"{name} is at VERSION {builder.VERSION}, its snapshot at {stored['version']}: "
        "run devtools/snapshots.py and commit the snapshot")
    assert json.loads(json.dumps(fresh)) == stored["group"], (
        f"{name} changed without a VERSION bump: bump VERSION in its builder, then run devtools/snapshots.py")


@pytest.mark.parametrize("name", NAMES)
def test_group_reads_left_to_right_without_overlaps(name):
    tree = snapshots.build_fresh(bpy, catalog.builder_named(name))
    boxes = {}
    for node in tree.nodes:
        if node.bl_idname != "NodeFrame":
            width, height = helper.node_size(node)
            x, y = node.location_absolute
            boxes[node.name] = (x, x + width, y - height, y)
    for (a, box_a), (b, box_b) in itertools.combinations(boxes.items(), 2):
        apart = box_a[1] <= box_b[0] or box_b[1] <= box_a[0] or box_a[3] <= box_b[2] or box_b[3] <= box_a[2]
        assert apart, f"{a} overlaps {b}"
    for link in tree.links:
        assert boxes[link.from_node.name][1] < boxes[link.to_node.name][0], (
            f"{link.from_node.name} -> {link.to_node.name} runs right to left")
    assert all(node.description for node in tree.interface.items_tree if node.item_type == "SOCKET")
    stages = [node for node in tree.nodes if node.bl_idname == "NodeFrame"]
    assert all(node.parent in stages for node in tree.nodes
               if node.bl_idname not in {"NodeFrame", "NodeGroupInput", "NodeGroupOutput"}) or len(boxes) <= 3
