"""The sand's EEVEE output: Cycles keeps its own, EEVEE gets the same surface balanced by the
driven sun; re-runs, looks, painted prints and a moved sun keep the two in step."""

import math

import bpy
import numpy as np
import pytest

from devtools import readback, scenes


def outputs(material):
    return {node.name: node.target for node in material.node_tree.nodes
            if node.bl_idname == "ShaderNodeOutputMaterial"}


def source(socket):
    return socket.links[0].from_socket if socket.links else None


def test_each_look_gets_its_own_eevee_output_once(sandscape):
    """Physical: the Cycles surface balanced. Journey: its EEVEE Shader, lit by the driven sun,
    with the glints' facets (or emission) on top. Re-runs and switching looks leave one of each."""
    plane = readback.uv_plane()
    for _ in range(2):
        assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    material = plane.active_material
    tree = material.node_tree
    assert outputs(material) == {"Sandscape Output": "CYCLES", "Sandscape EEVEE Output": "EEVEE"}
    names = [node.name for node in tree.nodes]
    assert len(names) == len(set(names))
    assert "Sandscape EEVEE Balance" in names and "Sandscape EEVEE Journey Surface" not in names
    for glints, on_top in (("LIT", "Facets"), ("EMISSION", "Emission"), ("LIT", "Facets")):
        assert bpy.ops.sandscape.add_sand_material(look="JOURNEY", glints=glints) == {"FINISHED"}
        assert outputs(material) == {"Sandscape Output": "CYCLES", "Sandscape EEVEE Output": "EEVEE"}
        names = [node.name for node in tree.nodes]
        assert len(names) == len(set(names)) and "Sandscape EEVEE Balance" not in names
        look, glint = sandscape.addon.sand.look_node(material), sandscape.addon.sand.glint_node(material)
        surface = tree.nodes["Sandscape EEVEE Journey Surface"]
        assert source(tree.nodes["Sandscape EEVEE Output"].inputs["Surface"]) == surface.outputs[0]
        assert source(surface.inputs[0]) == look.outputs["EEVEE Shader"]
        where_lit = tree.nodes["Sandscape EEVEE Glints Where Lit"]  # the glints where the sun reaches
        assert source(surface.inputs[1]) == where_lit.outputs[0] and not where_lit.inputs[1].links
        assert source(where_lit.inputs[2]) == glint.outputs[on_top]
        assert source(where_lit.inputs["Fac"]).node.name.startswith("Sandscape EEVEE Sun Reach")
        assert source(look.inputs["Sun Direction"]) == tree.nodes["Sandscape EEVEE Sun"].outputs[0]
        assert source(tree.nodes["Sandscape Output"].inputs["Surface"]).node in (
            glint, tree.nodes.get(sandscape.addon.sand.GLINTS_ADDED))  # Cycles keeps its Toons
    assert bpy.ops.sandscape.add_sand_material(look="PHYSICAL") == {"FINISHED"}
    assert outputs(material) == {"Sandscape Output": "CYCLES", "Sandscape EEVEE Output": "EEVEE"}
    assert "Sandscape EEVEE Journey Surface" not in tree.nodes


def test_the_balance_follows_the_sun_and_the_prints_reach_eevee(sandscape):
    terrain = scenes.height_field(8.0, 8, name="Their Sand")
    walker = scenes.keyframed_walker(lambda f: (-1.5 + 3.0 * (f - 1) / 30, 0.0, 0.0), range(1, 32))
    scenes.footprint_settings(terrain, walker, (1, 31), resolution=128)
    bpy.context.view_layer.objects.active = terrain
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    material = terrain.active_material
    tree = material.node_tree
    sun_node = tree.nodes["Sandscape EEVEE Sun"]
    assert tuple(sun_node.inputs[i].default_value for i in range(3)) == (0.0, 0.0, 0.0)  # no sun yet
    scene = bpy.context.scene
    scene.sandscape_atmosphere.sun_elevation = math.radians(20.0)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    sun = sandscape.addon.atmosphere.scene_sun(scene)
    for elevation in (20.0, 65.0):
        if elevation != 20.0:  # the artist turns our sun by hand
            sun.rotation_euler = (math.radians(90.0 - elevation), 0.0, 0.4)
        scene.frame_set(scene.frame_current)
        driven = np.array([sun_node.inputs[i].default_value for i in range(3)])
        axis = np.array(sun.matrix_world.col[2][:3])
        assert np.allclose(driven, axis, atol=1e-5)
        assert math.degrees(math.asin(axis[2] / np.linalg.norm(axis))) == pytest.approx(elevation, abs=0.01)
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    cycles, eevee = tree.nodes["Sandscape Output"], tree.nodes["Sandscape EEVEE Output"]
    assert source(cycles.inputs["Displacement"]) is not None
    assert source(eevee.inputs["Displacement"]) == source(cycles.inputs["Displacement"])
    # EEVEE's surface: the lit glints' sand blended with the sand under them by the sun's reach
    where_lit = tree.nodes["Sandscape EEVEE Glints Where Lit"]
    assert source(tree.nodes["Sandscape EEVEE Scale"].inputs[1]) == where_lit.outputs[0]
    assert source(where_lit.inputs[2]) == source(cycles.inputs["Surface"])
    assert source(where_lit.inputs[1]) == source(source(cycles.inputs["Surface"]).node.inputs["Base"])
    # the sand's own light (its sun's part lifted where the balance is above 1): the sand under the glints
    assert source(tree.nodes["Sandscape EEVEE Sand RGB"].inputs["Shader"]) == source(where_lit.inputs[1])


def test_an_older_balance_boosting_the_sky_too_is_rebuilt(sandscape):
    """A material made before the boost took the sun's light alone (a Lambert diffuse named as the
    boost) and before lit glints kept to the sun, or before the dimming balance gave the ambient
    back, or before its ambient had a balance of its own: the next Add Sand Material builds the
    EEVEE nodes anew, the same nodes as a new one's."""
    sand_eevee = sandscape.addon.sand_eevee
    plane = readback.uv_plane()
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    tree = plane.active_material.node_tree
    fresh = sorted(node.name for node in tree.nodes)
    boost = tree.nodes[sand_eevee.BOOST]
    assert boost.bl_idname == "ShaderNodeEmission"
    older = sand_eevee.SUN_LIGHT + sand_eevee.SUN_REACH + (
        sand_eevee.BOOST_LIGHT, sand_eevee.BOOST, sand_eevee.SUN_IRRADIANCE, sand_eevee.GLINTS_WHERE_LIT)
    for name in older:
        if name in tree.nodes:  # the geometry's normal only where the look's is unlinked
            tree.nodes.remove(tree.nodes[name])
    old = tree.nodes.new("ShaderNodeBsdfDiffuse")
    old.name = sand_eevee.BOOST
    tree.links.new(old.outputs[0], tree.nodes[sand_eevee.BOTH].inputs[1])
    surface = source(tree.nodes[sand_eevee.CYCLES_OUTPUT].inputs["Surface"])
    tree.links.new(surface, tree.nodes[sand_eevee.SCALE].inputs[1])
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    assert sorted(node.name for node in tree.nodes) == fresh
    assert tree.nodes[sand_eevee.BOOST].bl_idname == "ShaderNodeEmission"
    assert source(tree.nodes[sand_eevee.BOTH].inputs[1]).node == tree.nodes[sand_eevee.BOOST]
    # A build whose dimming balance scaled the ambient too (before its light was given back).
    tree.nodes.remove(tree.nodes[sand_eevee.AMBIENT_KEPT])
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    assert sorted(node.name for node in tree.nodes) == fresh
    kept = tree.nodes[sand_eevee.AMBIENT_KEPT]
    assert source(kept.inputs[0]).node == tree.nodes[sand_eevee.SAND_AMBIENT[-1]]
    # A build whose ambient was not balanced (before 2026-12-07): its own balance now scales it.
    tree.nodes.remove(tree.nodes[sand_eevee.AMBIENT_SCALE])
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    assert sorted(node.name for node in tree.nodes) == fresh
    given_back = source(tree.nodes[sand_eevee.AMBIENT_KEPT].inputs[1]).node
    given = source(given_back.inputs[0]).node
    assert given == tree.nodes[sand_eevee.AMBIENT_GIVEN]
    scale = source(given.inputs[0]).node
    tinted = source(scale.inputs[1]).node
    assert source(tinted.inputs["Scale"]) == tree.nodes[sand_eevee.BALANCE].outputs["Ambient Balance"]
    # A build whose ambient balance was one factor for all channels (before 2026-12-08).
    tree.nodes.remove(tinted)
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    assert sorted(node.name for node in tree.nodes) == fresh
    tinted = tree.nodes[sand_eevee.AMBIENT_TINTED]
    assert source(tinted.inputs[0]) == tree.nodes[sand_eevee.BALANCE].outputs["Ambient Tint"]
    # A build whose light added went negative where the ambient balance took light away, drawn as
    # none (before 2026-12-08): what it takes now comes off the surface's scale.
    for name in sand_eevee.POSITIVE:
        tree.nodes.remove(tree.nodes[name])
    tree.links.new(tree.nodes[sand_eevee.DOWN_HELD].outputs[0], tree.nodes[sand_eevee.SCALE].inputs["Fac"])
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    assert sorted(node.name for node in tree.nodes) == fresh
    assert source(tree.nodes[sand_eevee.SCALE].inputs["Fac"]).node.name in sand_eevee.POSITIVE


def test_the_sands_ambient_follows_its_twin(sandscape):
    """The sand's ambient in its EEVEE output (the ambient light at the normal times the sand's
    colour plus W(N·V), what EEVEE's sheen and specular add) built on a constant light and rendered
    by Cycles on a plane seen from 1.6 m, grazing to steep: each pixel as
    core.eevee_balance.sand_ambient at its N·V, within 1e-4 (W's curve is not flat there)."""
    from core import eevee_balance as twin

    bpy.ops.mesh.primitive_plane_add(size=200)
    plane = bpy.context.active_object
    material = bpy.data.materials.new("Sand Ambient")
    tree = material.node_tree
    tree.nodes.clear()
    light, colour = (0.9, 0.7, 0.5), (0.62, 0.45, 0.27)
    sockets = []
    for value in (light, colour):
        node = tree.nodes.new("ShaderNodeRGB")
        node.outputs[0].default_value = (*value, 1.0)
        sockets.append(node.outputs[0])
    ambient, _ = sandscape.addon.sand_eevee_light.sand_ambient(tree, None, *sockets)
    emission = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(ambient, emission.inputs["Color"])
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(emission.outputs[0], output.inputs["Surface"])
    plane.data.materials.append(material)
    scene = readback.cycles_scene(bpy.context.scene, (16, 24), 1)
    scene.cycles.filter_width = 0.01  # each pixel its centre's ray
    camera = scenes.camera("PERSP", location=(0.0, 0.0, 1.6), rotation=(math.radians(55), 0.0, 0.0), lens=20)
    scene.camera = camera
    pixels = readback.render(scene)[..., :3]
    _, directions = scenes.camera_rays(camera, 16, 24)
    v = -directions[..., 2]
    ground = v > 0.02
    expected = twin.sand_ambient(light, colour, v)
    assert v[ground].min() < 0.1 and v[ground].max() > 0.8
    assert np.ptp(twin.sheen_ambient(v[ground]), axis=0).min() > 0.05
    assert np.abs(pixels[ground] - expected[ground]).max() < 1e-4
