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

# Chosen from the curves of bench/quality.py (demo frame 150, 240x135, 2 cores; RMSE clipped at
# the display's white). Blender's defaults took 65.8 s for RMSE 0.039; the same settings at fewer
# samples are the curve a preset is held against. Raw samples with ray-marched volumes lie lowest:
#   draft:   32 spp (2.8 s, 0.134; the defaults need 7.1 s for that error)
#   preview: 64 spp (5.0 s, 0.093; the defaults need 10.0 s)
#   final:   384 spp (27.3 s, 0.039: the shipped defaults' own error, 2.4x faster)
# The other knobs keep Blender's values: moved alone around preview, adaptive thresholds and the
# volume step rate stayed on the samples curve, and dicing 0.5-4 and 2-8 bounces changed < 2 %.
# Volume bounces are for clouds (bench/clouds.py, "Clouds"): their light grows with bounces up to
# about 128, 0.5 % short of 512 (2.3x the time of 4 bounces); 64 is 3.3 % short, 16 is 16 %.
# Thin dust ends its paths long before, so without clouds the bounces cost next to nothing. The
# total cap (max_bounces, 12 by default) must let them run.
_RAW_RAY_MARCHED = {"use_adaptive_sampling": False, "adaptive_threshold": 0.0, "use_denoising": False,
                    "volume_biased": True, "volume_step_rate": 1.0, "dicing_rate": 1.0,
                    "sampling_pattern": "AUTOMATIC"}


def _preset(samples, volume_bounces, denoise=True):
    return {"samples": samples, **_RAW_RAY_MARCHED, "volume_bounces": volume_bounces,
            "max_bounces": max(12, volume_bounces), DENOISE: denoise}


DENOISE = "denoise_but_glints"  # not a Cycles setting: the post-effects tree's denoising
PRESETS = {"DRAFT": _preset(16, 16), "PREVIEW": _preset(64, 64), "FINAL": _preset(256, 128)}


def apply(scene, settings):
    """Set the Cycles settings of a preset (or any dict of the same keys) on the scene, and the
    compositor's denoising of all but the glints when the preset names it."""
    for key, value in settings.items():
        if key != DENOISE:
            setattr(scene.cycles, key, value)
    if DENOISE in settings:
        from . import post  # bpy-heavy; presets stay importable for the bench's tables

        post.set_denoise(scene, settings[DENOISE])
