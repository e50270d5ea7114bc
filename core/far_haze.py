"""The haze beyond the dust box, in numpy: the shell's shape and what it does to a ray.

Under fair-weather cumulus the haze fills the mixed layer, whose top is the clouds' base; the dust
box holds the haze round the camera and stops kilometres out, so a far cloud kept its full
contrast against the sky. The shell fills the rest, from the ground to the clouds' base, outside
the dust box, with the haze's extinction beta, and glows with the sky's colour in the ray's
direction (at least HORIZON_RISE up: below the horizon the haze is the horizon's colour, not the
sky model's ground). Along a ray that crosses L of it, what lies behind is seen as
T behind + (1 - T) sky with T = exp(-beta L) (Koschmieder): clear sky is left as it is, a far
cloud or dune fades into the sky beside it.
"""

import numpy as np

HORIZON_RISE = 0.01  # the sky is looked up at least this far up (z of the direction): 0.6 degrees


def shell_mesh(region, bottom, top, cavity):
    """Vertices and quads of the shell over region (xmin, ymin, xmax, ymax) from bottom to top
    with the cavity (xmin, ymin, xmax, ymax, cavity top) cut out from the bottom up: a box with a
    box-shaped hollow from below, or, where the cavity reaches the top, a frame round it. Normals
    point out of the haze. None when the cavity leaves no haze."""
    xmin, ymin, xmax, ymax = region
    cx0, cy0, cx1, cy1, ctop = cavity
    if cx0 <= xmin and cy0 <= ymin and cx1 >= xmax and cy1 >= ymax or not top > bottom:
        return None
    # The hollow stays strictly inside the region: a wall shared with the outside would not be closed.
    inset = 1e-4 * max(xmax - xmin, ymax - ymin)
    cx0, cy0 = max(cx0, xmin + inset), max(cy0, ymin + inset)
    cx1, cy1 = min(cx1, xmax - inset), min(cy1, ymax - inset)
    ceiling = min(ctop, top)
    outer = [(xmin, ymin), (xmax, ymin), (xmax, ymax), (xmin, ymax)]
    inner = [(cx0, cy0), (cx1, cy0), (cx1, cy1), (cx0, cy1)]
    verts = ([(x, y, bottom) for x, y in outer] + [(x, y, top) for x, y in outer]
             + [(x, y, bottom) for x, y in inner] + [(x, y, ceiling) for x, y in inner])
    ob, ot, ib, it = 0, 4, 8, 12  # first index of each ring of four
    faces = []
    for i in range(4):
        j = (i + 1) % 4
        faces.append((ob + i, ob + j, ot + j, ot + i))  # outer wall, facing out
        faces.append((ib + j, ib + i, it + i, it + j))  # the hollow's wall, facing into it
        faces.append((ob + j, ob + i, ib + i, ib + j))  # the floor's frame, facing down
    if ceiling < top:
        faces.append((ot, ot + 1, ot + 2, ot + 3))  # the top, facing up
        faces.append((it + 3, it + 2, it + 1, it))  # the hollow's ceiling, facing down into it
    else:
        faces += [(ot + i, ot + (i + 1) % 4, it + (i + 1) % 4, it + i) for i in range(4)]  # the top's frame
    return np.array(verts, np.float64), faces


def enclosed_volume(verts, faces):
    """The volume a closed mesh encloses (the divergence theorem): positive when normals point out."""
    total = 0.0
    for face in faces:
        a = verts[face[0]]
        for b, c in zip(verts[list(face[1:-1])], verts[list(face[2:])], strict=True):
            total += np.dot(a, np.cross(b, c)) / 6.0
    return float(total)


def _slab_interval(origins, directions, low, high):
    """Where rays are inside the box low..high: (enter, leave) distances, leave < enter for a miss."""
    with np.errstate(divide="ignore", invalid="ignore"):
        inverse = 1.0 / directions
        t0 = (low - origins) * inverse
        t1 = (high - origins) * inverse
    near = np.where(np.isnan(t0), -np.inf, np.minimum(t0, t1))
    far = np.where(np.isnan(t1), np.inf, np.maximum(t0, t1))
    # A ray parallel to a slab: inside it everywhere or nowhere.
    parallel = directions == 0
    inside = (origins >= low) & (origins <= high)
    near = np.where(parallel, np.where(inside, -np.inf, np.inf), near)
    far = np.where(parallel, np.where(inside, np.inf, -np.inf), far)
    return near.max(axis=-1), far.min(axis=-1)


def _overlap(interval, start, end):
    enter, leave = interval
    return np.clip(np.minimum(leave, end) - np.maximum(enter, start), 0.0, None)


def haze_length(origins, directions, distances, region, bottom, top, cavity):
    """How far rays (unit directions) travel through the shell before `distances`."""
    origins, directions = np.asarray(origins, np.float64), np.asarray(directions, np.float64)
    distances = np.asarray(distances, np.float64)
    xmin, ymin, xmax, ymax = region
    cx0, cy0, cx1, cy1, ctop = cavity
    whole = _slab_interval(origins, directions, np.array([xmin, ymin, bottom]), np.array([xmax, ymax, top]))
    hollow = _slab_interval(origins, directions, np.array([cx0, cy0, bottom]),
                            np.array([cx1, cy1, min(ctop, top)]))
    return _overlap(whole, 0.0, distances) - _overlap(hollow, 0.0, distances)


def seen_through(behind, sky, beta, length):
    """Koschmieder: what lies behind, seen through `length` of haze that glows with the sky's colour."""
    transmittance = np.exp(-beta * np.asarray(length, np.float64))[..., None]
    return transmittance * np.asarray(behind) + (1.0 - transmittance) * np.asarray(sky)


def lookup_direction(directions):
    """The direction the shell looks the sky up in: at least HORIZON_RISE up (unnormalised, as the
    Sky Texture takes it)."""
    d = np.array(directions, np.float64)
    d[..., 2] = np.maximum(d[..., 2], HORIZON_RISE)
    return d
