"""Blender's white-noise hash (Bob Jenkins' lookup3, as in Cycles' util/hash.h) in numpy.

The White Noise Texture node hashes the *bit patterns* of its float inputs, so the
twin reinterprets float32 as uint32 and runs the same integer mixing on arrays.
"""

import numpy as np

_U32 = np.uint32
# float(n) * (1 / 0xFFFFFFFF) in float32, the way Cycles maps a hash to [0, 1].
_UINT_TO_UNIT = np.float32(1.0 / 0xFFFFFFFF)


def _rot(x, k):
    return (x << _U32(k)) | (x >> _U32(32 - k))


def _mix(a, b, c):
    a = a - c; a = a ^ _rot(c, 4); c = c + b  # noqa: E702 (one lookup3 line per row)
    b = b - a; b = b ^ _rot(a, 6); a = a + c  # noqa: E702
    c = c - b; c = c ^ _rot(b, 8); b = b + a  # noqa: E702
    a = a - c; a = a ^ _rot(c, 16); c = c + b  # noqa: E702
    b = b - a; b = b ^ _rot(a, 19); a = a + c  # noqa: E702
    c = c - b; c = c ^ _rot(b, 4); b = b + a  # noqa: E702
    return a, b, c


def _final(a, b, c):
    c = c ^ b; c = c - _rot(b, 14)  # noqa: E702
    a = a ^ c; a = a - _rot(c, 11)  # noqa: E702
    b = b ^ a; b = b - _rot(a, 25)  # noqa: E702
    c = c ^ b; c = c - _rot(b, 16)  # noqa: E702
    a = a ^ c; a = a - _rot(c, 4)  # noqa: E702
    b = b ^ a; b = b - _rot(a, 14)  # noqa: E702
    c = c ^ b; c = c - _rot(b, 24)  # noqa: E702
    return a, b, c


def _start(*keys):
    """Keys as broadcast uint32 arrays, and lookup3's initial a = b = c for that many words."""
    keys = np.broadcast_arrays(*(np.asarray(k, dtype=_U32) for k in keys))
    start = np.full(keys[0].shape, (0xDEADBEEF + (len(keys) << 2) + 13) & 0xFFFFFFFF, dtype=_U32)
    return keys, start, start.copy(), start.copy()


def hash_uint(kx):
    (kx,), a, b, c = _start(kx)
    with np.errstate(over="ignore"):
        a = a + kx
        return _final(a, b, c)[2]


def hash_uint2(kx, ky):
    (kx, ky), a, b, c = _start(kx, ky)
    with np.errstate(over="ignore"):
        b = b + ky
        a = a + kx
        return _final(a, b, c)[2]


def hash_uint3(kx, ky, kz):
    (kx, ky, kz), a, b, c = _start(kx, ky, kz)
    with np.errstate(over="ignore"):
        c = c + kz
        b = b + ky
        a = a + kx
        return _final(a, b, c)[2]


def hash_uint4(kx, ky, kz, kw):
    (kx, ky, kz, kw), a, b, c = _start(kx, ky, kz, kw)
    with np.errstate(over="ignore"):
        a = a + kx
        b = b + ky
        c = c + kz
        a, b, c = _mix(a, b, c)
        a = a + kw
        return _final(a, b, c)[2]


def float_bits(x):
    """The uint32 bit pattern of float32 values (what Cycles' __float_as_uint does)."""
    return np.ascontiguousarray(x, dtype=np.float32).view(_U32)


def uint_to_unit(n):
    return n.astype(np.float32) * _UINT_TO_UNIT


def white_noise_3d(vector):
    """Value output of the White Noise Texture node in 3D mode; vector has shape (..., 3)."""
    v = float_bits(vector)
    return uint_to_unit(hash_uint3(v[..., 0], v[..., 1], v[..., 2]))


def white_noise_4d(vector, w):
    """Value output of the White Noise Texture node in 4D mode (vector (..., 3), scalar or array w)."""
    v = float_bits(vector)
    wb = np.broadcast_to(float_bits(np.asarray(w, dtype=np.float32)), v.shape[:-1])
    return uint_to_unit(hash_uint4(v[..., 0], v[..., 1], v[..., 2], wb))


def white_noise_1d_color(w):
    """Color output of the White Noise Texture node in 1D mode: (hash(w), hash(w, 1), hash(w, 2))."""
    wb = float_bits(np.asarray(w, dtype=np.float32))
    one, two = float_bits(np.float32(1.0)), float_bits(np.float32(2.0))
    return np.stack([uint_to_unit(hash_uint(wb)), uint_to_unit(hash_uint2(wb, one)),
                     uint_to_unit(hash_uint2(wb, two))], axis=-1)


def white_noise_4d_color(vector, w):
    """Color output of the White Noise Texture node in 4D mode: the 4D hash of (x, y, z, w),
    (z, x, w, y) and (w, z, y, x), as Cycles' hash_float4_to_color."""
    v = float_bits(vector)
    wb = np.broadcast_to(float_bits(np.asarray(w, dtype=np.float32)), v.shape[:-1])
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    return np.stack([uint_to_unit(hash_uint4(x, y, z, wb)), uint_to_unit(hash_uint4(z, x, wb, y)),
                     uint_to_unit(hash_uint4(wb, z, y, x))], axis=-1)
