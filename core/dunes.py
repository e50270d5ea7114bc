"""A dune field from an artist's settings, in metres: lattice sizes, the slab run, the surface,
the field's mesh. The model is core/dune_field.py, the surface core/dune_surface.py and the
horizon ring core/dune_horizon.py.

Scale: the slab model has no metres of its own. Under one wind and the default supply its
dunes stand SPACING_CELLS coarse cells apart after COARSE_STEPS (measured,
tests/test_dune_model.py), so the coarse cell is the spacing asked for over SPACING_CELLS; a
slab is a third of that cell. Other supplies and winds keep that cell: scarcer sand gives
smaller, isolated dunes on the same scale, as in nature.

Sand supply is the depth the sand would have if spread evenly (Wasson and Hyde's equivalent
sand thickness), given in percent of the dune spacing so that a dune class keeps its sand
when the spacing changes.
"""

import math

import numpy as np

from . import dune_field, dune_surface

SPACING_CELLS = 48.0
COARSE_LIMIT = 512  # coarse cells along a side: a larger field repeats the lattice (it is periodic)
FINE_LIMIT = 1024  # fine cells along a side
FINE_CELLS_PER_SPACING = 90  # refine until this many (brinks and slip faces are sharp by then)
MESH_CELLS_PER_FINE = 0.6  # or until the fine cell is this share of the mesh's
SPACING_SMOOTH_CELLS = 2.0  # the spacing is measured on the field blurred this much (sand sheet out)
KEPT = 2  # fields grown last, kept for a redo
BYTES_PER_VERTEX = 600  # Blender's mesh with UVs and our arrays while building it (measured: ~450)


_kept = {}  # settings -> (surface, facts), oldest first


def supply_slabs(supply_percent):
    """Mean slabs per coarse cell for a sand supply in percent of the spacing."""
    return supply_percent / 100.0 * SPACING_CELLS * dune_field.SLAB_ASPECT


def plan(width, depth, cell, spacing):
    """The lattice for a field: (coarse cells a side, coarse cell in metres, refinements)."""
    coarse_cell = spacing / SPACING_CELLS
    wanted = math.ceil(max(width, depth) / coarse_cell / 8.0) * 8
    coarse = int(min(max(wanted, 64), COARSE_LIMIT))
    # Fine enough for sharp brinks, and no finer than the mesh can show (it reads the lattice
    # through a smooth spline at any cell size).
    target = max(spacing / FINE_CELLS_PER_SPACING, MESH_CELLS_PER_FINE * cell)
    refinements = 0
    while coarse_cell / 2**refinements > target and coarse * 2 ** (refinements + 1) <= FINE_LIMIT:
        refinements += 1
    return coarse, coarse_cell, refinements


def winds(second_angle=None, second_share=0.0):
    """The slab model's winds and its frame: (((unit direction, share), ...), frame angle).

    The model's grid is laid along the net transport (the shares' resultant), at `frame angle`
    radians from the main wind: one wind blows along the grid's x, two take equal angles either
    side of it (the grid's two axes drive dunes harder than its diagonals, so neither wind is
    favoured). The second wind is turned by second_angle (counter-clockwise) from the main one.
    """
    if second_angle is None or second_share <= 0.0:
        return (((1.0, 0.0), 1.0),), 0.0
    share = min(max(second_share, 0.0), 1.0)
    net = np.array([1.0 - share + share * math.cos(second_angle), share * math.sin(second_angle)])
    frame = math.atan2(net[1], net[0]) if np.hypot(*net) > 1e-9 else second_angle / 2.0
    return (((math.cos(-frame), math.sin(-frame)), 1.0 - share),
            ((math.cos(second_angle - frame), math.sin(second_angle - frame)), share)), frame


def grow_surface(width, depth, cell, spacing, supply_percent, seed, wind_angle, second_angle=None,
                 second_share=0.0, progress=None):
    """Grow the field and make its surface. Returns (DuneSurface, facts) where facts holds what
    was run: lattice sizes, slabs (constant through the run), measured spacing in metres.

    The last KEPT fields grown are kept: the same settings again (a redo, or only the horizon or
    the material changed) cost nothing. One seed gives one field, so a kept one is the same."""
    key = (width, depth, cell, spacing, supply_percent, seed, wind_angle, second_angle, second_share)
    if key not in _kept:
        _kept[key] = _grow_surface(*key, progress)
        while len(_kept) > KEPT:
            _kept.pop(next(iter(_kept)))
    surface, facts = _kept[key]
    return surface, dict(facts)


def _grow_surface(width, depth, cell, spacing, supply_percent, seed, wind_angle, second_angle, second_share,
                  progress):
    coarse, coarse_cell, refinements = plan(width, depth, cell, spacing)
    blowing, frame = winds(second_angle, second_share)
    field = dune_field.grow((coarse, coarse), supply_slabs(supply_percent), seed, blowing, refinements,
                            progress=progress)
    fine_cell = coarse_cell / 2**refinements
    surface = dune_surface.surface_from_slabs(field.slabs, fine_cell, wind_angle + frame)
    spacing_found = spacing_cells(field.slabs, SPACING_SMOOTH_CELLS * 2**refinements) * fine_cell
    facts = {"coarse": coarse, "refinements": refinements, "fine": field.slabs.shape[0],
             "fine_cell": fine_cell,
             "slabs": field.total(), "period": coarse * coarse_cell, "spacing": spacing_found,
             "height": float(np.percentile(surface.levels[0], 99.0)), "frame": frame}
    return surface, facts


def spacing_cells(slabs, smooth=SPACING_SMOOTH_CELLS):
    """Dune spacing in cells, crest to crest across the crests whichever way they run (linear
    dunes lie along the net wind, transverse ones across it). The field, blurred by `smooth`
    cells (the sand sheet's slab noise does not count), has its slopes' main direction (the
    gradient structure tensor's first eigenvector); its 2D spectrum is summed along the crests
    into a spectrum across them, whose peak gives the spacing as the power-weighted mean
    wavenumber within an octave either side."""
    z = dune_surface.gaussian_periodic(np.asarray(slabs, np.float64), smooth)
    gy, gx = np.gradient(z)
    tensor = np.array([[np.sum(gx * gx), np.sum(gx * gy)], [np.sum(gx * gy), np.sum(gy * gy)]])
    across = np.linalg.eigh(tensor)[1][:, -1]
    power = np.abs(np.fft.fft2(z - z.mean())) ** 2
    ky = np.fft.fftfreq(z.shape[0])[:, None]
    kx = np.fft.fftfreq(z.shape[1])[None, :]
    along = np.abs(kx * across[0] + ky * across[1])  # cycles per cell across the crests
    step = 1.0 / max(z.shape)
    bins = np.rint(along / step).astype(int)
    spectrum = np.bincount(bins.ravel(), power.ravel())
    spectrum[0] = 0.0
    peak = int(np.argmax(spectrum))
    if peak == 0:
        return float(max(z.shape))
    k = np.arange(len(spectrum))
    band = (k >= peak / 2.0) & (k <= peak * 2.0)
    return float(1.0 / (step * np.sum(k[band] * spectrum[band]) / spectrum[band].sum()))


def field_mesh(surface, width, depth, cell):
    """The field's vertices (N, 3) in metres, quads (M, 4) and per-corner UVs (M * 4, 2)."""
    x, y, quads = dune_surface.grid(width, depth, cell)
    z = surface.heights(x, y)
    vertices = np.stack([x, y, z], -1).reshape(-1, 3)
    uv = vertices[quads.ravel(), :2] / np.array([width, depth]) + 0.5
    return vertices, quads, uv


def vertex_count(width, depth, cell):
    return (max(int(round(width / cell)), 1) + 1) * (max(int(round(depth / cell)), 1) + 1)


def estimated_bytes(width, depth, cell, ring_vertices=0):
    """Memory the field (and ring) will take while being built, about."""
    return (vertex_count(width, depth, cell) + ring_vertices) * BYTES_PER_VERTEX
