"""Where feet land: a foot's contacts with the ground from its sole over the frames.

A foot is planted when the lowest point of its sole is within a small height of the ground
under it and moves slowly, both measured in foot lengths (a child's foot and a giant's alike),
and stays planted until it rises or moves clearly more (hysteresis), so a contact is never split
by a frame of jitter. Each contact gives one print: where the sole stood (the mean over the
planted frames), its heading (heel to toe), its first frame (the heel strike), how long it
lasted and how hard it struck (the sole's downward speed as it landed).
"""

from dataclasses import dataclass

import numpy as np

PLANT_HEIGHT = 0.1  # foot lengths above the ground: lower than this, the foot may be planted
LIFT_HEIGHT = 0.2  # higher than this, it has lifted
PLANT_SPEED = 1.0  # foot lengths per second: slower than this, it may be planted
LIFT_SPEED = 2.0  # faster than this, it has left
STRIKE_FRAMES = 3  # the frames before a contact whose downward speed is its strike


class ContactError(ValueError):
    """Feet that cannot give contacts; the message is for the artist."""


@dataclass
class Contact:
    first: int  # index of the heel-strike frame
    last: int
    position: np.ndarray  # world (x, y, z): the sole's mean place while planted, z the ground's
    heading: float  # radians about world Z, heel to toe
    strike: float  # downward speed of the sole as it landed, per second (world units)


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
        contacts.append(Contact(first, last, place, float(np.arctan2(along[1], along[0])),
                                float(max(-before.min(), 0.0))))
    return contacts
