"""Operators for the atmosphere: sun, sky and Rayleigh-scattering dust (scene.sandscape_atmosphere)."""

import math

import bpy

from ..blender import atmosphere
from ..core import atmosphere as air
from ..core import post


class SANDSCAPE_OT_add_atmosphere(bpy.types.Operator):
    """Add or update a sun, a matching sky and a Rayleigh-scattering dust volume around the scene"""

    bl_idname = "sandscape.add_atmosphere"
    bl_label = "Add Atmosphere"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        settings = context.scene.sandscape_atmosphere
        problem = _problem(settings)
        if problem:
            self.report({"ERROR"}, problem)
            return {"CANCELLED"}
        done = atmosphere.apply(context.scene, settings)
        beta = ", ".join(f"{b:.4g}" for b in done["coefficients"])
        volume = f"dust box '{done['volume'].name}'" if done["volume"] else "no volume (density 0)"
        replaced = (f"; world '{done['replaced'].name}' kept with a fake user (switch back in World "
                    "properties)" if done["replaced"] else "")
        marching = "; volume ray marching on (biased, faster)" if context.scene.cycles.volume_biased else ""
        self.report({"INFO"}, f"Sun '{done['sun'].name}', sky '{done['world'].name}', {volume}, "
                    f"scattering {beta} 1/m{replaced}{marching}")
        return {"FINISHED"}


def _problem(settings):
    try:
        air.rayleigh_coefficients(settings.density, tuple(settings.wavelengths))
    except air.AtmosphereError as error:
        return str(error).capitalize()
    if not (math.isfinite(settings.sun_elevation) and math.isfinite(settings.sun_azimuth)):
        return "Sun elevation and azimuth must be numbers"
    if not settings.margin >= 0:
        return f"Margin must be 0 or more, got {settings.margin:g}"
    if not (math.isfinite(settings.dust_density) and settings.dust_density >= 0):
        return f"Dust must be 0 or more, got {settings.dust_density:g}"
    if not -1 < settings.anisotropy < 1:
        return f"Anisotropy must lie in (-1, 1), got {settings.anisotropy:g}"
    if settings.use_wind and not (settings.dust_scale > 0 and settings.falloff > 0 and settings.softness > 0):
        return "Patch size, softness and height falloff must be greater than 0"
    return None


class SANDSCAPE_OT_add_post_effects(bpy.types.Operator):
    """Add or update the compositor: gated blur of the scattered light and god rays towards the sun"""

    bl_idname = "sandscape.add_post_effects"
    bl_label = "Add Post Effects"
    bl_options = {"REGISTER", "UNDO"}

    def execute(self, context):
        scene = context.scene
        settings = scene.sandscape_post
        problem = _post_problem(scene, settings)
        if problem:
            self.report({"ERROR"}, problem)
            return {"CANCELLED"}
        done = atmosphere.apply_post_effects(scene, settings)
        switches = (("gated blur", settings.use_blur), ("god rays", settings.use_god_rays))
        effects = [name for name, on in switches if on] or ["none"]
        replaced = f"; compositor '{done['replaced'].name}' kept with a fake user" if done["replaced"] else ""
        keyed = f", sun keyed on {len(done['curve'])} frames" if done["curve"] else ""
        keyed += "; render engine set to Cycles (the passes are Cycles')" if done["switched_engine"] else ""
        self.report({"INFO"}, f"Post effects: {', '.join(effects)}{keyed}{replaced}")
        if settings.use_blur and scene.cycles.use_denoising:
            # The volume passes are not denoised: the combined image minus a noisy pass shows specks.
            self.report({"WARNING"}, "Render denoising is on: the gated blur swaps noisy scattered light "
                        "into a denoised image. Switch denoising off, or the blur")
        return {"FINISHED"}


def _post_problem(scene, settings):
    if settings.use_god_rays:
        if scene.camera is None:
            return "The scene has no camera: god rays need one to place the sun on screen"
        if atmosphere.scene_sun(scene) is None:
            return "No sun lamp: run Add Atmosphere first, or add a sun"
        try:
            post.check_rays(settings.samples, settings.ray_density, settings.ray_weight, settings.ray_decay,
                            settings.ray_exposure)
        except post.PostError as error:
            return str(error).capitalize()
        if not settings.disc_radius > 0:
            return f"Sun disc must be greater than 0, got {settings.disc_radius:g}"
    if settings.use_blur and not settings.blur_threshold >= 0:
        return f"Blur threshold must be 0 or more, got {settings.blur_threshold:g}"
    return None


classes = (SANDSCAPE_OT_add_atmosphere, SANDSCAPE_OT_add_post_effects)
