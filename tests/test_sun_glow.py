"""The sun's glow (addon/post_glow.py) through the real compositor on synthetic float images:
only light above GLOW_THRESHOLD display whites glows (the sun's disc), so a sky and the sand's
glints below it pass unchanged and a glint stays one pixel; the threshold follows the exposure."""

import types

import bpy
import numpy as np
import pytest

from devtools import readback

W, H = 96, 64
SUN = (40, 24)  # column, row
GLINT = (80, 50)
SKY = 13.0  # the sky round the demo's sun, in display whites


def scene_image(sun=True, glint=0.0):
    image = np.zeros((H, W, 4))
    image[..., :3] = SKY
    image[..., 3] = 1.0
    if sun:
        image[SUN[1] - 1:SUN[1] + 2, SUN[0] - 1:SUN[0] + 2, :3] = 1e5
    if glint:
        image[GLINT[1], GLINT[0], :3] = glint
    return image


def glowing(sandscape, image, strength=1.0):
    tree = bpy.data.node_groups.new("Glow Probe", "CompositorNodeTree")
    tree.interface.new_socket("Image", in_out="OUTPUT", socket_type="NodeSocketColor")
    source = tree.nodes.new("CompositorNodeImage")
    source.image = readback.float_image(image, "Glow Input")
    out = tree.nodes.new("NodeGroupOutput")
    tree.links.new(sandscape.addon.post_glow.add_glow(tree, source.outputs["Image"], strength), out.inputs[0])
    try:
        return readback.composite_tree(tree, (W, H))[..., :3]
    finally:
        bpy.data.node_groups.remove(tree)


def test_only_the_sun_glows_and_a_glint_stays_a_pinpoint(sandscape):
    threshold = sandscape.addon.post_glow.GLOW_THRESHOLD
    # No light above the threshold: the sky and a glint just under it pass unchanged.
    calm = scene_image(sun=False, glint=0.9 * threshold)
    assert np.abs(glowing(sandscape, calm) - calm[..., :3]).max() <= 1e-4 * threshold
    # The sun's disc glows: brighter round it than the sky, less so farther out.
    lit = glowing(sandscape, scene_image())
    rows, cols = np.indices((H, W))
    distance = np.hypot(cols - SUN[0], rows - SUN[1])
    bands = ((3, 6), (6, 12), (12, 24))
    rings = [float(lit[(distance >= lo) & (distance < hi)].mean() - SKY) for lo, hi in bands]
    print("glow over the sky at 3-6, 6-12, 12-24 px:", [round(r, 2) for r in rings])
    assert rings[0] > rings[1] > rings[2] > 0.0 and rings[0] > SKY
    # A glint of 50 display whites by the glowing sun: it adds itself and nothing round it.
    with_glint = glowing(sandscape, scene_image(glint=50.0))
    halo = np.abs(with_glint - lit)
    halo[GLINT[1], GLINT[0]] = 0.0
    assert halo.max() <= 1e-3 and with_glint[GLINT[1], GLINT[0]].min() > lit[GLINT[1], GLINT[0]].min() + 30


def test_the_threshold_follows_the_exposure(sandscape):
    """The threshold is a driven value: 100 display whites at any exposure, no handler."""
    post, glow = sandscape.addon.post, sandscape.addon.post_glow
    scene = bpy.context.scene
    tree = bpy.data.node_groups.new("Glow Tree", "CompositorNodeTree")
    only_glow = types.SimpleNamespace(use_denoise=False, use_blur=False, use_god_rays=False,
                                      use_sun_glow=True, glow_strength=1.0)
    post.build(tree, only_glow, post.display_white(scene), scene=scene)
    scene.compositing_node_group = tree  # the depsgraph evaluates the drivers of the tree in use
    threshold = tree.nodes[glow.THRESHOLD].outputs[0]
    for exposure in (0.0, -2.7, 1.5):
        scene.view_settings.exposure = exposure
        scene.frame_set(scene.frame_current)  # drivers evaluate
        assert threshold.default_value == pytest.approx(glow.GLOW_THRESHOLD * 2.0 ** -exposure, rel=1e-5)
    assert tree.nodes[glow.GLOW].inputs["Threshold"].links[0].from_node.name == glow.THRESHOLD
