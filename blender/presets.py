"""Quality presets: render settings chosen from measured time-vs-error curves (bench/quality.py).

Each preset is a dict of Cycles settings. BLENDER_DEFAULTS holds what a new 5.2 scene uses,
for the comparison the bench draws. See bench/RESULTS.md ("Quality") for the curves.

Every preset names its sampling pattern: a new scene gets Tabulated Sobol in Blender 5.0 and
Automatic in 5.2, so without it the same build would render other noise on each version.
"""

BLENDER_DEFAULTS = {
    "samples": 4096, "use_adaptive_sampling": True, "adaptive_threshold": 0.01, "use_denoising": True,
    "volume_biased": False, "volume_step_rate": 1.0, "dicing_rate": 1.0, "max_bounces": 12,
    "volume_bounces": 0, "sampling_pattern": "AUTOMATIC",
}

# Chosen from the curves of bench/quality.py (bench/RESULTS.md, "Quality", 2026-11-23: the demo's
# frame 150 at 160x90 through its compositor, 2 cores; RMSE clipped at the display's white against
# a 1024-sample unbiased reference, its own noise taken out). Ray-marched volumes with the tree's
# denoising of all but the glints lie lowest until their step bias (about 0.045 at step rate 1)
# takes over; unbiased volumes cost about 33 s a render whatever the samples (Cycles builds
# their majorant grid), which sets the floor of Blender's defaults on this scene:
#   draft:   16 spp  (1.8 s, 0.064)
#   preview: 72 spp  (5.2 s, 0.049; 72 rather than 64 for the noise a viewer sees: σ 0.0047 at
#            320x180, "Quality, noise rows")
#   final:   256 spp at step rate 0.25 (27.0 s, 0.033; at step rate 1 it stopped at 0.045)
# Blender's defaults take 34-37 s from 1 to 64 spp (0.108 to 0.030) and 0.0094 at 4096 in 361 s:
# 3x faster than them means under 12 s, which ray marching reaches only above an RMSE of 0.05. Unbiased
# volumes with our denoising matched Cycles' own at 64 and 256 spp (0.031 and 0.018): on RMSE
# the route buys nothing, what it buys is glints OIDN does not smear (tests/test_denoise_but_glints.py).
# Volume bounces are for clouds (bench/clouds.py, "Clouds"): their light grows with bounces up to
# about 128, 0.5 % short of 512 (2.3x the time of 4 bounces); 64 is 3.3 % short, 16 is 16 %.
# Thin dust ends its paths long before, so without clouds the bounces cost next to nothing. The
# total cap (max_bounces, 12 by default) must let them run.
_RAW_RAY_MARCHED = {"use_adaptive_sampling": False, "adaptive_threshold": 0.0, "use_denoising": False,
                    "volume_biased": True, "volume_step_rate": 1.0, "dicing_rate": 1.0,
                    "sampling_pattern": "AUTOMATIC"}


def _preset(samples, volume_bounces, step_rate=1.0, denoise=True):
    return {"samples": samples, **_RAW_RAY_MARCHED, "volume_step_rate": step_rate,
            "volume_bounces": volume_bounces, "max_bounces": max(12, volume_bounces), DENOISE: denoise}


DENOISE = "denoise_but_glints"  # not a Cycles setting: the post-effects tree's denoising
PRESETS = {"DRAFT": _preset(16, 16), "PREVIEW": _preset(72, 64), "FINAL": _preset(256, 128, step_rate=0.25)}


def apply(scene, settings):
    """Set the Cycles settings of a preset (or any dict of the same keys) on the scene, and the
    compositor's denoising of all but the glints when the preset names it."""
    for key, value in settings.items():
        if key != DENOISE:
            setattr(scene.cycles, key, value)
    if DENOISE in settings:
        from . import post  # bpy-heavy; presets stay importable for the bench's tables

        post.set_denoise(scene, settings[DENOISE])
