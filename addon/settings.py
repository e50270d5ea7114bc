"""Scene settings: what the sidebar edits and the operators read (scene.sandscape_footprints,
scene.sandscape_atmosphere, scene.sandscape_post, scene.sandscape_clouds, scene.sandscape_dunes).

Scripts set them too: scene.sandscape_footprints.stride = 0.6, then
bpy.ops.sandscape.paint_footprints(). Limits in the UI are soft: a value out of range, NaN or
inf set from a script reaches the operator, which refuses it by the class's LIMITS before
changing anything.

Lengths are physical: they are stored in metres and read in scene units, so a centimetre scene
(unit scale 0.01) starts from a 0.7 m stride (70 units) like a metre scene does, and the
sidebar shows "70 cm" in both.
"""

import math

import bpy
from bpy.props import (
    BoolProperty,
    CollectionProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    IntProperty,
    PointerProperty,
    StringProperty,
)

from ..node_groups import footprint_height
from . import units

DEPTH = footprint_height.INPUTS["Depth"]
RIM = footprint_height.INPUTS["Rim"]
NOISE = footprint_height.INPUTS["Noise Amount"]
INT_MAX = 2**31 - 1


def length(key, name, metres, description, soft_max, soft_min=0.0, per_second=False):
    """A length (or a speed) shown in the scene's units, stored in metres under `key`.

    Reading gives scene units; writing takes scene units. Unset, it is `metres`.
    """
    def get(self):
        stored = self.get(key, metres)
        if per_second:
            return tuple(v / units.metres_per_unit(self.id_data) for v in stored)
        return stored / units.metres_per_unit(self.id_data)

    def set(self, value):
        scale = units.metres_per_unit(self.id_data)
        self[key] = tuple(v * scale for v in value) if per_second else value * scale

    if per_second:
        return FloatVectorProperty(name=name, size=3, default=metres, subtype="VELOCITY", unit="VELOCITY",
                                   description=description, get=get, set=set)
    return FloatProperty(name=name, default=metres, soft_min=soft_min, soft_max=soft_max, subtype="DISTANCE",
                         unit="LENGTH", precision=3, description=description, get=get, set=set)


def _is_mesh(_self, obj):
    return obj.type == "MESH"


class SandscapeWalkerEntry(bpy.types.PropertyGroup):
    """One more walker on the same terrain, painted into the same height image."""

    LIMITS = {"foot_scale": (0.01, 100.0), "depth_scale": (0.0, 100.0), "stride_scale": (0.01, 100.0)}

    walker: PointerProperty(name="Walker", type=bpy.types.Object,
                            description="Another animated object or rig that walks the same sand")
    foot_scale: FloatProperty(name="Foot Size", default=1.0, soft_min=0.2, soft_max=3.0, subtype="FACTOR",
                              description="Its feet against the Foot Length and Width above: 0.6 for a "
                              "child, 1.3 for a big boot")
    depth_scale: FloatProperty(name="Depth", default=1.0, soft_min=0.0, soft_max=3.0, subtype="FACTOR",
                               description="How deep its prints press against the Depth above (a heavier "
                               "walker, a loaded pack: more)")
    stride_scale: FloatProperty(name="Stride", default=1.0, soft_min=0.2, soft_max=3.0, subtype="FACTOR",
                                description="Its stride and stance against the Stride and Stance above, "
                                "for a walker along a path (a child: about 0.6); a rig's feet set their own")
    left_foot: StringProperty(name="Left Foot", default="",
                              description="A rig's left foot bone; empty: found by name")
    right_foot: StringProperty(name="Right Foot", default="", description="A rig's right foot bone")


class SandscapeFootprintSettings(bpy.types.PropertyGroup):
    # Valid values, in what the artist reads: metres for lengths, else the property's own unit.
    LIMITS = {
        "frame_start": (-1_000_000, 1_000_000), "frame_end": (-1_000_000, 1_000_000),
        "stride": (1e-4, 1e3), "stance": (0.0, 1e3), "foot_length": (1e-4, 1e2), "foot_width": (1e-4, 1e2),
        "depth": (0.0, 1e2), "rim": (0.0, 1e2), "rim_width": (0.0, 1e2), "variation": (0.0, 0.99),
        "noise_amount": (0.0, 1.0), "seed": (0, INT_MAX), "resolution": (1, 16384),
        "dicing_pixel_size": (0.1, 1e4), "refill_time": (0.0, 1e7),
    }

    source: EnumProperty(
        name="Source", default="WALKER",
        items=(("WALKER", "Walker", "Steps along the path of an animated object"),
               ("PARTICLES", "Particles", "One print where each particle of a particle system is born")))
    walker: PointerProperty(name="Walker", type=bpy.types.Object,
                            description="Any object whose world position is animated over the frame range; "
                            "a rig leaves a print where each foot lands")
    left_foot: StringProperty(name="Left Foot", default="",
                              description="The rig's left foot bone (its first child is the toe); empty: "
                              "found by Rigify, Mixamo or Auto-Rig Pro names")
    right_foot: StringProperty(name="Right Foot", default="",
                               description="The rig's right foot bone; empty: found by name")
    more_walkers: CollectionProperty(type=SandscapeWalkerEntry, name="More Walkers",
                                     description="Other walkers on the same terrain, each with its own "
                                     "foot size and depth, painted into the same height image")
    particle_object: PointerProperty(name="Particle Emitter", type=bpy.types.Object,
                                     description="Object whose first particle system marks the prints")
    terrain: PointerProperty(name="Terrain", type=bpy.types.Object, poll=_is_mesh,
                             description="Mesh the prints are projected onto (straight down, world -Z) "
                             "and painted into")
    use_scene_range: BoolProperty(name="Scene Frame Range", default=True,
                                  description="Walk over the scene's frame range")
    frame_start: IntProperty(name="Start", default=1, description="First frame of the walk")
    frame_end: IntProperty(name="End", default=250, description="Last frame of the walk")
    stride: length("stride_m", "Stride", 0.7, "Distance along the path from one print to the next", 3.0)
    stance: length("stance_m", "Stance", 0.2, "Distance between the left and right feet", 1.0)
    foot_length: length("foot_length_m", "Foot Length", 0.27, "Heel to toe", 2.0)
    foot_width: length("foot_width_m", "Foot Width", 0.10, "Across the ball of the foot", 1.0)
    depth: length("depth_m", "Depth", DEPTH[2], DEPTH[1], 0.5)
    rim: length("rim_m", "Rim", RIM[2], RIM[1], 0.2)
    rim_width: length("rim_width_m", "Rim Width", 0.04, "Width of the ring of pushed-up sand", 0.5)
    variation: FloatProperty(name="Variation", default=0.1, soft_min=0.0, soft_max=0.9, subtype="FACTOR",
                             description="Random spread of each print's depth scale: 0.1 is +-10 %")
    noise_amount: FloatProperty(name="Noise", default=NOISE[2], soft_min=0.0, soft_max=1.0,
                                subtype="FACTOR", description=NOISE[1])
    seed: IntProperty(name="Seed", default=0, min=0, description="Seed of the per-print variation")
    resolution: IntProperty(name="Resolution", default=2048, soft_min=16, soft_max=16384,
                            description="Texels along the longer side of the print region")
    dicing_pixel_size: FloatProperty(name="Dicing", default=1.0, soft_min=0.25, soft_max=16.0,
                                     description="Adaptive subdivision edge length in pixels over the prints")
    refill_time: FloatProperty(name="Refill Time", default=0.0, soft_min=0.0, soft_max=600.0,
                               unit="TIME_ABSOLUTE", description="Seconds in which the wind fills a print to "
                               "1/e (37 %) of its depth and rim; 0: prints stay as pressed")


class SandscapeAtmosphereSettings(bpy.types.PropertyGroup):
    LIMITS = {
        "sun_elevation": (-math.pi / 2, math.pi / 2), "sun_azimuth": (-20 * math.pi, 20 * math.pi),
        "density": (0.0, 1e6), "wavelengths": (100.0, 10_000.0), "dust_density": (0.0, 1e6),
        "anisotropy": (-0.99, 0.99), "wind": (-1e4, 1e4), "dust_scale": (1e-4, 1e5), "coverage": (0.0, 1.0),
        "softness": (1e-4, 1.0), "falloff": (1e-4, 1e5), "margin": (0.0, 1e6), "visibility": (1.0, 1e7),
    }

    sun_elevation: FloatProperty(name="Sun Elevation", default=math.radians(25.0), subtype="ANGLE",
                                 soft_min=math.radians(-10.0), soft_max=math.radians(90.0),
                                 description="Height of the sun above the horizon")
    sun_azimuth: FloatProperty(name="Sun Azimuth", default=math.radians(135.0), subtype="ANGLE",
                               description="Compass direction of the sun: 0 along +Y, 90 degrees along +X")
    sun_from_sky: BoolProperty(name="Sun from Sky", default=True,
                               description="Give the sun lamp the strength and colour of the sky model's own "
                               "sun at this elevation, so lamp and sky light the ground as one")
    aim_sun: BoolProperty(name="Aim Your Sun", default=False,
                          description="Turn a sun lamp Sandscape did not make to this elevation and azimuth "
                          "(and, with Sun from Sky, give it the sky's strength and colour). Off: your sun "
                          "stays as it is and the sky follows it")
    set_exposure: BoolProperty(name="Set Exposure", default=False,
                               description="Set the scene's exposure so that level grey ground under this "
                               "sun and sky reads as its own grey (the sky's sun is bright: about -2 to -5)")
    replace_world: BoolProperty(name="Replace World", default=False,
                                description="Put Sandscape's sky in place of a world you made (yours is kept "
                                "with a fake user). A new file's untouched grey world is replaced anyway")
    density: FloatProperty(name="Density", default=0.02, soft_min=0.0, soft_max=1.0, precision=4,
                           description="Scattering coefficient at 550 nm, per metre; 0 adds no volume at "
                           "all. The volume is a box around what the camera sees: a world volume would "
                           "block the sun lamp")
    wavelengths: FloatVectorProperty(name="Wavelengths", size=3, default=(680.0, 550.0, 440.0),
                                     soft_min=380.0, soft_max=780.0,
                                     description="Red, green, blue wavelengths in nm for the 1/lambda^4 law")
    dust_density: FloatProperty(name="Dust", default=0.0, soft_min=0.0, soft_max=1.0, precision=4,
                                description="Extra grey, forward-scattering dust (Henyey-Greenstein), per "
                                "metre; 0 leaves it out")
    anisotropy: FloatProperty(name="Anisotropy", default=0.6, soft_min=-0.9, soft_max=0.95,
                              description="Henyey-Greenstein g of the dust: above 0 scatters forwards")
    use_wind: BoolProperty(name="Wind-Lifted Dust", default=True,
                           description="Patches of dust carried by the wind and thinning with height; off "
                           "gives a homogeneous volume, far cheaper to render")
    wind: length("wind_m", "Wind", (3.0, 1.0, 0.0), "Wind velocity", 0.0, per_second=True)
    dust_scale: length("dust_scale_m", "Patch Size", 8.0, "Size of the dust patches", 100.0)
    coverage: FloatProperty(name="Coverage", default=0.5, soft_min=0.0, soft_max=1.0, subtype="FACTOR",
                            description="Share of the ground under dust")
    softness: FloatProperty(name="Softness", default=0.08, soft_min=0.001, soft_max=0.5,
                            description="Width of the patch edges")
    falloff: length("falloff_m", "Height Falloff", 1.5, "Height over which dust thins by 1/e", 50.0)
    use_haze: BoolProperty(name="Haze", default=True,
                           description="A thin haze through the whole box, not carried in patches: far dunes "
                           "fade toward the sky as exp(-extinction x distance)")
    visibility: length("visibility_m", "Visibility", 20000.0, "Distance at which far land keeps 2 % of its "
                       "contrast against the sky (extinction 3.912 / visibility, Koschmieder): desert haze "
                       "10-50 km, a dusty afternoon a few km", 100000.0, soft_min=100.0)
    margin: length("margin_m", "Margin", 2.0, "How far the dust box reaches beyond the camera's view "
                   "(the scene, without a camera)", 100.0)


CLOUD_TYPES = (("STRATUS", "Stratus", "Low, flat sheets"),
               ("CUMULUS", "Cumulus", "Heaped clouds: flat bases, domes up to 70 % of the layer"),
               ("CUMULONIMBUS", "Cumulonimbus", "Towers through the whole layer"),
               ("MIXED", "Mixed", "The type varies over the sky (the weather map's own type)"))


def length_field(for_operator):
    """A length setting as an operator takes it (scene units, not kept between runs) or as the
    scene stores it (metres under `key`, read in scene units): one definition for both."""
    def distance(key, name, metres, description, soft_max, soft_min=0.0):
        if for_operator:
            return FloatProperty(name=name, default=metres, soft_min=soft_min, soft_max=soft_max,
                                 subtype="DISTANCE", unit="LENGTH", description=description,
                                 options={"SKIP_SAVE"})
        return length(key, name, metres, description, soft_max, soft_min)
    return distance


def cloud_fields(for_operator):
    """The cloud settings, defined once: scene.sandscape_clouds stores lengths in metres (read in
    scene units); the operator takes every one of them in scene units, and a value it is not
    given comes from the scene's settings."""
    skip = {"options": {"SKIP_SAVE"}} if for_operator else {}
    distance = length_field(for_operator)

    fields = {
        "coverage": FloatProperty(name="Coverage", default=0.4, soft_min=0.0, soft_max=1.0, subtype="FACTOR",
                                  description="Share of the sky under cloud, seen straight up", **skip),
        "cloud_type": EnumProperty(name="Cloud Type", items=CLOUD_TYPES, default="CUMULUS", **skip),
        "seed": IntProperty(name="Seed", default=0, min=0, description="Another seed, another sky", **skip),
        "base": distance("base_m", "Base Altitude", 1500.0, "Height of the layer's bottom above the "
                         "scene's origin", 10000.0),
        "thickness": distance("thickness_m", "Thickness", 2500.0, "Height of the layer", 8000.0),
        "precipitation": FloatProperty(name="Precipitation", default=0.0, soft_min=0.0, soft_max=1.0,
                                       subtype="FACTOR", description="Rain in the clouds: denser, darker",
                                       **skip),
        "density": FloatProperty(name="Density", default=0.02, soft_min=0.0, soft_max=0.2, precision=4,
                                 description="Extinction of the densest cloud per metre (fair-weather "
                                 "cumulus: 0.01 to 0.1)", **skip),
        "map_scale": distance("map_scale_m", "Weather Scale", 6000.0, "Size of the weather map's features",
                              50000.0),
        "shape_scale": distance("shape_scale_m", "Shape Scale", 1200.0, "Size of the cloud shapes", 10000.0),
        "detail_scale": distance("detail_scale_m", "Detail Scale", 200.0, "Size of the eroded edge detail",
                                 2000.0),
        "erosion": FloatProperty(name="Erosion", default=0.35, soft_min=0.0, soft_max=0.9, subtype="FACTOR",
                                 description="How much the detail eats into the cloud edges", **skip),
        "curl": FloatProperty(name="Curl", default=0.5, soft_min=0.0, soft_max=2.0,
                              description="Swirl of the edge detail at the top of the layer", **skip),
        "skew": distance("skew_m", "Skew", 300.0, "How far the tops lean downwind", 2000.0, -2000.0),
        "reach": distance("reach_m", "Reach", 20000.0, "How far from the camera the layer extends", 100000.0),
        "weather_source": EnumProperty(
            name="Weather Map", default="PROCEDURAL",
            items=(("PROCEDURAL", "Procedural", "A seeded noise over the ground, calibrated to Coverage"),
                   ("IMAGE", "Image", "An image you paint: red coverage, green precipitation, blue type")),
            **skip),
        "map_size": distance("map_size_m", "Map Size", 20000.0, "Ground covered by the weather image "
                             "(a square centred on the origin)", 100000.0),
        "phase": EnumProperty(
            name="Phase", default="DUAL_LOBE",
            items=(("DUAL_LOBE", "Dual-Lobe", "Two Henyey-Greenstein lobes (seed 003): a forward glow and "
                    "a softer back lobe"),
                   ("MIE", "Mie", "Blender's Mie phase for water droplets of Droplet Size")), **skip),
        "forward": FloatProperty(name="Forward Lobe", default=0.8, soft_min=0.0, soft_max=0.95,
                                 description="Henyey-Greenstein g of the forward lobe", **skip),
        "back": FloatProperty(name="Back Lobe", default=-0.3, soft_min=-0.95, soft_max=0.0,
                              description="Henyey-Greenstein g of the back lobe", **skip),
        "back_weight": FloatProperty(name="Back Share", default=0.3, soft_min=0.0, soft_max=1.0,
                                     subtype="FACTOR", description="Share of the back lobe", **skip),
        "droplet_size": FloatProperty(name="Droplet Size", default=20.0, soft_min=5.0, soft_max=50.0,
                                      description="Water droplet diameter in micrometres, for the Mie phase",
                                      **skip),
        "step": distance("step_m", "Step", 200.0, "Ray-marching step through the clouds: smaller is slower "
                         "and more exact", 1000.0, 1.0),
        "evaluation": EnumProperty(
            name="Evaluation", default="GRID",
            items=(("GRID", "Voxel Grid", "Evaluate the density once into a voxel grid (geometry nodes): "
                    "renders look voxels up, fast"),
                   ("PROCEDURAL", "Procedural", "Evaluate every noise at every step of every ray: finest "
                    "detail, slowest")), **skip),
        "voxel": distance("voxel_m", "Voxel Size", 100.0, "Edge of one voxel of the cloud grid: smaller "
                          "holds finer detail and costs the cube of it", 500.0, 10.0),
    }
    if for_operator:
        fields["weather_image"] = StringProperty(name="Weather Image", description="Image for the Image "
                                                 "weather map", options={"SKIP_SAVE"})
    else:
        fields["weather_image"] = PointerProperty(name="Weather Image", type=bpy.types.Image,
                                                  description="Red coverage, green precipitation, blue type")
    return fields


CLOUD_LIMITS = {
    "coverage": (0.0, 1.0), "seed": (0, 2**24), "base": (-1e4, 1e5), "thickness": (1e-3, 1e5),
    "precipitation": (0.0, 1.0), "density": (0.0, 1e3), "map_scale": (1.0, 1e7), "shape_scale": (1e-2, 1e6),
    "detail_scale": (1e-2, 1e6), "erosion": (0.0, 0.99), "curl": (0.0, 10.0), "skew": (-1e5, 1e5),
    "reach": (1.0, 1e6), "map_size": (1.0, 1e7), "forward": (-0.99, 0.99), "back": (-0.99, 0.99),
    "back_weight": (0.0, 1.0), "droplet_size": (0.01, 50.0), "step": (1e-3, 1e5),
    "voxel": (1e-3, 1e5),
}

SandscapeCloudSettings = type("SandscapeCloudSettings", (bpy.types.PropertyGroup,),
                              {"__annotations__": cloud_fields(False), "LIMITS": CLOUD_LIMITS,
                               "__doc__": "The cloud layer's settings (scene.sandscape_clouds)"})


class SandscapePostSettings(bpy.types.PropertyGroup):
    LIMITS = {
        "blur_threshold": (0.0, 1e6), "samples": (1, 1024), "ray_density": (0.0, 1.0),
        "ray_weight": (0.0, 100.0), "ray_decay": (0.0, 1.0), "ray_exposure": (0.0, 1e4),
        "disc_radius": (1e-4, 10.0), "fade": (0.0, 10.0), "glow_strength": (0.0, 100.0),
    }

    use_denoise: BoolProperty(name="Denoise", default=True,
                              description="Denoise everything but the glints (OpenImageDenoise with albedo "
                              "and normal), then add the glints back sharp")
    use_blur: BoolProperty(name="Gated Blur", default=True,
                           description="Blur the scattered light where it changes the luminance (seed 000)")
    blur_threshold: FloatProperty(name="Threshold", default=0.01, soft_min=0.0, soft_max=1.0, precision=4,
                                  description="Luminance change below which the scattered light stays sharp")
    use_god_rays: BoolProperty(name="God Rays", default=True,
                               description="Screen-space light scattering towards the sun (GPU Gems 3)")
    samples: IntProperty(name="Samples", default=32, soft_min=4, soft_max=128,
                         description="The seed's sample count: with Decay, how far the rays reach before "
                         "they fade (the group always sums the same 256 taps: more is not slower)")
    ray_density: FloatProperty(name="Density", default=0.9, soft_min=0.0, soft_max=1.0,
                               description="Fraction of the way to the sun the samples span")
    ray_weight: FloatProperty(name="Weight", default=0.1, soft_min=0.0, soft_max=1.0,
                              description="Weight of each sample")
    ray_decay: FloatProperty(name="Decay", default=0.97, soft_min=0.5, soft_max=1.0,
                             description="Falloff per sample; above 1 the rays would grow without bound")
    ray_exposure: FloatProperty(name="Exposure", default=1.0, soft_min=0.0, soft_max=10.0,
                                description="Overall strength of the rays")
    disc_radius: FloatProperty(name="Sun Disc", default=0.08, soft_min=0.005, soft_max=0.5,
                               description="Radius of the glowing disc around the sun, in frame heights")
    fade: FloatProperty(name="Edge Fade", default=0.25, soft_min=0.0, soft_max=1.0,
                        description="How far outside the frame (in frame widths) the rays fade out")
    use_sun_glow: BoolProperty(name="Sun Glow", default=True,
                               description="A soft glow round the sun's disc where it is in view, as a "
                               "camera sees it (Fog Glow on light far above white: the sun, not the glints)")
    glow_strength: FloatProperty(name="Strength", default=1.0, soft_min=0.0, soft_max=4.0,
                                 description="How bright the sun's glow is")


def dune_fields(for_operator):
    """The dune field's settings, defined once as the clouds' are (scene.sandscape_dunes and the
    operator's arguments)."""
    skip = {"options": {"SKIP_SAVE"}} if for_operator else {}
    distance = length_field(for_operator)
    return {
        "width": distance("width_m", "Width", 200.0, "Extent of the field along X", 2000.0, 1.0),
        "depth": distance("depth_m", "Depth", 200.0, "Extent of the field along Y", 2000.0, 1.0),
        "cell_size": distance("cell_size_m", "Cell Size", 0.5, "Distance between the field's vertices", 4.0,
                              0.05),
        "spacing": distance("spacing_m", "Dune Spacing", 30.0, "Distance from crest to crest of transverse "
                            "dunes (real ones: 20 m to 500 m); they stand about a tenth of it high",
                            500.0, 1.0),
        "sand_supply": FloatProperty(
            name="Sand Supply", default=3.0, soft_min=0.3, soft_max=10.0, subtype="PERCENTAGE", precision=2,
            description="How much sand there is: the depth it would have spread evenly, in percent of the "
            "Dune Spacing (3 % of 30 m is 90 cm). Under 1 % leaves separate dunes on bare ground "
            "with horns downwind (barchans); 3 % and more builds transverse ridges", **skip),
        "seed": IntProperty(name="Seed", default=0, min=0, description="Another seed, another field", **skip),
        "use_second_wind": BoolProperty(name="Second Wind", default=False, description="A second wind "
                                        "takes turns with the scene's: two winds far apart build linear "
                                        "(seif) dunes", **skip),
        "second_wind_angle": FloatProperty(name="Second Wind Angle", default=math.radians(120.0),
                                           subtype="ANGLE", soft_min=-math.pi, soft_max=math.pi,
                                           description="Direction of the second wind, turned from the "
                                           "scene's wind (counter-clockwise seen from above)", **skip),
        "second_wind_share": FloatProperty(name="Second Wind Share", default=0.5, soft_min=0.0, soft_max=1.0,
                                           subtype="FACTOR", description="Share of the time the second "
                                           "wind blows", **skip),
        "horizon": distance("horizon_m", "Horizon", 20000.0, "How far the land reaches beyond the field: a "
                            "ring that coarsens with distance and follows the Earth's curve, so the dunes "
                            "meet the horizon; 0 leaves the field's edge", 50000.0),
        "sand_material": BoolProperty(name="Sand Material", default=True, description="Put the Sandscape "
                                      "sand material on the field (a field that has one keeps it)", **skip),
    }


DUNE_LIMITS = {
    "width": (0.01, 1e6), "depth": (0.01, 1e6), "cell_size": (1e-3, 1e4), "spacing": (0.01, 1e5),
    "sand_supply": (0.05, 30.0), "seed": (0, INT_MAX), "second_wind_angle": (-4 * math.pi, 4 * math.pi),
    "second_wind_share": (0.0, 1.0), "horizon": (0.0, 1e6),
}

SandscapeDuneSettings = type("SandscapeDuneSettings", (bpy.types.PropertyGroup,),
                             {"__annotations__": dune_fields(False), "LIMITS": DUNE_LIMITS,
                              "__doc__": "The dune field's settings (scene.sandscape_dunes)"})


classes = (SandscapeWalkerEntry, SandscapeFootprintSettings, SandscapeAtmosphereSettings,
           SandscapeCloudSettings, SandscapePostSettings, SandscapeDuneSettings)


def register():
    bpy.types.Scene.sandscape_footprints = PointerProperty(type=SandscapeFootprintSettings)
    bpy.types.Scene.sandscape_atmosphere = PointerProperty(type=SandscapeAtmosphereSettings)
    bpy.types.Scene.sandscape_post = PointerProperty(type=SandscapePostSettings)
    bpy.types.Scene.sandscape_clouds = PointerProperty(type=SandscapeCloudSettings)
    bpy.types.Scene.sandscape_dunes = PointerProperty(type=SandscapeDuneSettings)


def unregister():
    del bpy.types.Scene.sandscape_dunes
    del bpy.types.Scene.sandscape_clouds
    del bpy.types.Scene.sandscape_post
    del bpy.types.Scene.sandscape_atmosphere
    del bpy.types.Scene.sandscape_footprints
