"""The desert demo scene, built from an empty file with Sandscape's own bpy layer."""

import math

import bpy
import numpy as np

from . import atmosphere, clouds, dunes, footprints, post, presets, sand, walker
from .progress import Progress

# The dune field (lengths in metres; the demo's scene is in metres): transverse ridges 30 m apart
# under the scene's wind; seed 0 lays a crest along the walk (sky and prints in every frame; in a
# corridor the next dune hid the sun). The land reaches 4 km: the demo's haze lets under 1 %
# through by 3 km, and land further out only cost render time (its shadow rays cross kilometres
# of cloud layer under the low sun: +15-40 % on frame 120).
DUNES = {"width": 120.0, "depth": 120.0, "cell_size": 0.5, "spacing": 30.0, "sand_supply": 3.0, "seed": 0,
         "use_second_wind": False, "second_wind_angle": 0.0, "second_wind_share": 0.0, "horizon": 4000.0,
         "sand_material": True}
WIND = (0.6, 3.0, 0.0)  # metres per second, from the south: crests run east-west, along the walk
FRAMES = (1, 240)
# The walker sets off this many frames before the film starts, so from its first frame the camera
# behind it looks along a trail of prints (starting with the film, frames 1-70 showed bare sand).
PREROLL = 96  # 4 s: 5.6 m walked, past the camera's CAMERA_BEHIND and the frame's foot
WALK_FRAMES = (FRAMES[0] - PREROLL, FRAMES[1])
SUN = (math.radians(6.0), 1.05)  # low, ahead-left of the walker, in view: slopes lit from the side
# The camera walks the walker's own trail, CAMERA_BEHIND metres back along it, CAMERA_SIDE to its
# right and CAMERA_HEIGHT up: the prints run from the frame's foot to the walker's heels in every
# frame (a camera at a fixed offset turned by the heading saw the trail come in from the side).
CAMERA_BEHIND, CAMERA_SIDE, CAMERA_HEIGHT = 4.5, 0.5, 1.1  # metres
# From the first frame to the last here the camera eases back and up to (behind, height): the
# traveller walks on into the desert and the dunes open out under the end of the film (the sixth
# review: the figure the same size in the same place for 10 s). The hero frame is before it. Up to
# the start's angle down at the walker, no steeper: at 2.6 m the cloud deck left the frame's top
# (removing the clouds changed 3.5 % of frame 200's blocks, 6.4 % before).
CAMERA_PULL_BACK = ((90, FRAMES[1]), (9.0, 2.2))
CAMERA_LENS = 20.0  # mm: the near prints, the walker and the low sun in one frame
CAMERA_TURN_FRAMES = 24  # the camera's heading is smoothed over this many frames either side
WALK_SWAY = 0.03  # a straighter S than Add Walker's (it turns up to 11 degrees, not 32)
CAMERA_CLEARANCE = 0.6  # metres the camera keeps above the sand under it
CAMERA_SMOOTH_FRAMES = 12  # the lift over a crest eases in and out over about this many frames
CAMERA_SHIFT = (0.05, 0.0)  # lens shift, not a turn: the low sun further in
# Desert haze: visibility 10-50 km (../shared/look-references.md); the far dunes fade. Its upper end:
# the far haze veils the clouds out to 25 km, and at 20 km a cloud 5 degrees up kept 0.11 of its
# contrast, 3 degrees up 0.02 (now 0.42 and 0.20; core.far_haze.haze_length on the demo's boxes).
AIR = {"density": 0.003, "dust_density": 0.002, "margin": 20.0, "visibility": 50000.0, "set_exposure": True,
       "replace_world": True}
# Cumulus based at 1.2 km out to 25 km, so they recede to the haze at the horizon (within 8 km they
# only reached 8.5 degrees down the sky: one flat deck over the frame's top, "a lid" to five reviews).
# The 6 degree sun's ray crosses the layer 11-23 km off; of seeds 0-99 at this coverage only 51 leaves
# it and a 0.6 degree cone round it clear on every 40th frame (devtools/cloud_gap.py, on the twin; a
# clouded sun put the whole frame in shade), with cloud 2-6 degrees round the sun. 100 m voxels keep
# the grid at 3.6 M.
CLOUDS = {"coverage": 0.4, "seed": 51, "base": 1200.0, "thickness": 1200.0, "step": 400.0, "voxel": 100.0,
          "reach": 25000.0}
# Shot under the grey-card exposure Add Atmosphere sets, as golden hour is photographed: AgX then
# keeps the lit sand's colour instead of rolling it toward white (a milky frame at the card's).
EXPOSURE_SHIFT = -0.7  # stops
# metres: loose dry sand, a low soft rim spread wide enough that the low sun lights no razor lip
# along it (README, Footprints)
PRINTS = {"depth": 0.04, "rim": 0.006, "rim_width": 0.08}
# Texels along the walk's longer side: 2.5 mm over its 20 m. The nearest print is 1.5 m from the
# poster's camera, where 1 cm texels (2048) showed as stair-stepped facets 5 px wide on its walls.
PRINT_TEXELS = 8192
SAND = {"Threshold": 0.985, "Glint Size": 0.012, "Facing Power": 4.0, "Strength": 60.0, "Seed": 1.0}


def follow_camera(scene, figure, terrain):
    """A camera that walks the walker's trail behind it, never below CAMERA_CLEARANCE over the
    sand under it, and looks at the walker: its path is keyed on every frame (no scripts), its aim a
    Track To constraint."""
    camera = bpy.data.objects.new("Demo Camera", bpy.data.cameras.new("Demo Camera"))
    camera.data.lens = CAMERA_LENS
    camera.data.clip_end = 40000.0  # the clouds are kilometres away, the land reaches 20 km
    camera.data.shift_x, camera.data.shift_y = CAMERA_SHIFT
    scene.collection.objects.link(camera)
    scene.camera = camera
    walk_frames = np.arange(WALK_FRAMES[0], WALK_FRAMES[1] + 1)
    walk = []
    for frame in walk_frames:
        scene.frame_set(int(frame))
        walk.append(np.array(figure.matrix_world.translation))
    scene.frame_set(FRAMES[0])
    frames = np.arange(FRAMES[0], FRAMES[1] + 1)
    behind, height = pulled_back(walk_frames)
    places = trail_places(np.array(walk), behind, CAMERA_SIDE, height)[frames - WALK_FRAMES[0]]
    top = float(np.max([v[2] for v in terrain.bound_box]))
    floor = walker.ground_heights(scene, terrain, places[:, :2], top) + CAMERA_CLEARANCE
    places[:, 2] = np.maximum(places[:, 2], eased_lift(floor))
    for frame, place in zip(frames, places, strict=True):
        camera.location = tuple(place)
        camera.keyframe_insert("location", frame=int(frame))
    aim = camera.constraints.new("TRACK_TO")
    aim.target = figure
    aim.track_axis, aim.up_axis = "TRACK_NEGATIVE_Z", "UP_Y"
    return camera


def pulled_back(frames):
    """The camera's distance behind and height over the walker at `frames`: CAMERA_BEHIND and
    CAMERA_HEIGHT, eased (smoothstep) over CAMERA_PULL_BACK's frames to its own."""
    (first, last), (behind, height) = CAMERA_PULL_BACK
    t = np.clip((np.asarray(frames, np.float64) - first) / (last - first), 0.0, 1.0)
    eased = t * t * (3.0 - 2.0 * t)
    return CAMERA_BEHIND + (behind - CAMERA_BEHIND) * eased, CAMERA_HEIGHT + (height - CAMERA_HEIGHT) * eased


def trail_places(walk, behind, side, height):
    """Per frame, the place `behind` back along the walked path (before its start, straight back
    along its first heading), `side` to the right of the path's smoothed heading there and
    `height` over the walker's own height at that frame (not the trail's back there: a camera
    below a walker on a rise sees the trail edge-on). `behind` and `height`: one for all frames
    or one per frame."""
    arc = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(walk[:, :2], axis=0), axis=1))])
    back = arc - behind
    moving = np.flatnonzero(arc > 1e-6)
    start = (walk[moving[0], :2] - walk[0, :2]) / arc[moving[0]] if len(moving) else np.array([1.0, 0.0])
    trail = np.stack([np.interp(back, arc, walk[:, axis]) for axis in range(2)], axis=-1)
    trail[back < 0] = walk[0, :2] + back[back < 0, None] * start
    heading = np.gradient(trail, axis=0)
    heading[np.linalg.norm(heading, axis=1) < 1e-9] = start
    turn = smoothed(np.unwrap(np.arctan2(heading[:, 1], heading[:, 0])), CAMERA_TURN_FRAMES)
    right = np.stack([np.sin(turn), -np.cos(turn)], axis=-1)
    return np.concatenate([trail + side * right, walk[:, 2:] + np.reshape(height, (-1, 1))], axis=-1)


def eased_lift(floor):
    """The lowest heights the camera may take, eased: a running maximum over
    CAMERA_SMOOTH_FRAMES either side, then smoothed by the same span, never below the floor."""
    span = CAMERA_SMOOTH_FRAMES
    padded = np.pad(floor, span, mode="edge")
    highest = np.array([padded[i:i + 2 * span + 1].max() for i in range(len(floor))])
    return np.maximum(smoothed(highest, span), floor)


def smoothed(values, span):
    """A Hann-weighted running mean over `span` samples either side (the ends held)."""
    kernel = np.hanning(2 * span + 3)[1:-1]  # no zero weights at the ends
    return np.convolve(np.pad(values, span, mode="edge"), kernel / kernel.sum(), mode="valid")


def build(context):
    """Dunes, glinting sand, a walker with footprints, dusty air with a low sun, clouds, post effects,
    camera.

    Calls the bpy layer directly with known-good values (operators validate artists' input).
    """
    scene = context.scene
    scene.frame_start, scene.frame_end = FRAMES
    scene.render.engine = "CYCLES"  # the demo's presets and post effects are measured in Cycles
    # Its denoising comes with the post effects below, once there is a camera and a sun.
    presets.apply(scene, {k: v for k, v in presets.PRESETS["PREVIEW"].items() if k != presets.DENOISE})
    presets.apply_eevee(scene, presets.EEVEE_PRESETS["PREVIEW"])  # for an artist who switches to EEVEE
    scene.sandscape_atmosphere.wind = WIND
    progress = Progress("Sandscape demo")
    terrain = dunes.build(scene, DUNES, progress)["field"]
    progress.end()
    context.view_layer.objects.active = terrain
    sand.apply(terrain, {**sand.default_glint_values(), **SAND}, ripple_values=sand.default_ripples(scene),
               scene=scene)
    steps = scene.sandscape_footprints
    steps.terrain = terrain
    steps.walker, path = walker.ensure_walker(scene, terrain, *WALK_FRAMES, sway=WALK_SWAY)  # 19.6 m in 14 s
    steps.source = "WALKER"
    steps.use_scene_range = False
    steps.frame_start, steps.frame_end = WALK_FRAMES
    steps.resolution = PRINT_TEXELS
    for name, value in PRINTS.items():
        setattr(steps, name, value)
    footprints.paint(scene, steps)
    camera = follow_camera(scene, steps.walker, terrain)
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = SUN
    for name, value in AIR.items():
        setattr(air, name, value)
    # The sun lamp gets the sky's own sun (reddened 6 degrees up) and the scene the exposure
    # that shows level ground under it at its own grey; the dust box spans what the camera
    # sees over the frames, out to where the haze lets 1 % through.
    atmosphere.apply(scene, air)
    scene.view_settings.exposure += EXPOSURE_SHIFT
    scene.view_settings.view_transform = "AgX"
    scene.view_settings.look = "AgX - Punchy"  # the haze greys the sand; AgX's base look more so
    for name, value in CLOUDS.items():
        setattr(scene.sandscape_clouds, name, value)
    clouds.apply(scene, clouds.scene_settings(scene))  # spans the camera's views over the frames
    post.apply_post_effects(scene, scene.sandscape_post)
    return {"terrain": terrain, "camera": camera, "walker": steps.walker}
