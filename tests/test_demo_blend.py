"""The committed demo.blend is what `make demo-blend` builds: same data-block names, same group versions."""

import pathlib

import bpy

REPO = pathlib.Path(__file__).resolve().parent.parent
COLLECTIONS = ("objects", "meshes", "materials", "node_groups", "images", "worlds", "cameras", "lights",
               "curves", "actions", "scenes")


def inventory():
    names = {kind: sorted(block.name for block in getattr(bpy.data, kind)) for kind in COLLECTIONS}
    versions = {group.name: group.get("sandscape_version") for group in bpy.data.node_groups}
    return names, versions


def test_committed_demo_matches_a_fresh_build(demo_scene):
    fresh = inventory()  # the run's own build (tests/conftest.py)
    bpy.ops.wm.open_mainfile(filepath=str(REPO / "demo.blend"), load_ui=False)
    committed = inventory()
    assert committed[0] == fresh[0], "demo.blend is stale: run `make demo-blend` and commit it"
    assert committed[1] == fresh[1], "a node group version changed: run `make demo-blend`, commit demo.blend"
