"""Quality presets: render settings chosen from measured time-vs-error curves (bench/quality.py).

Each preset is a dict of Cycles settings. BLENDER_DEFAULTS holds what a new 5.2 scene uses,
for the comparison the bench draws. See bench/RESULTS.md ("Quality") for the curves.

Every preset names its sampling pattern: a new scene gets Tabulated Sobol in Blender 5.0 and
Automatic in 5.2, so without it the same build would render other noise on each version.
"""

BLENDER_DEFAULTS = {
    "samples": 4096, "use_adaptive_sampling": True, "adaptive_threshold": 0.01, "use_denoising": True,
    "volume_biased": False, "volume_step_rate": 1.0, "dicing_rate": 1.0, "max_bounces": 12,
    "volume_bounces": 0, "sampling_pattern": "AUTOMATIC", "pixel_filter_type": "BLACKMAN_HARRIS",
    "filter_width": 1.5,
}

# Chosen from the time-versus-error curves of bench/quality.py; the figures are in the README
# ("Quality presets") and bench/RESULTS.md ("Quality"), not here, where they would drift. Why each
# part: ray-marched volumes with the tree's denoising of all but the glints lie lowest at few
# samples; past them their step bias takes over, and unbiased volumes, which pay a fixed
# majorant-grid cost per render, with adaptive sampling and Cycles' denoiser (the tree then takes
# the sparkles from its noisy image) lie lowest (Final); volume bounces are for clouds, whose light
# grows with bounces up to about 128 (bench/clouds.py), and the total cap (max_bounces) must let
# them run. The pixel filter stays Blender's: at half a pixel (SHARP_FILTER, an option of the
# operator) every sample stays in its pixel and the glint splat's sparkles converge four times
# faster, but the denoised frame lies further from its own sharper reference (bench/RESULTS.md,
# "Pixel filter and the presets"). Cycles spreads a Blackman-Harris filter over twice its width:
# at 1.5 px two in five of a pixel's samples land in its neighbours.
SHARP_FILTER = {"pixel_filter_type": "BLACKMAN_HARRIS", "filter_width": 0.5}
_RAW_RAY_MARCHED = {"use_adaptive_sampling": False, "adaptive_threshold": 0.0, "use_denoising": False,
                    "volume_biased": True, "volume_step_rate": 1.0, "dicing_rate": 1.0,
                    "sampling_pattern": "AUTOMATIC"}


def _preset(samples, volume_bounces, step_rate=1.0, denoise=True):
    return {"samples": samples, **_RAW_RAY_MARCHED, "volume_step_rate": step_rate,
            "volume_bounces": volume_bounces, "max_bounces": max(12, volume_bounces), DENOISE: denoise}


DENOISE = "denoise_but_glints"  # not a Cycles setting: the post-effects tree's denoising
_UNBIASED_ADAPTIVE = {"use_adaptive_sampling": True, "adaptive_threshold": 0.01, "use_denoising": True,
                      "volume_biased": False, "volume_step_rate": 1.0, "dicing_rate": 1.0,
                      "sampling_pattern": "AUTOMATIC"}
PRESETS = {"DRAFT": _preset(16, 16), "PREVIEW": _preset(72, 64),
           "FINAL": {"samples": 512, **_UNBIASED_ADAPTIVE, "volume_bounces": 128, "max_bounces": 128,
                     DENOISE: True}}


# EEVEE's own, chosen from bench/eevee_quality.py's curves (bench/RESULTS.md, "EEVEE quality"):
# render samples (EEVEE's anti-aliasing, soft shadows and volume jitter all converge with them)
# and the volume froxels' size in pixels. The finest froxels (2 px) cost the demo little time and
# lowered its error at every sample count measured, so every preset has them.
# Clamp Surface Indirect off: at EEVEE's 10 the world's light is scaled down whenever lit sand
# (our world's light from below, addon/sky_eevee.py) is brighter than that.
# The froxels' depth slices fully exponential: EEVEE spreads them over every volume in view, and
# at Blender's 0.8, near linear, a layer reaching kilometres (clouds, far haze) left the slices by
# the camera tens of metres deep: dust metres off was smeared through them (the demo's walker
# veiled grey; tests/test_eevee_froxel_depth.py). Twice the slices where time allows.
# Volume shadows off: the cloud grid carries its own sun's light (addon/cloud_sunlight.py), which
# EEVEE's shadows would take twice; theirs end at the view's frustum (clouds lit from behind the
# camera unshaded) and let the far haze dim the dust's sun (tests/test_eevee_cloud_shading.py).
_EEVEE_COMMON = {"volumetric_tile_size": "2", "clamp_surface_indirect": 0.0,
                 "volumetric_sample_distribution": 1.0, "use_volumetric_shadows": False}
EEVEE_PRESETS = {"DRAFT": {"taa_render_samples": 16, "volumetric_samples": 64, **_EEVEE_COMMON},
                 "PREVIEW": {"taa_render_samples": 64, "volumetric_samples": 128, **_EEVEE_COMMON},
                 "FINAL": {"taa_render_samples": 128, "volumetric_samples": 128, **_EEVEE_COMMON}}


def apply_eevee(scene, settings):
    """Set EEVEE settings of a preset (or any dict of scene.eevee's keys) on the scene."""
    for key, value in settings.items():
        setattr(scene.eevee, key, value)


def apply(scene, settings):
    """Set the Cycles settings of a preset (or any dict of the same keys) on the scene, and the
    compositor's denoising of all but the glints when the preset names it."""
    for key, value in settings.items():
        if key != DENOISE:
            setattr(scene.cycles, key, value)
    if DENOISE in settings:
        from . import post  # bpy-heavy; presets stay importable for the bench's tables

        post.set_denoise(scene, settings[DENOISE])
