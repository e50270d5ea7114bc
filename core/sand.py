"""Numpy twins of the sand looks' node groups, in float32 like Cycles where it matters.

glint_facets        <-> "Sandscape Glint Facet" / "Sandscape Lit Glints": which grains can glint
                        and which way each grain's mirror facet faces
mirrors_view_above  <-> "Sandscape Glint Facet": whether a facet's mirror is seen (the view it
                        mirrors leaves the surface)
facet_fresnel       <-> "Sandscape Glint Facet": the share of the light a quartz facet's mirror
                        reflects at its angle (Fresnel's equations, through Snell's law)
sand_normal         <-> "Sandscape Sand Normal": the surface normal nudged towards a random
                        direction per grain (Journey's sand normal, an nlerp)
journey_contrast        the seed's own diffuse contrast, saturate(4 N'.L), N' the normal with
                        its vertical part scaled by 0.3 (not renormalised): the reference
journey_diffuse     <-> the Diffuse Contrast part of "Sandscape Journey Sand": that contrast as
                        the two Toon BSDFs Cycles renders (a ramp in two straight pieces)
journey_eevee       <-> the EEVEE Shader's diffuse: the seed's contrast through one Diffuse BSDF
                        whose colour factor (journey_eevee_factor) undoes Lambert's cosine
ocean_roughness     <-> the Ocean Specular part: a Blinn-Phong exponent as Beckmann roughness
rim                 <-> the Rim part: (1 - N.V)^power x strength
ripples             <-> "Sandscape Ripples": wind ripples' height and shading normal
ripple_defects      <-> "Sandscape Ripple Defects": one lattice of dislocation pairs (a crest
                        that begins and ends in Y-junctions) as a phase and its gradient
"""

import numpy as np

from .glints import F32, _safe_divide
from .noise_hash import white_noise_3d, white_noise_4d, white_noise_4d_color
from .shaping import smoothstep, wind_direction

MIN_FACET_COS = 0.15  # a facet tilts at most acos(0.15) = 81 degrees, whatever the power
TOON_SIZE = 0.839  # acos(0.25) over pi / 2: fully lit where N'.L reaches 0.25, Journey's 4 N'.L
SQUASH = 0.3  # Journey's factor on the normal's vertical component
SAND_COLOR = (0.62, 0.45, 0.27, 1.0)  # linear albedo of both looks (a warm quartz sand)
REPOSE = np.radians(35.0)  # the slope at which ripples keep their Steep Fraction
QUARTZ_IOR = 1.54  # a sand grain's facet: about 4.5 % of the light face-on, all of it at grazing


def _unit(v):
    v = np.asarray(v, dtype=np.float64)
    length = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(length > 0, length, 1.0)


def facet_spread(power):
    """tan of the angle at which (N.V)^power falls to 1/2: how far a facet may tilt.

    The emission glints kept to where (N.V)^power was large; lit glints let the facets tilt up
    to that half angle instead, so Facing Power means the same: higher, fewer directions glint.
    """
    power = max(float(power), 1e-6)
    c = max(0.5 ** (1.0 / power), MIN_FACET_COS)
    return float(np.sqrt(1.0 - c * c) / c)


def glint_cells(position, size, seed):
    """Per object-space cell: the grain's noise (can it glint?) and its tilt (a colour, 0..1)."""
    cell = np.floor(_safe_divide(position, size) + F32(0.5)).astype(F32)
    return white_noise_4d(cell, F32(seed)), white_noise_4d_color(cell, F32(seed))


def glint_facets(noise, tilt, normal, threshold, power):
    """(mask, facet normal): mask 1 where a grain can glint; its facet is the surface normal
    leaning by facet_spread(power) x the part of (2 tilt - 1) along the surface, renormalised
    (so a facet leans less than 90 degrees: atan(spread x sqrt 2) at most)."""
    mask = (np.asarray(noise, F32) > F32(threshold)).astype(F32)
    normal = np.broadcast_to(_unit(normal), np.shape(tilt)[:-1] + (3,))
    lean = 2.0 * np.asarray(tilt, np.float64) - 1.0
    lean = lean - np.sum(lean * normal, axis=-1, keepdims=True) * normal
    return mask, _unit(normal + facet_spread(power) * lean)


def mirrors_view_above(facet, normal, view):
    """1 where a facet mirrors the view direction (unit, towards the camera) above the surface:
    R·N = 2 (F·V)(F·N) − V·N > 0. Elsewhere the grains around the facet hide what it mirrors."""
    f_v = np.sum(np.asarray(facet, np.float64) * np.asarray(view, np.float64), axis=-1)
    f_n = np.sum(np.asarray(facet, np.float64) * np.asarray(normal, np.float64), axis=-1)
    v_n = np.sum(np.asarray(view, np.float64) * np.asarray(normal, np.float64), axis=-1)
    return (2.0 * f_v * f_n - v_n > 0.0).astype(F32)


def facet_fresnel(cos_incidence, ior=QUARTZ_IOR):
    """Unpolarised Fresnel reflectance of a dielectric facet lit at `cos_incidence` (its normal
    against the view, which its mirror shares with the light it reflects): the mean of the s and
    p reflectances, the refracted angle from Snell's law (total reflection: 1)."""
    cos_i = np.clip(np.abs(np.asarray(cos_incidence, np.float64)), 0.0, 1.0)
    sin_t = np.sqrt(1.0 - cos_i * cos_i) / ior
    total = sin_t >= 1.0
    cos_t = np.sqrt(np.maximum(1.0 - sin_t * sin_t, 0.0))
    r_s = (cos_i - ior * cos_t) / np.maximum(cos_i + ior * cos_t, 1e-300)
    r_p = (ior * cos_i - cos_t) / np.maximum(ior * cos_i + cos_t, 1e-300)
    return np.where(total, 1.0, 0.5 * (r_s * r_s + r_p * r_p))


def sand_normal(normal, grain, strength):
    """nlerp(N, G, strength), G the grain's random direction (2 grain - 1, turned to N's side)."""
    normal = np.asarray(normal, np.float64)
    g = 2.0 * np.asarray(grain, np.float64) - 1.0
    g = np.where((np.sum(g * normal, axis=-1, keepdims=True) < 0), -g, g)
    return _unit((1.0 - strength) * normal + strength * _unit(g))


def toon_intensity(angle, size, smooth):
    """Cycles' Toon BSDF: 1 within size x 90 degrees of the light, falling linearly to 0 over
    smooth x 90 degrees (size and smooth may be arrays: the group drives them per point)."""
    full, soft = np.asarray(size) * np.pi / 2, np.asarray(smooth) * np.pi / 2
    angle = np.asarray(angle, np.float64)
    ramp = 1.0 - (angle - full) / np.where(soft > 0, soft, 1.0)
    return np.where(angle < full, 1.0, np.where((angle < full + soft) & (soft > 0), ramp, 0.0))


def journey_contrast(normal, light, size=TOON_SIZE, squash=SQUASH):
    """Seed 004's diffuse contrast, saturate(N'.L / cos(size x 90 deg)) (4 N'.L at the default),
    N' the normal with its vertical component times squash, not renormalised: level ground
    under a 30 degree sun gets 4 x 0.3 x 0.5 = 0.6, slopes facing the sun full light."""
    squashed = _unit(normal) * np.array([1.0, 1.0, squash])
    threshold = max(np.cos(size * np.pi / 2), 1e-4)
    return np.clip(np.sum(squashed * np.asarray(light, np.float64), axis=-1) / threshold, 0.0, 1.0)


def _squashed(normal, size, squash):
    """(unit squashed normal, k = |N'| / cos(size x 90 deg)): what every Journey contrast twin starts from."""
    squashed = _unit(normal) * np.array([1.0, 1.0, squash])
    return _unit(squashed), np.linalg.norm(squashed, axis=-1) / max(np.cos(size * np.pi / 2), 1e-4)


def contrast_toons(normal, size=TOON_SIZE, squash=SQUASH):
    """How the node group renders journey_contrast with Toon BSDFs, whose light is a function
    of the angle to their normal only: on the unit squashed normal the contrast is
    min(1, k cos angle), k = |N'| / cos(size x 90 deg); two Toons ramp it in two straight
    pieces (fully lit up to acos(1/k), the knee halfway to 90 degrees).
    Returns (unit normal, full angle, knee angle, light at full, light at the knee)."""
    unit, k = _squashed(normal, size, squash)
    full = np.arccos(np.minimum(1.0 / np.maximum(k, 1e-12), 1.0))
    knee = 0.5 * full + np.pi / 4
    return unit, full, knee, np.minimum(k, 1.0), k * np.cos(knee)


def journey_diffuse(normal, light, size=TOON_SIZE, squash=SQUASH):
    """Radiance per unit of sun irradiance and albedo of the group's two Toon BSDFs.

    Cycles' Toon BSDF returns intensity x pdf with no cosine, the pdf uniform over its cone:
    1 / (2 pi (1 - cos cone)). The group scales each Toon's colour by 1 - cos cone, so the sum
    is journey_contrast's piecewise-linear ramp / 2 pi (bump-map correction off: the material
    does not soften a closure whose normal is not the surface's)."""
    unit, full, knee, top, middle = contrast_toons(normal, size, squash)
    angle = np.arccos(np.clip(np.sum(unit * np.asarray(light, np.float64), axis=-1), 0.0, 1.0))
    first = toon_intensity(angle, full / (np.pi / 2), (knee - full) / (np.pi / 2))
    second = toon_intensity(angle, knee / (np.pi / 2), 1.0 - knee / (np.pi / 2))
    return ((top - middle) * first + middle * second) / (2 * np.pi)


def journey_eevee_factor(normal, light, size=TOON_SIZE, squash=SQUASH):
    """The colour factor of the EEVEE Shader's one Diffuse BSDF on the unit squashed normal:
    min(1/c, k) / 2, c = that normal . the unit light (no light: c = 0, the factor k / 2)."""
    unit, k = _squashed(normal, size, squash)
    return 0.5 * np.minimum(1.0 / np.maximum(_cosine(unit, light), 1e-4), k)


def journey_eevee(normal, light, size=TOON_SIZE, squash=SQUASH):
    """Radiance per unit of sun irradiance and albedo of the EEVEE Shader's diffuse: Lambert's
    max(c, 0) / pi times the factor, which is journey_contrast / 2 pi (the Cycles output's scale)."""
    unit, _ = _squashed(normal, size, squash)
    return np.maximum(_cosine(unit, light), 0.0) / np.pi * journey_eevee_factor(normal, light, size, squash)


def _cosine(unit, light):
    """unit . the unit light (a zero light: 0)."""
    light = np.asarray(light, np.float64)
    length = np.linalg.norm(light)
    return np.sum(unit * (light / length if length > 0 else light), axis=-1)


def ocean_roughness(exponent):
    """Beckmann roughness (Blender's, the square root of alpha) for a Blinn-Phong exponent:
    alpha^2 = 2 / (p + 2), the classic match of the two lobes."""
    return (2.0 / (np.asarray(exponent, np.float64) + 2.0)) ** 0.25


def blinn_phong_half_width(exponent):
    """Angle between N and H at which (N.H)^p falls to half: the width of a Blinn-Phong highlight."""
    return np.arccos(0.5 ** (1.0 / np.asarray(exponent, np.float64)))


def rim(n_dot_v, power, strength):
    return strength * (1.0 - np.clip(n_dot_v, 0.0, 1.0)) ** power



def ripple_weight(normal, wind, steep_fraction, lee_fraction):
    """How much ripple a surface keeps: Steep Fraction at the 35 degree angle of repose (less in
    between), and less again on slopes turned away from the wind, down to Lee Fraction."""
    normal = _unit(normal)
    direction = wind_direction(wind)[:2]
    slope = np.arccos(np.clip(np.abs(normal[..., 2]), 0.0, 1.0))
    steep = 1.0 + (steep_fraction - 1.0) * smoothstep(0.0, REPOSE, slope)
    downwind = normal[..., 0] * direction[0] + normal[..., 1] * direction[1]
    lee = 1.0 + (lee_fraction - 1.0) * smoothstep(0.0, np.sin(REPOSE), downwind)
    return steep * lee



def ripple_lattice(position, scale):
    """Smooth value noise on a horizontal lattice of `scale` for the ripples' irregularity:
    (meander m, variation g, gradient of m per unit length (..., 2)), m and g in 0..1.

    Lattice corners (i, j, 0) get White Noise 3D's Value (m) and its Color's green (g, the 4D
    hash of (i, j, 0, 1)); inside a cell they blend bilinearly with smoothstep weights, so the
    noise and its gradient are continuous. In float32, as Cycles computes it.
    """
    q = np.asarray(position, F32)[..., :2] * (F32(1.0) / F32(scale))
    cell = np.floor(q)
    f = (q - cell).astype(np.float64)
    s = f * f * (3.0 - 2.0 * f)
    ds = 6.0 * f * (1.0 - f)
    value, green = {}, {}
    for dx in (0, 1):
        for dy in (0, 1):
            corner = np.stack([cell[..., 0] + dx, cell[..., 1] + dy, np.zeros_like(cell[..., 0])], axis=-1)
            value[dx, dy] = white_noise_3d(corner).astype(np.float64)
            green[dx, dy] = white_noise_4d(corner, 1.0).astype(np.float64)

    def lerp(a, b, t):
        return a + (b - a) * t

    def blend(c):
        return lerp(lerp(c[0, 0], c[1, 0], s[..., 0]), lerp(c[0, 1], c[1, 1], s[..., 0]), s[..., 1])

    v = value
    dx = ds[..., 0] * lerp(v[1, 0] - v[0, 0], v[1, 1] - v[0, 1], s[..., 1])
    dy = ds[..., 1] * lerp(v[0, 1] - v[0, 0], v[1, 1] - v[1, 0], s[..., 0])
    return blend(value), blend(green), np.stack([dx, dy], axis=-1) / scale


# 8 wavelengths a cell (11 left the demo's ripples corduroy to the sixth review: 5 crest ends per
# 1000 px of crest against 4 without any); the inserted crest 2-4 wavelengths long, its cores
# and their flattening inside the phase's whole reach, the reach inside the cell.
DEFECT_CELL = 8.0  # wavelengths: a lattice cell, one dislocation pair at most
DEFECT_JITTER = 0.5  # wavelengths: how far a pair's centre strays from its cell's
DEFECT_HALF = (1.0, 2.0)  # wavelengths: half the inserted crest's length, from .. to
DEFECT_REACH = (2.6, 3.5)  # wavelengths: the pair's phase whole within the first, gone at the second
DEFECT_CORE = 0.5  # wavelengths: the ripples flatten toward a core (no point where the normal spins)
# (lattice offset in cells, hash layer): four lattices (two left 5 crest ends per 1000 px of traced
# crest in the poster's foreground, the seventh review; real ripple fields fork and end every few
# wavelengths)
DEFECT_LAYERS = ((0.0, 2.0), (0.5, 3.0), (0.25, 4.0), (0.75, 5.0))


def ripple_defects(position, direction, wavelength, share, offset, layer):
    """(phase, its gradient (..., 2), keep, its gradient) of one lattice of ripple dislocation pairs.

    A lattice of DEFECT_CELL wavelengths, shifted by `offset` cells; a cell whose White Noise 3D
    value h at (cell, layer) is under `share` holds a pair: two phase vortices of opposite sign
    at c +- l t (t along the crests), c the cell's centre moved by the noise's green and blue,
    l from h. Their phase, the angle from p - a to p - b, jumps by exactly 2 pi between them (a
    crest inserted there, ending in a Y-junction at each core; sin does not see the jump) and
    fades to nothing by DEFECT_REACH, inside the cell, so cells join without a seam. Keep, the
    share of the ripples' height left, falls to 0 within DEFECT_CORE of each core.
    """
    p = np.asarray(position, F32)[..., :2].astype(np.float64)
    size = DEFECT_CELL * wavelength
    cell = np.floor((p / size).astype(F32) + F32(offset)).astype(np.float64)
    key = np.stack([cell[..., 0], cell[..., 1], np.full(cell.shape[:-1], layer)], axis=-1)
    h = white_noise_3d(key).astype(np.float64)
    jitter = np.stack([white_noise_4d(key, 1.0), white_noise_4d(key, 2.0)], axis=-1).astype(np.float64)
    centre = (cell + 0.5 - offset) * size + (jitter - 0.5) * (2.0 * DEFECT_JITTER * wavelength)
    draw = _safe_divide(h, share)
    sign = np.where(draw < 0.5, -1.0, 1.0) * (h < share)
    half = wavelength * (DEFECT_HALF[0] + (DEFECT_HALF[1] - DEFECT_HALF[0]) * np.mod(2.0 * draw, 1.0))
    along = np.array([-direction[1], direction[0]])
    e = p - centre
    u, v = e - half[..., None] * along, e + half[..., None] * along
    angle = np.arctan2(u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0], np.sum(u * v, axis=-1))
    r = np.linalg.norm(e, axis=-1) / wavelength
    low, high = DEFECT_REACH
    t = np.clip((r - low) / (high - low), 0.0, 1.0)
    whole = 1.0 - t * t * (3.0 - 2.0 * t)

    def swirl(w):  # the gradient of the direction of w: perp(w) / |w|^2 (0 on the core, as Cycles)
        square = np.sum(w * w, axis=-1, keepdims=True)
        return np.stack([-w[..., 1], w[..., 0]], axis=-1) / np.where(square > 0.0, square, np.inf)

    fading = -6.0 * t * (1.0 - t) / (high - low) / wavelength
    gradient = whole[..., None] * (swirl(v) - swirl(u)) + (angle * fading)[..., None] * _unit_2d(e)
    core_u, core_v = (_flattening(w, wavelength, sign != 0.0) for w in (u, v))
    keep = core_u[0] * core_v[0]
    keep_gradient = core_u[0][..., None] * core_v[1] + core_v[0][..., None] * core_u[1]
    return sign * whole * angle, sign[..., None] * gradient, keep, keep_gradient


def _unit_2d(w):
    return w / np.maximum(np.linalg.norm(w, axis=-1, keepdims=True), 1e-12)


def _flattening(w, wavelength, present):
    """(share kept, its gradient) at w from a core: smoothstep from 0 at the core to 1 at
    DEFECT_CORE wavelengths; 1 where the cell holds no pair."""
    reach = DEFECT_CORE * wavelength
    t = np.clip(np.linalg.norm(w, axis=-1) / reach, 0.0, 1.0)
    kept = np.where(present, t * t * (3.0 - 2.0 * t), 1.0)
    slope = np.where(present, 6.0 * t * (1.0 - t) / reach, 0.0)
    return kept, slope[..., None] * _unit_2d(w)


def ripples(position, normal, wind, wavelength, amplitude, steep_fraction=0.2, lee_fraction=0.3,
            meander=0.0, meander_scale=1.0, variation=0.0, flatten=0.0, defects=0.0):
    """(height, normal) of the ripples at world positions (..., 3) with world normals.

    Crests run across the wind and wander: phase = 2 pi ((p . wind) / wavelength + meander (2 m - 1)),
    m the lattice noise (ripple_lattice), plus the dislocation pairs of the DEFECT_LAYERS lattices
    (ripple_defects) in `defects` of their cells; height = amplitude x weight x (1 - variation g) x
    (1 - flatten) x keep x sin(phase), flatten 1 where a foot trampled them, keep the flattening
    toward the defects' cores.
    The normal tilts by the height's gradient through the phase; the slow change of amplitude and
    weight is left out (0.2 degrees of a 13 degree tilt at the defaults, tests/test_ripples.py).
    """
    position = np.asarray(position, np.float64)
    normal = _unit(normal)
    direction = wind_direction(wind)[:2]
    k = 2 * np.pi / wavelength
    m, g, dm = ripple_lattice(position, meander_scale)
    phase = k * (position[..., 0] * direction[0] + position[..., 1] * direction[1]) + \
        2 * np.pi * meander * (2.0 * m - 1.0)
    phase_gradient = k * direction + 4 * np.pi * meander * dm
    keep, keep_gradient = np.ones(phase.shape), np.zeros(phase.shape + (2,))
    for offset, layer in DEFECT_LAYERS:
        shift, bend, kept, kept_gradient = ripple_defects(position, direction, wavelength, defects, offset,
                                                          layer)
        phase, phase_gradient = phase + shift, phase_gradient + bend
        keep_gradient = keep_gradient * kept[..., None] + keep[..., None] * kept_gradient
        keep = keep * kept
    size = amplitude * ripple_weight(normal, wind, steep_fraction, lee_fraction) * (1.0 - variation * g) * \
        (1.0 - np.asarray(flatten, np.float64))
    height = size * keep * np.sin(phase)
    gradient = np.zeros(position.shape)
    gradient[..., :2] = (size * keep * np.cos(phase))[..., None] * phase_gradient + \
        (size * np.sin(phase))[..., None] * keep_gradient
    along = np.sum(gradient * normal, axis=-1, keepdims=True)
    return height, _unit(normal - (gradient - along * normal))
