"""Operators for the atmosphere: sun, sky and Rayleigh-scattering dust (scene.sandscape_atmosphere)."""

import math

import bpy

from ..addon import atmosphere
from ..core import atmosphere as air


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
        self.report({"INFO"}, f"Sun '{done['sun'].name}', sky '{done['world'].name}', {volume}, "
                    f"scattering {beta} 1/m{replaced}")
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
    return None


classes = (SANDSCAPE_OT_add_atmosphere,)
