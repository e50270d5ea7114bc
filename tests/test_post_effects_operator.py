"""bpy.ops.sandscape.add_post_effects: rays only with the sun in front, a continuous fade at the
frame edge, effects absent when off, a user's compositor kept, bad input refused."""

import math

import bpy
import numpy as np
import pytest

from devtools import readback, scenes

LAST = 181


@pytest.fixture
def desert():
    """A ground plane and a block, a low sun due +Y, and a camera panning from facing it to away."""
    bpy.ops.mesh.primitive_plane_add(size=20)
    bpy.ops.mesh.primitive_cube_add(size=1, location=(0, 4, 0.5))
    scene = bpy.context.scene
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth, air.density = math.radians(10), 0.0, 0.0
    bpy.ops.sandscape.add_atmosphere()
    camera = scenes.camera("PERSP", location=(0, -6, 1.0), rotation=(math.radians(85), 0, 0), lens=35)
    scene.frame_start, scene.frame_end = 1, LAST
    for frame in range(1, LAST + 1):  # turn from facing the sun (+Y) to facing away, 1 degree a frame
        camera.rotation_euler[2] = math.radians(frame - 1)
        camera.keyframe_insert("rotation_euler", frame=frame)
    readback.cycles_scene(resolution=(64, 36), samples=1)
    return scene


def tree_groups(tree):
    return {node.node_tree.get("sandscape_group") for node in tree.nodes if getattr(node, "node_tree", None)}


def test_intensity_fades_continuously_and_is_zero_behind(desert, sandscape):
    settings = desert.sandscape_post
    settings.use_blur = False
    bpy.ops.sandscape.add_post_effects()
    tree = desert.compositing_node_group
    assert tree.animation_data.action is None and len(tree.animation_data.drivers) > 0  # no keys
    curve = np.array(sandscape.addon.sun_screen.driven_curve(tree, desert))[:, 3]
    # Facing the sun, then facing away (the sun behind the camera).
    assert curve[0] == pytest.approx(1.0, abs=1e-6) and curve[-1] == pytest.approx(0.0, abs=1e-6)
    assert (np.diff(curve) <= 1e-9).all()  # fades out as the sun leaves the frame, never back
    assert np.abs(np.diff(curve)).max() < 0.2  # no jump: it eases over several frames
    assert ((curve > 0) & (curve < 1)).sum() >= 5


def test_rays_appear_only_with_the_sun_in_front(desert):
    desert.sandscape_post.use_blur = desert.sandscape_post.use_denoise = False
    bpy.ops.sandscape.add_post_effects()
    difference = {}
    for frame in (1, LAST):
        desert.frame_set(frame)
        desert.render.use_compositing = True
        with_rays = readback.render(desert)
        desert.render.use_compositing = False
        without = readback.render(desert)
        assert np.isfinite(with_rays).all()
        difference[frame] = float(np.abs(with_rays[..., :3] - without[..., :3]).max())
    assert difference[1] > 0.05 and difference[LAST] <= 1e-6


def test_switched_off_effects_are_absent(desert, sandscape):
    own, post, post_glow = sandscape.addon.ownership, sandscape.addon.post, sandscape.addon.post_glow
    settings = desert.sandscape_post
    bpy.ops.sandscape.add_post_effects()
    tree = desert.compositing_node_group
    assert {"Sandscape Gated Blur", "Sandscape God Rays"} <= tree_groups(tree)
    assert own.node(tree, post.DENOISE) is not None
    settings.use_denoise = False
    bpy.ops.sandscape.add_post_effects()
    assert own.node(tree, post.DENOISE) is None
    settings.use_god_rays = False
    bpy.ops.sandscape.add_post_effects()
    assert desert.compositing_node_group == tree  # updated in place
    assert tree_groups(tree) == {"Sandscape Gated Blur"}
    settings.use_blur, settings.use_god_rays = False, True
    bpy.ops.sandscape.add_post_effects()
    assert tree_groups(tree) == {"Sandscape God Rays", "Sandscape Sun Place"}
    assert own.node(tree, post_glow.GLOW) is not None
    settings.use_god_rays = False
    bpy.ops.sandscape.add_post_effects()
    assert tree_groups(tree) == set() and own.node(tree, post_glow.GLOW) is not None
    settings.use_sun_glow = False
    bpy.ops.sandscape.add_post_effects()
    assert desert.compositing_node_group is None
    assert not [g for g in bpy.data.node_groups if g.get("sandscape_compositor")]


def test_a_users_compositor_is_kept_and_restored(desert):
    theirs = bpy.data.node_groups.new("Their Grade", "CompositorNodeTree")
    desert.compositing_node_group = theirs
    bpy.ops.sandscape.add_post_effects()
    assert desert.compositing_node_group != theirs and theirs.use_fake_user
    assert desert.compositing_node_group["replaced_tree"] == "Their Grade"
    settings = desert.sandscape_post
    settings.use_denoise = settings.use_blur = settings.use_god_rays = settings.use_sun_glow = False
    bpy.ops.sandscape.add_post_effects()
    assert desert.compositing_node_group == theirs


@pytest.mark.parametrize("case, message", [("no camera", "no camera"), ("decay", "Decay must lie"),
                                           ("samples", "Samples"), ("no sun", "No sun")])
def test_bad_input_is_refused_and_changes_nothing(desert, case, message):
    settings = desert.sandscape_post
    if case == "no camera":
        desert.camera = None
    elif case == "decay":
        settings.ray_decay = 1.01  # stated: an error, since above 1 the sum grows without bound
    elif case == "samples":
        settings.samples = 0
    else:
        for obj in [o for o in desert.objects if o.type == "LIGHT"]:
            bpy.data.objects.remove(obj)
    before = readback.data_snapshot()
    with pytest.raises(RuntimeError, match=message):
        bpy.ops.sandscape.add_post_effects()
    assert readback.data_snapshot() == before


def test_every_sample_count_shares_one_god_rays_group(desert):
    """Samples is an input: 32, 200 and 1024 leave one group of the same nodes behind."""
    settings = desert.sandscape_post
    sizes = set()
    for samples in (32, 200, 1024):
        settings.samples = samples
        assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}
        rays = [g for g in bpy.data.node_groups if g.name.startswith("Sandscape God Rays")]
        assert len(rays) == 1
        sizes.add(len(rays[0].nodes))
        node = next(n for n in desert.compositing_node_group.nodes if n.label == "God Rays")
        assert node.inputs["Samples"].default_value == samples
    assert len(sizes) == 1 and sizes.pop() < 150
