"""The print map read as four Closest lookups blended bilinearly (Sandscape Texel Corners and Texel
Blend) against Cycles' own Linear lookup of the same image, and against the twin (core.texels),
over a region wider than the image (Clip extension: transparent black outside)."""

import bpy
import numpy as np

from core import texels
from devtools import readback

SIZE = (7, 5)  # texels: odd, not square, not a power of two
BAKE = 64


def lookup_material(sandscape, image, linear):
    """Emission of the image at UV stretched 1.3× round the centre, through one Linear lookup or
    through the four-lookup groups wired as the sand material wires them."""
    material = bpy.data.materials.new("Lookup")
    tree = material.node_tree
    tree.nodes.clear()
    coords = tree.nodes.new("ShaderNodeTexCoord")
    mapping = tree.nodes.new("ShaderNodeMapping")
    mapping.inputs["Location"].default_value = (-0.15, -0.15, 0.0)
    mapping.inputs["Scale"].default_value = (1.3, 1.3, 1.0)
    tree.links.new(coords.outputs["UV"], mapping.inputs["Vector"])
    emission = tree.nodes.new("ShaderNodeEmission")
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(emission.outputs[0], out.inputs["Surface"])
    if linear:
        texture = tree.nodes.new("ShaderNodeTexImage")
        texture.image, texture.interpolation, texture.extension = image, "Linear", "CLIP"
        tree.links.new(mapping.outputs["Vector"], texture.inputs["Vector"])
        tree.links.new(texture.outputs["Color"], emission.inputs["Color"])
        return material
    sandscape.addon.print_lookup.build(tree, mapping, _Sink(emission))
    corners = tree.nodes[sandscape.addon.print_lookup.PRINT_CORNERS]
    corners.inputs["Width"].default_value, corners.inputs["Height"].default_value = SIZE
    for name in sandscape.addon.print_lookup.PRINT_TEXELS:
        tree.nodes[name].image = image
    return material


class _Sink:
    """The node whose "Print Map" input takes the blend: here the emission's colour."""

    def __init__(self, emission):
        self.inputs = {"Print Map": emission.inputs["Color"]}


def test_four_closest_lookups_are_the_linear_lookup(sandscape):
    rng = np.random.default_rng(3)
    values = rng.uniform(0.0, 4.0, (SIZE[1], SIZE[0], 4)).astype(np.float32)
    values[..., 3] = 1.0
    image = readback.float_image(values, "Print Map Probe")
    plane = readback.uv_plane()
    results = []
    for linear in (True, False):
        material = lookup_material(sandscape, image, linear)
        plane.data.materials.clear()
        plane.data.materials.append(material)
        results.append(readback.bake_emit(plane, material, BAKE)[..., :3])
    linear, ours = results
    centres = (np.arange(BAKE) + 0.5) / BAKE
    u, v = np.meshgrid(centres, centres)
    uv = np.stack([u, v], -1) * 1.3 - 0.15  # the mapping: uv × scale + location
    twin = texels.bilinear(values[..., :3].astype(np.float64), uv)
    off = np.abs(ours - twin)
    print(f"four lookups against Linear: max {np.abs(ours - linear).max():.2e}; against the twin: "
          f"max {off.max():.2e}, mean {off.mean():.1e}; outside the image {np.mean(twin == 0):.0%}")
    assert np.mean(np.all(twin == 0, axis=-1)) > 0.1 and linear.max() > 1.0  # the clip border is in view
    assert np.abs(ours - linear).max() <= 1e-4
    # The twin takes the bake's points as texel centres; the bake's own sit off them by about 1e-5,
    # and the values change by up to 36 per unit of UV here.
    assert off.max() <= 2e-3 and off.mean() <= 5e-4
