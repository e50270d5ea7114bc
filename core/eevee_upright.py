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

A wall turned from the sun (a backlit walker's face toward the camera) sees our sand brighter
still: the sand looked at with the sun behind the eye sends back more (opposition), and more so
in red under a low sun. Two bands can hold that only as a lobe, the ground brighter on the side
turned from the sun and as much darker toward it (BACKLIT_ROWS, from the same wall turned with
its back to the sun); a wall facing the sun is lit by the sun itself, which that shift barely
changes.
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


# (sun elevation in degrees, lobe R, G, B): the lower hemisphere's radiance times 1 + lobe x (the
# direction's horizontal part along the sun's horizontal opposite), from the backlit wall.
BACKLIT_ROWS = (
    (3.0, 0.240, 0.181, 0.192),
    (6.0, 0.501, 0.349, 0.236),
    (10.0, 0.733, 0.562, 0.282),
    (15.0, 0.709, 0.543, 0.333),
    (25.0, 0.498, 0.400, 0.216),
    (40.0, 0.265, 0.204, 0.085),
    (60.0, 0.077, 0.068, 0.000),
    (80.0, 0.038, 0.032, 0.006),
)

# The lobe's largest value: at 1 the lower hemisphere's radiance reaches 0 toward the sun. Its
# second band along that axis is then at most 2/3 x below / (above + below) of the first, inside
# 5.0's deringing limit (2/3, core.atmosphere) while the ground is held within its ratio.
LOBE_CAP = 1.0


def measured_gain(cycles, eevee, no_ground):
    """The gain on the lower hemisphere that brings EEVEE's wall (`eevee`; `no_ground` without the
    lower hemisphere) to Cycles' (`cycles`), per channel."""
    cycles, eevee, no_ground = (np.asarray(v, np.float64) for v in (cycles, eevee, no_ground))
    return (cycles - no_ground) / np.maximum(eevee - no_ground, 1e-12)


def lobe_from_gains(edge, backlit):
    """The lobe that gives a backlit wall its gain (`backlit`) where an edge-on wall's is `edge`.

    EEVEE lights a wall from the world's first two bands: the lower hemisphere of radiance G
    gives an upright face pi G / 2, and G x lobe x cos(azimuth from the face) adds pi G lobe / 3
    on the face turned from the sun (its share 2/3 lobe) and takes as much from one facing it;
    an edge-on face gets none. So 1 + 2/3 lobe = backlit / edge; held within [0, LOBE_CAP]."""
    edge, backlit = np.asarray(edge, np.float64), np.asarray(backlit, np.float64)
    return np.clip(1.5 * (backlit / edge - 1.0), 0.0, LOBE_CAP)


def rows(table=ROWS):
    """(elevations in degrees, values (N, 3)) of ROWS (gains) or BACKLIT_ROWS (lobes)."""
    table = np.array(table, np.float64)
    return table[:, 0], table[:, 1:]


def gain(elevation):
    """The gain (R, G, B) at a sun elevation in radians: linear between the rows, the end rows'
    beyond them."""
    return _at(ROWS, elevation)


def lobe(elevation):
    """The backlit lobe (R, G, B) at a sun elevation in radians, as gain() reads its rows."""
    return _at(BACKLIT_ROWS, elevation)


def _at(table, elevation):
    degrees, values = rows(table)
    at = np.clip(np.degrees(float(elevation)), degrees[0], degrees[-1])
    return np.array([np.interp(at, degrees, column) for column in values.T])
