"""A .blend Sandscape writes renders the same with the extension disabled and Python auto-run off,
on the Blender that wrote it and on the other supported one."""

import pathlib

import bpy
import numpy as np

from devtools import readback, session

REPO = pathlib.Path(__file__).resolve().parent.parent
FRAME = 150
# The committed demo.blend (written by the default Blender, 5.2) against a fresh build on the
# Blender under test, both rendered here at 2 spp with the same seed and sampling pattern: the
# same scene data give the same pixels to round-off. Measured: 0.0 on 5.2, 7.6e-6 on 5.0 (pixels
# reach 6.7e5 in the sun disc). What opening the 5.2 file in 5.0 once lost, a compositor link
# from a socket type 5.0 does not know, moved pixels by 8.3. With OpenImageDenoise in the
# compositor the 5.0 difference grew to 3.1e-4 (pixels up to 4.5; the denoiser's round-off).
SAME_SCENE_TOLERANCE = 1e-3


def small_render(scene):
    scene.render.resolution_x, scene.render.resolution_y = 64, 36
    scene.render.resolution_percentage = 100
    scene.cycles.samples = 2
    scene.frame_set(FRAME)
    return readback.render(scene)


def node_trees():
    for group in bpy.data.node_groups:
        yield group.name, group
    for kind in ("materials", "worlds", "lights"):
        for block in getattr(bpy.data, kind):
            if block.node_tree is not None:
                yield block.name, block.node_tree


def animated_blocks():
    for kind in ("objects", "materials", "worlds", "node_groups", "scenes", "cameras", "lights"):
        for block in getattr(bpy.data, kind):
            yield block
            tree = getattr(block, "node_tree", None)
            if tree is not None:
                yield tree


def open_problems():
    """What a file lost in opening: missing or linked data-blocks, unknown nodes, group nodes
    without their group, images without pixels, drivers that fail or need Python auto-run."""
    problems = []
    problems += [f"library {lib.filepath}" for lib in bpy.data.libraries]
    for kind in ("objects", "meshes", "materials", "node_groups", "images", "worlds", "curves", "actions"):
        problems += [f"missing {kind[:-1]} {b.name}" for b in getattr(bpy.data, kind) if b.is_missing]
    for owner, tree in node_trees():
        for node in tree.nodes:
            if node.bl_idname == "NodeUndefined":
                problems.append(f"unknown node {node.name} in {owner}")
            if node.bl_idname.endswith("NodeGroup") and node.node_tree is None:
                problems.append(f"group node {node.name} in {owner} lost its group")
    for image in bpy.data.images:
        # Reading the size loads the pixels: (0, 0) when the packed file cannot be read.
        if image.source == "FILE" and (image.packed_file is None or 0 in tuple(image.size)):
            problems.append(f"image {image.name} has no packed pixels")
    for block in animated_blocks():
        animation = block.animation_data
        for fcurve in (animation.drivers if animation else ()):
            driver = fcurve.driver
            if not (fcurve.is_valid and driver.is_valid):
                problems.append(f"driver {block.name}.{fcurve.data_path} is invalid")
            if driver.type == "SCRIPTED" and not driver.is_simple_expression:
                problems.append(f"driver {block.name}.{fcurve.data_path} needs Python auto-run")
    return problems


def links():
    """Every node link, by tree and node names: a link Blender could not read is gone from here."""
    return {owner: sorted((link.from_node.name, link.from_socket.identifier, link.to_node.name,
                           link.to_socket.identifier) for link in tree.links)
            for owner, tree in node_trees()}


def test_demo_renders_identically_without_the_extension(demo_scene, tmp_path):
    path = tmp_path / "demo.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(path), compress=True)
    with_addon = small_render(bpy.context.scene)
    with session.extension_off():
        bpy.ops.wm.open_mainfile(filepath=str(path), load_ui=False)
        without = small_render(bpy.context.scene)
    assert np.isfinite(without).all()
    assert np.abs(without - with_addon).max() <= 1e-6


def test_committed_demo_opens_and_renders_on_this_blender(demo_files):
    """demo.blend, saved by the default Blender, opens here with the extension off and loses nothing."""
    bpy.ops.wm.open_mainfile(filepath=str(demo_files["built"]), load_ui=False)  # this run's fresh build
    fresh, fresh_links = small_render(bpy.context.scene), links()
    with session.extension_off():
        bpy.ops.wm.open_mainfile(filepath=str(REPO / "demo.blend"), load_ui=False)
        problems = open_problems()
        committed_links = links()
        committed = small_render(bpy.context.scene)
        saved_by = tuple(bpy.data.version[:2])
        drivers = sum(len(b.animation_data.drivers) for b in animated_blocks() if b.animation_data)
    assert not problems, problems
    # Every tree a fresh build makes, with every link (a 5.2 file also brings the node tree 5.2
    # gives each light by default, which a 5.0 build has not).
    assert {owner: committed_links.get(owner) for owner in fresh_links} == fresh_links
    assert drivers >= 2  # the footprint and dust frame drivers were checked, not skipped
    assert np.isfinite(committed).all()
    if saved_by == tuple(bpy.app.version[:2]):
        assert np.abs(committed - fresh).max() <= SAME_SCENE_TOLERANCE
    else:
        # Saved by another Blender, the file renders here with other noise in the haze, which every
        # pixel marches through (on 5.0: 0.06 % in the mean, one sparkle pixel 0.24 off).
        difference = np.abs(committed - fresh)[..., :3]
        assert difference.mean() <= 0.005 * np.abs(fresh[..., :3]).mean()
        assert np.mean(difference > 0.05 * np.abs(fresh[..., :3]) + SAME_SCENE_TOLERANCE) <= 0.02
