"""The land beyond the dune field, out to the horizon: a ring of loops around the field whose
steps grow with distance, so that it costs about as many vertices as the field and still has
dunes where a camera in the field can make them out.

- Loop 0 is the field's own boundary (the same points), so field and ring meet without a crack.
- Each further loop is a rectangle a step further out. The step, radial and along the loop, is
  the field's cell near the field and ANGULAR_STEP of the distance beyond it further out (dunes
  30 m apart still stand out 2 km away, seen from 50 m up), FAR_ANGULAR_STEP past NEAR_M, where
  they are under a pixel tall from the ground and the haze takes them.
- Heights come from the same periodic surface, blurred by BLUR_PER_STEP of the step (a coarse
  loop cannot hold dunes smaller than its step; sampled raw they would alias into spikes), and
  lowered by the Earth's curvature beyond the field (d^2 / 2R): seen from the ground the land
  then ends at a true horizon, before the ring's outer edge.
- Beyond DRAA_START_M the land swells into draa, the megadunes that dune fields sit on
  (spacing over 500 m, heights of tens to hundreds of metres: Lancaster, Dune Morphology and
  Dynamics): ridges across the wind with saddles, DRAA_RELIEF times the field's relief, so the
  horizon is a line of far crests fading into the haze rather than a ruler-straight edge.
- Consecutive loops are zipped into triangles by their positions along the loop (side index
  plus the fraction along that side, so corners meet corners).
"""

import math

import numpy as np

EARTH_RADIUS_M = 6_371_000.0
ANGULAR_STEP = 0.0125  # within NEAR_M of the field: dunes there still show from 50 m up
NEAR_M = 2000.0
FAR_ANGULAR_STEP = 0.05  # beyond: dunes under a pixel tall from the ground, and the haze
BLUR_PER_STEP = 0.4
DRAA_SPACING_M = 1500.0  # crest to crest, downwind
DRAA_RELIEF = 8.0  # draa crest height over the field's own crest-to-trough relief
DRAA_START_M, DRAA_FULL_M = 250.0, 1000.0  # beyond the field's edge: flat to full height between
DRAA_WANDER = 1.2  # radians the crests' phase wanders along them, over DRAA_WANDER_SPACINGS
DRAA_WANDER_SPACINGS = 2.3
DRAA_SADDLE = 0.5  # crests dip this share of their height at saddles, DRAA_SADDLE_SPACINGS apart:
DRAA_SADDLE_SPACINGS = 0.6  # seen along its length a straight crest would draw a level line


def angular_step(offset):
    return ANGULAR_STEP if offset <= NEAR_M else FAR_ANGULAR_STEP


def draa(x, y, offset, wind_angle, relief):
    """Height in metres the draa add at (x, y) metres, `offset` beyond the field's edge: 0 up to
    DRAA_START_M, easing in to ridges from 0 to DRAA_RELIEF * relief by DRAA_FULL_M. Crests run
    across the wind, wandering and dipping at saddles along their length; never below the land
    under them."""
    along = x * math.cos(wind_angle) + y * math.sin(wind_angle)
    across = y * math.cos(wind_angle) - x * math.sin(wind_angle)
    t = np.clip((np.asarray(offset, np.float64) - DRAA_START_M) / (DRAA_FULL_M - DRAA_START_M), 0.0, 1.0)
    ease = t * t * (3.0 - 2.0 * t)
    wander = DRAA_WANDER * np.sin(2.0 * math.pi * across / (DRAA_WANDER_SPACINGS * DRAA_SPACING_M))
    ridge = 0.5 * (1.0 + np.sin(2.0 * math.pi * along / DRAA_SPACING_M + wander))
    saddles = 1.0 - DRAA_SADDLE * 0.5 * (1.0 + np.sin(2.0 * math.pi * across / (DRAA_SADDLE_SPACINGS
                                                                                 * DRAA_SPACING_M)))
    return ease * DRAA_RELIEF * max(float(relief), 0.0) * ridge * saddles


def loop_offsets(cell, reach):
    """Distances of the loops beyond the field's edge: 0 (the edge itself), then growing steps
    until `reach` is passed."""
    offsets = [0.0]
    while offsets[-1] < reach:
        offsets.append(offsets[-1] + max(cell, angular_step(offsets[-1]) * offsets[-1]))
    return np.array(offsets)


def rectangle_loop(half_x, half_y, count_x, count_y):
    """Points counter-clockwise around a rectangle from its (-x, -y) corner, count_x steps along
    each x side and count_y along each y side. Returns (x, y, position), position = side index
    (0 bottom, 1 right, 2 top, 3 left) plus the fraction along that side."""
    fx = np.arange(count_x) / count_x
    fy = np.arange(count_y) / count_y
    x = np.concatenate([-half_x + 2 * half_x * fx, np.full(count_y, half_x),
                        half_x - 2 * half_x * fx, np.full(count_y, -half_x)])
    y = np.concatenate([np.full(count_x, -half_y), -half_y + 2 * half_y * fy,
                        np.full(count_x, half_y), half_y - 2 * half_y * fy])
    position = np.concatenate([fx, 1 + fy, 2 + fx, 3 + fy])
    return x, y, position


def zip_loops(inner, inner_position, outer, outer_position):
    """Triangles (counter-clockwise seen from above) joining two closed loops of vertex indices
    ordered by position (0..4). Each triangle advances one loop by one edge, whichever loop's
    next point comes first, so neither loop's edges are skipped (no T-junction, no crack)."""
    n, m = len(inner), len(outer)
    next_inner = np.append(inner_position[1:], 4.0)
    next_outer = np.append(outer_position[1:], 4.0)
    keys = np.concatenate([next_inner, next_outer])
    is_inner = np.concatenate([np.ones(n, bool), np.zeros(m, bool)])
    order = np.lexsort((~is_inner, keys))  # by position; on a tie the inner loop first
    is_inner = is_inner[order]
    i = np.cumsum(is_inner) - is_inner  # inner edges taken before this event
    j = np.cumsum(~is_inner) - ~is_inner
    a = inner[i % n]
    b = np.where(is_inner, inner[(i + 1) % n], outer[(j + 1) % m])
    c = outer[j % m]
    # inner runs counter-clockwise with the outer loop on its right: (a, c, b) turns left.
    return np.stack([a, c, b], -1)


def ring(surface, width, depth, cell, reach, boundary):
    """The horizon ring around a field of width x depth metres centred on the origin.

    boundary: (x, y, z) of the field mesh's boundary vertices counter-clockwise from its
    (-x, -y) corner (boundary_indices gives them), the ring's first loop.
    Returns (vertices (N, 3) in metres, triangles (M, 3)).
    """
    count_x = max(int(round(width / cell)), 1)
    count_y = max(int(round(depth / cell)), 1)
    offsets = loop_offsets(cell, reach)
    relief = float(np.ptp(surface.levels[0]))
    x, y, position = rectangle_loop(width / 2, depth / 2, count_x, count_y)
    points = [np.stack([np.asarray(c, np.float64) for c in boundary], -1)]
    previous = (np.arange(len(x)), position)
    start, triangles = len(x), []
    for index in range(1, len(offsets)):
        offset, step = offsets[index], offsets[index] - offsets[index - 1]
        half_x, half_y = width / 2 + offset, depth / 2 + offset
        along = max(cell, angular_step(offset) * offset)
        nx = min(max(int(math.ceil(2 * half_x / along)), 1), count_x)
        ny = min(max(int(math.ceil(2 * half_y / along)), 1), count_y)
        x, y, position = rectangle_loop(half_x, half_y, nx, ny)
        z = surface.heights(x, y, blur=BLUR_PER_STEP * max(step, along))
        z = z + draa(x, y, offset, surface.wind_angle, relief)
        points.append(np.stack([x, y, z - offset**2 / (2.0 * EARTH_RADIUS_M)], -1))
        indices = np.arange(start, start + len(x))
        triangles.append(zip_loops(previous[0], previous[1], indices, position))
        previous, start = (indices, position), start + len(x)
    return np.concatenate(points), np.concatenate(triangles) if triangles else np.zeros((0, 3), np.int64)


def boundary_indices(count_x, count_y):
    """Indices into a (count_y + 1, count_x + 1) grid of its boundary, in rectangle_loop's order."""
    index = np.arange((count_x + 1) * (count_y + 1)).reshape(count_y + 1, count_x + 1)
    return np.concatenate([index[0, :-1], index[:-1, -1], index[-1, :0:-1], index[:0:-1, 0]])


def horizon_depression(height, distance):
    """Angle in radians below the horizontal at which a camera `height` metres above the ground
    sees level ground `distance` metres away on the curved Earth (for tests and warnings)."""
    return math.atan2(height + distance**2 / (2.0 * EARTH_RADIUS_M), distance)
