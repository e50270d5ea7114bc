"""A sparkle stays in its own pixel through the compositor: Blender's 1.5 px pixel filter hands
two in five of the samples that see a one-pixel sparkle to the pixels beside it (a plus of four
arms, 0.16 of its light each by the filter's integral), and the post-effects tree moves that light
back into the sparkle's pixel, keeping the frame's light."""

import bpy
import numpy as np

from devtools import readback, sparkles

RESOLUTION = (320, 180)
BLENDER_FILTER = 1.5  # px, the presets' own


def isolated_cores(level, bar=8.0):
    """Sparkles' own pixels: over `bar` times the 5x5 median and the brightest of the 5x5, away
    from the frame's edge (their arms then belong to them alone)."""
    h, w = level.shape
    padded = np.pad(level, 2, mode="edge")
    windows = np.stack([padded[dy:dy + h, dx:dx + w] for dy in range(5) for dx in range(5)])
    ground = np.median(windows, axis=0)
    cores = (level >= windows.max(0)) & (level > bar * ground)
    cores[:2, :] = cores[-2:, :] = cores[:, :2] = cores[:, -2:] = False
    return cores, ground


def straddling_pairs(level, bar=8.0, twin_share=0.35):
    """Grains that straddle two pixels: the brightest of their 5x5 with a side neighbour at least
    `twin_share` as bright (a centred one-pixel sparkle's arm is about 0.27 of it), together over
    `bar` times the 5x5 median, and nothing else of the 5x5 over 0.4 of the brighter (not a blob,
    not an edge). [(y, x, y2, x2)], away from the frame's edge."""
    h, w = level.shape
    padded = np.pad(level, 2, mode="edge")
    windows = np.stack([padded[dy:dy + h, dx:dx + w] for dy in range(5) for dx in range(5)])
    ground = np.median(windows, axis=0)
    pairs = []
    for y, x in zip(*np.nonzero(level >= windows.max(0)), strict=True):
        if not (3 <= y < h - 3 and 3 <= x < w - 3):
            continue
        sides = [(level[y + dy, x + dx], y + dy, x + dx) for dy, dx in ((-1, 0), (1, 0), (0, -1), (0, 1))]
        twin, y2, x2 = max(sides)
        window = level[y - 2:y + 3, x - 2:x + 3].copy()
        window[2, 2] = window[2 + y2 - y, 2 + x2 - x] = 0.0
        if twin >= twin_share * level[y, x] and level[y, x] + twin > bar * ground[y, x] \
                and window.max() < 0.4 * level[y, x]:
            pairs.append((y, x, y2, x2))
    return pairs, ground


def pair_arm_share(level, pairs, ground):
    """The light over the ground of the six pixels beside a straddling pair against all of its
    light over the ground in the 3x4 round it (the median over the pairs)."""
    shares = []
    for y, x, y2, x2 in pairs:
        box = {(y + dy, x + dx) for dy in (-1, 0, 1) for dx in (-1, 0, 1)} | \
            {(y2 + dy, x2 + dx) for dy in (-1, 0, 1) for dx in (-1, 0, 1)}
        beside = {(a + dy, b + dx) for a, b in ((y, x), (y2, x2))
                  for dy, dx in ((-1, 0), (1, 0), (0, -1), (0, 1))} - {(y, x), (y2, x2)}
        g = ground[y, x]
        shares.append(sum(level[p] - g for p in beside) / sum(level[p] - g for p in box))
    return float(np.median(shares))


def arm_share(level, cores, ground):
    """The light over the ground of the four pixels beside each sparkle's own, against all of its
    light over the ground in its 3x3 (the median over the sparkles)."""
    y, x = np.nonzero(cores)
    over = level - ground
    arms = over[y - 1, x] + over[y + 1, x] + over[y, x - 1] + over[y, x + 1]
    whole = sum(over[y + dy, x + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1))
    return float(np.median(arms / whole))


def test_sparkles_keep_to_their_own_pixel_through_the_compositor(sandscape):
    scene = sparkles.sparkling_sand(sandscape, RESOLUTION, True, 16, 0)
    scene.cycles.filter_width = BLENDER_FILTER
    post = scene.sandscape_post
    post.use_blur = post.use_god_rays = False
    assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}
    scene.render.use_compositing = False
    raw = readback.render(scene)[..., :3].astype(np.float64).mean(-1)
    scene.render.use_compositing = True
    ours = readback.render(scene)[..., :3].astype(np.float64).mean(-1)
    cores, ground = isolated_cores(raw)
    before, after = arm_share(raw, cores, ground), arm_share(ours, cores, ground)
    light = ours[cores].sum() / raw[cores].sum()
    frame = ours.mean() / raw.mean()
    # The pixels beside a sparkle are not taken below the sand round them: at Draft's 16 samples
    # they came out as dark specks before the take was capped by what each stands over its ground
    # (here 7 of the 68 under 0.9x the 5x5 median against raw's 1; capped, none).
    y, x = np.nonzero(cores)

    def dark_beside(pixels):
        beside = np.stack([pixels[y - 1, x], pixels[y + 1, x], pixels[y, x - 1], pixels[y, x + 1]])
        return int((beside < 0.9 * ground[y, x]).sum())

    dark, raw_dark = dark_beside(ours), dark_beside(raw)
    # A grain that straddles two pixels is gathered too: the eight neighbours held its twin, and
    # until the ring round the 3x3 judged a sparkle alone its arms stayed (the sixteenth review).
    # At 0.35 (not 0.5) enough pairs for a median on 5.0 too: 15 on 5.2, 6 on 5.0 (2 at 0.5).
    pairs, pair_ground = straddling_pairs(raw)
    pair_before = pair_arm_share(raw, pairs, pair_ground)
    pair_after = pair_arm_share(ours, pairs, pair_ground)
    print(f"{len(pairs)} straddling pairs: the six pixels beside each hold {pair_before:.3f} of the "
          f"light round it raw, {pair_after:.3f} composited")
    print(f"{cores.sum()} sparkles: the four pixels beside each hold {before:.3f} of its 3x3's light "
          f"raw, {after:.3f} composited; its own pixel {light:.2f}x raw; frame {frame:.4f}x; "
          f"{dark} pixels beside them under 0.9x the sand composited, {raw_dark} raw")
    assert cores.sum() >= 15
    # Raw, the filter's arms are there (the integral gives 0.36 to the four, 0.06 to the corners);
    # composited, under half of them stays (measured 0.339 and 0.124 on 5.2: what stays is the
    # denoiser's smear of the sparkle, which no glint pass holds).
    assert before > 0.25
    assert after < 0.16
    # Their light went into the sparkle's pixel, not away: the frame keeps its light.
    assert light > 1.2
    assert abs(frame - 1.0) < 0.02
    assert dark <= raw_dark + 2
    # Measured 0.228 -> 0.058 on 5.2, 0.280 -> 0.047 on 5.0; judged alone against its eight
    # neighbours, 0.228 -> 0.151 (0.66x).
    assert len(pairs) >= 4
    assert pair_before > 0.2
    assert pair_after < 0.45 * pair_before
