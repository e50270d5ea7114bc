"""bpy.ops.sandscape.add_sand_material: idempotent updates, users' data left alone, bad input refused."""

import math

import bpy
import pytest

from devtools import operators, readback


def ours(datablocks, key):
    return [d for d in datablocks if d.get(key)]


def test_rerun_updates_instead_of_duplicating(sandscape):
    plane = readback.uv_plane()
    bpy.ops.sandscape.add_sand_material(threshold=0.9)
    bpy.ops.sandscape.add_sand_material(threshold=0.5, roughness=0.2)
    assert len(ours(bpy.data.materials, "sandscape_material")) == 1
    assert len(plane.material_slots) == 1
    # physical sand + its sand normal, lit glints + their cells, splat and facet, ripples + their
    # defects, the EEVEE balance
    assert len(ours(bpy.data.node_groups, "sandscape_group")) == 9
    node = sandscape.addon.sand.glint_node(plane.active_material)
    assert node.inputs["Threshold"].default_value == pytest.approx(0.5)
    assert node.inputs["Roughness"].default_value == pytest.approx(0.2)
    assert plane.active_material.cycles.emission_sampling == "NONE"  # glints light nothing else
    assert plane.active_material.cycles.use_bump_map_correction  # Physical: Blender's default
    # Switching source rebuilds our material in place, still one of everything.
    bpy.ops.sandscape.add_sand_material(source="IMAGE", image_resolution=16)
    bpy.ops.sandscape.add_sand_material(source="IMAGE", image_resolution=16, seed=3)
    assert len(ours(bpy.data.materials, "sandscape_material")) == 1
    assert len(ours(bpy.data.images, "sandscape_image")) == 1
    bpy.ops.sandscape.add_sand_material(source="PROCEDURAL")
    assert sandscape.addon.sand.image_node(plane.active_material) is None
    # Another look and emission glints: the same material, rebuilt, one of everything again.
    bpy.ops.sandscape.add_sand_material(look="JOURNEY", glints="EMISSION", ripples=False)
    assert len(ours(bpy.data.materials, "sandscape_material")) == 1
    assert sandscape.addon.sand.structure(plane.active_material) == ("JOURNEY", "EMISSION", "PROCEDURAL",
                                                                       False)
    assert not plane.active_material.cycles.use_bump_map_correction  # the contrast's slopes stay lit


def test_one_ior_reaches_the_sand_and_its_facets(sandscape):
    """The sand's Fresnel and its glint facets are the same grains: the operator's IOR sets both,
    and the sidebar's Update (invoke) gives the facets the IOR an artist typed on the sand."""
    plane = readback.uv_plane()
    sand = sandscape.addon.sand
    bpy.ops.sandscape.add_sand_material()
    material = plane.active_material
    surface, facets = sand.look_node(material).inputs["IOR"], sand.glint_node(material).inputs["IOR"]
    quartz = sandscape.core.sand.QUARTZ_IOR
    assert surface.default_value == pytest.approx(quartz) and facets.default_value == pytest.approx(quartz)
    bpy.ops.sandscape.add_sand_material(ior=1.6)
    assert surface.default_value == pytest.approx(1.6) and facets.default_value == pytest.approx(1.6)
    surface.default_value = 1.45  # typed on Physical Sand in the node editor
    # What Update starts from (invoke; background mode has no window to invoke in).
    assert sand.read_settings(material)["ior"] == pytest.approx(1.45)
    bpy.ops.sandscape.add_sand_material(ior=sand.read_settings(material)["ior"])
    assert facets.default_value == pytest.approx(1.45) and surface.default_value == pytest.approx(1.45)


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
    assert sandscape.addon.sand.glint_node(mine).node_tree != their_group


def test_outdated_group_is_rebuilt_and_users_move_over(sandscape):
    helper, glints = sandscape.node_groups.helper, sandscape.node_groups.glints
    plane = readback.uv_plane()
    bpy.ops.sandscape.add_sand_material(glints="EMISSION")
    old = helper.find_group(glints.NAME)
    old[helper.VERSION_KEY] = glints.VERSION - 1
    old_pointer = old.as_pointer()
    new = helper.ensure_group(glints)
    assert new.as_pointer() != old_pointer and new.name == glints.NAME
    assert len([g for g in bpy.data.node_groups if g.get(helper.GROUP_KEY) == glints.NAME]) == 1
    assert sandscape.addon.sand.glint_node(plane.active_material).node_tree == new
    assert helper.ensure_group(glints) == new  # current version: returned as is


def scene_for(case):
    if case == "no object":
        return None
    if case == "not a mesh":
        bpy.ops.curve.primitive_bezier_curve_add()
        return bpy.context.active_object
    if case == "no faces":
        mesh = bpy.data.meshes.new("Their Points")
        mesh.from_pydata([(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], [(0, 1)], [])
        obj = bpy.data.objects.new("Their Points", mesh)
        bpy.context.scene.collection.objects.link(obj)
        bpy.context.view_layer.objects.active = obj
        return obj
    obj = readback.uv_plane()
    if case == "no uv map":
        obj.data.uv_layers.remove(obj.data.uv_layers[0])
    return obj


@pytest.mark.parametrize("case", ["no object", "not a mesh"])
def test_without_a_mesh_the_button_is_greyed_out_with_a_reason(case):
    scene_for(case)
    before = readback.data_snapshot()
    assert not bpy.ops.sandscape.add_sand_material.poll()
    with pytest.raises(RuntimeError, match="Select a mesh"):
        bpy.ops.sandscape.add_sand_material()
    assert readback.data_snapshot() == before


BAD_INPUT = [
    ("plane", {"glint_size": 0.0}, "Glint Size must lie in 1e-07 m"),  # not "in 0 m .., got 0 m"
    ("plane", {"glint_size": -1.0}, "Glint Size"),
    ("plane", {"glint_size": math.nan}, "Glint Size"),
    ("plane", {"glint_size": math.inf}, "Glint Size"),
    ("plane", {"threshold": -0.1}, "Threshold"),
    ("plane", {"threshold": 1.5}, "Threshold"),
    ("plane", {"threshold": math.nan}, "Threshold"),
    ("plane", {"strength": -1.0}, "Strength"),
    ("plane", {"strength": math.inf}, "Strength"),
    ("plane", {"facing_power": -2.0}, "Facing Power"),
    ("plane", {"color": (1.0, math.nan, 1.0, 1.0)}, "Color"),
    ("plane", {"roughness": 2.0}, "Roughness"),
    ("plane", {"roughness": math.nan}, "Roughness"),
    ("plane", {"ripple_wavelength": 0.0}, "Ripple Wavelength"),
    ("plane", {"ripple_wavelength": math.nan}, "Ripple Wavelength"),
    ("plane", {"ripple_amplitude": math.inf}, "Ripple Amplitude"),
    ("plane", {"ripple_amplitude": -0.01}, "Ripple Amplitude"),
    ("plane", {"ripple_meander": math.nan}, "Ripple Meander"),
    ("plane", {"ripple_meander": 5.0}, "Ripple Meander"),
    ("plane", {"ripple_meander_scale": 0.0}, "Meander Scale"),
    ("plane", {"ripple_variation": 1.5}, "Ripple Variation"),
    ("plane", {"ior": math.nan}, "IOR"),
    ("plane", {"ior": 0.5}, "IOR"),
    ("plane", {"ior": math.inf}, "IOR"),
    ("plane", {"source": "IMAGE", "image": "no such image"}, "No image named"),
    ("no uv map", {"source": "IMAGE"}, "no UV map"),
    ("no faces", {}, "has no faces"),
]


@pytest.mark.parametrize("case,props,message", BAD_INPUT)
def test_bad_input_is_refused_and_changes_nothing(case, props, message):
    obj = scene_for(case)
    # A user's material already on the object must survive the refusal as well.
    obj.data.materials.append(bpy.data.materials.new("Their Material"))
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match=message):
        bpy.ops.sandscape.add_sand_material(**props)
    assert readback.data_snapshot() == before
    # The operator itself returns CANCELLED (bpy.ops turns the ERROR report into the exception).
    result, reports = operators.run_execute("sandscape.add_sand_material", **props)
    assert result == {"CANCELLED"} and reports[0][0] == {"ERROR"} and message in reports[0][1]
    assert readback.data_snapshot() == before
