"""The sand material operator: Add (or Update) Sand Material on the active mesh."""

import bpy
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    IntProperty,
    StringProperty,
)

from ..addon import glint_noise, sand, units
from ..node_groups import glints, lit_glints, ripples
from .base import SandscapeOperator, active_mesh, editable_problem, value_problem

# SKIP_SAVE: a value not passed is not the last run's but the material's (invoke) or the default.
SKIP = {"SKIP_SAVE"}
# The operator mirrors the groups' inputs: name, tooltip and default come from their socket tables.
MIRROR = {name: {"name": name, "description": spec[1], "default": spec[2], "options": SKIP}
          for name, spec in {**glints.INPUTS, **lit_glints.INPUTS}.items()}
GLINT_SIZE_METRES = glints.INPUTS["Glint Size"][2]
RIPPLE_METRES = {"ripple_wavelength": ripples.WAVELENGTH, "ripple_amplitude": ripples.AMPLITUDE,
                 "ripple_meander_scale": ripples.MEANDER_SCALE}
LENGTH_METRES = {"glint_size": GLINT_SIZE_METRES, **RIPPLE_METRES}


class SANDSCAPE_OT_add_sand_material(SandscapeOperator, bpy.types.Operator):
    """Put a Sandscape sand material with glints and wind ripples on the active mesh, or update the one
    it has"""

    bl_idname = "sandscape.add_sand_material"
    bl_label = "Add Sand Material"
    POLL = ((active_mesh, "Select a mesh: the sand material goes on the active object"),)
    LIMITS = {"threshold": (0.0, 1.0), "glint_size": (1e-7, 1e7), "facing_power": (0.0, 1e7),
              "color": (0.0, 1e4), "strength": (0.0, 1e7), "roughness": (0.0, 1.0), "seed": (0, 2**24),
              "image_resolution": (1, 16384), "ripple_wavelength": (1e-4, 1e3),
              "ripple_amplitude": (0.0, 10.0), "ripple_meander": (0.0, 4.0),
              "ripple_meander_scale": (1e-4, 1e4), "ripple_variation": (0.0, 1.0),
              "ripple_defects": (0.0, 1.0), "ior": (1.0, 3.0)}

    look: EnumProperty(
        name="Look", default="PHYSICAL", options=SKIP,
        items=(("PHYSICAL", "Physical", "Sand as a physical surface: rough diffuse, quartz Fresnel, sheen "
                "rim, grainy normals"),
               ("JOURNEY", "Journey", "The sand of Journey (seed 004): diffuse contrast, rim, ocean "
                "specular, glitter")))
    glints: EnumProperty(
        name="Glints", default="LIT", options=SKIP,
        items=(("LIT", "Lit", "Mirror facets: a grain glints only where light reaches it and its facet "
                "reflects it to the camera"),
               ("EMISSION", "Emission", "Seed 000's sparkles: glints shine by themselves (stylised looks, "
                "EEVEE)")))
    source: EnumProperty(
        name="Glint Source", options=SKIP,
        items=(("PROCEDURAL", "Procedural", "Seeded white noise on object-space cells of Glint Size"),
               ("IMAGE", "Image", "A noise image through the mesh UVs: one texel, one grain")),
        default="PROCEDURAL")
    threshold: FloatProperty(**MIRROR["Threshold"], soft_min=0.0, soft_max=1.0, subtype="FACTOR")
    glint_size: FloatProperty(**MIRROR["Glint Size"], soft_min=1e-5, soft_max=1.0, subtype="DISTANCE",
                              unit="LENGTH", precision=4)
    facing_power: FloatProperty(**MIRROR["Facing Power"], soft_min=0.0, soft_max=256.0)
    color: FloatVectorProperty(**MIRROR["Color"], size=4, subtype="COLOR", soft_min=0.0, soft_max=1.0)
    strength: FloatProperty(**MIRROR["Strength"], soft_min=0.0, soft_max=1000.0)
    roughness: FloatProperty(**MIRROR["Roughness"], soft_min=0.0, soft_max=1.0, subtype="FACTOR")
    ior: FloatProperty(name="IOR", default=MIRROR["IOR"]["default"], soft_min=1.0, soft_max=3.0, options=SKIP,
                       description="Index of refraction of the grains, for the sand's Fresnel and its glint "
                       "facets alike (quartz 1.54)")
    seed: IntProperty(name="Seed", description="Another seed, another set of glinting grains",
                      default=0, min=0, max=2 ** 24, options=SKIP)
    image: StringProperty(
        name="Image", description="Image for the Image source; empty makes a seeded noise image",
        options=SKIP)
    image_resolution: IntProperty(
        name="Noise Resolution", description="Size of the generated noise image in texels",
        default=1024, min=1, max=16384, options=SKIP)
    ripples: BoolProperty(name="Wind Ripples", default=True, options=SKIP,
                          description="Ripples across the wind of the scene's atmosphere settings")
    ripple_wavelength: FloatProperty(
        name="Ripple Wavelength", default=RIPPLE_METRES["ripple_wavelength"], soft_min=0.02, soft_max=0.5,
        subtype="DISTANCE", unit="LENGTH", options=SKIP,
        description="Distance from crest to crest (sand ripples: 5 to 20 cm)")
    ripple_amplitude: FloatProperty(
        name="Ripple Amplitude", default=RIPPLE_METRES["ripple_amplitude"], soft_min=0.0, soft_max=0.05,
        subtype="DISTANCE", unit="LENGTH", precision=4, options=SKIP,
        description="Height of a crest above the mean")
    ripple_meander: FloatProperty(
        name="Ripple Meander", default=ripples.MEANDER, soft_min=0.0, soft_max=1.0,
        options=SKIP, description="How far crests wander, in wavelengths: 0 gives straight parallel crests")
    ripple_meander_scale: FloatProperty(
        name="Meander Scale", default=RIPPLE_METRES["ripple_meander_scale"], soft_min=0.1, soft_max=5.0,
        subtype="DISTANCE", unit="LENGTH", options=SKIP,
        description="Distance over which a crest bends one way and back")
    ripple_variation: FloatProperty(
        name="Ripple Variation", default=ripples.VARIATION, soft_min=0.0, soft_max=1.0,
        subtype="FACTOR", options=SKIP,
        description="How much the ripples' height varies from place to place: 0 keeps the amplitude "
        "everywhere")
    ripple_defects: FloatProperty(
        name="Ripple Defects", default=ripples.DEFECTS, soft_min=0.0, soft_max=1.0,
        subtype="FACTOR", options=SKIP,
        description="Share of places where a crest splits in two and ends (Y-junctions): 0 gives "
        "unbroken crests")
    ripple_displacement: BoolProperty(
        name="Ripple Displacement", default=False, options=SKIP,
        description="Also displace by the ripples (true geometry where the footprint patch dices finely); "
        "off: shading only")

    def invoke(self, context, _event):
        """Start from the material the object has (the sidebar's Update button); values a script
        passed are kept."""
        current = sand.read_settings(sand.find_sand_material(context.active_object))
        for name, value in current.items():
            if not self.properties.is_property_set(name):
                setattr(self, name, value)
        return self.execute(context)

    def problem(self, context):
        obj = context.active_object
        problem = value_problem(self.properties, self.LIMITS, context.scene) or editable_problem(obj)
        if problem:
            return problem
        if not obj.data.polygons:  # nothing would show the sand: say so rather than succeed
            return f"'{obj.name}' has no faces for the sand to cover"
        if self.source == "IMAGE" and self.image and self.image not in bpy.data.images:
            return f"No image named '{self.image}'"
        if self.source == "IMAGE" and not obj.data.uv_layers:
            return f"'{obj.name}' has no UV map, which the Image glint source needs"
        return None

    def execute(self, context):
        for name, metres in LENGTH_METRES.items():  # a length not given is its default in metres
            if not self.properties.is_property_set(name):
                setattr(self, name, units.to_units(context.scene, metres))
        problem = self.problem(context)
        if problem:
            return self.fail(problem)
        obj = context.active_object
        image = None
        if self.source == "IMAGE":
            image = (bpy.data.images[self.image] if self.image
                     else glint_noise.ensure_noise_image(self.image_resolution, self.seed))
        values = {"Threshold": self.threshold, "Glint Size": self.glint_size,
                  "Facing Power": self.facing_power, "Color": self.color, "Strength": self.strength,
                  "Roughness": self.roughness, "Seed": float(self.seed), "IOR": self.ior}
        waves = None
        if self.ripples:
            waves = {"Wind": tuple(context.scene.sandscape_atmosphere.wind),
                     **{name: getattr(self, setting) for setting, name in sand.RIPPLE_SETTINGS.items()},
                     "Displacement": self.ripple_displacement}
        theirs = [slot.material.name for slot in obj.material_slots if slot.material is not None]
        sharing = [o.name for o in bpy.data.objects if o.data == obj.data and o != obj]
        material, added = sand.apply(obj, values, image, self.look, self.glints, waves, context.scene)
        look = f"{self.look.title()} sand, {self.glints.lower()} glints" + (", ripples" if waves else "")
        changed = ""
        if added and theirs:
            keep = "keep their slots" if len(theirs) > 1 else "keeps its slot"
            changed = (f"; changed: every face of '{obj.name}' uses it (your "
                       f"{', '.join(repr(name) for name in theirs)} {keep})")
        if added and sharing:
            changed += (f"{'; changed:' if not changed else ';'} {', '.join(repr(n) for n in sharing)} "
                        "shares the mesh and gets the sand too")
        self.report({"INFO"}, f"{'Added' if added else 'Updated'} '{material.name}' on '{obj.name}': {look}"
                    + changed)
        return {"FINISHED"}


classes = (SANDSCAPE_OT_add_sand_material,)
