"""From grown slabs to a smooth surface in metres: the dune field's height at any point.

The slab field is periodic, so the surface is too: the field mesh and its horizon ring sample
one function and meet without a seam. Slabs come in steps a third of a cell high; a Gaussian of
SMOOTH_CELLS fine cells takes the steps out (no stairs or terraces at render scale) and a
slope limit keeps every face at or below MAX_SLOPE_DEGREES, the angle of repose of dry sand
(30 to 34 degrees; the slab model's own avalanches allow atan(2/3) = 33.7 degrees along the
grid's axes, more along its diagonals). Points between lattice cells are read through a
periodic cubic B-spline, which is smooth across cells (no facets at the lattice's scale).
"""

import math

import numpy as np

from . import dune_field

SMOOTH_CELLS = 1.5
MAX_SLOPE_DEGREES = 32.5
# The 8 neighbours and the 8 knight's moves: a rise limited along these 16 directions is limited
# within a factor 1 / cos(13.3 degrees) along any other.
NEIGHBOURS = tuple((dy, dx) for dy in range(-2, 3) for dx in range(-2, 3)
                   if (dy, dx) != (0, 0) and max(abs(dy), abs(dx)) == 1 or abs(dy * dx) == 2)


def gaussian_periodic(z, sigma_cells):
    """z blurred by a Gaussian of sigma_cells, wrapping around (through the FFT)."""
    if sigma_cells <= 0:
        return np.array(z, np.float64)
    ky = np.fft.fftfreq(z.shape[0])[:, None]
    kx = np.fft.rfftfreq(z.shape[1])[None, :]
    kernel = np.exp(-2.0 * (math.pi * sigma_cells) ** 2 * (kx**2 + ky**2))
    return np.fft.irfft2(np.fft.rfft2(z) * kernel, s=z.shape)


def limit_slope(z, cell, degrees, max_rounds=10_000):
    """The highest surface at or below z whose rise to any of NEIGHBOURS is at most
    tan(degrees) x their distance (periodic). Only what stands too steep is lowered."""
    rise = math.tan(math.radians(degrees)) * cell
    z = np.array(z, np.float64)
    lowest = np.empty_like(z)
    for _ in range(max_rounds):
        lowest[...] = z
        for dy, dx in NEIGHBOURS:
            np.minimum(lowest, np.roll(z, (dy, dx), axis=(0, 1)) + rise * math.hypot(dy, dx), out=lowest)
        if np.array_equal(lowest, z):
            break
        z, lowest = lowest, z
    return z


def bspline_weights(t):
    """Uniform cubic B-spline weights of the four lattice points around fraction t."""
    t2, t3 = t * t, t * t * t
    return ((1 - t) ** 3 / 6.0, (3 * t3 - 6 * t2 + 4) / 6.0, (-3 * t3 + 3 * t2 + 3 * t + 1) / 6.0, t3 / 6.0)


def sample_periodic(z, u, v):
    """z at fractional lattice coordinates (u along x, v along y), periodic cubic B-spline."""
    ny, nx = z.shape
    u, v = np.asarray(u, np.float64), np.asarray(v, np.float64)
    iu, iv = np.floor(u).astype(np.int64), np.floor(v).astype(np.int64)
    wu, wv = bspline_weights(u - iu), bspline_weights(v - iv)
    columns = [(iu + i - 1) % nx for i in range(4)]
    out = np.zeros(np.broadcast(u, v).shape)
    for j in range(4):
        row = (iv + j - 1) % ny
        out += wv[j] * sum(wu[i] * z[row, columns[i]] for i in range(4))
    return out


class DuneSurface:
    """Heights in metres of a periodic dune field whose main wind blows along `wind_angle`
    (radians from +X, in the plane of the surface's own X and Y).

    heights: the fine lattice in metres, laid along the wind: lattice x is downwind.
    cell: the fine lattice's cell in metres.
    """

    def __init__(self, heights, cell, wind_angle):
        self.levels = [np.asarray(heights, np.float64)]
        self.cell = float(cell)
        self.wind_angle = float(wind_angle)
        self._cos, self._sin = math.cos(wind_angle), math.sin(wind_angle)

    @property
    def period(self):
        """The lattice's extent in metres across and along the wind (it repeats after it)."""
        ny, nx = self.levels[0].shape
        return nx * self.cell, ny * self.cell

    def lattice_coordinates(self, x, y):
        along = (np.asarray(x, np.float64) * self._cos + np.asarray(y, np.float64) * self._sin) / self.cell
        across = (np.asarray(y, np.float64) * self._cos - np.asarray(x, np.float64) * self._sin) / self.cell
        return along, across

    def heights(self, x, y, blur=0.0):
        """Height in metres at (x, y) metres. blur: a Gaussian of about that many metres first
        (a coarse mesh far away reads a blurred field, which it can hold without aliasing),
        blended between the two nearest of the levels, which double from one fine cell up."""
        u, v = self.lattice_coordinates(x, y)
        blur = np.broadcast_to(np.asarray(blur, np.float64), np.shape(u))
        octave = np.log2(np.maximum(blur / self.cell, 1.0))
        below = np.floor(octave).astype(np.int64)
        out = np.zeros(np.shape(u))
        for index in np.unique(below):
            here = below == index
            blend = (octave[here] - index)[None]
            low = sample_periodic(self.level(index), u[here], v[here])
            high = sample_periodic(self.level(index + 1), u[here], v[here]) if np.any(blend > 0) else low
            out[here] = ((1 - blend) * low + blend * high)[0]
        return out

    def level(self, index):
        """The lattice blurred by a Gaussian of 2**index fine cells (index 0: not blurred)."""
        while len(self.levels) <= index:
            self.levels.append(gaussian_periodic(self.levels[0], 2.0 ** len(self.levels)))
        return self.levels[index]

    def mean_height(self):
        return float(self.levels[0].mean())


def surface_from_slabs(slabs, cell, wind_angle, smooth_cells=SMOOTH_CELLS, max_slope=MAX_SLOPE_DEGREES):
    """A DuneSurface from a grown slab field: slabs (fine lattice, along the wind) of `cell`
    metres a side, each a third of a cell high, smoothed and slope-limited."""
    z = np.asarray(slabs, np.float64) * (cell / dune_field.SLAB_ASPECT)
    z = limit_slope(gaussian_periodic(z, smooth_cells), cell, max_slope)
    return DuneSurface(z, cell, wind_angle)


def grid(width, depth, cell):
    """A grid of vertices over width x depth centred on the origin, about `cell` apart.

    Returns (x, y) of shape (ny + 1, nx + 1) and quads (M, 4) into their ravelled order,
    counter-clockwise seen from above.
    """
    nx = max(int(round(width / cell)), 1)
    ny = max(int(round(depth / cell)), 1)
    x, y = np.meshgrid(np.linspace(-width / 2, width / 2, nx + 1), np.linspace(-depth / 2, depth / 2, ny + 1))
    index = np.arange((nx + 1) * (ny + 1)).reshape(ny + 1, nx + 1)
    quads = np.stack([index[:-1, :-1], index[:-1, 1:], index[1:, 1:], index[1:, :-1]], -1).reshape(-1, 4)
    return x, y, quads


def face_slopes(vertices, triangles):
    """Slope in degrees of each triangle (vertices (N, 3), triangles (M, 3))."""
    a, b, c = (vertices[triangles[:, i]] for i in range(3))
    normal = np.cross(b - a, c - a)
    length = np.linalg.norm(normal, axis=1)
    return np.degrees(np.arccos(np.clip(np.abs(normal[:, 2]) / np.maximum(length, 1e-300), 0.0, 1.0)))


def limit_triangle_slopes(vertices, triangles, degrees, fixed=None, max_rounds=500):
    """Lower the highest corner of every triangle steeper than `degrees` until none is (in place
    on vertices[:, 2]); vertices marked in `fixed` stay. Returns the rounds taken.

    A limit on the heights along grid edges does not bound a triangle: two legs at the limit
    in opposite senses tilt it by atan(sqrt(2) tan(limit)). So the triangles are limited.
    Triangles with no area seen from above are left alone.
    """
    limit = math.tan(math.radians(degrees))
    triangles = np.asarray(triangles)
    z = vertices[:, 2]
    keep = np.zeros(len(vertices), bool) if fixed is None else np.asarray(fixed, bool)
    # Which triangles touch each vertex (CSR), to look again only where something moved.
    corner_order = np.argsort(triangles.ravel(), kind="stable")
    starts = np.searchsorted(triangles.ravel()[corner_order], np.arange(len(vertices) + 1))
    look = np.arange(len(triangles))
    for rounds in range(max_rounds):
        tri = triangles[look]
        corners = vertices[tri]
        edge1, edge2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        normal = np.cross(edge1, edge2)
        steep = np.hypot(normal[:, 0], normal[:, 1]) > limit * np.abs(normal[:, 2]) * (1 + 1e-7)
        # Seen from above a sliver has no area (it stands on edge): it has no slope to limit.
        reach = np.maximum((edge1[:, :2] ** 2).sum(1), (edge2[:, :2] ** 2).sum(1))
        steep &= np.abs(normal[:, 2]) > 1e-9 * reach
        if not steep.any():
            return rounds
        tri = tri[steep]
        rows = np.arange(len(tri))
        high = np.argmax(z[tri], axis=1)
        top, first, second = tri[rows, high], tri[rows, (high + 1) % 3], tri[rows, (high + 2) % 3]
        p, a, b = vertices[top], vertices[first], vertices[second]
        # The plane's gradient is linear in the top's height h (g0 + h g1, from the two edges
        # leaving the top), so |gradient| = limit is a quadratic in h: within the limit between
        # its roots, and the top stands above the higher one.
        e1, e2 = a[:, :2] - p[:, :2], b[:, :2] - p[:, :2]
        det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
        det = np.where(np.abs(det) > 1e-300, det, 1e-300)
        g0 = np.stack([e2[:, 1] * a[:, 2] - e1[:, 1] * b[:, 2], e1[:, 0] * b[:, 2] - e2[:, 0] * a[:, 2]], -1)
        g1 = -np.stack([e2[:, 1] - e1[:, 1], e1[:, 0] - e2[:, 0]], -1)
        g0 /= det[:, None]
        g1 /= det[:, None]
        qa, qb, qc = (g1 * g1).sum(1), 2 * (g0 * g1).sum(1), (g0 * g0).sum(1) - limit**2
        discriminant = qb * qb - 4 * qa * qc
        root = (-qb + np.sqrt(np.maximum(discriminant, 0.0))) / (2 * np.maximum(qa, 1e-300))
        # Stuck: no top height above the other two helps, the lowest corner lies too far below
        # them. The top and the higher other come down together, to where the plane through
        # them, level, rises from the lowest corner at the limit.
        a_higher = a[:, 2] >= b[:, 2]
        upper, lower = np.where(a_higher[:, None], a, b), np.where(a_higher[:, None], b, a)
        stuck = (discriminant < 0) | (root <= upper[:, 2])
        span = upper[:, :2] - p[:, :2]
        across = np.abs(span[:, 0] * (lower[:, 1] - p[:, 1]) - span[:, 1] * (lower[:, 0] - p[:, 0]))
        across /= np.maximum(np.hypot(span[:, 0], span[:, 1]), 1e-300)
        lowered = np.minimum(np.where(stuck, lower[:, 2] + limit * across, root), p[:, 2])
        targets = np.concatenate([top, np.where(a_higher, first, second)[stuck]])
        heights = np.concatenate([lowered, lowered[stuck]])
        free = ~keep[targets]
        targets, heights = targets[free], heights[free]
        before = z[targets].copy()
        np.minimum.at(z, targets, heights)
        moved = targets[z[targets] < before]
        if not len(moved):
            return rounds
        look = np.unique(_touching(corner_order, starts, np.unique(moved)) // 3)
    return max_rounds


def _touching(corner_order, starts, vertices):
    """Corner indices (into triangles.ravel()) of every corner at one of these vertices."""
    counts = starts[vertices + 1] - starts[vertices]
    offsets = np.repeat(starts[vertices] - np.concatenate([[0], np.cumsum(counts)[:-1]]), counts)
    return corner_order[np.arange(counts.sum()) + offsets]


def quad_triangles(quads):
    """Both ways of cutting each quad into two triangles (a renderer may take either)."""
    return np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]], quads[:, [0, 1, 3]],
                           quads[:, [1, 2, 3]]])
