"""Where feet land: a foot's contacts with the ground from its sole over the frames.

A foot is planted when the lowest point of its sole is within a small height of the ground
under it and moves slowly, both measured in foot lengths (a child's foot and a giant's alike),
and stays planted until it rises or moves clearly more (hysteresis), so a contact is never split
by a frame of jitter. Each contact gives one print: where the sole stood (the mean over the
planted frames), its heading (heel to toe), its first frame (the heel strike), how long it
lasted and how hard it struck (the sole's downward speed as it landed).

A run leaves another print than a walk: the foot is down a quarter of a second instead of over
half a second, lands moving and slides a little, and pushes off from the forefoot, so the print
is longer and deepest at the toe. gait_shape turns a contact's length of time into that shape.
"""

from dataclasses import dataclass

import numpy as np

from .shaping import smoothstep

PLANT_HEIGHT = 0.1  # foot lengths above the ground: lower than this, the foot may be planted
LIFT_HEIGHT = 0.2  # higher than this, it has lifted
PLANT_SPEED = 1.0  # foot lengths per second: slower than this, it may be planted
LIFT_SPEED = 2.0  # faster than this, it has left
STRIKE_FRAMES = 3  # the frames before a contact whose downward speed is its strike
RUN_CONTACT = 0.25  # seconds a running foot stays down (ground contact of a run: 0.2-0.3 s)
WALK_CONTACT = 0.5  # seconds: this long or longer is a walk (a walking foot: 0.6-0.7 s)
RUN_STRETCH = 0.25  # a run's print is this much longer: the landing slide and the toe's push
RUN_TOE_BIAS = 0.4  # a run's print: depth x (1 + bias) at the toe, x (1 - bias) at the heel


class ContactError(ValueError):
    """Feet that cannot give contacts; the message is for the artist."""


@dataclass
class Contact:
    first: int  # index of the heel-strike frame
    last: int
    position: np.ndarray  # world (x, y, z): the sole's mean place while planted, z the ground's
    heading: float  # radians about world Z, heel to toe
    strike: float  # downward speed of the sole as it landed, per second (world units)
    seconds: float  # how long the sole stood: its frames within the planting thresholds, in seconds


def gait_shape(seconds):
    """(length scale, toe bias) of the prints of contacts lasting `seconds`: a walk's (1, 0) from
    WALK_CONTACT up, a run's (1 + RUN_STRETCH, RUN_TOE_BIAS) from RUN_CONTACT down, smooth between."""
    running = 1.0 - smoothstep(RUN_CONTACT, WALK_CONTACT, seconds)
    return 1.0 + RUN_STRETCH * running, RUN_TOE_BIAS * running


def planted_runs(height, speed, foot_length):
    """[(first, last)] index runs in which the foot is planted, with hysteresis."""
    if not foot_length > 0:
        raise ContactError(f"a foot needs a length above 0, got {foot_length}")
    planted, runs, first = False, [], 0
    for index, (h, v) in enumerate(zip(height, speed, strict=True)):
        if not planted and h <= PLANT_HEIGHT * foot_length and v <= PLANT_SPEED * foot_length:
            planted, first = True, index
        elif planted and (h > LIFT_HEIGHT * foot_length or v > LIFT_SPEED * foot_length):
            planted = False
            runs.append((first, index - 1))
    if planted:
        runs.append((first, len(height) - 1))
    return runs


def foot_contacts(frames, heel, toe, ground, foot_length, fps):
    """The contacts of one foot.

    frames (F,): the frames sampled, one apart. heel, toe (F, 3): world points of the sole's back
    and front. ground (F,): the terrain's height under the sole's lowest point (nan off the
    terrain: never planted there). fps: frames per second, for speeds per second.
    """
    frames = np.asarray(frames, np.float64)
    heel, toe = np.asarray(heel, np.float64), np.asarray(toe, np.float64)
    if len(frames) < 2:
        raise ContactError("feet need at least two frames to tell standing from moving")
    lowest = np.where((heel[:, 2] <= toe[:, 2])[:, None], heel, toe)
    sole = (heel + toe) / 2.0
    height = lowest[:, 2] - np.asarray(ground, np.float64)
    height = np.where(np.isfinite(height), height, np.inf)
    velocity = np.gradient(sole, frames, axis=0) * fps
    speed = np.linalg.norm(velocity, axis=1)
    contacts = []
    for first, last in planted_runs(height, speed, foot_length):
        planted = slice(first, last + 1)
        place = sole[planted].mean(axis=0)
        place[2] = float(np.nanmean(np.asarray(ground, np.float64)[planted]))
        along = (toe[planted] - heel[planted]).mean(axis=0)
        before = velocity[max(first - STRIKE_FRAMES, 0):first + 1, 2]
        # The stance without the hysteresis' lift-off allowance, what a gait study would time; the
        # central differences of the speed lose half a frame at each end.
        standing = ((height[planted] <= PLANT_HEIGHT * foot_length)
                    & (speed[planted] <= PLANT_SPEED * foot_length))
        contacts.append(Contact(first, last, place, float(np.arctan2(along[1], along[0])),
                                float(max(-before.min(), 0.0)), float(standing.sum() + 1) / fps))
    return contacts
