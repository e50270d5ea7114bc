"""Walker paths in plain numpy: arc length, footstep planning, print frames on a surface.

A path is the walker's world position sampled at frames. Steps fall every `stride` along
the arc, alternate left and right of it at half the stance width, and face along the
path's horizontal tangent. Heights are not decided here: the caller projects each
contact onto the terrain (ray casting) and then builds the print's frame from the normal.
"""

import numpy as np

UP = np.array((0.0, 0.0, 1.0))
LEFT, RIGHT = 1, -1
# Share of a stride by which a foot lands before the hip passes over its print: core.gait's
# pendulum has the foot down on the print from there (a print that waited for the hip would
# appear under a foot already standing in the sand).
LANDING_LEAD = 0.25
# A walking adult's foot points about 5-10 degrees out of the line of walk (its progression
# angle): the left print turned left, the right turned right, so the two read as a pair.
TOE_OUT = np.radians(7.0)


class PathError(ValueError):
    """The path cannot carry footsteps (it does not move, or has too few samples)."""


def arc_length(positions):
    """Cumulative 3D arc length at each sample, starting at 0."""
    positions = np.asarray(positions, dtype=np.float64)
    steps = np.linalg.norm(np.diff(positions, axis=0), axis=1)
    return np.concatenate(([0.0], np.cumsum(steps)))


def _unit(vectors, fallback=None):
    length = np.linalg.norm(vectors, axis=-1, keepdims=True)
    good = length[..., 0] > 1e-12
    out = np.where(good[..., None], vectors / np.where(length > 1e-12, length, 1.0), 0.0)
    if fallback is not None:
        out[~good] = fallback
    return out


def horizontal_tangents(positions):
    """Unit horizontal tangent at each sample (second-order differences).

    Samples where the walker moves only vertically borrow the nearest valid tangent.
    """
    positions = np.asarray(positions, dtype=np.float64)
    # Second-order differences at the ends too: a first-order end tangent is off by half a
    # frame's turn (0.4 deg on a 5 m circle at 24 fps).
    tangent = np.gradient(positions, axis=0, edge_order=2 if len(positions) > 2 else 1)
    tangent[:, 2] = 0.0
    tangent = _unit(tangent)
    valid = np.flatnonzero(np.linalg.norm(tangent, axis=1) > 0.5)
    if valid.size == 0:
        raise PathError("the path never moves horizontally")
    nearest = valid[np.clip(np.searchsorted(valid, np.arange(len(tangent))), 0, valid.size - 1)]
    return tangent[nearest] if valid.size < len(tangent) else tangent


def plan_steps(positions, frames, stride, stance, first_side=LEFT, toe_out=0.0):
    """Footstep contacts along a sampled walker path.

    positions: (F, 3) world positions at `frames` (F,), in order of time.
    Returns a dict of arrays, one row per step at arc lengths 0, stride, 2 stride, ...:
      contact (N, 3): path point moved sideways by side * stance / 2 (height of the path)
      forward (N, 3): unit horizontal tangent (the tangent linearly interpolated between
                      samples and renormalised, so a circle sampled per frame keeps < 0.01 deg)
      heading (N,):   atan2 of forward, radians about +Z
    toe_out: radians each foot points out of the line of walk (the left foot turned left, the
    right turned right; TOE_OUT for a walking adult), applied to forward and heading.
      side (N,):      +1 left, -1 right, alternating
      birth (N,):     frame at which the walker passes the step (interpolated along the arc)
      landing (N,):   frame at which its foot lands, LANDING_LEAD of a stride earlier (the
                      first step lands on the first frame)
    """
    positions = np.asarray(positions, dtype=np.float64)
    frames = np.asarray(frames, dtype=np.float64)
    if positions.ndim != 2 or positions.shape[1] != 3 or len(positions) != len(frames):
        raise PathError("positions must be (F, 3) and match the frames")
    if len(positions) < 2:
        raise PathError("the path needs at least two samples")
    if not stride > 0.0:
        raise PathError(f"stride must be greater than 0, got {stride:g}")
    arc = arc_length(positions)
    if not arc[-1] > 1e-9:
        raise PathError("the walker does not move in the frame range")
    # Keep strictly increasing arc samples (a walker that pauses repeats positions).
    keep = np.concatenate(([True], np.diff(arc) > 1e-12))
    arc, positions, frames = arc[keep], positions[keep], frames[keep]
    tangents = horizontal_tangents(positions)
    count = int(np.floor(arc[-1] / stride + 1e-6)) + 1  # a step a micro-stride short of the end counts
    s = np.minimum(np.arange(count) * stride, arc[-1])
    point = np.stack([np.interp(s, arc, positions[:, k]) for k in range(3)], axis=1)
    forward = np.stack([np.interp(s, arc, tangents[:, k]) for k in range(3)], axis=1)
    forward = _unit(forward, fallback=tangents[0])
    lateral = np.cross(UP, forward)
    side = np.where(np.arange(count) % 2 == 0, first_side, -first_side)
    turn = (side * toe_out)[:, None]
    toes = forward * np.cos(turn) + lateral * np.sin(turn)
    return {
        "contact": point + lateral * (side * stance * 0.5)[:, None],
        "forward": toes,
        "heading": np.arctan2(toes[:, 1], toes[:, 0]),
        "side": side.astype(np.int32),
        "birth": np.interp(s, arc, frames),
        "landing": np.interp(np.maximum(s - LANDING_LEAD * stride, 0.0), arc, frames),
    }


def surface_frames(forward, normals):
    """Print axes in the tangent plane of a surface.

    The forward axis is the horizontal heading lifted vertically into the tangent plane, so
    seen from above a print still points along the path on any slope; lateral = normal x forward.
    Returns (forward, lateral), both (N, 3) unit vectors.
    """
    forward = np.asarray(forward, dtype=np.float64)
    normals = _unit(np.asarray(normals, dtype=np.float64))
    nz = np.where(np.abs(normals[:, 2]) > 1e-9, normals[:, 2], 1e-9)
    lift = -(normals[:, 0] * forward[:, 0] + normals[:, 1] * forward[:, 1]) / nz
    tangent = _unit(np.stack([forward[:, 0], forward[:, 1], lift], axis=1))
    lateral = _unit(np.cross(normals, tangent))
    return tangent, lateral


def print_axes(forward, normals, side):
    """Forward and lateral axes of each print in the painting plane, (N, 2) each: surface_frames'
    axes with the lateral one pointing to the foot's inner side, where the sole has its arch (to
    the right of a left foot, side +1; to the left of a right or unknown one)."""
    forward, lateral = surface_frames(forward, normals)
    inner = np.where(np.asarray(side) > 0, -1.0, 1.0)[:, None]
    return forward[:, :2], inner * lateral[:, :2]
