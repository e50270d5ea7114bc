"""The atmosphere operator: sun, sky and Rayleigh-scattering dust (scene.sandscape_atmosphere)."""

import math

import bpy

from ..addon import atmosphere, cloud_shadows, clouds, ownership, shot, units
from ..addon.settings import SandscapeAtmosphereSettings
from ..core import atmosphere as air
from .base import SandscapeOperator, editable_problem, value_problem


def settings_problem(scene, settings):
    problem = value_problem(settings, SandscapeAtmosphereSettings.LIMITS, scene)
    if problem:
        return problem
    try:
        air.rayleigh_coefficients(settings.density, tuple(settings.wavelengths))
    except air.AtmosphereError as error:
        return str(error).capitalize()
    # What the operator changes in place: the sun (the artist's only when asked), our world, our dust.
    sun = atmosphere.scene_sun(scene)
    if sun is not None and not atmosphere.is_ours(sun) and not settings.aim_sun:
        sun = None
    return editable_problem(sun, ownership.scene_world(scene),
                            ownership.scene_object(scene, ownership.DUST_VOLUME))


def report_line(scene, settings, done):
    """One line: what Sandscape made or updated, then everything it changed or left of the artist's."""
    sun = done["sun"]
    where = f"{math.degrees(done['elevation']):.1f}° up, azimuth {math.degrees(done['azimuth']) % 360:.1f}°"
    parts = [f"Sun '{sun.name}' {sun.data.energy:.4g} W/m² at {where}"]
    if done["followed"]:
        follows = "; the sky follows it" if done["world"] is not None else ""
        why = ("keys, drivers or constraints move it, so Aim Your Sun leaves it" if settings.aim_sun
               else "Aim Your Sun turns it to the settings")
        parts[0] = f"Your sun '{sun.name}' kept at {where}{follows} ({why})"
    if done["world"] is not None:
        parts.append(f"sky '{done['world'].name}'")
    else:
        parts.append(f"your world '{scene.world.name}' kept (Replace World puts the sky in its place)")
    volume = done["volume"]
    if volume is None:
        parts.append("no volume (nothing scatters)")
    else:
        haze = ""
        if settings.use_haze:
            haze = f" with haze to {units.length_text(scene, settings.visibility)} visibility"
        beta = ", ".join(f"{b:.4g}" for b in done["coefficients"])
        parts.append(f"dust box '{volume.name}'{haze}, scattering {beta} per metre")
    if not settings.set_exposure and done["world"] is not None and abs(
            scene.view_settings.exposure - done["exposure"]) > 0.5:
        parts.append(f"exposure kept at {scene.view_settings.exposure:+.2f} (Set Exposure would make it "
                     f"{done['exposure']:+.2f} for this sky)")
    if done["world"] is not None and scene.render.engine == "BLENDER_EEVEE" and \
            scene.eevee.clamp_surface_indirect > 0:
        parts.append(f"EEVEE's Clamp Surface Indirect kept at {scene.eevee.clamp_surface_indirect:g} "
                     "(it dims the ground's light; the Render section's EEVEE presets set 0)")
    if (ground := ground_part(scene, done)) is not None:
        parts.append(ground)
    changed = "; changed: " + "; ".join(done["changes"]) if done["changes"] else ""
    return ", ".join(parts) + changed


def ground_part(scene, done):
    """Whose colour EEVEE's light from the ground takes, when it is not our sand; or None."""
    ground = done.get("ground")
    if done["world"] is None or (ground is not None and ground.get(ownership.MATERIAL_KEY) == ownership.SAND):
        return None
    if ground is None:
        if scene.camera is None:
            return None
        return (f"EEVEE's light from the ground takes the sand's colour: nothing opaque lies below camera "
                f"'{scene.camera.name}', ahead of it or low in its frame")
    image = done.get("ground_image")
    if done["ground_read"] and image is not None:
        return (f"EEVEE's light from the ground takes the mean colour of image '{image.name}' "
                f"on your '{ground.name}' (run Add Atmosphere again after changing the image)")
    if done["ground_read"]:
        return f"EEVEE's light from the ground takes the colour of your '{ground.name}'"
    if image is not None:
        return (f"EEVEE's light from the ground takes the sand's colour: image '{image.name}' on your "
                f"'{ground.name}' has no pixels to read (is its file missing?)")
    return (f"EEVEE's light from the ground takes the sand's colour: your '{ground.name}' gets its colour "
            "from a texture other than an image, or a shader it cannot read")


class SANDSCAPE_OT_add_atmosphere(SandscapeOperator, bpy.types.Operator):
    """Add or update a sun, a matching sky and a Rayleigh-scattering dust volume around the scene"""

    bl_idname = "sandscape.add_atmosphere"
    bl_label = "Add Atmosphere"

    def execute(self, context):
        scene = context.scene
        settings = scene.sandscape_atmosphere
        problem = settings_problem(scene, settings)
        if problem:
            return self.fail(problem)
        done = atmosphere.apply(scene, settings)
        self.report({"INFO"}, report_line(scene, settings, done))
        if warning := atmosphere.clip_warning(scene, done["volume"]):
            self.report({"WARNING"}, warning)
        if depth := shot.eevee_depth_warning(scene):
            self.report({"WARNING"}, depth)
        if cloud_shadows.stale(scene):  # made for the sun as it was
            if clouds.refresh_shadows(scene):
                self.report({"INFO"}, "EEVEE's cloud shadows remade for this sun")
            elif cloud_shadows.to_sun(scene) is None:
                self.report({"INFO"}, f"EEVEE's cloud shadows removed: the sun is under "
                            f"{cloud_shadows.LOWEST_SUN}° up")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_atmosphere,)
