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
