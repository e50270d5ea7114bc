"""The stand-in walker's stride in plain numpy: legs swing as pendulums from the hips, phased to
the prints core.paths plans, so each foot passes under its hip exactly where its print lies.

Angles are forward swings in radians: positive puts the foot ahead of its pivot.
"""

import numpy as np

from .paths import LEFT

MAX_SWING = 0.6  # radians: a longer stride than a leg can reach swings no further
KNEE_BEND = np.radians(60.0)  # the most a swinging knee bends (people walk with about 60-65)


def leg_amplitude(leg_length, stride):
    """The swing at which the planted foot stands still as the hip passes over it.

    The foot sits L sin(theta) ahead of the hip; with theta = -A sin(pi s / stride) it moves back
    at L A pi / stride per unit of walk at mid-stance, which cancels the walk when
    A = stride / (pi L).
    """
    if not (leg_length > 0 and stride > 0):
        raise ValueError("leg length and stride must be > 0")
    return min(stride / (np.pi * leg_length), MAX_SWING)


def leg_swing(arc, stride, amplitude, side):
    """Forward swing of the leg on `side` (LEFT +1, RIGHT -1) at arc lengths `arc` along the walk.

    core.paths puts the left prints at arc 0, 2 stride, ... and the right ones at stride,
    3 stride, ...: each leg passes upright there, moving back (planted), and passes upright
    again a stride later, moving forward (swinging through).
    """
    return -side * LEFT * amplitude * np.sin(np.pi * np.asarray(arc, np.float64) / stride)


def knee_bend(arc, stride, side, most=KNEE_BEND):
    """How far the knee on `side` bends (radians, the shin back from the thigh's line): straight
    through the stance, bending up to `most` as the leg swings through (a smooth hump)."""
    swinging = np.maximum(0.0, -side * LEFT * np.cos(np.pi * np.asarray(arc, np.float64) / stride))
    return most * swinging**2


def foot_offset(arc, stride, amplitude, side, leg_length):
    """(ahead, below) of a foot from its hip, in the walker's plane, at arc lengths `arc`."""
    theta = leg_swing(arc, stride, amplitude, side)
    return leg_length * np.sin(theta), leg_length * np.cos(theta)
