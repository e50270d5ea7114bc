"""The haze's light in EEVEE's lighting world: the lamp's light the dust box's haze scatters down,
from the directions it comes (core.haze_light.radiance, in nodes).

Cycles renders it by itself; EEVEE's volumes light no surface, so without it shaded sand was lit
by the blue sky alone and came out grey where Cycles keeps it warm. Held per direction, not as
a uniform hemisphere: it comes mostly from around a low sun, so slopes turned from the sun (the
shade) get less of it than level sand, as in Cycles. The haze's extinction, anisotropy and the
box's height and half-width are set by Add Atmosphere (follow); the lamp's light and axis are
the world's driven sockets, so a farm needs no Python.
"""

import math

from ..node_groups import helper as h
from . import ownership as own

BEND, PHASE = "Sandscape EEVEE Haze Phase Bend", "Sandscape EEVEE Haze Phase Scale"
HEIGHT, RADIUS = "Sandscape EEVEE Haze Height", "Sandscape EEVEE Haze Radius"
EXTINCTION = "Sandscape EEVEE Haze Extinction"
NODES = (BEND, PHASE, HEIGHT, RADIUS, EXTINCTION)
LEAST = 1e-6  # keeps a level or vertical ray's reach finite


def build(tree, direction, to_sun, light):
    """Nodes giving pi times the haze's radiance in the lighting ray's direction (irradiance
    units, as the world's hemispheres); zero until follow() sets the haze."""
    unit = h.vector_math(tree, "NORMALIZE", direction)
    axes = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, unit.outputs[0], axes.inputs[0])
    cosine = h.vector_math(tree, "DOT_PRODUCT", unit.outputs[0], to_sun, label="View · Sun")
    # Henyey-Greenstein: (1 - g^2) / (4 pi) over (1 + g^2 - 2 g cos)^1.5.
    bend = h.math(tree, "MULTIPLY_ADD", h.socket(cosine.outputs, "Value"), 0.0, label="1 + g² − 2g cos",
                  c=1.0)
    bend.name = BEND
    power = h.math(tree, "POWER", bend.outputs[0], 1.5)
    phase = h.math(tree, "DIVIDE", 0.0, power.outputs[0], label="Phase: (1 − g²) / 4π ÷ …")
    phase.name = PHASE
    z = axes.outputs["Z"]
    up = h.math(tree, "MAXIMUM", z, LEAST)
    to_top = h.math(tree, "DIVIDE", 0.0, up.outputs[0], label="Height ÷ Sine")
    to_top.name = HEIGHT
    square = h.math(tree, "MULTIPLY", z, z)
    level = h.math(tree, "SUBTRACT", 1.0, square.outputs[0])
    level_held = h.math(tree, "MAXIMUM", level.outputs[0], LEAST * LEAST)
    flat = h.math(tree, "SQRT", level_held.outputs[0])
    to_side = h.math(tree, "DIVIDE", 0.0, flat.outputs[0], label="Half-Width ÷ Cosine")
    to_side.name = RADIUS
    reach = h.math(tree, "MINIMUM", to_top.outputs[0], to_side.outputs[0], label="Reach to the Box's Edge")
    depth = h.math(tree, "MULTIPLY", reach.outputs[0], 0.0, label="× −Extinction")
    depth.name = EXTINCTION
    kept = h.math(tree, "EXPONENT", depth.outputs[0])
    scattered = h.math(tree, "SUBTRACT", 1.0, kept.outputs[0], label="Share Scattered on the Way")
    above = h.math(tree, "GREATER_THAN", z, 0.0)
    share = h.math(tree, "MULTIPLY", phase.outputs[0], scattered.outputs[0])
    shown = h.math(tree, "MULTIPLY", share.outputs[0], above.outputs[0])
    times_pi = h.math(tree, "MULTIPLY", shown.outputs[0], math.pi, label="× π")
    result = h.vector_math(tree, "SCALE", light, label="Haze Light (× π)")
    h.link(tree, times_pi.outputs[0], result.inputs["Scale"])
    return result.outputs[0]


def _nodes(world):
    """{name: node} of the haze's settable nodes in this world, or None (not ours, or older)."""
    tree = world.node_tree if world is not None else None
    nodes = {name: own.node(tree, name) for name in NODES}
    return None if None in nodes.values() else nodes


def follow(world, extinction=0.0, anisotropy=0.0, height=0.0, radius=0.0):
    """Set the haze: extinction per scene unit (0: none), its Henyey-Greenstein anisotropy, and
    the box's height over the ground and half-width, in scene units."""
    nodes = _nodes(world)
    if nodes is None:
        return
    g = min(max(float(anisotropy), -0.99), 0.99)
    nodes[BEND].inputs[1].default_value = -2.0 * g
    nodes[BEND].inputs[2].default_value = 1.0 + g * g
    nodes[PHASE].inputs[0].default_value = (1.0 - g * g) / (4.0 * math.pi)
    nodes[HEIGHT].inputs[0].default_value = max(float(height), 0.0)
    nodes[RADIUS].inputs[0].default_value = max(float(radius), 0.0)
    nodes[EXTINCTION].inputs[1].default_value = -max(float(extinction), 0.0)


def held(world):
    """(extinction, anisotropy, height, radius) the world holds, or None."""
    nodes = _nodes(world)
    if nodes is None:
        return None
    return (-nodes[EXTINCTION].inputs[1].default_value, -nodes[BEND].inputs[1].default_value / 2.0,
            nodes[HEIGHT].inputs[0].default_value, nodes[RADIUS].inputs[0].default_value)
