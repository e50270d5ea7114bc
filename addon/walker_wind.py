"""The scarf's tail streams downwind as the walker turns: the Sandscape Scarf Wind group as a
geometry-nodes modifier on the walker's body, ahead of the flutter's Wave (which ripples the tail
wherever it points). It reads the walker's own transform each frame; we set its wind (the scene's,
again whenever Add Atmosphere changes it), the walk's speed and frames (none is felt once the
walker has stopped and the scarf settled), the nape and the tail's built heading.
"""

import math

from ..core import scarf
from ..node_groups import helper as h
from ..node_groups import scarf_wind
from . import compat, shot, units, walker_figure

MODIFIER = "Sandscape Scarf Wind"


def find_modifier(walker):
    return next((m for m in walker.modifiers if m.type == "NODES" and m.node_group is not None
                 and m.node_group.get(h.GROUP_KEY) == scarf_wind.NAME), None)


def ensure(scene, walker, walk_speed, start, end):
    """The walker's Scarf Wind modifier, made or updated, first in the stack; `walk_speed`: scene
    units a second from frame `start` to `end`, felt less and less after it. None (and
    any old one removed) where the body has no tail to turn."""
    modifier = find_modifier(walker)
    if walker.data.attributes.get(scarf.FLUTTER_ATTRIBUTE) is None:
        if modifier is not None:
            walker.modifiers.remove(modifier)
        return None
    if modifier is None:
        modifier = walker.modifiers.new(MODIFIER, "NODES")
    if modifier.node_group is None or modifier.node_group.get(h.VERSION_KEY) != scarf_wind.VERSION:
        modifier.node_group = h.ensure_group(scarf_wind)
    index = list(walker.modifiers).index(modifier)
    if index:
        walker.modifiers.move(index, 0)
    scale = units.to_units(scene, 1.0)
    heading = walker_figure.TAIL_HEADING
    inputs = {"Wind": tuple(float(v) for v in scene.sandscape_atmosphere.wind),
              "Walk Speed": float(walk_speed), "Walk Start": float(start), "Walk End": float(end),
              "Settle Frames": scarf.SETTLE_TIME * shot.frames_per_second(scene),
              "Nape": tuple(float(v) * scale for v in walker_figure.tail_centre(0.0)),
              "Built Heading": math.atan2(heading[1], heading[0]),
              "Calm Speed": scarf.CALM_SPEED * scale}
    for name, value in inputs.items():
        compat.set_modifier_input_named(modifier, name, value)
    return modifier


def set_wind(scene, wind):
    """The wind of every walker's scarf in the scene (Add Atmosphere changed it)."""
    done = 0
    for obj in scene.objects:
        modifier = find_modifier(obj) if obj.type == "MESH" else None
        if modifier is not None:
            compat.set_modifier_input_named(modifier, "Wind", tuple(float(v) for v in wind))
            obj.update_tag()
            done += 1
    return done
