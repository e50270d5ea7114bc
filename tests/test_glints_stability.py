"""Glints stay on the surface when the camera moves (object space), unlike screen-space noise.

Render A and B (camera moved 5 cm and turned 1°). Each glinting pixel of A is traced to its
point on the ground plane, projected into B, and kept when B glints there. Pixels whose
3×3 neighbourhood in B straddles a glint edge are left out: that is aliasing, not crawling.
"""

import math

from devtools import readback, scenes

WIDTH, HEIGHT = 128, 96
CELL_PX = 5


def ground_with(material):
    obj = readback.uv_plane(8.0, "Ground")
    obj.data.materials.append(material)
    return obj


def screen_space_material(sandscape):
    """The seed's way: noise fixed to the screen (Window coordinates), then the same shade group."""
    helper = sandscape.node_groups.helper
    shade = helper.ensure_group(sandscape.node_groups.glint_shade)
    material = scenes.group_material(shade, {"Threshold": 0.7, "Facing Power": 0.0,
                                             "Color": (1, 1, 1, 1), "Strength": 1.0}, "Mask")
    tree = material.node_tree
    group_node = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeGroup")
    coords = tree.nodes.new("ShaderNodeTexCoord")
    scale = tree.nodes.new("ShaderNodeVectorMath")
    scale.operation = "MULTIPLY"
    scale.inputs[1].default_value = (WIDTH / CELL_PX, HEIGHT / CELL_PX, 1.0)
    floor = tree.nodes.new("ShaderNodeVectorMath")
    floor.operation = "FLOOR"
    noise = tree.nodes.new("ShaderNodeTexWhiteNoise")
    tree.links.new(coords.outputs["Window"], scale.inputs[0])
    tree.links.new(scale.outputs[0], floor.inputs[0])
    tree.links.new(floor.outputs[0], noise.inputs["Vector"])
    tree.links.new(noise.outputs["Value"], group_node.inputs["Noise"])
    return material


def kept_fraction(material):
    readback.cycles_scene(resolution=(WIDTH, HEIGHT), samples=1)
    scenes.sharp_pixels()
    ground_with(material)
    cam = scenes.camera("PERSP", location=(0.0, -5.0, 3.0), rotation=(math.radians(59), 0.0, 0.0))
    return scenes.glints_kept_after_camera_move(cam, lambda: readback.render()[..., 0] > 0.5, WIDTH, HEIGHT,
                                                enough=200)


def test_object_space_glints_stay_on_the_surface(glints_group):
    material = scenes.group_material(glints_group, {"Threshold": 0.7, "Glint Size": 0.15,
                                             "Facing Power": 0.0, "Seed": 5.0}, "Mask")
    kept = kept_fraction(material)
    print(f"object-space glints kept after the camera move: {kept:.1%}")
    assert kept >= 0.95


def test_screen_space_glints_crawl(sandscape):
    """The same measure fails the seed's screen-space noise: it can tell stable from not."""
    kept = kept_fraction(screen_space_material(sandscape))
    print(f"screen-space glints kept after the camera move: {kept:.1%}")
    assert kept < 0.8
