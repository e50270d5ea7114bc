"""Contacts from a foot's sole over the frames (core/contacts.py) on gaits written down here: a
walk, a run, a stop and a turn, with jitter. Reference: the plants the gait was made of."""

import math

import numpy as np
import pytest

from core import contacts

FOOT = 0.26  # metres: an adult's foot
FPS = 24.0


def gait(plants, swing_height, frames_total, jitter=0.0, seed=0):
    """Heel and toe (F, 3) of one foot planted at each (x, y, heading, first, last) in turn,
    swinging in an arc of swing_height between plants; ground at 0."""
    frames = np.arange(frames_total, dtype=np.float64)
    heel, toe = np.zeros((frames_total, 3)), np.zeros((frames_total, 3))

    def sole(x, y, heading, lift):
        along = np.array([math.cos(heading), math.sin(heading), 0.0]) * FOOT / 2
        centre = np.array([x, y, lift])
        return centre - along, centre + along

    for index, frame in enumerate(frames):
        for k, (x, y, heading, first, last) in enumerate(plants):
            if first <= frame <= last:
                heel[index], toe[index] = sole(x, y, heading, 0.0)
                break
            following = plants[k + 1] if k + 1 < len(plants) else None
            if following is not None and last < frame < following[3]:
                t = (frame - last) / (following[3] - last)
                a, b = np.array([x, y, heading]), np.array(following[:3])
                here = a + (b - a) * t
                heel[index], toe[index] = sole(*here, swing_height * math.sin(math.pi * t))
                break
        else:
            heel[index], toe[index] = heel[index - 1], toe[index - 1]
    noise = np.random.default_rng(seed).normal(0.0, jitter, heel.shape)
    return frames, heel + noise, toe + noise


def found(frames, heel, toe):
    return contacts.foot_contacts(frames, heel, toe, np.zeros(len(frames)), FOOT, FPS)


@pytest.mark.parametrize("name, plants, swing, jitter", [
    ("walk", [(0.0, 0.0, 0.0, 0, 14), (1.4, 0.0, 0.0, 26, 40), (2.8, 0.0, 0.0, 52, 66)], 0.12, 0.002),
    ("run", [(0.0, 0.0, 0.0, 0, 5), (3.0, 0.0, 0.0, 17, 22), (6.0, 0.0, 0.0, 34, 39)], 0.35, 0.002),
    ("turn", [(0.0, 0.0, 0.0, 0, 14), (1.2, 0.4, 0.6, 26, 40), (2.0, 1.4, 1.2, 52, 66)], 0.12, 0.002),
])
def test_one_contact_per_plant_where_the_foot_stood(name, plants, swing, jitter):
    frames, heel, toe = gait(plants, swing, 70, jitter)
    seen = found(frames, heel, toe)
    assert len(seen) == len(plants), [(c.first, c.last) for c in seen]
    for contact, (x, y, heading, first, _last) in zip(seen, plants, strict=True):
        assert np.hypot(contact.position[0] - x, contact.position[1] - y) < 0.03  # the 3 cm
        assert abs(math.remainder(contact.heading - heading, math.tau)) < math.radians(3)
        assert abs(contact.first - first) <= 2  # heel strike within two frames
        assert contact.position[2] == pytest.approx(0.0)


def test_a_run_strikes_harder_than_a_walk():
    walk = found(*gait([(0.0, 0, 0, 0, 14), (1.4, 0, 0, 26, 40)], 0.12, 44))
    run = found(*gait([(0.0, 0, 0, 0, 5), (3.0, 0, 0, 17, 22)], 0.35, 26))
    assert run[1].strike > 2.0 * walk[1].strike > 0.0


def test_a_stop_is_one_long_contact_and_a_hover_is_none():
    frames, heel, toe = gait([(0.0, 0, 0, 0, 14), (1.4, 0, 0, 26, 99)], 0.12, 100, jitter=0.003)
    stop = found(frames, heel, toe)
    assert len(stop) == 2 and stop[1].last == 99 and stop[1].last - stop[1].first >= 70
    hover = found(frames, heel + [0, 0, 0.2], toe + [0, 0, 0.2])  # 20 cm up: never touches
    assert hover == []


def test_bad_feet_are_refused():
    with pytest.raises(contacts.ContactError, match="length"):
        contacts.foot_contacts([0, 1], np.zeros((2, 3)), np.zeros((2, 3)), np.zeros(2), 0.0, FPS)
    with pytest.raises(contacts.ContactError, match="two frames"):
        contacts.foot_contacts([0], np.zeros((1, 3)), np.zeros((1, 3)), np.zeros(1), FOOT, FPS)


def test_a_run_prints_longer_and_deeper_at_the_toe_a_walk_evenly():
    """A run's foot is down about a quarter of a second, a walk's over half a second (gait
    studies: 0.2-0.3 s and 0.6-0.7 s): their prints' length scale and toe bias."""
    walk = found(*gait([(0.0, 0, 0, 0, 14), (1.4, 0, 0, 26, 40), (2.8, 0, 0, 52, 66)], 0.12, 70))
    run = found(*gait([(0.0, 0, 0, 0, 5), (3.0, 0, 0, 17, 22), (6.0, 0, 0, 34, 39)], 0.35, 40))
    walk_seconds, run_seconds = walk[1].seconds, run[1].seconds
    print(f"stance: walk {walk_seconds:.3f} s, run {run_seconds:.3f} s")
    assert walk_seconds > 0.5 and run_seconds < 0.3
    assert contacts.gait_shape(walk_seconds) == (1.0, 0.0)
    stretch, toe = contacts.gait_shape(run_seconds)
    assert stretch == pytest.approx(1.0 + contacts.RUN_STRETCH)
    assert toe == pytest.approx(contacts.RUN_TOE_BIAS)
    between = [contacts.gait_shape(s) for s in np.linspace(0.25, 0.5, 6)]
    assert all(a[0] >= b[0] and a[1] >= b[1] for a, b in zip(between[:-1], between[1:], strict=True))
