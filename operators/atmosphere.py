"""The atmosphere operator: sun, sky and Rayleigh-scattering dust (scene.sandscape_atmosphere)."""

import bpy

from ..blender import atmosphere, ownership, units
from ..blender.settings import SandscapeAtmosphereSettings
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
    # What the operator changes in place: the scene's sun, our world and our dust box.
    theirs = [atmosphere.scene_sun(scene), ownership.scene_world(scene),
              ownership.scene_object(scene, ownership.DUST_VOLUME)]
    return editable_problem(*theirs)


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
        beta = ", ".join(f"{b:.4g}" for b in done["coefficients"])
        volume = f"dust box '{done['volume'].name}'" if done["volume"] else "no volume (nothing scatters)"
        if done["volume"] and settings.use_haze:
            volume += f" with haze to {units.length_text(scene, settings.visibility)} visibility"
        replaced = (f"; world '{done['replaced'].name}' kept with a fake user (switch back in World "
                    "properties)" if done["replaced"] else "")
        marching = "; volume ray marching on (biased, faster)" if scene.cycles.volume_biased else ""
        sun = done["sun"].data
        exposure = f"; exposure {done['exposure']:+.2f}" if done["exposure"] is not None else ""
        self.report({"INFO"}, f"Sun '{done['sun'].name}' {sun.energy:.4g} W/m², sky '{done['world'].name}', "
                    f"{volume}, scattering {beta} per metre{replaced}{marching}{exposure}")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_atmosphere,)
