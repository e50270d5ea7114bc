"""bpy.ops.sandscape.optimize_scene: finds what does not reach the image, lists it on a dry run,
switches it off otherwise, and leaves the demo's working parts alone."""

import math

import bpy
import pytest

from devtools import scenes


def messages(capture):
    return [line for line in capture if line]


@pytest.fixture
def wasteful_demo(demo_scene):
    """The demo plus things that cost render time and add nothing."""
    scene = demo_scene
    fog = scenes.empty_fog(2, (0, 0, 5))
    bpy.ops.mesh.primitive_plane_add(size=4, location=(0, 0, 0.5))
    slab = bpy.context.active_object
    slab.name = "Flat Slab"
    dicing = slab.modifiers.new("Subdivision", "SUBSURF")
    dicing.use_adaptive_subdivision = True
    scene.view_layers[0].use_pass_z = True
    scene.cycles.volume_bounces = 2
    scenes.world_volume(scene.world, density=0.0)
    return scene, fog, slab, dicing


def world_volume_linked(scene):
    return any(n.bl_idname == "ShaderNodeOutputWorld" and n.inputs["Volume"].is_linked
               for n in scene.world.node_tree.nodes)


def test_a_world_volume_that_scatters_stays(demo_scene):
    scene = demo_scene
    scenes.world_volume(scene.world, density=1e-4)
    assert not any("World" in line for line in run(dry_run=False))
    assert world_volume_linked(scene)


def run(dry_run):
    cls = bpy.types.SANDSCAPE_OT_optimize_scene
    reports = []

    class Fake:
        def report(self, kind, text):
            reports.append(text)

    fake = Fake()
    fake.dry_run = dry_run
    assert cls.execute(fake, bpy.context) == {"FINISHED"}
    return reports


def test_dry_run_lists_and_changes_nothing(wasteful_demo):
    scene, fog, slab, dicing = wasteful_demo
    lines = run(dry_run=True)
    assert any("Empty Fog" in line and "density 0" in line for line in lines)
    assert any("Flat Slab" in line and "does not displace" in line for line in lines)
    assert any("pass 'Depth'" in line for line in lines)
    assert any(line.startswith("would: World") and "density 0" in line for line in lines)
    assert all(line.startswith("would: ") for line in lines[:-1])
    assert not fog.hide_render and dicing.use_adaptive_subdivision and scene.view_layers[0].use_pass_z
    assert world_volume_linked(scene)


def test_switches_off_only_what_does_not_contribute(sandscape, wasteful_demo):
    scene, fog, slab, dicing = wasteful_demo
    run(dry_run=False)
    assert fog.hide_render and not dicing.use_adaptive_subdivision and not scene.view_layers[0].use_pass_z
    assert not world_volume_linked(scene)
    # The demo's own parts contribute and stay: the displacing patch, the dust, the passes the tree reads.
    patch = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprint_patch")
    assert patch.modifiers[0].use_adaptive_subdivision
    dust = next(o for o in bpy.data.objects if o.get("sandscape_object") == "dust_volume")
    assert not dust.hide_render and scene.cycles.volume_bounces == 2
    assert scene.view_layers[0].cycles.use_pass_volume_direct and scene.view_layers[0].use_pass_environment
    assert run(dry_run=False)[-1] == "Nothing to switch off"  # a second run finds nothing


def test_dark_glints_idle_rays_and_bounces(sandscape, wasteful_demo):
    scene, fog, slab, dicing = wasteful_demo
    terrain = scene.sandscape_footprints.terrain
    bpy.context.view_layer.objects.active = terrain
    bpy.ops.sandscape.add_sand_material(glints="EMISSION", strength=0.0)  # sparkles turned off
    scene.sandscape_atmosphere.sun_azimuth = math.radians(270.0)  # behind the walker and the camera
    air = scene.sandscape_atmosphere
    air.density = air.dust_density = 0.0
    air.use_haze = False  # no dust box
    bpy.ops.sandscape.add_atmosphere()
    assert bpy.ops.sandscape.add_clouds(coverage=0.0) == {"FINISHED"}  # clear sky: no volume is left
    bpy.ops.sandscape.add_post_effects()
    fog.name = "Dune's 'Empty' Fog"  # quotes in a name: the findings are matched by kind, not text
    lines = run(dry_run=False)
    assert any("glint strength 0" in line for line in lines)
    assert any("God rays removed" in line and "out of view" in line for line in lines)
    assert any("Sun glow removed" in line and "out of view" in line for line in lines)
    assert any("Volume bounces 2 -> 0" in line for line in lines)
    material = terrain.active_material
    output = next(n for n in material.node_tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
    assert output.inputs["Surface"].links[0].from_node == sandscape.addon.sand.look_node(material)
    assert sandscape.addon.sun_screen.rays_node(scene.compositing_node_group) is None
    assert scene.compositing_node_group.nodes.get(sandscape.addon.post_glow.GLOW) is None
    assert scene.cycles.volume_bounces == 0


def test_in_eevee_it_weighs_what_eevee_renders(wasteful_demo):
    """In EEVEE, Cycles' dicing, volume bounces and passes cost nothing and stay as they are;
    EEVEE's own unread passes and what both engines spend on (an empty volume, a pass) go."""
    scene, fog, slab, dicing = wasteful_demo
    scene.render.engine = "BLENDER_EEVEE"
    layer = scene.view_layers[0]
    layer.eevee.use_pass_transparent = True
    layer.cycles.use_pass_volume_indirect = True  # Cycles' pass: not EEVEE's cost
    lines = run(dry_run=False)
    assert fog.hide_render and not layer.use_pass_z and not layer.eevee.use_pass_transparent
    assert dicing.use_adaptive_subdivision and scene.cycles.volume_bounces == 2
    assert layer.cycles.use_pass_volume_indirect
    assert not any("Flat Slab" in line or "Volume bounces" in line for line in lines)
    assert any("pass 'Transparent'" in line for line in lines)
    assert lines[-1].endswith("in EEVEE (Cycles' settings left alone)")
    scene.render.engine = "CYCLES"  # the same scene in Cycles: its own waste, not EEVEE's
    layer.eevee.use_pass_transparent = True
    lines = run(dry_run=True)
    assert any("Flat Slab" in line for line in lines) and not any("Transparent" in line for line in lines)
