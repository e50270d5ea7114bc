"""bpy.ops.sandscape.build_demo_scene: every part of the desert in one call, into an empty file."""

import bpy
import pytest


def ours(kind):
    return [o for o in bpy.data.objects if o.get("sandscape_object") == kind]


def test_builds_every_part(sandscape):
    assert bpy.ops.sandscape.build_demo_scene() == {"FINISHED"}
    scene = bpy.context.scene
    terrain = scene.sandscape_footprints.terrain
    material = terrain.active_material
    groups = sandscape.blender.sand
    assert groups.glint_node(material) is not None and groups.footprint_node(material) is not None
    assert len(ours("footprints")[0].data.vertices) > 20 and ours("footprint_patch")
    assert ours("walker") and ours("sun") and ours("dust_volume")
    tree = scene.compositing_node_group
    assert tree is not None and tree.get("sandscape_compositor")
    assert [c.type for c in scene.camera.constraints] == ["COPY_LOCATION", "TRACK_TO"]
    assert not scene.cycles.use_denoising


def test_refuses_a_scene_with_meshes():
    bpy.ops.mesh.primitive_cube_add()
    with pytest.raises(RuntimeError, match="empty scene"):
        bpy.ops.sandscape.build_demo_scene()
