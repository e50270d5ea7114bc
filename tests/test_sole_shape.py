"""A print's wall as dry sand leaves it: slumped across the cut (keeping the foot's volume) and
crumbled into lumps. References: the area of the foot's outline, and the outline itself."""

import numpy as np
import pytest

from core import footprints as fp
from core import sole as soles

TEXEL, DEPTH, RADIUS = 0.002, 0.04, 0.2


def round_print(region_origin=(-0.35, -0.35), **shape):
    """A round sole of RADIUS (a capsule whose circles meet) painted alone: image, region."""
    sole = soles.Sole(length=2 * RADIUS, width=2 * RADIUS, heel_ratio=1.0, **shape)
    region = fp.Region(*region_origin, TEXEL, 350, 350)
    return fp.paint([[0.0, 0.0]], [[1.0, 0.0]], [[0.0, 1.0]], [0.0], 1.0, region, sole), region, sole


def radial(region):
    xs = region.x0 + (np.arange(region.width) + 0.5) * region.texel
    ys = region.y0 + (np.arange(region.height) + 0.5) * region.texel
    x, y = np.meshgrid(xs, ys)
    return np.hypot(x, y), np.arctan2(y, x)


def test_a_slumped_wall_keeps_the_feet_volume():
    """Sand slumping to its angle of repose moves as much inward at the wall's foot as the top
    retreats outward: the pressed volume is the foot's (area pi r^2 at full depth) within 1 %,
    where a wall standing wholly outside the outline adds its ring."""
    edge = soles.wall_width(DEPTH)
    slumped, region, _ = round_print(edge=edge, rim_width=0.0, inside=soles.SLUMPED)
    outside, _, _ = round_print(edge=edge, rim_width=0.0)
    area = np.pi * RADIUS ** 2
    volumes = [image[..., 0].astype(np.float64).sum() * TEXEL ** 2 for image in (slumped, outside)]
    print(f"pressed volume over the foot's: slumped {volumes[0] / area:.4f}, outside {volumes[1] / area:.4f}")
    assert volumes[0] == pytest.approx(area, rel=0.01)
    # Wholly outside: the foot's volume plus the wall's ring, integrated in numpy (+41 %).
    u = np.linspace(0.0, edge, 100001)
    pressed = soles.wall_ramp(1.0 - u / edge) * (RADIUS + u)
    ring = 2.0 * np.pi * np.sum((pressed[1:] + pressed[:-1]) / 2 * np.diff(u))  # trapezoids (numpy 1.2x too)
    assert volumes[1] == pytest.approx(area + ring, rel=0.01)
    assert ring > 0.4 * area
    # Half pressed on the outline, untouched beyond half a wall, the floor within half a wall.
    r, _ = radial(region)
    on_outline = np.abs(r - RADIUS) < TEXEL / 2
    np.testing.assert_allclose(slumped[on_outline, 0], 0.5, atol=0.05)
    assert (slumped[r > RADIUS + edge / 2 + TEXEL, 0] == 0).all()
    assert (slumped[r < RADIUS - edge / 2 - TEXEL, 0] == 1).all()


def test_a_crumbled_wall_wanders_in_lumps_and_stays_within_reach():
    """With `crumble`, the wall's middle (half pressed) wanders in and out around the outline by
    up to `crumble`, and the rim's height varies along the ring; nothing lies beyond reach().
    Without it, the outline is a circle within a texel and the rim even."""
    edge = soles.wall_width(DEPTH)
    crumble = soles.CRUMBLE * edge
    shapes = {"crumbled": dict(edge=edge, rim_width=0.03, inside=soles.SLUMPED, crumble=crumble),
              "clean": dict(edge=edge, rim_width=0.03, inside=soles.SLUMPED)}
    found = {}
    for name, shape in shapes.items():
        image, region, sole = round_print(**shape)
        r, angle = radial(region)
        assert (image[r > sole.reach(TEXEL) + TEXEL] == 0).all()
        rays = np.linspace(-np.pi, np.pi, 180, endpoint=False)
        middle, rim_peak = [], []
        for ray in rays:
            on_ray = np.abs(np.angle(np.exp(1j * (angle - ray)))) * r < TEXEL
            order = np.argsort(r[on_ray])
            radii, pressed, rim = r[on_ray][order], image[on_ray, 0][order], image[on_ray, 1][order]
            middle.append(radii[np.argmin(np.abs(pressed - 0.5))])
            rim_peak.append(rim.max())
        middle, rim_peak = np.array(middle) - RADIUS, np.array(rim_peak)
        found[name] = (middle.std(), np.abs(middle).max(), rim_peak.std() / rim_peak.mean())
    print({name: tuple(round(float(v), 4) for v in values) for name, values in found.items()})
    wander, farthest, rim_variation = found["crumbled"]
    assert 0.2 * crumble < wander and farthest < crumble + 2 * TEXEL
    assert rim_variation > 0.15
    assert found["clean"][1] < 2 * TEXEL and found["clean"][2] < 0.02


def test_crumbling_belongs_to_the_ground_not_to_the_image():
    """The lumps are taken at each texel's place in the plane: the same print painted into an
    image shifted by whole texels has the same values where the two overlap."""
    edge = soles.wall_width(DEPTH)
    shape = dict(edge=edge, rim_width=0.03, inside=soles.SLUMPED, crumble=soles.CRUMBLE * edge)
    first, _, _ = round_print(**shape)
    shifted, _, _ = round_print(region_origin=(-0.35 + 40 * TEXEL, -0.35 + 25 * TEXEL), **shape)
    np.testing.assert_allclose(shifted[:-25, :-40], first[25:, 40:], atol=1e-5)


def test_crumbling_follows_the_scene_units():
    """Unit scale 0.01: the same crumbled print with every length in centimetres (sole, wall,
    crumble, rim, texel, region) paints the same image as in metres: lumps a wall wide, whatever
    the unit."""
    edge = soles.wall_width(DEPTH)
    images = []
    for k in (1, 100):
        shape = dict(length=0.27 * k, width=0.10 * k, edge=edge * k, rim_width=0.03 * k, inside=soles.SLUMPED,
                     crumble=soles.CRUMBLE * edge * k, arch=soles.FOOT_ARCH, waist=soles.FOOT_WAIST)
        region = fp.Region(-0.2 * k, -0.1 * k, TEXEL * k, 200, 100)
        images.append(fp.paint([[0.013 * k, 0.0]], [[1.0, 0.0]], [[0.0, 1.0]], [0.0], 1.0, region,
                               soles.Sole(**shape)))
    metres, centimetres = images
    assert np.ptp(metres[..., 1]) > 0.5  # a lumpy rim, not a flat one
    different = np.abs(metres[..., :2] - centimetres[..., :2]).max(axis=-1) > 1e-3
    assert different.mean() < 0.002  # texels on a lattice cell's edge may round the other way
