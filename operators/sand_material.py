"""Operators for the glinting sand material."""

import bpy
from bpy.props import EnumProperty, FloatProperty, FloatVectorProperty, IntProperty, StringProperty

from ..blender import images
from ..blender import sand as sand_material
from ..node_groups import glints

# The operator mirrors the group's inputs: name, tooltip and default come from its socket table.
MIRROR = {name: {"name": name, "description": spec[1], "default": spec[2]}
          for name, spec in glints.INPUTS.items()}


class SANDSCAPE_OT_add_sand_material(bpy.types.Operator):
    """Put a Sandscape sand material with glints on the active mesh, or update the one it has"""

    bl_idname = "sandscape.add_sand_material"
    bl_label = "Add Sand Material"
    bl_options = {"REGISTER", "UNDO"}

    # Soft limits only: out-of-range values from scripts are reported, not silently clamped.
    source: EnumProperty(
        name="Glint Source",
        items=(("PROCEDURAL", "Procedural", "Seeded white noise on object-space cells of Glint Size"),
               ("IMAGE", "Image", "A noise image through the mesh UVs: one texel, one grain")),
        default="PROCEDURAL")
    threshold: FloatProperty(**MIRROR["Threshold"], soft_min=0.0, soft_max=1.0, subtype="FACTOR")
    glint_size: FloatProperty(**MIRROR["Glint Size"], soft_min=1e-5, soft_max=1.0, subtype="DISTANCE",
                              unit="LENGTH", precision=4)
    facing_power: FloatProperty(**MIRROR["Facing Power"], soft_min=0.0, soft_max=256.0)
    color: FloatVectorProperty(**MIRROR["Color"], size=4, subtype="COLOR", soft_min=0.0, soft_max=1.0)
    strength: FloatProperty(**MIRROR["Strength"], soft_min=0.0, soft_max=1000.0)
    seed: IntProperty(name="Seed", description="Another seed, another set of glinting grains",
                      default=0, min=0, max=2 ** 24)
    image: StringProperty(
        name="Image", description="Image for the Image source; empty makes a seeded noise image")
    image_resolution: IntProperty(
        name="Noise Resolution", description="Size of the generated noise image in texels",
        default=1024, min=1, max=16384)

    def _problem(self, obj):
        if obj is None:
            return "No active object: select a mesh to put the sand material on"
        if obj.type != "MESH":
            return f"'{obj.name}' is a {obj.type.lower()}, not a mesh"
        if not 0.0 <= self.threshold <= 1.0:
            return f"Threshold must lie in [0, 1], got {self.threshold:g}"
        if not self.glint_size > 0.0:
            return f"Glint size must be greater than 0, got {self.glint_size:g}"
        if not self.facing_power >= 0.0:
            return f"Facing power must be 0 or more, got {self.facing_power:g}"
        if not self.strength >= 0.0:
            return f"Strength must be 0 or more, got {self.strength:g}"
        if self.source == "IMAGE" and self.image and self.image not in bpy.data.images:
            return f"No image named '{self.image}'"
        if self.source == "IMAGE" and not obj.data.uv_layers:
            return f"'{obj.name}' has no UV map, which the Image glint source needs"
        return None

    def execute(self, context):
        obj = context.active_object
        problem = self._problem(obj)
        if problem:
            self.report({"ERROR"}, problem)
            return {"CANCELLED"}
        image = None
        if self.source == "IMAGE":
            image = (bpy.data.images[self.image] if self.image
                     else images.ensure_noise_image(self.image_resolution, self.seed))
        material = sand_material.find_sand_material(obj)
        verb = "Updated"
        if material is None:
            material = sand_material.assign_new_material(obj)
            verb = "Added"
        sand_material.update_material(material, {
            "Threshold": self.threshold, "Glint Size": self.glint_size,
            "Facing Power": self.facing_power, "Color": self.color,
            "Strength": self.strength, "Seed": float(self.seed)}, image)
        self.report({"INFO"}, f"{verb} '{material.name}' on '{obj.name}'")
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_sand_material,)
