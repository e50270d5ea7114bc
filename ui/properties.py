"""Scene settings: what the sidebar's Footprints section edits and the operators read.

Scripts set them too: scene.sandscape_footprints.stride = 0.6, then
bpy.ops.sandscape.paint_footprints(). Limits are soft: out-of-range values set from a
script reach the operator, which reports them instead of silently clamping.
"""

import math

import bpy
from bpy.props import (
    BoolProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    IntProperty,
    PointerProperty,
)

from ..node_groups import footprint_height

DEPTH = footprint_height.INPUTS["Depth"]
RIM = footprint_height.INPUTS["Rim"]
NOISE = footprint_height.INPUTS["Noise Amount"]


def _is_mesh(_self, obj):
    return obj.type == "MESH"


class SandscapeFootprintSettings(bpy.types.PropertyGroup):
    source: EnumProperty(
        name="Source", default="WALKER",
        items=(("WALKER", "Walker", "Steps along the path of an animated object"),
               ("PARTICLES", "Particles", "One print where each particle of a particle system is born")))
    walker: PointerProperty(name="Walker", type=bpy.types.Object,
                            description="Any object whose world position is animated over the frame range")
    particle_object: PointerProperty(name="Particle Emitter", type=bpy.types.Object,
                                     description="Object whose first particle system marks the prints")
    terrain: PointerProperty(name="Terrain", type=bpy.types.Object, poll=_is_mesh,
                             description="Mesh the prints are projected onto and painted into")
    use_scene_range: BoolProperty(name="Scene Frame Range", default=True,
                                  description="Walk over the scene's frame range")
    frame_start: IntProperty(name="Start", default=1, description="First frame of the walk")
    frame_end: IntProperty(name="End", default=250, description="Last frame of the walk")
    stride: FloatProperty(name="Stride", default=0.7, soft_min=0.05, soft_max=3.0, subtype="DISTANCE",
                          unit="LENGTH", description="Distance along the path from one print to the next")
    stance: FloatProperty(name="Stance", default=0.2, soft_min=0.0, soft_max=1.0, subtype="DISTANCE",
                          unit="LENGTH", description="Distance between the left and right feet")
    foot_length: FloatProperty(name="Foot Length", default=0.27, soft_min=0.02, soft_max=2.0,
                               subtype="DISTANCE", unit="LENGTH", description="Heel to toe")
    foot_width: FloatProperty(name="Foot Width", default=0.10, soft_min=0.01, soft_max=1.0,
                              subtype="DISTANCE", unit="LENGTH", description="Across the ball of the foot")
    depth: FloatProperty(name="Depth", default=DEPTH[2], soft_min=0.0, soft_max=0.5, subtype="DISTANCE",
                         unit="LENGTH", description=DEPTH[1])
    rim: FloatProperty(name="Rim", default=RIM[2], soft_min=0.0, soft_max=0.2, subtype="DISTANCE",
                       unit="LENGTH", description=RIM[1])
    rim_width: FloatProperty(name="Rim Width", default=0.04, soft_min=0.0, soft_max=0.5, subtype="DISTANCE",
                             unit="LENGTH", description="Width of the ring of pushed-up sand")
    variation: FloatProperty(name="Variation", default=0.1, soft_min=0.0, soft_max=0.9, subtype="FACTOR",
                             description="Random spread of each print's depth scale: 0.1 is +-10 %")
    noise_amount: FloatProperty(name="Noise", default=NOISE[2], soft_min=0.0, soft_max=1.0,
                                subtype="FACTOR", description=NOISE[1])
    seed: IntProperty(name="Seed", default=0, min=0, description="Seed of the per-print variation")
    resolution: IntProperty(name="Resolution", default=2048, soft_min=16, soft_max=16384,
                            description="Texels along the longer side of the print region")
    dicing_pixel_size: FloatProperty(name="Dicing", default=1.0, soft_min=0.25, soft_max=16.0,
                                     description="Adaptive subdivision edge length in pixels over the prints")


class SandscapeAtmosphereSettings(bpy.types.PropertyGroup):
    sun_elevation: FloatProperty(name="Sun Elevation", default=math.radians(25.0), subtype="ANGLE",
                                 soft_min=math.radians(-10.0), soft_max=math.radians(90.0),
                                 description="Height of the sun above the horizon")
    sun_azimuth: FloatProperty(name="Sun Azimuth", default=math.radians(135.0), subtype="ANGLE",
                               description="Compass direction of the sun: 0 along +Y, 90 degrees along +X")
    density: FloatProperty(name="Density", default=0.02, soft_min=0.0, soft_max=1.0, precision=4,
                           description="Scattering coefficient at 550 nm, 1/m; 0 adds no volume at all. "
                           "The volume is a box around the scene: a world volume would block the sun lamp")
    wavelengths: FloatVectorProperty(name="Wavelengths", size=3, default=(680.0, 550.0, 440.0),
                                     soft_min=380.0, soft_max=780.0,
                                     description="Red, green, blue wavelengths in nm for the 1/lambda^4 law")
    dust_density: FloatProperty(name="Dust", default=0.0, soft_min=0.0, soft_max=1.0, precision=4,
                                description="Extra grey, forward-scattering dust (Henyey-Greenstein), 1/m; "
                                "0 leaves it out")
    anisotropy: FloatProperty(name="Anisotropy", default=0.6, soft_min=-0.9, soft_max=0.95,
                              description="Henyey-Greenstein g of the dust: above 0 scatters forwards")
    use_wind: BoolProperty(name="Wind-Lifted Dust", default=True,
                           description="Patches of dust carried by the wind and thinning with height; off "
                           "gives a homogeneous volume, far cheaper to render")
    wind: FloatVectorProperty(name="Wind", size=3, default=(3.0, 1.0, 0.0), subtype="VELOCITY",
                              description="Wind velocity in metres per second")
    dust_scale: FloatProperty(name="Patch Size", default=8.0, soft_min=0.1, soft_max=100.0,
                              subtype="DISTANCE", unit="LENGTH", description="Size of the dust patches")
    coverage: FloatProperty(name="Coverage", default=0.5, soft_min=0.0, soft_max=1.0, subtype="FACTOR",
                            description="Share of the ground under dust")
    softness: FloatProperty(name="Softness", default=0.08, soft_min=0.001, soft_max=0.5,
                            description="Width of the patch edges")
    falloff: FloatProperty(name="Height Falloff", default=1.5, soft_min=0.05, soft_max=50.0,
                           subtype="DISTANCE", unit="LENGTH",
                           description="Height over which dust thins by 1/e")
    margin: FloatProperty(name="Margin", default=2.0, soft_min=0.0, soft_max=100.0, subtype="DISTANCE",
                          unit="LENGTH", description="How far the dust box reaches beyond the scene")


class SandscapePostSettings(bpy.types.PropertyGroup):
    use_blur: BoolProperty(name="Gated Blur", default=True,
                           description="Blur the scattered light where it changes the luminance (seed 000)")
    blur_threshold: FloatProperty(name="Threshold", default=0.01, soft_min=0.0, soft_max=1.0, precision=4,
                                  description="Luminance change below which the scattered light stays sharp")
    use_god_rays: BoolProperty(name="God Rays", default=True,
                               description="Screen-space light scattering towards the sun (GPU Gems 3)")
    samples: IntProperty(name="Samples", default=32, soft_min=4, soft_max=128,
                         description="Samples along each ray: more is smoother and slower")
    ray_density: FloatProperty(name="Density", default=0.9, soft_min=0.0, soft_max=1.0,
                               description="Fraction of the way to the sun the samples span")
    ray_weight: FloatProperty(name="Weight", default=0.05, soft_min=0.0, soft_max=1.0,
                              description="Weight of each sample")
    ray_decay: FloatProperty(name="Decay", default=0.97, soft_min=0.5, soft_max=1.0,
                             description="Falloff per sample; above 1 the rays would grow without bound")
    ray_exposure: FloatProperty(name="Exposure", default=1.0, soft_min=0.0, soft_max=10.0,
                                description="Overall strength of the rays")
    disc_radius: FloatProperty(name="Sun Disc", default=0.08, soft_min=0.005, soft_max=0.5,
                               description="Radius of the glowing disc around the sun, in frame heights")
    fade: FloatProperty(name="Edge Fade", default=0.25, soft_min=0.0, soft_max=1.0,
                        description="How far outside the frame (in frame widths) the rays fade out")


classes = (SandscapeFootprintSettings, SandscapeAtmosphereSettings, SandscapePostSettings)


def register():
    bpy.types.Scene.sandscape_footprints = PointerProperty(type=SandscapeFootprintSettings)
    bpy.types.Scene.sandscape_atmosphere = PointerProperty(type=SandscapeAtmosphereSettings)
    bpy.types.Scene.sandscape_post = PointerProperty(type=SandscapePostSettings)


def unregister():
    del bpy.types.Scene.sandscape_post
    del bpy.types.Scene.sandscape_atmosphere
    del bpy.types.Scene.sandscape_footprints
