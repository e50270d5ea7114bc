"""The scarf's tail flutters in the wind: a Wave modifier on the walker's body, weighted along the
tail by the figure's flutter attribute (0 at the nape, 1 at its end), its waves running out from
the nape along the ribbon and pushing it across its face. A modifier, not keys or a handler: it
follows the frame on a farm with no Python, and a re-run sets it again rather than adding one.
"""

import numpy as np

from . import walker_figure

GROUP = MODIFIER = "Sandscape Scarf Flutter"
AMPLITUDE = 0.08  # metres across the ribbon's face at its end
WAVELENGTH = 0.45  # metres between the crests running along the tail
SPEED = 0.06  # metres a frame out from the nape: about three flaps a second at 24 fps
EDGE_EXPONENT = 3.0  # the bump falls to e^-3 of its crest at its edge
LEAD = -200.0  # the waves start this many frames before frame 0: the tail is already astir at 1


def ensure(walker, scale):
    """The walker's flutter group from its body's attribute and its Wave modifier; `scale`: scene
    units per metre. Nothing where the body has no flutter attribute (an artist's own mesh)."""
    attribute = walker.data.attributes.get(walker_figure.FLUTTER_ATTRIBUTE)
    modifier = next((m for m in walker.modifiers if m.type == "WAVE" and m.vertex_group == GROUP), None)
    if attribute is None:
        if modifier is not None:
            walker.modifiers.remove(modifier)
        return None
    weights = np.empty(len(attribute.data), np.float32)
    attribute.data.foreach_get("value", weights)
    group = walker.vertex_groups.get(GROUP) or walker.vertex_groups.new(name=GROUP)
    group.remove(range(len(weights)))
    for index in np.flatnonzero(weights > 0.0):
        group.add([int(index)], float(weights[index]), "REPLACE")
    if modifier is None:
        modifier = walker.modifiers.new(MODIFIER, "WAVE")
        modifier.vertex_group = GROUP
    nape = walker_figure.tail_centre(0.0)
    modifier.start_position_x, modifier.start_position_y = float(nape[0] * scale), float(nape[1] * scale)
    modifier.use_x = modifier.use_y = True  # rings out from the nape
    modifier.use_normal = modifier.use_normal_x = modifier.use_normal_y = modifier.use_normal_z = True
    modifier.use_cyclic = True
    # Blender's waves: a bump exp(-(x narrowness)^2) within `width` of each crest, crests 2 width
    # apart, less its value at the bump's edge (MOD_wave.cc).
    half = WAVELENGTH / 2 * scale
    modifier.height, modifier.width = AMPLITUDE * scale, half
    modifier.narrowness = float(np.sqrt(EDGE_EXPONENT)) / half
    modifier.speed, modifier.time_offset, modifier.lifetime = SPEED * scale, LEAD, 0.0
    modifier.falloff_radius = 0.0
    return modifier
