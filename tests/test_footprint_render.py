"""Rendered proof: the displaced sand sits the set depth lower under each print's ball, and only
once its foot has landed.

An orthographic camera looks straight down on a flat terrain; the material's surface is
swapped for an emission of the shading point's world Z (+1), a position pass of the
displaced, adaptively diced surface. Displacement is left as the operator built it.
"""

import bpy
import numpy as np
import pytest

from devtools import readback, scenes

DEPTH = 0.03
TOLERANCE = 0.05 * DEPTH  # the 5 %
SIZE = 320  # pixels: 1 cm each over the 3.2 m the camera sees


def z_pass_material(material):
    """Emit world Z + 1 as the surface; the Displacement link stays."""
    tree = material.node_tree
    output = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    split = tree.nodes.new("ShaderNodeSeparateXYZ")
    lift = tree.nodes.new("ShaderNodeMath")
    lift.operation, lift.inputs[1].default_value = "ADD", 1.0
    emission = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(geometry.outputs["Position"], split.inputs[0])
    tree.links.new(split.outputs["Z"], lift.inputs[0])
    tree.links.new(lift.outputs[0], emission.inputs["Color"])
    tree.links.new(emission.outputs[0], output.inputs["Surface"])


@pytest.fixture
def painted_walk():
    terrain = scenes.height_field(6.0, 12, name="Sand")
    walker = scenes.keyframed_walker(lambda f: (-1.5 + 0.1 * (f - 1), 0.0, 0.0), range(1, 32))
    scenes.footprint_settings(terrain, walker, (1, 31), stride=0.7, variation=0.0, noise_amount=0.0,
                              depth=DEPTH, resolution=1024)
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    z_pass_material(terrain.active_material)
    scene = readback.cycles_scene(resolution=(SIZE, SIZE), samples=1)
    scenes.sharp_pixels(scene)
    camera = scenes.camera("ORTHO", location=(0.0, 0.0, 5.0), ortho_scale=3.2)
    points = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprints")
    co = np.array([v.co for v in points.data.vertices])
    births = np.array([a.value for a in points.data.attributes["birth_frame"].data])
    # The ball's circle centre: a foot presses its ball (and its heel) to the set depth; the
    # ball is the wider, so the slumped and crumbled wall leaves its floor whole.
    ball = co + (0.27 / 2 - 0.10 / 2, 0.0, 0.0)
    col, row = scenes.project(camera, ball, SIZE, SIZE)
    return scene, col.astype(int), row.astype(int), births


def heights(scene, frame, col, row):
    scene.frame_set(frame)
    return readback.render(scene)[row, col, 0] - 1.0


def test_prints_sink_by_the_set_depth(painted_walk):
    scene, col, row, births = painted_walk
    assert len(col) == 5
    z = heights(scene, 31, col, row)
    assert np.abs(z + DEPTH).max() < TOLERANCE, z


def test_a_print_appears_only_when_its_foot_lands(painted_walk):
    scene, col, row, births = painted_walk
    middle = 2  # passed at frame 15.0 (x = -0.1 m), born as its foot lands a quarter stride before
    assert births[middle] == pytest.approx(15.0 - 0.25 * 0.7 / 0.1)
    before = heights(scene, 13, col, row)
    after = heights(scene, 14, col, row)
    assert abs(before[middle]) < TOLERANCE and abs(after[middle] + DEPTH) < TOLERANCE
    assert abs(before[0] + DEPTH) < TOLERANCE and abs(after[-1]) < TOLERANCE  # older shown, later not yet
