"""A footprint's shape in plain numpy: the sole's outline, its floor, its wall and its rim.

A print is a sole outline (heel circle, toe circle, tangent lines between them: an uneven
capsule, optionally waisted on its inner side at the arch) pressed into a floor (flat, or
deepest under heel and ball), a wall across the outline (dry sand crumbles to its angle of
repose: a straight cut slumps, its top retreating outward as far as its foot fills inward,
so the hollow keeps the foot's volume), optionally wandering in lumps, and a low rim bump
beyond the wall's top. The painter (footprints.py) stamps it.
"""

import numpy as np

F32 = np.float32
REPOSE = np.radians(34.0)  # dry quartz sand's angle of repose: the steepest a crumbled wall stands
WALL_ROUNDING = 0.2  # share of the wall, at its foot and at its top, that curves into the flat sand
WALL_STEEPNESS = 1.0 / (1.0 - WALL_ROUNDING)  # the wall's straight part's slope over its mean slope
FOOT_ARCH = 0.8  # a foot presses its arch this deep against its heel and ball
FOOT_WAIST = 0.5  # the sole's inner half-width at its arch against a straight outline's: the
# outer edge of a foot's print runs straight, its inner edge curves in at the arch
SLUMPED = 0.5  # share of a slumped wall inside the cut's outline: top and foot move alike
CRUMBLE = 0.25  # how far a crumbled wall's top wanders, against the wall's width
RIM_LUMPS = 0.8  # how much a crumbled rim's height varies about its mean (0: an even lip)


class Sole:
    """Sole shape and profile, in metres. Immutable; `reach` bounds a stamp's influence.

    edge: width of the wall down to the floor (wall_width gives the one that stands at the
    angle of repose for a depth).
    inside: the share of the wall inside the outline (0: the wall starts at the outline and
    runs out to the sand; SLUMPED: a cut wall slumped, keeping the pressed volume).
    crumble: how far (metres) the wall wanders in and out in lumps about a wall wide, the rim's
    height varying with it by RIM_LUMPS (0: a clean outline and an even rim).
    arch: the floor's depth between heel and ball against theirs (1: a flat floor; FOOT_ARCH).
    waist: the outline's inner half-width (+b, toward the body's midline) midway from heel to
    toe against a straight capsule's (1: none; FOOT_WAIST); the outer half stays straight."""

    __slots__ = ("length", "width", "heel_ratio", "edge", "rim_width", "arch", "waist", "inside", "crumble")

    def __init__(self, length=0.27, width=0.10, heel_ratio=0.75, edge=0.012, rim_width=0.04, arch=1.0,
                 waist=1.0, inside=0.0, crumble=0.0):
        if not (length > 0 and width > 0 and rim_width >= 0 and edge >= 0 and crumble >= 0):
            raise ValueError("sole length and width must be > 0, edge, rim width and crumble >= 0")
        if not 0 <= inside < 1:
            raise ValueError("the wall's share inside the outline must lie in [0, 1)")
        if width > length:
            raise ValueError("sole width must not exceed its length")
        if not 0 < heel_ratio <= 1:
            raise ValueError("heel ratio must lie in (0, 1]")
        if not (0 < arch <= 1 and 0 < waist <= 1):
            raise ValueError("arch and waist must lie in (0, 1]")
        self.length, self.width, self.heel_ratio = float(length), float(width), float(heel_ratio)
        self.edge, self.rim_width = float(edge), float(rim_width)
        self.arch, self.waist = float(arch), float(waist)
        self.inside, self.crumble = float(inside), float(crumble)

    def centres(self):
        """Where along the sole (a) the heel circle's and the toe circle's centres lie."""
        return -self.length / 2 + self.heel_radius(), self.length / 2 - self.toe_radius()

    def toe_radius(self):
        return self.width / 2

    def heel_radius(self):
        return self.heel_ratio * self.width / 2

    def edge_width(self, texel):
        return max(self.edge, texel)

    def rim_band(self, texel):
        return max(self.rim_width, 2.0 * texel) if self.rim_width > 0 else 0.0

    def outer_band(self, texel):
        """How far beyond the outline the stamp reaches: the wall's outer part, the crumbling
        and the rim."""
        return self.edge_width(texel) * (1.0 - self.inside) + self.crumble + self.rim_band(texel)

    def reach(self, texel=0.0):
        """Distance from the print centre beyond which the stamp is exactly zero."""
        return self.length / 2 + self.outer_band(texel)


def wall_width(depth, repose=REPOSE):
    """Width of a wall down `depth` whose straight part stands at the angle of repose."""
    return WALL_STEEPNESS * max(float(depth), 0.0) / np.tan(repose)


def dry_sand_sole(depth, length=0.27, width=0.10, rim_width=0.04):
    """A foot's sole pressed `depth` into dry sand (any one length unit): waisted, deepest under
    heel and ball, its wall as wide as dry sand crumbles at that depth, slumped across the
    outline and lumpy."""
    edge = wall_width(depth)
    return Sole(length=length, width=width, edge=edge, rim_width=rim_width, arch=FOOT_ARCH, waist=FOOT_WAIST,
                inside=SLUMPED, crumble=CRUMBLE * edge)


def wall_ramp(t, rounding=WALL_ROUNDING):
    """0 at t <= 0 to 1 at t >= 1: a straight slope whose ends curve (C1) over `rounding` of the
    width into the flat floor and the flat sand, as a crumbled wall does."""
    t = np.clip(t, 0.0, 1.0)
    q = rounding
    curve = 1.0 / (2.0 * q * (1.0 - q))
    return np.where(t < q, curve * t * t,
                    np.where(t > 1.0 - q, 1.0 - curve * (1.0 - t) ** 2, (t - q / 2) / (1.0 - q)))


def arch_hump(a, sole):
    """0 at the heel's and toe's circle centres (and beyond), 1 midway between them; flat to the
    second derivative at its ends (a kink there would draw a line across the print's shading)."""
    heel, toe = sole.centres()
    u = np.clip((a - heel) / max(toe - heel, 1e-9), 0.0, 1.0)
    return (4.0 * u * (1.0 - u)) ** 3


def floor_depth(a, sole, hump=None):
    """The floor's depth along the sole (a forward): 1 under the heel and the ball, `arch` between
    them, through a smooth dip: a foot's heel and ball carry its weight. `hump`: arch_hump(a)
    where the caller has it already."""
    return 1.0 - (1.0 - sole.arch) * (arch_hump(a, sole) if hump is None else hump)


# Lump values on a 256 x 256 lattice, two per node (the wall's wander, the rim's height),
# fixed so every paint of the same ground crumbles alike.
LUMP_LATTICE = np.random.default_rng(20261127).uniform(-1.0, 1.0, (2, 256 * 256)).astype(F32)


def crumble_noise(x, y, lump):
    """Two signed value noises (-1..1, smooth) over the painting plane in lumps `lump` wide: how
    far the wall's top wanders and how the rim's height varies. Taken at the texel's place, not
    the print's, so overlapping prints crumble alike. A lattice lookup: Perlin noise here took
    several times as long (README, Footprints)."""
    u, v = np.asarray(x, np.float64) / lump, np.asarray(y, np.float64) / lump
    cu, cv = np.floor(u), np.floor(v)
    fu, fv = (u - cu).astype(F32), (v - cv).astype(F32)
    fu, fv = fu * fu * (F32(3.0) - F32(2.0) * fu), fv * fv * (F32(3.0) - F32(2.0) * fv)
    i, j = (cu.astype(np.int64) & 255) << 8, cv.astype(np.int64) & 255
    i1, j1 = (i + 256) & 0xFF00, (j + 1) & 255
    corners = (i | j, i1 | j, i | j1, i1 | j1)
    noises = []
    for lattice in LUMP_LATTICE:
        n00, n10, n01, n11 = (np.take(lattice, corner) for corner in corners)
        low, high = n00 + (n10 - n00) * fu, n01 + (n11 - n01) * fu
        noises.append(low + (high - low) * fv)
    return noises[0], noises[1]


def sole_distance(a, b, sole, hump=None):
    """Signed distance to the sole outline (negative inside); a forward, b lateral, metres.

    The outline is an uneven capsule from the heel circle (radius r1, centre at
    a = -L/2 + r1) to the toe circle (r2, at a = L/2 - r2), centred on a = 0. `hump`: the
    arch's arch_hump(a) where the caller has it already.
    """
    r1, r2 = sole.heel_radius(), sole.toe_radius()
    heel = -sole.length / 2 + r1
    h = sole.length / 2 - r2 - heel
    px = np.abs(b)
    py = a - heel
    if h <= 1e-12:  # a round sole
        return np.hypot(px, py) - max(r1, r2)
    slope = (r1 - r2) / h
    along = np.sqrt(max(1.0 - slope * slope, 0.0))
    k = -slope * px + along * py
    distance = np.where(k < 0, np.hypot(px, py) - r1,
                        np.where(k > along * h, np.hypot(px, py - h) - r2, along * px + slope * py - r1))
    if sole.waist < 1:
        # A waist on the inner side (b > 0): the outline moved in at the arch, blended to nothing
        # at the midline so the distance stays continuous (a jump would draw a crease down the
        # print once the wall reaches inside the outline).
        hump = arch_hump(a, sole) if hump is None else hump
        half_width = np.maximum((r1 - slope * py) / max(along, 1e-9), 0.0)  # the straight outline's
        blend = np.clip(b / (0.5 * sole.waist * min(r1, r2)), 0.0, 1.0)
        blend = blend * blend * (3.0 - 2.0 * blend)
        distance = distance + along * (1.0 - sole.waist) * half_width * hump * blend
    return distance


def sole_profile(distance, sole, texel):
    """Pressed fraction s (1 on the floor, falling to 0 across the wall: from the outline
    outward, or across it by the sole's `inside` share) and rim bump (0..1, peak 1) beyond the
    wall's top."""
    wall = sole.edge_width(texel)
    pressed = 1.0 - wall_ramp(distance / wall + sole.inside)
    band = sole.rim_band(texel)
    if band <= 0:
        return pressed, np.zeros_like(pressed)
    t = (distance - wall * (1.0 - sole.inside)) / band
    rim = np.where((t > 0) & (t < 1), (4.0 * t * (1.0 - t)) ** 2, 0.0)
    # A float32 distance a hair short of the band's end leaves ~1e-13: that is outside the stamp.
    return pressed, np.where(rim > 1e-9, rim, 0.0)
