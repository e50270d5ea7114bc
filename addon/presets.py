"""Quality presets: render settings chosen from measured time-vs-error curves (bench/quality.py).

Each preset is a dict of Cycles settings. BLENDER_DEFAULTS holds what a new 5.0 scene uses,
for the comparison the bench draws. See bench/RESULTS.md ("Quality") for the curves.
"""

BLENDER_DEFAULTS = {
    "samples": 4096, "use_adaptive_sampling": True, "adaptive_threshold": 0.01, "use_denoising": True,
    "volume_biased": False, "volume_step_rate": 1.0, "dicing_rate": 1.0, "max_bounces": 12,
}

# Chosen from the curves of bench/quality.py (demo frame 150, 240x135, 2 cores), where Blender's
# defaults took 38.4 s for RMSE 0.160: OIDN smears the glints, so its error floor stays near 0.16
# at any sample count, while raw samples with volume ray marching keep falling.
#   draft:   the cheapest row at or below the defaults' error: 32 spp, raw, ray march (2.8 s, 0.116)
#   preview: 64 spp, raw, ray march (4.8 s, 0.073)
#   final:   256 spp, raw, ray march (16.4 s, 0.031)
# The other knobs keep Blender's values: moved alone around preview, adaptive thresholds stayed on
# the raw curve, dicing 0.5-4 and 2-8 bounces changed time under 3 %, a step rate of 4 saved 7 %.
_RAW_RAY_MARCHED = {"use_adaptive_sampling": False, "adaptive_threshold": 0.0, "use_denoising": False,
                    "volume_biased": True, "volume_step_rate": 1.0, "dicing_rate": 1.0, "max_bounces": 12}
PRESETS = {
    "DRAFT": {"samples": 32, **_RAW_RAY_MARCHED},
    "PREVIEW": {"samples": 64, **_RAW_RAY_MARCHED},
    "FINAL": {"samples": 256, **_RAW_RAY_MARCHED},
}


def apply(scene, settings):
    """Set the Cycles settings of a preset (or any dict of the same keys) on the scene."""
    for key, value in settings.items():
        setattr(scene.cycles, key, value)
