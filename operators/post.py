"""The post-effects operator: the gated blur and god rays in the scene's compositor."""

import bpy

from ..addon import atmosphere, post
from ..addon import post_passes as passes
from ..addon.settings import SandscapePostSettings
from ..core import post as post_twin
from .base import SandscapeOperator, has_camera, value_problem


def _camera_for_rays(context):
    return not context.scene.sandscape_post.use_god_rays or has_camera(context)


def _sun_for_rays(context):
    return not context.scene.sandscape_post.use_god_rays or atmosphere.scene_sun(context.scene) is not None


def settings_problem(scene, settings):
    if scene.render.engine not in passes.ENGINE_NAMES:
        return (f"Post effects read render passes that Cycles and EEVEE make; this scene renders with "
                f"{scene.render.engine.replace('BLENDER_', '').title()}: pick Cycles or EEVEE in Render "
                "properties")
    problem = value_problem(settings, SandscapePostSettings.LIMITS, scene)
    if problem or not settings.use_god_rays:
        return problem
    try:
        post_twin.check_rays(settings.samples, settings.ray_density, settings.ray_weight, settings.ray_decay,
                             settings.ray_exposure)
    except post_twin.PostError as error:
        return str(error).capitalize()
    return None


class SANDSCAPE_OT_add_post_effects(SandscapeOperator, bpy.types.Operator):
    """Add or update the compositor: gated blur of the scattered light and god rays towards the sun"""

    bl_idname = "sandscape.add_post_effects"
    bl_label = "Add Post Effects"
    POLL = (
        (_camera_for_rays, "The scene has no camera: god rays need one to place the sun on screen"),
        (_sun_for_rays, "No sun lamp: run Add Atmosphere first, or add a sun"),
    )

    def execute(self, context):
        scene = context.scene
        settings = scene.sandscape_post
        problem = settings_problem(scene, settings)
        if problem:
            return self.fail(problem)
        done = post.apply_post_effects(scene, settings)
        switches = (("denoising (all but the glints)", settings.use_denoise and not done["skipped"]),
                    ("gated blur", settings.use_blur), ("god rays", settings.use_god_rays),
                    ("sun glow", settings.use_sun_glow))
        effects = [name for name, on in switches if on] or ["none"]
        line = f"Post effects in {passes.ENGINE_NAMES[scene.render.engine]}: {', '.join(effects)}"
        if settings.use_god_rays and done["tree"] is not None:
            line += " (the sun's place on screen follows the camera and the sun on every frame)"
        kept_denoiser = settings.use_denoise and post.route(scene, settings).endswith(" denoised")
        if done["tree"] is not None and kept_denoiser:
            line += "; Cycles' own denoising kept (the sparkles come from its Noisy Image)"
        if done["skipped"]:
            line += "; not done: " + ", ".join(done["skipped"])
        if done["changes"]:
            line += "; changed: " + "; ".join(done["changes"])
        self.report({"INFO"}, line)
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_post_effects,)
