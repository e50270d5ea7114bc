import bpy


def test_operator_adds_material(sandscape):
    bpy.ops.mesh.primitive_plane_add()
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    obj = bpy.context.active_object
    assert obj.active_material.get("sandscape_material") == "sand"
