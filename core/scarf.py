"""The scarf's tail turned downwind: the twin of the Sandscape Scarf Wind group.

The tail is built streaming along one heading in the walker's own space; as the walker turns, the
wind it feels stays put. Each frame the tail turns about the upright axis through the nape to the
heading of the wind the walker feels (the scene's wind less its own walking velocity), reflected
to the walker's back half: a ribbon tied at the nape streams behind or to the side, never through
the body ahead of it. The more that wind blows forward (a wind from behind outrunning the walk),
the nearer the tail hangs straight back: reflected alone, it whipped from one shoulder to the
other, 20 degrees a frame, as a weaving walker turned across such a wind. Its root turns least:
the turn grows from none at the nape to all of it ROOT_SHARE along the tail. Under CALM_SPEED it
eases to straight back too.
"""

import numpy as np

FLUTTER_ATTRIBUTE = "sandscape_flutter"  # on the figure's points: t^FLUTTER_GROWTH along the tail, 0 off it
FLUTTER_GROWTH = 1.5  # held at the nape, free at the end
ROOT_SHARE = 0.25  # of the tail's length: where the turn reaches its full angle
CALM_SPEED = 1.5  # metres a second of felt wind (a light breeze) at which the tail takes its full heading
SETTLE_TIME = 1.0  # seconds the tail takes to stop feeling the walk once the walker stops


def felt_heading(felt_xy):
    """The tail's heading (radians from the walker's forward +X toward its left +Y) for the wind
    it feels, `felt_xy` in its own space: the wind's heading reflected into the back half, its
    swing from straight back shrunk by the share the wind blows forward (1 - max(cos, 0))."""
    felt_xy = np.asarray(felt_xy, float)
    heading = np.arctan2(felt_xy[..., 1], felt_xy[..., 0])
    aside = np.arcsin(np.clip(np.sin(heading - np.pi), -1.0, 1.0))
    return np.pi + aside * (1.0 - np.maximum(np.cos(heading), 0.0))


def turn_angle(felt_xy, built_heading, felt_speed, calm_speed):
    """How far the whole tail turns (radians, counter-clockwise seen from above): from its built
    heading to the felt wind's, which eases to straight back below `calm_speed` (the same units
    as `felt_speed`)."""
    fade = np.clip(np.asarray(felt_speed, float) / calm_speed, 0.0, 1.0)
    return np.pi + (felt_heading(felt_xy) - np.pi) * fade - built_heading


def root_weight(flutter):
    """Share of the turn a tail point takes from its flutter weight (t^FLUTTER_GROWTH, t along the
    tail): a smoothstep in t from the nape to ROOT_SHARE."""
    t = np.clip(np.asarray(flutter, float), 0.0, 1.0) ** (1.0 / FLUTTER_GROWTH)
    x = np.clip(t / ROOT_SHARE, 0.0, 1.0)
    return x * x * (3.0 - 2.0 * x)


def turn_points(points, flutter, angle, pivot):
    """The points (N x 3, the walker's space) turned about the upright axis through `pivot` by
    `angle` x root_weight(flutter) each; points off the tail (flutter 0) stay."""
    points = np.asarray(points, float)
    share = np.asarray(angle, float) * root_weight(flutter)
    share = np.where(np.asarray(flutter) > 0.0, share, 0.0)
    cos, sin = np.cos(share), np.sin(share)
    dx, dy = points[:, 0] - pivot[0], points[:, 1] - pivot[1]
    out = points.copy()
    out[:, 0] = pivot[0] + cos * dx - sin * dy
    out[:, 1] = pivot[1] + sin * dx + cos * dy
    return out


def walk_speed_at(frame, speed, start, end, settle_frames):
    """The walking speed the tail feels at `frame`: `speed` from the walk's first frame to its
    last, easing linearly to none over `settle_frames` after it (the scarf swings round as the
    walker stands; it lags, so no ease before the walk: the shot may open mid-stride). The group
    reads the scene's frame for it."""
    frame = np.asarray(frame, float)
    fade = np.clip((end + settle_frames - frame) / settle_frames, 0.0, 1.0)
    return np.where(frame >= start, speed * fade, 0.0)


def felt_wind(wind, walker_matrix, walk_speed):
    """The wind the walker feels in its own space: (scene wind - walk_speed x its forward) taken
    into the walker's axes (its 4x4 world matrix; scale and all), and that wind's world speed."""
    matrix = np.asarray(walker_matrix, float)[:3, :3]
    forward = matrix @ np.array([1.0, 0.0, 0.0])
    forward /= max(np.linalg.norm(forward), 1e-30)
    felt_world = np.asarray(wind, float) - walk_speed * forward
    return np.linalg.solve(matrix, felt_world), float(np.linalg.norm(felt_world))
