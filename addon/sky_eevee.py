"""The sky world's output for EEVEE: the sky the camera sees, and a lighting world made for EEVEE.

The camera's sky gets the sun's disc drawn in (EEVEE draws no Sky Texture disc: Cycles only):
an even disc as wide as the lamp's, as bright as gives the lamp's irradiance (core.sun), both
driven from the lamp. EEVEE keeps the film in half floats: a real sun's disc (some 10^6) is held
at 65504, far past white at any exposure a sunlit frame takes.

EEVEE lights diffuse surfaces from the world's first two spherical-harmonic bands, derung, and
clamped by the scene's Clamp Surface Indirect. Its lighting world is therefore two uniform
hemispheres (core.atmosphere.eevee_world_hemispheres): above, the sky's irradiance on level
ground, so level sand gets the sky's light as in Cycles, changed by the cloud layer (its
scattered sunlight in, the sky it hides out: sky_eevee_clouds.py), with the lamp's light the
dust box's haze scatters down added where it comes from (sky_eevee_haze.py); below, the lit
sand's, which lights a walker's legs and the undersides of things as the sand's bounce does in
Cycles (EEVEE bounces none without a baked probe).

Both follow the scene's sun lamp through simple-expression drivers (its axis, strength and
colour), with the sky's irradiance at that elevation from core/sun_table.py in an RGB Curves
node, and the ground takes the colour of the scene's ground (sky_eevee_ground.py): no Python on
a farm.
"""

import math

import numpy as np

from ..core import atmosphere as air
from ..core import eevee_upright
from ..core import sun as sky_sun
from ..node_groups import helper as h
from . import compat, drivers, sky_eevee_clouds, sky_eevee_ground, sky_eevee_haze
from . import ownership as own
from .sun_lamp import SKY_SUN_SIZE

OUTPUT = "Sandscape EEVEE World Output"
SUN, SUN_LIGHT = "Sandscape EEVEE Ground Sun", "Sandscape EEVEE Ground Sun Light"
SKY_LIGHT, GROUND_COLOR = "Sandscape EEVEE Ground Sky Light", sky_eevee_ground.NODE
CLAMP = "Sandscape EEVEE Clamp"
# The ground's light on upright things as our sand gives it (core/eevee_upright.py), by the sun's
# elevation; sky_eevee_ground's share says how much of it applies (1 on our sand).
UPRIGHT_GAIN = "Sandscape EEVEE Sand Upright Gain"
CLAMP_EXPRESSION = "limit if limit > 0 else 1e9"  # 0: EEVEE clamps nothing
DISC, DISC_EDGE = "Sandscape EEVEE Sun Disc", "Sandscape EEVEE Sun Disc Edge"
DISC_EDGE_EXPRESSION = "angle / 2"
DISC_STRENGTH_EXPRESSION = "1 / (2 * pi * max(1 - cos(angle / 2), 1e-12))"  # core.sun.disc_solid_angle
# Their values without a lamp: the sky's own disc.
DISC_EDGE_DEFAULT, DISC_STRENGTH_DEFAULT = 0.5 * SKY_SUN_SIZE, 1.0 / sky_sun.disc_solid_angle(SKY_SUN_SIZE)


def build(tree, ray, shown):
    """The world output EEVEE renders: the sky for camera rays; for lighting the two hemispheres."""
    direction = h.add_node(tree, "ShaderNodeTexCoord", name="Sandscape EEVEE Sky Direction")
    axes = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, direction.outputs["Generated"], axes.inputs[0])
    above = h.math(tree, "GREATER_THAN", axes.outputs["Z"], 0.0, label="Above the Horizon")
    sky, ground, sun_unit, sun_light = _level_light(tree)
    # The ground held within the contrast EEVEE keeps without deringing (the sky stays exact).
    ratio = air.eevee_ground_ratio(compat.eevee_dering_limit())
    floor = h.add_node(tree, "ShaderNodeVectorMath", operation="SCALE", inputs={"Scale": 1 / ratio})
    ceiling = h.add_node(tree, "ShaderNodeVectorMath", operation="SCALE", inputs={"Scale": ratio})
    h.link(tree, sky, floor.inputs[0])
    h.link(tree, sky, ceiling.inputs[0])
    raised = h.add_node(tree, "ShaderNodeVectorMath", operation="MAXIMUM")
    h.link(tree, ground, raised.inputs[0])
    h.link(tree, floor.outputs[0], raised.inputs[1])
    held = h.add_node(tree, "ShaderNodeVectorMath", operation="MINIMUM")
    h.link(tree, raised.outputs[0], held.inputs[0])
    h.link(tree, ceiling.outputs[0], held.inputs[1])
    # EEVEE scales the whole world's light down where its brightest direction passes the scene's
    # Clamp Surface Indirect: the ground, not the sky, gives way.
    clamp = h.math(tree, "MULTIPLY", 0.0, math.pi / air.EEVEE_CLAMP_BELOW_WEIGHT,
                   label="Clamp Surface Indirect (driven) × π / 1.25")
    clamp.name = CLAMP
    cap = h.add_node(tree, "ShaderNodeVectorMath", operation="MULTIPLY_ADD",
                     inputs={1: (air.EEVEE_CLAMP_SKY_SHARE,) * 3})
    h.link(tree, sky, cap.inputs[0])
    h.link(tree, clamp.outputs[0], cap.inputs[2])
    below = h.add_node(tree, "ShaderNodeVectorMath", operation="MINIMUM",
                       name="Sandscape EEVEE Light from Below")
    h.link(tree, held.outputs[0], below.inputs[0])
    h.link(tree, cap.outputs[0], below.inputs[1])
    hemispheres = h.add_node(tree, "ShaderNodeMix", name="Sandscape EEVEE Two Hemispheres", data_type="RGBA")
    h.link(tree, above.outputs[0], hemispheres.inputs["Factor"])
    h.link(tree, below.outputs[0], h.socket(hemispheres.inputs, "A"))
    h.link(tree, sky, h.socket(hemispheres.inputs, "B"))
    haze = sky_eevee_haze.build(tree, direction.outputs["Generated"], sun_unit, sun_light)
    with_haze = h.add_node(tree, "ShaderNodeVectorMath", operation="ADD", label="+ Haze Light")
    h.link(tree, h.socket(hemispheres.outputs, "Result"), with_haze.inputs[0])
    h.link(tree, haze, with_haze.inputs[1])
    lit = h.add_node(tree, "ShaderNodeBackground", name="Sandscape EEVEE Sky Light",
                     inputs={"Strength": 1 / math.pi})  # irradiance on level ground: radiance x pi
    h.link(tree, with_haze.outputs[0], lit.inputs["Color"])
    seen = _with_disc(tree, direction.outputs["Generated"], sun_unit, sun_light, shown.outputs[0])
    mix = h.add_node(tree, "ShaderNodeMixShader", name="Sandscape EEVEE Camera Sees the Disc")
    h.link(tree, ray.outputs["Is Camera Ray"], mix.inputs["Fac"])
    h.link(tree, lit.outputs[0], mix.inputs[1])
    h.link(tree, seen, mix.inputs[2])
    output = h.add_node(tree, "ShaderNodeOutputWorld", name=OUTPUT, target="EEVEE")
    h.link(tree, mix.outputs[0], output.inputs["Surface"])


def sun_nodes(tree, direction_name, light_name=None, lowest=0.0, with_light=True):
    """The lamp's direction (a Combine XYZ for the caller to drive: drivers.follow_lamp_axis),
    normalised, the sine of its elevation (at least `lowest`) and, with_light, a Combine Color
    for its light (drivers.follow_lamp_light): (direction node, unit socket, sine node, light
    node or None). Any node tree: the world's, a material's, geometry nodes'."""
    sun = h.add_node(tree, "ShaderNodeCombineXYZ", name=direction_name, label="Sun Direction (driven)")
    sun_unit = h.add_node(tree, "ShaderNodeVectorMath", operation="NORMALIZE")
    h.link(tree, sun.outputs[0], sun_unit.inputs[0])
    sun_axes = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, sun_unit.outputs[0], sun_axes.inputs[0])
    height = h.math(tree, "MAXIMUM", sun_axes.outputs["Z"], lowest, label="Sine of the Sun's Elevation")
    light = None
    if with_light:
        light = h.add_node(tree, "ShaderNodeCombineColor", name=light_name,
                           label="Sun Strength × Colour (driven)")
    return sun, sun_unit.outputs[0], height, light


def _level_light(tree):
    """(sky, ground): colour sockets of the sky's irradiance on level sand and of the lit sand's
    radiance times pi (its colour times the sun's and the sky's irradiance on it)."""
    _sun, sun_unit, height, light = sun_nodes(tree, SUN, SUN_LIGHT)
    direct = h.add_node(tree, "ShaderNodeVectorMath", operation="SCALE", label="Sun on Level Sand")
    h.link(tree, light.outputs[0], direct.inputs[0])
    h.link(tree, height.outputs[0], direct.inputs["Scale"])
    # Combine Color: a driver on each channel's input, as for the sun's light.
    color = h.add_node(tree, "ShaderNodeCombineColor", name=GROUND_COLOR, label="Ground Colour")
    sky_eevee_ground.drive(color, None)
    clear = sky_irradiance(tree, height.outputs[0])
    sky = sky_eevee_clouds.build(tree, height.outputs[0], light.outputs[0], clear, color.outputs[0])
    level = h.add_node(tree, "ShaderNodeVectorMath", operation="ADD", label="Light on Level Sand")
    h.link(tree, direct.outputs[0], level.inputs[0])
    h.link(tree, sky, level.inputs[1])
    ground = h.add_node(tree, "ShaderNodeVectorMath", operation="MULTIPLY", label="Ground Radiance × π")
    h.link(tree, level.outputs[0], ground.inputs[0])
    h.link(tree, color.outputs[0], ground.inputs[1])
    upright = h.add_node(tree, "ShaderNodeVectorMath", operation="MULTIPLY", label="× Upright Gain")
    h.link(tree, ground.outputs[0], upright.inputs[0])
    h.link(tree, _upright_gain(tree, height.outputs[0]), upright.inputs[1])
    return sky, upright.outputs[0], sun_unit, light.outputs[0]


def _upright_gain(tree, height):
    """Our sand's gain on the ground's light (core/eevee_upright.py) by the sine of the sun's
    elevation, mixed from 1 by the share of it the ground takes (sky_eevee_ground.upright_share_node)."""
    degrees, gains = eevee_upright.rows()
    gain = table_curve(tree, height, np.sin(np.radians(degrees)), gains, UPRIGHT_GAIN,
                       "Sand's Upright Gain ÷ Its Peak")
    share = sky_eevee_ground.upright_share_node(tree)
    mix = h.add_node(tree, "ShaderNodeMix", data_type="RGBA", label="Upright Gain Where the Ground Is Ours")
    h.link(tree, share.outputs[0], mix.inputs["Factor"])
    h.socket(mix.inputs, "A").default_value = (1.0, 1.0, 1.0, 1.0)
    h.link(tree, gain, h.socket(mix.inputs, "B"))
    return h.socket(mix.outputs, "Result")


def _with_disc(tree, view, sun, light, shown):
    """The camera's sky with the sun's disc on it: where the view lies within the disc's radius
    of the sun's direction, the lamp's light over the disc's solid angle."""
    unit = h.add_node(tree, "ShaderNodeVectorMath", operation="NORMALIZE")
    h.link(tree, view, unit.inputs[0])
    # The chord between the unit view and the sun's direction against the disc's radius: for a
    # sun's sizes the two agree within 1e-4. (A cosine against a driven cos of the radius failed:
    # a driven socket holds 0.99995 as 1.0, and the disc vanished.)
    chord = h.add_node(tree, "ShaderNodeVectorMath", operation="DISTANCE", label="View to Sun")
    h.link(tree, unit.outputs[0], chord.inputs[0])
    h.link(tree, sun, chord.inputs[1])
    inside = h.math(tree, "LESS_THAN", h.socket(chord.outputs, "Value"), DISC_EDGE_DEFAULT,
                    label="Within the Disc (its radius, driven)")
    inside.name = DISC_EDGE
    radiance = h.add_node(tree, "ShaderNodeVectorMath", operation="SCALE", label="Disc Radiance")
    h.link(tree, light, radiance.inputs[0])
    h.link(tree, inside.outputs[0], radiance.inputs["Scale"])
    disc = h.add_node(tree, "ShaderNodeBackground", name=DISC, label="Sun Disc (EEVEE draws none)",
                      inputs={"Strength": DISC_STRENGTH_DEFAULT})
    h.link(tree, radiance.outputs[0], disc.inputs["Color"])
    both = h.add_node(tree, "ShaderNodeAddShader", label="Sky + Disc")
    h.link(tree, shown, both.inputs[0])
    h.link(tree, disc.outputs[0], both.inputs[1])
    return both.outputs[0]


def sky_irradiance(tree, height):
    """The sky's irradiance on level ground by the sine of the sun's elevation (the sky model's
    table, linear between its rows)."""
    degrees, columns = sky_sun.sky_rows()
    rows = degrees >= 0
    return table_curve(tree, height, np.sin(np.radians(degrees[rows])), columns[rows], SKY_LIGHT,
                       "Sky on Level Sand ÷ Its Peak")


def table_curve(tree, height, sines, columns, name, label):
    """A table's (R, G, B) columns by the sine of the sun's elevation, linear between its rows and
    held beyond them, through an RGB Curves node per channel (each divided by its peak: a curve
    holds 0-1) and multiplied back: the colour socket."""
    peaks = columns.max(axis=0)
    curves = h.add_node(tree, "ShaderNodeRGBCurve", name=name, label=label)
    for channel in range(3):
        h.polyline_curve(curves.mapping.curves[channel], sines, columns[:, channel] / peaks[channel])
    curves.mapping.extend = "HORIZONTAL"
    curves.mapping.update()
    grey = h.add_node(tree, "ShaderNodeCombineColor")
    for index in range(3):
        h.link(tree, height, grey.inputs[index])
    h.link(tree, grey.outputs[0], curves.inputs["Color"])
    scaled = h.add_node(tree, "ShaderNodeVectorMath", operation="MULTIPLY", label="× Peak")
    h.link(tree, curves.outputs[0], scaled.inputs[0])
    scaled.inputs[1].default_value = tuple(float(p) for p in peaks)
    return scaled.outputs[0]


def follow_sun(world, sun):
    """Drive the ground's light from this sun lamp (None: no sun, no ground light)."""
    tree = world.node_tree if world is not None else None
    direction, light = own.node(tree, SUN), own.node(tree, SUN_LIGHT)
    if direction is None or light is None:
        return
    drivers.follow_lamp_axis(direction.inputs[:3], sun)
    _follow_disc_size(tree, sun)
    drivers.follow_lamp_light(light.inputs[:3], sun)


def _follow_disc_size(tree, sun):
    """The disc's edge and its radiance per unit irradiance from the lamp's angle (the sky's disc
    size without a lamp)."""
    edge, disc = own.node(tree, DISC_EDGE), own.node(tree, DISC)
    if edge is None or disc is None:
        return
    follows = ((edge.inputs[1], DISC_EDGE_EXPRESSION, DISC_EDGE_DEFAULT),
               (disc.inputs["Strength"], DISC_STRENGTH_EXPRESSION, DISC_STRENGTH_DEFAULT))
    for socket, expression, value in follows:
        if sun is None:
            socket.driver_remove("default_value")
            socket.default_value = value
        else:
            drivers.drive(socket, "default_value", expression, [("angle", "OBJECT", sun, "data.angle")])


def follow_clamp(world, scene):
    """Drive the ground's cap from this scene's EEVEE Clamp Surface Indirect."""
    node = own.node(world.node_tree if world is not None else None, CLAMP)
    if node is not None:
        drivers.drive(node.inputs[0], "default_value", CLAMP_EXPRESSION,
                      [("limit", "SCENE", scene, "eevee.clamp_surface_indirect")])


def _driven_by(world, name):
    return drivers.driven_by(world.node_tree if world is not None else None, name)


def followed_sun(world):
    """The lamp the ground's light follows, or None."""
    return _driven_by(world, SUN)


def followed_ground(world):
    """The material whose colour the ground takes (by drivers, or its image's mean), or None."""
    return sky_eevee_ground.followed(world.node_tree if world is not None else None)
