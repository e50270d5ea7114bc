"""Blender's Noise Texture (Perlin fBM) and Voronoi Texture (F1, Euclidean) in numpy.

The clouds are built from these two nodes, so their twins are needed to check the cloud
group by bake and to find, before rendering, where the weather map has cloud. Each follows
Cycles' kernel (svm/noise.h, svm/fractal_noise.h, svm/voronoi.h): the same integer hashes on
the lattice cells (Jenkins for Perlin, PCG for Voronoi), the same gradients, fade curve and
scale factors, in float32.
"""

import numpy as np

from .noise_hash import hash_uint2, hash_uint3

_F = np.float32
NOISE_SCALE_2D, NOISE_SCALE_3D = _F(0.6616), _F(0.9820)  # Cycles' noise_scale2 / noise_scale3
PERIOD = _F(100000.0)  # Cycles repeats Perlin noise every 1e5 to keep float precision


def _fade(t):
    return t * t * t * (t * (t * _F(6.0) - _F(15.0)) + _F(10.0))


def _cell(x):
    """floorfrac: the lattice cell as uint32 bits of the int, and the fraction."""
    floor = np.floor(x)
    return floor.astype(np.int32).view(np.uint32), (x - floor).astype(_F)


def _negate_if(value, flag):
    return np.where(flag != 0, -value, value)


def _grad2(hashed, x, y):
    h = hashed & np.uint32(7)
    u = np.where(h < 4, x, y)
    v = _F(2.0) * np.where(h < 4, y, x)
    return _negate_if(u, h & np.uint32(1)) + _negate_if(v, h & np.uint32(2))


def _grad3(hashed, x, y, z):
    h = hashed & np.uint32(15)
    u = np.where(h < 8, x, y)
    vt = np.where((h == 12) | (h == 14), x, z)
    v = np.where(h < 4, y, vt)
    return _negate_if(u, h & np.uint32(1)) + _negate_if(v, h & np.uint32(2))


def _mix(a, b, t):
    return (_F(1.0) - t) * a + t * b


def perlin_2d(x, y):
    """Signed Perlin noise in 2D, roughly -1..1 (snoise_2d)."""
    x, y = (np.fmod(np.asarray(v, _F), PERIOD) for v in (x, y))
    cx, fx = _cell(x)
    cy, fy = _cell(y)
    one = np.uint32(1)
    with np.errstate(over="ignore"):
        g00 = _grad2(hash_uint2(cx, cy), fx, fy)
        g10 = _grad2(hash_uint2(cx + one, cy), fx - _F(1), fy)
        g01 = _grad2(hash_uint2(cx, cy + one), fx, fy - _F(1))
        g11 = _grad2(hash_uint2(cx + one, cy + one), fx - _F(1), fy - _F(1))
    u, v = _fade(fx), _fade(fy)
    return NOISE_SCALE_2D * _mix(_mix(g00, g10, u), _mix(g01, g11, u), v)


def perlin_3d(x, y, z):
    """Signed Perlin noise in 3D, roughly -1..1 (snoise_3d)."""
    x, y, z = (np.fmod(np.asarray(v, _F), PERIOD) for v in (x, y, z))
    (cx, fx), (cy, fy), (cz, fz) = _cell(x), _cell(y), _cell(z)
    corners = {}
    with np.errstate(over="ignore"):
        for i in (0, 1):
            for j in (0, 1):
                for k in (0, 1):
                    hashed = hash_uint3(cx + np.uint32(i), cy + np.uint32(j), cz + np.uint32(k))
                    corners[i, j, k] = _grad3(hashed, fx - _F(i), fy - _F(j), fz - _F(k))
    u, v, w = _fade(fx), _fade(fy), _fade(fz)

    def row(j, k):
        return _mix(corners[0, j, k], corners[1, j, k], u)
    return NOISE_SCALE_3D * _mix(_mix(row(0, 0), row(1, 0), v), _mix(row(0, 1), row(1, 1), v), w)


def fbm(signed_noise, points, detail, roughness=0.5, lacunarity=2.0):
    """The Noise Texture's Fac in fBM mode, normalised to about 0..1, at points (..., n) already
    multiplied by the node's Scale. signed_noise: perlin_2d or perlin_3d."""
    points = np.asarray(points, _F)
    scale, amplitude, top, total = _F(1.0), _F(1.0), _F(0.0), np.zeros(points.shape[:-1], _F)
    for _ in range(int(detail) + 1):
        total = total + signed_noise(*np.moveaxis(scale * points, -1, 0)) * amplitude
        top = top + amplitude
        amplitude = amplitude * _F(roughness)
        scale = scale * _F(lacunarity)
    rest = _F(detail - np.floor(detail))
    value = _F(0.5) * total / top + _F(0.5)
    if rest != 0:
        more = total + signed_noise(*np.moveaxis(scale * points, -1, 0)) * amplitude
        value = _mix(value, _F(0.5) * more / (top + amplitude) + _F(0.5), rest)
    return value


def _pcg3d(x, y, z):
    """Cycles' hash_pcg3d_i on int32 lattice keys given as uint32 bits (wrapping arithmetic, the
    shift by 16 arithmetic as on signed ints)."""
    m, c = np.uint32(1664525), np.uint32(1013904223)
    with np.errstate(over="ignore"):
        x, y, z = x * m + c, y * m + c, z * m + c
        x = x + y * z
        y = y + z * x
        z = z + x * y
        x, y, z = (v ^ (v.view(np.int32) >> 16).view(np.uint32) for v in (x, y, z))
        x = x + y * z
        y = y + z * x
        z = z + x * y
    return (v & np.uint32(0x7FFFFFFF) for v in (x, y, z))


def _cell_point(cx, cy, cz):
    """hash_int3_to_float3: a feature point's offset inside its cell, 0..1 on each axis."""
    scale = _F(1.0) / _F(0x7FFFFFFF)
    return np.stack([v.astype(_F) * scale for v in _pcg3d(cx, cy, cz)], axis=-1)


def voronoi_f1(points, randomness=1.0):
    """The Voronoi Texture's Distance (F1, Euclidean, detail 0) at points (..., 3) already
    multiplied by the node's Scale."""
    points = np.asarray(points, _F)
    floor = np.floor(points)
    local = (points - floor).astype(_F)
    cell = floor.astype(np.int32)
    nearest = np.full(points.shape[:-1], np.inf, _F)
    for k in (-1, 0, 1):
        for j in (-1, 0, 1):
            for i in (-1, 0, 1):
                offset = np.array([i, j, k], np.int32)
                key = (cell + offset).view(np.uint32)
                jitter = _cell_point(key[..., 0], key[..., 1], key[..., 2])
                point = offset.astype(_F) + jitter * _F(randomness)
                distance = np.sqrt(np.sum((point - local) ** 2, axis=-1, dtype=_F)).astype(_F)
                nearest = np.minimum(nearest, distance)
    return nearest
