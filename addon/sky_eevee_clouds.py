"""The clouds' light in EEVEE's lighting world: the change the cloud layer makes to the light from
above on level sand (core.cloud_light, in nodes), added to the clear sky's.

Cycles lights the sand with the clouds' scattered sunlight, which EEVEE's volumes give no surface:
without it EEVEE's shade under the demo's 6° sun was the clear sky's grey-blue where Cycles' is
gold. The shares D (of the lamp's light), G (of the lamp's light tinted by the sand: the sunlit
sand's light the clouds' bases send back) and B (of the sky's) by the sine of the sun's
elevation sit in an RGB Curves node (its red, green and blue curves, each over its peak), set by
Add Clouds for the layer's coverage and optical depth and cleared when the layer goes; the lamp's
light and axis are the world's driven sockets, and a driver on the layer's Disable in Renders
takes the change away when the layer is hidden: no Python on a farm.
"""

import numpy as np

from ..core import cloud_light
from ..core import clouds as clouds_twin
from ..node_groups import helper as h
from . import drivers, units
from . import ownership as own

CURVES, PEAKS = "Sandscape EEVEE Cloud Light", "Sandscape EEVEE Cloud Light Peaks"
SHOWN = "Sandscape EEVEE Cloud Layer Shown"


def build(tree, sine, sun_light, sky, ground):
    """A colour socket: the sky's light on level sand (sky) with the clouds' change; no change
    until follow() sets it. sine: the sine of the sun's elevation (0 below the horizon); ground:
    the ground's colour."""
    grey = h.add_node(tree, "ShaderNodeCombineColor")
    for index in range(3):
        h.link(tree, sine, grey.inputs[index])
    curves = h.add_node(tree, "ShaderNodeRGBCurve", name=CURVES,
                        label="Clouds: Sun's (R), Sand's (G), Sky's (B) Shares ÷ Peaks")
    h.link(tree, grey.outputs[0], curves.inputs["Color"])
    _set_curves(curves, np.array([0.0, 1.0]), np.zeros((3, 2)))
    peaks = h.add_node(tree, "ShaderNodeVectorMath", operation="MULTIPLY", name=PEAKS, label="× Peaks")
    h.link(tree, curves.outputs[0], peaks.inputs[0])
    peaks.inputs[1].default_value = (0.0, 0.0, 0.0)
    shown = h.math(tree, "MULTIPLY", 1.0, 1.0, label="Layer Shown in Renders (driven)")
    shown.name = SHOWN
    gated = h.add_node(tree, "ShaderNodeVectorMath", operation="SCALE")
    h.link(tree, peaks.outputs[0], gated.inputs[0])
    h.link(tree, shown.outputs[0], gated.inputs["Scale"])
    axes = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, gated.outputs[0], axes.inputs[0])
    # The sun's share comes down in the lamp's colour, the sand's in the lamp's times the sand's.
    tint = h.add_node(tree, "ShaderNodeVectorMath", operation="MULTIPLY_ADD", label="D + G × Sand")
    h.link(tree, ground, tint.inputs[0])
    h.link(tree, axes.outputs["Y"], tint.inputs[1])
    h.link(tree, axes.outputs["X"], tint.inputs[2])
    sun_part = h.add_node(tree, "ShaderNodeVectorMath", operation="MULTIPLY",
                          label="Sun's Light the Clouds Send Down")
    h.link(tree, sun_light, sun_part.inputs[0])
    h.link(tree, tint.outputs[0], sun_part.inputs[1])
    sky_kept = h.math(tree, "SUBTRACT", 1.0, axes.outputs["Z"], label="Sky's Light Left")
    sky_part = h.add_node(tree, "ShaderNodeVectorMath", operation="SCALE")
    h.link(tree, sky, sky_part.inputs[0])
    h.link(tree, sky_kept.outputs[0], sky_part.inputs["Scale"])
    total = h.add_node(tree, "ShaderNodeVectorMath", operation="ADD", label="Sky + Clouds on Level Sand")
    h.link(tree, sky_part.outputs[0], total.inputs[0])
    h.link(tree, sun_part.outputs[0], total.inputs[1])
    return total.outputs[0]


def _set_curves(node, sines, values):
    """D, G, B (rows of values) each over its peak on the red, green and blue curves at these
    sines; the combined curve straight. Returns the peaks."""
    peaks = [max(float(v.max()), 1e-12) for v in values]
    for channel, (row, peak) in enumerate(zip(values, peaks, strict=True)):
        h.polyline_curve(node.mapping.curves[channel], sines, row / peak)
    node.mapping.use_clip = False
    node.mapping.update()
    return [peak if row.max() > 0 else 0.0 for row, peak in zip(values, peaks, strict=True)]


def follow(world, layer=None, coverage=0.0, optical_depth=0.0):
    """Set the clouds' change for a layer of this coverage and optical depth (density x
    thickness), gated by the layer object's Disable in Renders; no layer: none."""
    tree = world.node_tree if world is not None else None
    curves, peaks, shown = own.node(tree, CURVES), own.node(tree, PEAKS), own.node(tree, SHOWN)
    if curves is None or peaks is None or shown is None:
        return
    if layer is None:
        coverage = optical_depth = 0.0
    degrees, *values = cloud_light.curves(coverage, optical_depth)
    sines = np.append(np.sin(np.radians(degrees)), 1.0)
    values = np.array([np.append(v, v[-1]) for v in values])
    peaks.inputs[1].default_value = _set_curves(curves, sines, values)
    if layer is None:
        shown.inputs[0].driver_remove("default_value")
        shown.inputs[0].default_value = 0.0
    else:
        drivers.drive(shown.inputs[0], "default_value", "1 - hidden",
                      [("hidden", "OBJECT", layer, "hide_render")])


def held(world):
    """[(sine, D, G, B)] the world holds at its curve's points, or None."""
    tree = world.node_tree if world is not None else None
    curves, peaks = own.node(tree, CURVES), own.node(tree, PEAKS)
    if curves is None or peaks is None:
        return None
    scale = peaks.inputs[1].default_value
    points = [curves.mapping.curves[channel].points for channel in range(3)]
    return [(d.location[0], *(p.location[1] * k for p, k in zip((d, g, b), scale, strict=True)))
            for d, g, b in zip(*points, strict=True)]


def weather_red(image):
    """A painted weather map's red channel, its coverage: (rows = y, columns = x)."""
    width, height = image.size
    pixels = np.empty(width * height * 4, np.float32)
    image.pixels.foreach_get(pixels)
    return pixels.reshape(height, width, 4)[..., 0]


def layer_coverage(stored):
    """The layer's coverage: the setting, or a painted map's mean red."""
    image = stored.weather_image if stored.weather_source == "IMAGE" else None
    if image is None:
        return float(stored.coverage)
    red = weather_red(image)
    return float(np.clip(red.mean(), 0.0, 1.0)) if red.size else 0.0


def follow_scene(scene):
    """The scene's world follows its cloud layer as it is now (none: no change)."""
    layer = own.scene_object(scene, own.CLOUDS)
    if layer is None:
        follow(scene.world)
        return
    stored = scene.sandscape_clouds
    wet = 1.0 if stored.weather_source == "IMAGE" else clouds_twin.wet(stored.precipitation)
    depth = stored.density * stored.thickness * units.metres_per_unit(scene) * float(wet)
    follow(scene.world, layer, layer_coverage(stored), depth)
