"""bpy.ops.sandscape.add_sand_material: idempotent updates, users' data left alone, bad input refused."""

import math
import types

import bpy
import pytest

from devtools import readback


def ours(datablocks, key):
    return [d for d in datablocks if d.get(key)]


def test_rerun_updates_instead_of_duplicating(sandscape):
    plane = readback.uv_plane()
    bpy.ops.sandscape.add_sand_material(threshold=0.9)
    bpy.ops.sandscape.add_sand_material(threshold=0.5, strength=4.0)
    assert len(ours(bpy.data.materials, "sandscape_material")) == 1
    assert len(plane.material_slots) == 1
    assert len(ours(bpy.data.node_groups, "sandscape_group")) == 2  # glints + shade
    node = sandscape.blender.sand.glint_node(plane.active_material)
    assert node.inputs["Threshold"].default_value == pytest.approx(0.5)
    assert node.inputs["Strength"].default_value == pytest.approx(4.0)
    assert plane.active_material.cycles.emission_sampling == "NONE"  # glints light nothing else
    # Switching source rebuilds our material in place, still one of everything.
    bpy.ops.sandscape.add_sand_material(source="IMAGE", image_resolution=16)
    bpy.ops.sandscape.add_sand_material(source="IMAGE", image_resolution=16, seed=3)
    assert len(ours(bpy.data.materials, "sandscape_material")) == 1
    assert len(ours(bpy.data.images, "sandscape_image")) == 1
    bpy.ops.sandscape.add_sand_material(source="PROCEDURAL")
    assert sandscape.blender.sand.image_node(plane.active_material) is None


def test_users_look_alike_data_is_never_touched(sandscape):
    plane = readback.uv_plane()
    theirs = bpy.data.materials.new("Sandscape Sand")
    theirs.diffuse_color = (0.1, 0.2, 0.3, 1.0)
    plane.data.materials.append(theirs)
    their_group = bpy.data.node_groups.new("Sandscape Glints", "ShaderNodeTree")
    bpy.ops.sandscape.add_sand_material()
    assert theirs.get("sandscape_material") is None
    assert tuple(theirs.diffuse_color) == pytest.approx((0.1, 0.2, 0.3, 1.0))
    assert plane.material_slots[0].material == theirs  # still on the object, so never orphaned
    mine = plane.active_material
    assert mine != theirs and mine.get("sandscape_material") == "sand"
    assert all(p.material_index == plane.active_material_index for p in plane.data.polygons)
    assert len(their_group.nodes) == 0 and their_group.get("sandscape_group") is None
    assert sandscape.blender.sand.glint_node(mine).node_tree != their_group


def test_outdated_group_is_rebuilt_and_users_move_over(sandscape):
    helper, glints = sandscape.node_groups.helper, sandscape.node_groups.glints
    plane = readback.uv_plane()
    bpy.ops.sandscape.add_sand_material()
    old = helper.find_group(glints.NAME)
    old[helper.VERSION_KEY] = glints.VERSION - 1
    old_pointer = old.as_pointer()
    new = helper.ensure_group(glints)
    assert new.as_pointer() != old_pointer and new.name == glints.NAME
    assert len([g for g in bpy.data.node_groups if g.get(helper.GROUP_KEY) == glints.NAME]) == 1
    assert sandscape.blender.sand.glint_node(plane.active_material).node_tree == new
    assert helper.ensure_group(glints) == new  # current version: returned as is


def scene_for(case):
    if case == "no object":
        return None
    if case == "not a mesh":
        bpy.ops.curve.primitive_bezier_curve_add()
        return bpy.context.active_object
    obj = readback.uv_plane()
    if case == "no uv map":
        obj.data.uv_layers.remove(obj.data.uv_layers[0])
    return obj


BAD_INPUT = [
    ("no object", {}, "No active object"),
    ("not a mesh", {}, "not a mesh"),
    ("plane", {"glint_size": 0.0}, "Glint size"),
    ("plane", {"glint_size": -1.0}, "Glint size"),
    ("plane", {"glint_size": math.nan}, "Glint size"),
    ("plane", {"threshold": -0.1}, "Threshold"),
    ("plane", {"threshold": 1.5}, "Threshold"),
    ("plane", {"threshold": math.nan}, "Threshold"),
    ("plane", {"strength": -1.0}, "Strength"),
    ("plane", {"facing_power": -2.0}, "Facing power"),
    ("plane", {"source": "IMAGE", "image": "no such image"}, "No image named"),
    ("no uv map", {"source": "IMAGE"}, "no UV map"),
]


@pytest.mark.parametrize("case,props,message", BAD_INPUT)
def test_bad_input_is_refused_and_changes_nothing(sandscape, case, props, message):
    obj = scene_for(case)
    # A user's material already on the object must survive the refusal as well.
    if obj is not None and obj.type == "MESH":
        obj.data.materials.append(bpy.data.materials.new("Their Material"))
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match=message):
        bpy.ops.sandscape.add_sand_material(**props)
    assert readback.data_snapshot() == before

    # The operator itself returns CANCELLED (bpy.ops turns the ERROR report into the exception).
    cls = bpy.types.SANDSCAPE_OT_add_sand_material
    reports = []
    rna = bpy.ops.sandscape.add_sand_material.get_rna_type().properties
    defaults = {p.identifier: tuple(p.default_array) if getattr(p, "is_array", False) else p.default
                for p in rna if p.identifier != "rna_type"}
    fake = types.SimpleNamespace(**{**defaults, **props},
                                 report=lambda kind, text: reports.append((kind, text)))
    fake._problem = types.MethodType(cls._problem, fake)
    assert cls.execute(fake, bpy.context) == {"CANCELLED"}
    assert reports and reports[0][0] == {"ERROR"} and message in reports[0][1]
    assert readback.data_snapshot() == before
