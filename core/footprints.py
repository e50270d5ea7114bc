"""Footprint painter in plain numpy: prints in, a float RGBA height image out.

Channels (the numpy twin of what node group "Sandscape Footprint Height" reads):
  R  depression, 0..depth scale: the sole pressed into the sand (1 = the set depth)
  G  raised rim, 0..depth scale: sand pushed up in a ring around the sole (1 = the set rim;
     a crumbled rim's lumps reach 1 + RIM_LUMPS)
  B  birth frame of the print that owns the texel, normalised to the frame range (0..1)
  A  sole coverage, 0..1: where any sole pressed the sand (the owner test uses it)

The print's shape (outline, floor, wall, rim) is in sole.py.
Edges are never narrower than about a texel, so the image carries no aliasing steps.

Composition, per texel, in birth order (it is associative, so prints go in chunks):
  R = max of the prints' depressions          never deeper than the deepest print
  G = max_i rim_i * prod_{j later} (1 - s_j)  a later sole flattens an earlier rim
  B = birth of the latest print whose sole covers the texel; failing that, of the latest
      print whose surviving rim reaches it.

Work is vectorised over texel windows of whole batches of prints: no Python loop per texel
or per print.
"""

import numpy as np

from .shaping import wind_direction
from .sole import REPOSE, RIM_LUMPS, Sole, arch_hump, crumble_noise, floor_depth, sole_distance, sole_profile

F32 = np.float32
LOG_FLOOR = -69.0  # log(1e-30): a fully pressed texel keeps no rim, without log(0)
CHUNK_ENTRIES = 1 << 22  # texel-print pairs per batch: bounds memory at any print count
WINDWARD_SPEEDUP = 2.0  # the wind's fractional speed-up per unit of windward gradient


class Region:
    """The image's footprint in the painting plane: origin (x0, y0), square texels, size."""

    __slots__ = ("x0", "y0", "texel", "width", "height")

    def __init__(self, x0, y0, texel, width, height):
        self.x0, self.y0, self.texel = float(x0), float(y0), float(texel)
        self.width, self.height = int(width), int(height)

    def extent(self):
        return self.width * self.texel, self.height * self.texel


def fit_region(centres, reach, resolution, margin=0.0):
    """The smallest texel grid over the prints' bounding box plus reach and margin.

    The longer side gets `resolution` texels; texels are square, so the short side gets
    proportionally fewer (at least 1). Texels are spent only where prints are.
    """
    centres = np.asarray(centres, dtype=np.float64).reshape(-1, 2)
    if len(centres) == 0:
        raise ValueError("no prints to fit a region around")
    if int(resolution) < 1:
        raise ValueError("resolution must be at least 1")
    pad = reach + margin
    low = centres.min(axis=0) - pad
    high = centres.max(axis=0) + pad
    span = np.maximum(high - low, 1e-6)
    texel = span.max() / int(resolution)
    size = np.maximum(np.ceil(span / texel - 1e-9), 1).astype(int)
    # Centre the grid on the box so rounding spreads evenly on both sides.
    origin = (low + high) / 2 - size * texel / 2
    return Region(origin[0], origin[1], texel, size[0], size[1])


def _prepare(centres, forward, lateral, births, depth_scales, frame_range):
    centres = np.asarray(centres, dtype=np.float64).reshape(-1, 2)
    n = len(centres)
    forward = np.asarray(forward, dtype=np.float64).reshape(n, 2)
    lateral = np.asarray(lateral, dtype=np.float64).reshape(n, 2)
    births = np.broadcast_to(np.asarray(births, dtype=np.float64), (n,))
    scales = np.broadcast_to(np.asarray(depth_scales, dtype=np.float64), (n,))
    start, end = frame_range
    span = frame_span(start, end)
    birth_unit = np.clip((births - start) / span, 0.0, 1.0)
    # Sole coordinates (a, b) of a plane offset d solve [forward lateral] (a, b) = d.
    det = forward[:, 0] * lateral[:, 1] - forward[:, 1] * lateral[:, 0]
    finite = np.isfinite(centres).all(1) & np.isfinite(det) & np.isfinite(scales) & np.isfinite(birth_unit)
    usable = finite & (np.abs(det) > 1e-6) & (scales > 0)
    order = np.argsort(births, kind="stable")
    order = order[usable[order]]
    inverse = np.stack([lateral[:, 1], -lateral[:, 0], -forward[:, 1], forward[:, 0]], axis=1)
    inverse /= np.where(usable, det, 1.0)[:, None]
    return centres, inverse, birth_unit, scales, order


def paint(centres, forward, lateral, births, depth_scales, region, sole=None, frame_range=(0.0, 1.0),
          toe_bias=0.0):
    """Stamp prints into a (height, width, 4) float32 image; returns it (rows from y0 up).

    centres (N, 2): print centres in the painting plane (the print frame's X and Y: world-aligned).
    forward, lateral (N, 2): the print's unit forward and lateral axes projected onto the
        plane (on flat ground, (cos h, sin h) and +-(-sin h, cos h); on a slope, shorter). The
        lateral axis points to the foot's inner side (a waisted sole narrows there): for a left
        foot, to the right of its heading.
    births (N,): frames; depth_scales (N,): per-print multipliers of depth and rim (> 0).
    toe_bias (N,) or scalar: a print's depth runs from (1 - bias) at the heel to (1 + bias) at
        the toe (a run pushes off from the forefoot); 0 presses evenly.
    Prints with a non-finite value, a zero scale or a degenerate frame are skipped.
    """
    sole = sole or Sole()
    texel = region.texel
    out = np.zeros((region.height, region.width, 4), dtype=F32)
    centres, inverse, birth_unit, scales, order = _prepare(centres, forward, lateral, births,
                                                           depth_scales, frame_range)
    if len(order) == 0:
        return out
    toe = np.nan_to_num(np.broadcast_to(np.asarray(toe_bias, np.float64), (len(centres),)))
    toe = np.clip(toe, -1.0, 1.0)
    # Each print's box in the plane: the sole's half-length and half-width plus the wall and the
    # rim band, through its (projected) axes. A square of the full reach would hold twice the texels.
    band = sole.outer_band(texel)
    along, across = sole.length / 2 + band, sole.width / 2 + band
    forward_abs = np.abs(np.asarray(forward, np.float64).reshape(-1, 2))
    lateral_abs = np.abs(np.asarray(lateral, np.float64).reshape(-1, 2))
    half = np.nan_to_num(forward_abs * along + lateral_abs * across)  # (N, 2): half extents in x, y
    windows = np.ceil(2 * half / texel).astype(np.int64) + 2
    largest = int(windows[order].prod(axis=1).max())
    per_chunk = max(1, CHUNK_ENTRIES // largest)
    flat = out.reshape(-1, 4)
    for begin in range(0, len(order), per_chunk):
        prints = order[begin:begin + per_chunk]
        _stamp_chunk(flat, region, sole, windows[prints].max(axis=0), half[prints], prints,
                     centres, inverse, birth_unit, scales, toe)
    return out


def _stamp_chunk(flat, region, sole, window, half, prints, centres, inverse, birth_unit, scales, toe):
    texel = region.texel
    c = centres[prints]
    first = np.floor((c - (region.x0, region.y0) - half) / texel).astype(np.int64)
    col = first[:, 0, None, None] + np.arange(window[0])[None, None, :]
    row = first[:, 1, None, None] + np.arange(window[1])[None, :, None]
    col, row = np.broadcast_arrays(col, row)
    x = region.x0 + (col + 0.5) * texel  # texel centres in the plane
    y = region.y0 + (row + 0.5) * texel
    dx, dy = x - c[:, 0, None, None], y - c[:, 1, None, None]
    m = inverse[prints][:, :, None, None]
    # Offsets need float64 (texel positions far from the origin); the profile does not.
    a = (m[:, 0] * dx + m[:, 1] * dy).astype(F32)
    b = (m[:, 2] * dx + m[:, 3] * dy).astype(F32)
    hump = arch_hump(a, sole) if sole.arch < 1 or sole.waist < 1 else None
    distance = sole_distance(a, b, sole, hump)
    if sole.crumble > 0:
        wander, lumps = crumble_noise(x, y, sole.edge_width(texel))
        distance = distance + F32(sole.crumble) * wander
    pressed, rim = sole_profile(distance, sole, texel)
    if sole.crumble > 0:
        rim = rim * np.maximum(1.0 + F32(RIM_LUMPS) * lumps, 0.0)
    inside = ((col >= 0) & (col < region.width) & (row >= 0) & (row < region.height)
              & ((pressed > 0) | (rim > 0)))
    rank = np.broadcast_to(np.arange(len(prints))[:, None, None], inside.shape)[inside]
    pixel = (row * region.width + col)[inside]
    pressed, rim = pressed[inside].astype(np.float64), rim[inside].astype(np.float64)
    if pixel.size == 0:
        return
    scale = scales[prints][rank]
    birth = birth_unit[prints][rank]
    # The depth tilts from heel (-1) to toe (+1) along the sole; the rim stays even.
    along = a[inside].astype(np.float64)
    tilt = 1.0 + toe[prints][rank] * np.clip(along / (sole.length / 2), -1.0, 1.0)
    if sole.arch < 1:
        tilt = tilt * floor_depth(along, sole, hump[inside].astype(np.float64))
    # Group by texel, in birth order within each texel (prints arrive sorted by birth).
    sort = np.argsort(pixel * len(prints) + rank, kind="stable")
    pixel, pressed, rim, scale, birth = pixel[sort], pressed[sort], rim[sort], scale[sort], birth[sort]
    tilt = tilt[sort]
    starts = np.flatnonzero(np.concatenate(([True], pixel[1:] != pixel[:-1])))
    ends = np.append(starts[1:], pixel.size)
    texels = pixel[starts]

    keep = np.maximum(np.log(np.maximum(1.0 - pressed, 1e-300)), LOG_FLOOR)
    # Sum of log(1 - s_j) over the later prints of the same texel: a suffix sum per group.
    suffix = np.concatenate((np.cumsum(keep[::-1])[::-1], [0.0]))
    group_end = np.repeat(ends, ends - starts)
    later = suffix[np.arange(pixel.size) + 1] - suffix[group_end]
    surviving = _flush(rim * scale * np.exp(later))
    depth = pressed * scale * tilt

    chunk_depth = np.maximum.reduceat(depth, starts)
    chunk_rim = np.maximum.reduceat(surviving, starts)
    chunk_keep = np.exp(suffix[starts] - suffix[ends])
    chunk_cover = np.maximum.reduceat(pressed, starts)
    sole_birth = np.maximum.reduceat(np.where(pressed > 0, birth, -1.0), starts)
    rim_birth = np.maximum.reduceat(np.where(surviving > 1e-7, birth, -1.0), starts)

    old = flat[texels].astype(np.float64)
    new = np.empty_like(old)
    new[:, 0] = np.maximum(old[:, 0], chunk_depth)
    new[:, 1] = np.maximum(_flush(old[:, 1] * chunk_keep), chunk_rim)
    owned_by_rim = (old[:, 3] <= 0) & (rim_birth >= 0)
    new[:, 2] = np.where(sole_birth >= 0, sole_birth, np.where(owned_by_rim, rim_birth, old[:, 2]))
    new[:, 3] = np.maximum(old[:, 3], chunk_cover)
    flat[texels] = new


def _flush(values):
    # What LOG_FLOOR leaves of a flattened rim (1e-30) is zero, not a denormal speck.
    return np.where(values < 1e-12, 0.0, values)


def frame_span(start, end):
    """Frames that B = 0..1 stands for: at least one, so a one-frame range still works."""
    return max(float(end) - float(start), 1.0)


def windward_refill_rate(normal, wind):
    """How many times faster the wind fills a print where the ground rises into it: the wind
    speeds up over a windward slope by about 1 + 2 g (g its gradient; Jackson and Hunt 1975 give
    a speed-up of about 2 H / L over a low hill) and the sand it carries grows as the cube of its
    speed (Bagnold), so (1 + 2 g)^3, g up to the angle of repose. 1 on flat ground, in the lee
    and in a calm. normal (..., 3): the ground's unit normal, world axes; wind: the scene's."""
    normal = np.asarray(normal, np.float64)
    direction = wind_direction(wind)
    windy = float(np.hypot(wind[0], wind[1]) >= 1e-9)
    into = -(normal @ direction) / np.maximum(normal[..., 2], 1e-3)
    rise = np.clip(into, 0.0, np.tan(REPOSE)) * windy
    return (1.0 + WINDWARD_SPEEDUP * rise) ** 3


def revealed_height(image, depth, rim, frame, frame_range, margin=1e-3, refill=0.0, normal=(0, 0, 1),
                    wind=(0, 0, 0)):
    """Twin of node group Sandscape Footprint Height at Noise Amount 0 (float32, like Cycles).

    A texel shows once B * span + start < frame + margin; with a refill time (frames) the wind
    has filled it to exp(-age rate / refill) of its depth and rim, rate the windward_refill_rate of
    the ground's normal (a vector or one per texel) in the wind.
    """
    f = np.float32
    start, end = frame_range
    rgb = image[..., :3].astype(f)
    birth = rgb[..., 2] * f(frame_span(start, end)) + f(start)
    born = (birth < f(frame) + f(margin)).astype(f)
    left = f(1)
    if refill > 0:
        rate = windward_refill_rate(normal, wind).astype(f)
        left = np.exp(-np.maximum(f(frame) - birth, f(0)) * rate / f(refill)).astype(f)
    return (rgb[..., 1] * f(rim) - rgb[..., 0] * f(depth)) * born * left


def revealed_pressed(image, depth, frame, frame_range, **kwargs):
    """Twin of the group's Pressed output: the revealed, not yet refilled share of R (0..1); none
    at depth 0."""
    return revealed_height(image, -1.0, 0.0, frame, frame_range, **kwargs) * np.float32(depth > 0)


def region_for_faces(corners_xy, corner_face, face_centres, low, high):
    """The X-Y box grown so that every face reaching into (low, high) has its centre inside:
    by the largest distance, per axis, from a face's centre to its corners. A coarse terrain's
    faces are wider than a narrow trail's region, and their centres fall outside it.
    corners_xy: (L, 2) each corner's point; corner_face: (L,) its face's index."""
    reach = np.abs(np.asarray(corners_xy)[:, :2] - np.asarray(face_centres)[np.asarray(corner_face), :2])
    grow = reach.max(axis=0) if len(reach) else np.zeros(2)
    return np.asarray(low, np.float64)[:2] - grow, np.asarray(high, np.float64)[:2] + grow


def eevee_levels(points, corner_vertex, corner_face, keep, edge, most=6):
    """Subdivision levels (each halves an edge) that bring the longest edge of the kept faces
    down to `edge`, at most `most`: EEVEE displaces only the vertices it is given."""
    corner_vertex, corner_face = np.asarray(corner_vertex), np.asarray(corner_face)
    following = np.roll(np.arange(len(corner_vertex)), -1)
    starts = np.flatnonzero(np.r_[True, corner_face[1:] != corner_face[:-1]])
    ends = np.r_[starts[1:], len(corner_vertex)] - 1
    following[ends] = starts  # a face's last corner closes on its first
    lengths = np.linalg.norm(np.asarray(points)[corner_vertex[following]] - np.asarray(points)[corner_vertex],
                             axis=1)
    kept = np.asarray(keep)[corner_face]
    longest = lengths[kept].max() if kept.any() else 0.0
    if not longest > edge > 0:
        return 0
    return int(min(most, np.ceil(np.log2(longest / edge))))


def faces_in_region(face_centres, low, high):
    """Twin of node group Sandscape Region Cut: faces whose centre lies in the X-Y box."""
    xy = np.asarray(face_centres)[:, :2]
    return np.all((xy >= np.asarray(low)[:2]) & (xy <= np.asarray(high)[:2]), axis=1)
