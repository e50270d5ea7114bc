"""Dunes grown by the wind: Werner's (1995) slab model in numpy, vectorised.

Why this model: it is the simplest published morphodynamic model that grows every dune class
from a handful of rules (Werner 1995, Geology 23:1107; Nield and Baas 2008; Eastwood et al.
2011): barchans where sand is scarce, transverse ridges where it is plentiful, linear dunes
under two winds. Continuum models (Kroy, Sauermann and Herrmann 2002) resolve the wind over
each dune and cost far more per cell; the slab model's rules are local and run in whole-grid
numpy operations.

The rules, on a periodic grid of square cells holding stacks of slabs (a slab is a third of a
cell high, so a difference of REPOSE_SLABS between neighbours is atan(2/3) = 33.7 degrees):
- Pick cells at random. A picked cell with sand that is not in the wind shadow (below a line
  falling SHADOW_DEGREES downwind from any upwind stack) loses its top slab.
- The slab hops downwind and lands with probability P_SAND on sand, P_BARE on bare ground and
  always in shadow; otherwise it hops again. A hop grows with the height it starts from
  (SPEEDUP: Momiji et al. 2000, the wind's speed-up over a dune's back), which keeps windward
  slopes gentle.
- Where a stack stands more than REPOSE_SLABS above a neighbour (one slab more across a
  diagonal), slabs avalanche down.

Vectorised, not slab by slab: each sweep picks a share BATCH of the cells at once, moves all
their slabs in parallel hops and avalanches until the grid rests. Slabs are only ever
moved, never made or lost (tested), and one seed gives one field.

Coarse to fine: a coarse grid grows the dunes (their spacing comes from the run), then each
refinement halves the cell, doubles the slab count of every stack (the same sand, in slabs an
eighth the volume) and runs a few more sweeps, which sharpen brinks and slip faces at the finer
cell instead of leaving the coarse grid's stairs to be smoothed into mush.
"""

import math

import numpy as np

SHADOW_DEGREES = 15.0
SLAB_ASPECT = 3.0  # cell width over slab height
REPOSE_SLABS = 2
P_SAND, P_BARE = 0.6, 0.4
HOP = 1.0  # cells, on level ground
SPEEDUP = 1.0  # hop = HOP (1 + SPEEDUP x height in cells)
BATCH = 0.25  # share of the cells picked per sweep
TURN_STEPS = 1  # time units one wind blows before the next takes over
MAX_HOPS = 64  # a slab still in flight after this many hops lands where it is
PATCH_CELLS = 4.0  # correlation length of the sand's first patches, in coarse cells
PATCH_DEPTH = 8.0  # slabs per unit of the patch noise above its threshold
COARSE_STEPS = 250  # time units (each picks every cell once on average)
REFINE_STEPS = (20, 10, 6, 4)  # time units after each refinement


def repose_degrees():
    return math.degrees(math.atan(REPOSE_SLABS / SLAB_ASPECT))


def _roll_into(out, a, shift, axis):
    """out = np.roll(a, shift, axis), written into `out` without a temporary."""
    n = a.shape[axis]
    shift %= n
    if shift == 0:
        out[...] = a
    elif axis == 1:
        out[:, shift:] = a[:, :n - shift]
        out[:, :shift] = a[:, n - shift:]
    else:
        out[shift:] = a[:n - shift]
        out[:shift] = a[n - shift:]
    return out


def _shift_into(out, a, dy, dx, scratch):
    """out[y, x] = a[y - dy, x - dx] with wrap-around (scratch: an array like `a`)."""
    if dy and dx:
        return _roll_into(out, _roll_into(scratch, a, dy, 0), dx, 1)
    if dy:
        return _roll_into(out, a, dy, 0)
    return _roll_into(out, a, dx, 1)


def _shifted(a, dy, dx, out, scratch):
    """out[p] = a[p - (dy, dx)] with wrap-around, for fractional shifts read bilinearly."""
    iy, ix = math.floor(dy), math.floor(dx)
    fy, fx = dy - iy, dx - ix
    if fy == 0 and fx == 0:
        return _shift_into(out, a, iy, ix, scratch)
    out[...] = 0
    for oy, wy in ((iy, 1 - fy), (iy + 1, fy)):
        for ox, wx in ((ix, 1 - fx), (ix + 1, fx)):
            if wy * wx > 0:
                out += wy * wx * _shift_into(np.empty_like(a), a, oy, ox, scratch)
    return out


def shadow_mask(h, direction, shadow_slabs_per_cell):
    """Cells whose top lies below the shadow line cast from upwind stacks, for a wind along the
    unit vector `direction` (dx, dy) in cells: max_k h(p - k u) - k t by doubling (a max-plus
    scan: after the step of span d, every upwind distance below 2 d has been taken). Off the
    grid's axes the upwind points fall between cells and are read bilinearly."""
    top = h.astype(np.float32)
    shade, moved, scratch = np.empty_like(top), np.empty_like(top), np.empty_like(top)
    dx, dy = float(direction[0]), float(direction[1])
    if abs(dx) < 1e-9:
        dx = 0.0
    if abs(dy) < 1e-9:
        dy = 0.0
    _shifted(top, dy, dx, shade, scratch)
    shade -= shadow_slabs_per_cell
    span, longest = 1, max(h.shape)
    while span < longest:
        _shifted(shade, dy * span, dx * span, moved, scratch)
        moved -= shadow_slabs_per_cell * span
        np.maximum(shade, moved, out=shade)
        span *= 2
    return shade > top


# The edges avalanches run along, and the steepest step each may keep: the grid's axes hold
# REPOSE_SLABS over a cell, its diagonals one slab more over sqrt(2) cells (35.3 against 33.7
# degrees), so slip faces stand near repose whichever way they face.
AVALANCHE_EDGES = (((0, 1), REPOSE_SLABS), ((1, 0), REPOSE_SLABS), ((1, 1), REPOSE_SLABS + 1),
                   ((1, -1), REPOSE_SLABS + 1))


SPARSE_SHARE = 0.05  # below this share of cells still moving, avalanches look only near them


def avalanche(h, edges=AVALANCHE_EDGES, sparse_below=SPARSE_SHARE):
    """Move slabs down every step steeper than its edge allows until none is left (in place).

    Each pass takes the edges of one kind: the higher side of every step gives half the excess
    (rounded down, so a stack never goes below zero) to the lower side, all edges at once;
    passes repeat until a round moves nothing. Returns the rounds taken.

    A slide down a long slip face takes a round per cell, yet touches few cells: once under
    SPARSE_SHARE of the cells moved in a round, a pass looks only at the edges of the cells
    that moved since that kind of edge was last looked at (an edge neither of whose cells moved
    cannot have turned steep), which moves exactly the slabs the full pass would.
    """
    ny, nx = h.shape
    flat = h.reshape(-1)
    neighbour, step, over, flow, scratch = (np.empty_like(h) for _ in range(5))
    dirty = [None] * len(edges)  # per kind: cells moved since its last pass (None: all of them)
    rounds = 0
    while True:
        moved_any = False
        for kind, ((dy, dx), threshold) in enumerate(edges):
            if dirty[kind] is None:
                _shift_into(neighbour, h, dy, dx, scratch)
                np.subtract(h, neighbour, out=step)  # this cell minus its neighbour at -(dy, dx)
                np.abs(step, out=over)
                if over.max() <= threshold:
                    dirty[kind] = np.zeros(0, np.int64)
                    continue
                over -= threshold - 1
                np.maximum(over, 0, out=over)
                over //= 2
                np.sign(step, out=flow)
                flow *= over  # > 0: this cell gives to that neighbour; < 0: it takes
                h -= flow
                h += _shift_into(neighbour, flow, -dy, -dx, scratch)
                given = np.flatnonzero(flow)
                moved = np.concatenate([given, _neighbours(given, -dy, -dx, ny, nx)])
            else:
                moved = _sparse_pass(flat, dirty[kind], dy, dx, threshold, ny, nx)
            dirty[kind] = np.zeros(0, np.int64)
            if len(moved):
                moved_any = True
                dense = len(moved) > sparse_below * flat.size
                for other in range(len(edges)):
                    if dense or dirty[other] is None:
                        dirty[other] = None
                    else:
                        dirty[other] = np.concatenate([dirty[other], moved])
        rounds += 1
        if not moved_any:
            return rounds


def _neighbours(cells, dy, dx, ny, nx):
    """Flat indices of the cells (dy, dx) away from flat indices `cells`, wrapping."""
    return ((cells // nx + dy) % ny) * nx + (cells % nx + dx) % nx


def _distinct(cells):
    """The distinct values of an index array, sorted (a sort: cheaper than hashing here)."""
    cells = np.sort(cells)
    return cells[np.concatenate([[True], cells[1:] != cells[:-1]])] if len(cells) else cells


def _sparse_pass(flat, dirty, dy, dx, threshold, ny, nx):
    """One pass over the edges of one kind touching `dirty` cells; returns the cells that moved."""
    if not len(dirty):
        return dirty
    # The edge of kind (dy, dx) belongs to the cell p whose neighbour is p - (dy, dx).
    owners = _distinct(np.concatenate([dirty, _neighbours(dirty, dy, dx, ny, nx)]))
    lower = _neighbours(owners, -dy, -dx, ny, nx)
    step = flat[owners] - flat[lower]
    over = (np.abs(step) - (threshold - 1)) // 2
    steep = over > 0
    if not steep.any():
        return np.zeros(0, np.int64)
    owners, lower = owners[steep], lower[steep]
    flow = (np.sign(step[steep]) * over[steep]).astype(flat.dtype)
    flat[owners] -= flow  # owners are unique, and so are their lower neighbours
    flat[lower] += flow
    return np.concatenate([owners, lower])


class SlabField:
    """A periodic grid of slab stacks and the random stream that moves them."""

    def __init__(self, slabs, seed):
        self.slabs = np.ascontiguousarray(slabs, dtype=np.int32)
        self.rng = np.random.default_rng(seed)
        self.hop = HOP
        self.shadow_per_cell = math.tan(math.radians(SHADOW_DEGREES)) * SLAB_ASPECT

    def total(self):
        return int(self.slabs.sum(dtype=np.int64))

    def sweep(self, direction):
        """Pick BATCH of the cells, blow their top slabs downwind, avalanche."""
        h, rng = self.slabs, self.rng
        ny, nx = h.shape
        shade = shadow_mask(h, direction, self.shadow_per_cell)
        picked = (rng.random(h.shape, dtype=np.float32) < BATCH) & (h > 0) & ~shade
        ys, xs = np.nonzero(picked)
        h[ys, xs] -= 1
        # A slab flies along the wind's line from a random point of its cell (so the mean hop is
        # `length` whatever the direction) and lands in the cell under it: no sideways random walk.
        x = xs + rng.random(len(xs))
        y = ys + rng.random(len(ys))
        flying = np.arange(len(xs))
        for _ in range(MAX_HOPS):
            if not len(flying):
                break
            start = h[np.floor(y[flying]).astype(np.int64) % ny, np.floor(x[flying]).astype(np.int64) % nx]
            length = self.hop * (1.0 + SPEEDUP * start / SLAB_ASPECT)
            x[flying] += direction[0] * length
            y[flying] += direction[1] * length
            cy, cx = np.floor(y[flying]).astype(np.int64) % ny, np.floor(x[flying]).astype(np.int64) % nx
            stick = np.where(shade[cy, cx], 1.0, np.where(h[cy, cx] > 0, P_SAND, P_BARE))
            flying = flying[rng.random(len(flying)) >= stick]
        landed = (np.floor(y).astype(np.int64) % ny) * nx + np.floor(x).astype(np.int64) % nx
        h += np.bincount(landed, minlength=ny * nx).reshape(ny, nx).astype(np.int32)
        avalanche(h)

    def run(self, steps, winds, progress=None):
        """`steps` time units under `winds`: ((unit direction (dx, dy), share), ...), taken in
        turns of TURN_STEPS time units, in proportion to their shares."""
        sweeps = int(round(steps / BATCH))
        schedule = wind_schedule(winds, sweeps)
        for index, direction in enumerate(schedule):
            self.sweep(direction)
            if progress is not None and index % 16 == 0:
                progress(index / max(sweeps, 1))

    def refine(self):
        """Halve the cell: every stack becomes 2 x 2 stacks of twice the slabs (the same sand in
        slabs an eighth the volume); hops stay HOP cells, now half as long."""
        self.slabs = np.kron(self.slabs, np.ones((2, 2), np.int32)) * 2
        avalanche(self.slabs)


def wind_schedule(winds, sweeps):
    """Which wind blows in each sweep: turns of TURN_STEPS time units (TURN_STEPS / BATCH
    sweeps), each wind's turns spread evenly in proportion to its share."""
    directions = [np.asarray(d, np.float64) / np.linalg.norm(d) for d, _ in winds]
    shares = np.array([max(float(s), 0.0) for _, s in winds])
    shares = shares / shares.sum() if shares.sum() > 0 else np.full(len(winds), 1.0 / len(winds))
    turn = max(int(round(TURN_STEPS / BATCH)), 1)
    turns = -(-sweeps // turn)
    # Largest remainder: after t turns, wind i has had about t x share_i of them.
    counts = np.zeros(len(winds))
    order = []
    for _ in range(turns):
        pick = int(np.argmax(shares * (len(order) + 1) - counts))
        counts[pick] += 1
        order.extend([pick] * turn)
    return [directions[i] for i in order[:sweeps]]


def initial_slabs(shape, mean_slabs, rng):
    """Sand in patches (a smooth noise above a threshold, PATCH_CELLS across) holding
    `mean_slabs` per cell on average: from patches, scarce sand gathers into barchans."""
    ny, nx = shape
    noise = np.fft.fft2(rng.standard_normal(shape))
    ky, kx = np.fft.fftfreq(ny)[:, None], np.fft.fftfreq(nx)[None, :]
    noise = np.real(np.fft.ifft2(noise * np.exp(-2.0 * (math.pi * PATCH_CELLS) ** 2 * (kx**2 + ky**2))))
    noise = (noise - noise.mean()) / max(noise.std(), 1e-12)
    low, high = -8.0, 8.0  # threshold so that the patches hold the mean
    for _ in range(60):
        middle = 0.5 * (low + high)
        if np.maximum(noise - middle, 0.0).mean() * PATCH_DEPTH > mean_slabs:
            low = middle
        else:
            high = middle
    return rng.poisson(np.maximum(noise - high, 0.0) * PATCH_DEPTH).astype(np.int32)


def grow(coarse_shape, mean_slabs, seed, winds=(((1.0, 0.0), 1.0),), refinements=1,
         steps=COARSE_STEPS, progress=None):
    """A dune field: coarse run, then `refinements` halvings of the cell.

    Returns the SlabField. The main wind of `winds` should be +x (the grid is laid along it); a
    second wind blows any way.
    """
    rng = np.random.default_rng(seed)
    field = SlabField(initial_slabs(coarse_shape, mean_slabs, rng), rng.integers(2**63))
    stages = [steps] + [REFINE_STEPS[min(i, len(REFINE_STEPS) - 1)] for i in range(refinements)]
    work = np.array([s * 4**i for i, s in enumerate(stages)], np.float64)  # cells x steps
    done = np.concatenate([[0.0], np.cumsum(work)]) / work.sum()

    def stage_progress(index):
        if progress is None:
            return None
        return lambda share: progress(done[index] + share * (done[index + 1] - done[index]))

    field.run(steps, winds, stage_progress(0))
    for level in range(refinements):
        field.refine()
        field.run(stages[level + 1], winds, stage_progress(level + 1))
    return field
