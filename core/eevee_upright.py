"""How brightly our Physical Sand lights upright things, against the Lambert ground EEVEE's
lighting world stands in for it: the gain on the world's lower hemisphere (addon/sky_eevee.py).

EEVEE lights an upright surface with the mean of the world's two hemispheres: the sky's light on
level ground above, the lit ground's (a Lambert ground of the sand's colour) below. Physical Sand
in Cycles is no Lambert ground: under a low sun it is several times brighter seen at grazing
angles (back-scatter and sheen), so a wall or a walker's shaded back standing on it got too little
light in EEVEE (the demo's walker a third too dark); under a high sun it sends less light
sideways than a Lambert ground, and the same wall came out twice as bright as in Cycles. An
upright surface also sees the sky's bright horizon, which two hemispheres cannot hold.

The gain is measured, not derived (devtools/eevee_upright_data.py): a grey wall standing on a
plane of Physical Sand, edge-on to the sun, in Cycles (two bounces) and in EEVEE with and without
the world's lower hemisphere. With C, E and E0 those three, the lower hemisphere times
(C - E0) / (E - E0) gives the wall Cycles' light. It folds the horizon's light in too, so it is a
calibration for walls on our sand, per channel, by the sun's elevation.
"""

import numpy as np

# (sun elevation in degrees, gain R, G, B): devtools/eevee_upright_data.py, Blender 5.2.
ROWS = (
    (3.0, 2.255, 2.365, 2.180),
    (6.0, 1.891, 2.197, 2.474),
    (10.0, 1.615, 1.905, 2.490),
    (15.0, 1.403, 1.655, 2.165),
    (25.0, 1.111, 1.287, 1.714),
    (40.0, 0.882, 0.994, 1.304),
    (60.0, 0.748, 0.822, 1.052),
    (80.0, 0.688, 0.754, 0.957),
)


def measured_gain(cycles, eevee, no_ground):
    """The gain on the lower hemisphere that brings EEVEE's wall (`eevee`; `no_ground` without the
    lower hemisphere) to Cycles' (`cycles`), per channel."""
    cycles, eevee, no_ground = (np.asarray(v, np.float64) for v in (cycles, eevee, no_ground))
    return (cycles - no_ground) / np.maximum(eevee - no_ground, 1e-12)


def rows():
    """(elevations in degrees, gains (N, 3))."""
    table = np.array(ROWS, np.float64)
    return table[:, 0], table[:, 1:]


def gain(elevation):
    """The gain (R, G, B) at a sun elevation in radians: linear between the rows, the end rows'
    beyond them."""
    degrees, gains = rows()
    at = np.clip(np.degrees(float(elevation)), degrees[0], degrees[-1])
    return np.array([np.interp(at, degrees, column) for column in gains.T])
