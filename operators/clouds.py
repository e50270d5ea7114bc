"""The cloud operator: Add (or Update) Clouds from scene.sandscape_clouds or its own arguments."""

import bpy

from ..addon import cloud_shadows, clouds, far_haze, ownership, shot, units
from ..addon.settings import CLOUD_LIMITS, cloud_fields
from .base import SandscapeOperator, SceneSettings, editable_problem, has_camera, value_problem

FIELDS = cloud_fields(True)
UNSHADED = ("; in EEVEE unshaded: the clouds' undersides get the whole sun (Voxel Grid bakes their sun's "
            "light; or turn on Render ▸ Shadows ▸ Volume Shadows)")


class SANDSCAPE_OT_add_clouds(SceneSettings, SandscapeOperator, bpy.types.Operator):
    """Add or update a cloud layer over what the scene camera sees: a weather map, cloud types, wind
    and real volume scattering (in EEVEE, with a mesh that casts the clouds' shadows)"""

    bl_idname = "sandscape.add_clouds"
    bl_label = "Add Clouds"
    POLL = ((has_camera, "Add a camera: the cloud layer spans what the scene camera sees"),)
    LIMITS = CLOUD_LIMITS
    __annotations__ = dict(FIELDS)

    def settings(self, context):
        """Every field: the value passed, else the scene's setting (scene units)."""
        values = clouds.scene_settings(context.scene)
        for name in FIELDS:
            if self.properties.is_property_set(name):
                values[name] = getattr(self, name)
            setattr(self, name, values[name])
        return values

    def problem(self, context, values):
        problem = value_problem(self.properties, self.LIMITS, context.scene)
        if problem:
            return problem
        if values["weather_source"] == "IMAGE":
            if not values["weather_image"]:
                return "Choose a weather image (red coverage, green precipitation, blue type)"
            if values["weather_image"] not in bpy.data.images:
                return f"No image named '{values['weather_image']}'"
            image = bpy.data.images[values["weather_image"]]
            if image.size[0] == 0 or image.size[1] == 0:
                return f"Image '{image.name}' has no pixels"
        return editable_problem(ownership.scene_object(context.scene, ownership.CLOUDS))

    def store(self, stored, name, value):
        if name == "weather_image":  # a name here, an image pointer on the scene
            stored.weather_image = bpy.data.images.get(value) if value else None
        else:
            setattr(stored, name, value)

    def execute(self, context):
        scene = context.scene
        values, problem = self.checked_settings(context)
        if problem:
            return self.fail(problem)
        image = bpy.data.images[values["weather_image"]] if values["weather_source"] == "IMAGE" else None
        plan = clouds.plan(scene, values, image)
        self.remember(scene.sandscape_clouds, values)
        done = clouds.apply(scene, values, image, plan)
        if done["layer"] is None:
            self.report({"INFO"}, "No cloud where the camera looks (coverage 0, or the weather map is clear "
                        "over the shot): no cloud layer")
            return {"FINISHED"}
        if values["evaluation"] == "GRID":
            how = f"a grid of {done['voxels']:,} voxels (at most {done['voxels'] * 4 / 2**20:.0f} MiB)"
        else:
            how = "procedural"
        width = units.length_text(scene, done["region"][2] - done["region"][0])
        depth = units.length_text(scene, done["region"][3] - done["region"][1])
        if done["far_haze"]:
            stale = far_haze.stale_visibility(scene)
            hazed = "; hazed from the dust box out to the clouds" + (f" {stale}" if stale else "")
        else:
            hazed = f"; far clouds not hazed: {done['no_far_haze']}"
        self.report({"INFO"}, f"Cloud layer '{done['layer'].name}': {values['cloud_type'].lower()}, coverage "
                    f"{values['coverage']:.2f}, {width} × {depth} of sky, {how}"
                    + (f"; EEVEE's shadow of it: a {shadows['texels'][1]} × {shadows['texels'][0]} map"
                       if (shadows := done.get("eevee_shadows")) else "")
                    + hazed
                    + (UNSHADED if cloud_shadows.unshaded(scene) else "")
                    + ("; changed: " + "; ".join(done["changes"]) if done["changes"] else ""))
        if done["warning"]:
            self.report({"WARNING"}, done["warning"])
        if depth := shot.eevee_depth_warning(scene):
            self.report({"WARNING"}, depth)
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_clouds,)
