"""Post effects in plain numpy: the luminance-gated blur and screen-space god rays.

Twins of the compositor groups "Sandscape Gated Blur" and "Sandscape God Rays". Images are
(height, width, channels) float arrays with row 0 at the bottom, like Blender's.

Gated blur (seed 000, section 4.2): a 3x3 Gaussian (centre 0.147761, edges 0.118318,
corners 0.0947416, normalised to sum 1) replaces a pixel only where the luminance of the
blurred and the original pixel differ by more than a threshold, so flat areas keep detail; and
not across the outline of what hides the sky (a guide image, the environment pass), so cloud
light is not smeared over the sky. Beyond the image the nearest edge pixel repeats.

God rays (seed 002, GPU Gems 3 ch. 13): for a pixel at uv and the sun at L, the seed sums
    rays(uv) = exposure * sum_{i=1..N} weight * decay^(i-1) * occlusion(uv - i * (uv - L) * density / N)
(god_rays_seed). The group sums M = 2^RAY_PASSES taps at the geometric scales r^j, r^M = 1 -
density, weighted c^(j-1) with c = r * decay^(N/M) and scaled to the seed's total weight, in
RAY_PASSES passes that each double the taps (god_rays): its node count does not grow with N.
Bilinear sampling reads 0 outside the image.
"""

import numpy as np

RAY_PASSES = 8  # 256 taps
MAX_DENSITY = 0.999  # the taps' span stops short of the sun itself (density 1 puts r at 0)
GAUSS_CENTRE, GAUSS_EDGE, GAUSS_CORNER = 0.147761, 0.118318, 0.0947416
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Rec. 709, Blender's linear scene luminance
# The blur stops where the sky seen changes by more than this share across 3x3 pixels: cloud
# light blurred over a cloud's outline made a bright one-pixel ring in the sky (bench/glow_ring.py).
EDGE = 0.1


class PostError(ValueError):
    """Parameters that would make the effect diverge or mean nothing."""


def gaussian_kernel():
    """The seed's 3x3 kernel, normalised to sum exactly 1 (the raw weights sum to 0.9999994)."""
    kernel = np.array([[GAUSS_CORNER, GAUSS_EDGE, GAUSS_CORNER],
                       [GAUSS_EDGE, GAUSS_CENTRE, GAUSS_EDGE],
                       [GAUSS_CORNER, GAUSS_EDGE, GAUSS_CORNER]])
    return kernel / kernel.sum()


def luminance(image):
    return np.asarray(image, dtype=np.float64)[..., :3] @ LUMINANCE


def blur3(image):
    """3x3 Gaussian with edge pixels repeated beyond the border."""
    image = np.asarray(image, dtype=np.float64)
    padded = np.pad(image, ((1, 1), (1, 1), (0, 0)), mode="edge")
    kernel = gaussian_kernel()
    height, width = image.shape[:2]
    out = np.zeros_like(image)
    for dy in range(3):
        for dx in range(3):
            out += kernel[dy, dx] * padded[dy:dy + height, dx:dx + width]
    return out


def guide_edges(guide, edge=EDGE):
    """Where the guide's luminance spans more than `edge` of its largest value over the 3x3
    neighbourhood (edge pixels repeated): an opaque outline, such as a cloud or the land against
    the sky in the environment pass. A black guide has none."""
    values = np.pad(luminance(guide), 1, mode="edge")
    height, width = values.shape[0] - 2, values.shape[1] - 2
    shifted = np.stack([values[dy:dy + height, dx:dx + width] for dy in range(3) for dx in range(3)])
    high = shifted.max(axis=0)
    return high - shifted.min(axis=0) > edge * high


def gated_blur(image, threshold, guide=None, edge=EDGE):
    """The blurred pixel where |L(blurred) - L(original)| > threshold and the guide has no edge
    (guide_edges), else the original."""
    image = np.asarray(image, dtype=np.float64)
    blurred = blur3(image)
    gate = np.abs(luminance(blurred) - luminance(image)) > threshold
    if guide is not None:
        gate &= ~guide_edges(guide, edge)
    return np.where(gate[..., None], blurred, image)


def sample_bilinear(image, u, v):
    """Bilinear samples at normalised (u, v) (pixel centres at (i + 0.5) / size); 0 outside."""
    height, width = image.shape[:2]
    x = np.asarray(u) * width - 0.5
    y = np.asarray(v) * height - 0.5
    x0, y0 = np.floor(x).astype(np.int64), np.floor(y).astype(np.int64)
    fx, fy = x - x0, y - y0
    out = 0.0
    for oy, wy in ((0, 1 - fy), (1, fy)):
        for ox, wx in ((0, 1 - fx), (1, fx)):
            xi, yi = x0 + ox, y0 + oy
            valid = (xi >= 0) & (xi < width) & (yi >= 0) & (yi < height)
            texel = image[np.clip(yi, 0, height - 1), np.clip(xi, 0, width - 1)]
            weight = np.where(valid, wx * wy, 0.0)
            out = out + texel * (weight[..., None] if texel.ndim > weight.ndim else weight)
    return out


def check_rays(samples, density, weight, decay, exposure):
    if int(samples) < 1:
        raise PostError(f"god rays need at least 1 sample, got {samples}")
    if not 0.0 <= decay <= 1.0:
        raise PostError(f"decay must lie in [0, 1] (above 1 the rays grow without bound), got {decay}")
    for name, value in (("density", density), ("weight", weight), ("exposure", exposure)):
        if not (np.isfinite(value) and value >= 0):
            raise PostError(f"{name} must be 0 or more, got {value}")


def god_rays_seed(occlusion, sun_uv, samples=32, density=0.9, weight=0.05, decay=0.97, exposure=1.0):
    """The seed's radial sum: N samples of the occlusion on the line to the sun (normalised screen
    position)."""
    check_rays(samples, density, weight, decay, exposure)
    occlusion = np.asarray(occlusion, dtype=np.float64)
    u, v = _pixel_uv(occlusion)
    out = 0.0
    for i in range(1, int(samples) + 1):
        scale = 1.0 - i * density / samples  # the sample sits at L + scale * (uv - L)
        su = sun_uv[0] + scale * (u - sun_uv[0])
        sv = sun_uv[1] + scale * (v - sun_uv[1])
        out = out + weight * decay ** (i - 1) * sample_bilinear(occlusion, su, sv)
    return exposure * out


def ray_taps(samples, density, weight, decay, passes=RAY_PASSES):
    """(r, c, first): tap j = 1..2^passes at scale r^j with weight first * c^(j-1), their sum the
    seed's total weight."""
    taps = 2 ** passes
    ratio = (1.0 - min(float(density), MAX_DENSITY)) ** (1.0 / taps)
    step = ratio * float(decay) ** (samples / taps)
    total = weight * (samples if decay > 1.0 - 1e-6 else (1.0 - decay ** samples) / (1.0 - decay))
    return ratio, step, total / sum(step ** j for j in range(taps))


def god_rays(occlusion, sun_uv, samples=32, density=0.9, weight=0.05, decay=0.97, exposure=1.0,
             passes=RAY_PASSES):
    """The group's rays: 2^passes geometric taps towards the sun, summed in `passes` passes that
    each add the image so far, sampled (bilinear) nearer the sun, to itself."""
    check_rays(samples, density, weight, decay, exposure)
    occlusion = np.asarray(occlusion, dtype=np.float64)
    u, v = _pixel_uv(occlusion)
    ratio, step, first = ray_taps(samples, density, weight, decay, passes)

    def towards_sun(image, scale):
        return sample_bilinear(image, sun_uv[0] + scale * (u - sun_uv[0]),
                               sun_uv[1] + scale * (v - sun_uv[1]))

    image = towards_sun(occlusion, ratio)
    for k in range(passes):
        image = image + step ** (2 ** k) * towards_sun(image, ratio ** (2 ** k))
    return exposure * first * image


def _pixel_uv(image):
    height, width = image.shape[:2]
    v, u = (np.indices((height, width)) + 0.5) / np.array([height, width])[:, None, None]
    return u, v


FRONT_EPSILON = 1e-9  # the sun is in front of the camera when its camera-space z is below minus this


def screen_position(view_projection, direction):
    """Normalised screen position (u, v) of a direction at infinity, and whether it is in front.

    view_projection: the camera's 4x4 projection @ view matrix.
    """
    clip = np.asarray(view_projection, dtype=np.float64) @ np.append(np.asarray(direction, float), 0.0)
    w = clip[3]
    if w <= 1e-12:
        return (np.nan, np.nan), False
    return ((clip[0] / w + 1.0) / 2.0, (clip[1] / w + 1.0) / 2.0), True


def sun_on_screen(direction, scale, shift, perspective, fade=0.25):
    """(u, v, intensity) of the sun for Sandscape Sun Screen (its twin).

    direction: the sun's direction in camera space (the camera looks down -Z); scale: the
    screen widths and heights one unit of x / -z and y / -z spans; shift: the camera's shift
    in the same units; perspective: 1 for a perspective camera (anything else gives no rays).
    """
    x, y, z = (float(c) for c in direction)
    in_front = perspective > 0.5 and z < -FRONT_EPSILON
    if not in_front:
        return 0.5, 0.5, 0.0
    depth = min(z, -FRONT_EPSILON)
    u = 0.5 + x / -depth * scale[0] - shift[0]
    v = 0.5 + y / -depth * scale[1] - shift[1]
    return u, v, sun_intensity((u, v), True, fade)


def sun_intensity(sun_uv, in_front, fade=0.25):
    """1 with the sun in the frame, easing to 0 at `fade` (screen widths) outside it; 0 behind."""
    if not in_front or not np.isfinite(sun_uv).all():
        return 0.0
    u, v = sun_uv
    outside = max(0.0, -u, u - 1.0, -v, v - 1.0)
    if fade <= 0:
        return float(outside == 0.0)
    t = min(outside / fade, 1.0)
    return float(1.0 - t * t * (3.0 - 2.0 * t))
