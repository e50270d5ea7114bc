"""The sand material operator: Add (or Update) Sand Material on the active mesh."""

import bpy
from bpy.props import EnumProperty, FloatProperty, FloatVectorProperty, IntProperty, StringProperty

from ..blender import sand, units
from ..node_groups import glints
from .base import SandscapeOperator, active_mesh, editable_problem, value_problem

# The operator mirrors the group's inputs: name, tooltip and default come from its socket table.
# SKIP_SAVE: a value not passed is not the last run's but the material's (invoke) or the default.
MIRROR = {name: {"name": name, "description": spec[1], "default": spec[2], "options": {"SKIP_SAVE"}}
          for name, spec in glints.INPUTS.items()}
GLINT_SIZE_METRES = glints.INPUTS["Glint Size"][2]


class SANDSCAPE_OT_add_sand_material(SandscapeOperator, bpy.types.Operator):
    """Put a Sandscape sand material with glints on the active mesh, or update the one it has"""

    bl_idname = "sandscape.add_sand_material"
    bl_label = "Add Sand Material"
    POLL = ((active_mesh, "Select a mesh: the sand material goes on the active object"),)
    LIMITS = {"threshold": (0.0, 1.0), "glint_size": (1e-7, 1e7), "facing_power": (0.0, 1e7),
              "color": (0.0, 1e4), "strength": (0.0, 1e7), "seed": (0, 2**24), "image_resolution": (1, 16384)}

    # Soft limits only: out-of-range values from scripts are reported, not silently clamped.
    source: EnumProperty(
        name="Glint Source",
        items=(("PROCEDURAL", "Procedural", "Seeded white noise on object-space cells of Glint Size"),
               ("IMAGE", "Image", "A noise image through the mesh UVs: one texel, one grain")),
        default="PROCEDURAL", options={"SKIP_SAVE"})
    threshold: FloatProperty(**MIRROR["Threshold"], soft_min=0.0, soft_max=1.0, subtype="FACTOR")
    glint_size: FloatProperty(**MIRROR["Glint Size"], soft_min=1e-5, soft_max=1.0, subtype="DISTANCE",
                              unit="LENGTH", precision=4)
    facing_power: FloatProperty(**MIRROR["Facing Power"], soft_min=0.0, soft_max=256.0)
    color: FloatVectorProperty(**MIRROR["Color"], size=4, subtype="COLOR", soft_min=0.0, soft_max=1.0)
    strength: FloatProperty(**MIRROR["Strength"], soft_min=0.0, soft_max=1000.0)
    seed: IntProperty(name="Seed", description="Another seed, another set of glinting grains",
                      default=0, min=0, max=2 ** 24, options={"SKIP_SAVE"})
    image: StringProperty(
        name="Image", description="Image for the Image source; empty makes a seeded noise image",
        options={"SKIP_SAVE"})
    image_resolution: IntProperty(
        name="Noise Resolution", description="Size of the generated noise image in texels",
        default=1024, min=1, max=16384, options={"SKIP_SAVE"})

    def invoke(self, context, _event):
        """Start from the material the object has (the sidebar's Update button), else from the
        defaults in the scene's units; values a script passed are kept."""
        current = sand.read_settings(sand.find_sand_material(context.active_object))
        if not current and not self.properties.is_property_set("glint_size"):
            self.glint_size = units.to_units(context.scene, GLINT_SIZE_METRES)
        for name, value in current.items():
            if not self.properties.is_property_set(name):
                setattr(self, name, value)
        return self.execute(context)

    def problem(self, context):
        obj = context.active_object
        problem = value_problem(self.properties, self.LIMITS, context.scene) or editable_problem(obj)
        if problem:
            return problem
        if self.source == "IMAGE" and self.image and self.image not in bpy.data.images:
            return f"No image named '{self.image}'"
        if self.source == "IMAGE" and not obj.data.uv_layers:
            return f"'{obj.name}' has no UV map, which the Image glint source needs"
        return None

    def execute(self, context):
        problem = self.problem(context)
        if problem:
            return self.fail(problem)
        obj = context.active_object
        image = None
        if self.source == "IMAGE":
            image = (bpy.data.images[self.image] if self.image
                     else sand.ensure_noise_image(self.image_resolution, self.seed))
        values = {"Threshold": self.threshold, "Glint Size": self.glint_size,
                  "Facing Power": self.facing_power, "Color": self.color, "Strength": self.strength,
                  "Seed": float(self.seed)}
        material, added = sand.apply(obj, values, image)
        self.report({"INFO"}, f"{'Added' if added else 'Updated'} '{material.name}' on '{obj.name}'")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_sand_material,)
