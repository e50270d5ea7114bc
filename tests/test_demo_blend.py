"""The committed demo.blend is what `make demo-blend` builds: same data-block names, same group versions,
the same nodes in its worlds' and materials' trees (a change to the world's EEVEE light shows there)."""

import pathlib

import bpy

REPO = pathlib.Path(__file__).resolve().parent.parent
COLLECTIONS = ("objects", "meshes", "materials", "node_groups", "images", "worlds", "cameras", "lights",
               "curves", "actions", "scenes")


def inventory():
    names = {kind: sorted(block.name for block in getattr(bpy.data, kind)) for kind in COLLECTIONS}
    versions = {group.name: group.get("sandscape_version") for group in bpy.data.node_groups}
    trees = {f"{kind} {block.name}": sorted(node.name for node in block.node_tree.nodes)
             for kind in ("worlds", "materials") for block in getattr(bpy.data, kind) if block.node_tree}
    return names, versions, trees


def test_committed_demo_matches_a_fresh_build(demo_scene):
    fresh = inventory()  # the run's own build (tests/conftest.py)
    bpy.ops.wm.open_mainfile(filepath=str(REPO / "demo.blend"), load_ui=False)
    committed = inventory()
    assert committed[0] == fresh[0], "demo.blend is stale: run `make demo-blend` and commit it"
    assert committed[1] == fresh[1], "a node group version changed: run `make demo-blend`, commit demo.blend"
    assert committed[2] == fresh[2], "a world's or material's nodes changed: run `make demo-blend`, commit it"
