"""An artist's eye-level shot of a trail: shared by bench/print_visibility.py and its test.

Flat sand 40 m wide, a walker crossing 10 m along -Y to +Y over frames 1-169, its prints painted
(5 cm deep, 6 mm rim: loose dry sand), a sun 15 degrees up from the side (+X), the demo's air,
and a camera at eye level (1.6 m) 3 m behind where the walk ends, looking back along the trail.
"""

import math

import bpy
import numpy as np

from . import readback, scenes, session

RESOLUTION = (480, 270)
DEPTH, RIM = 0.05, 0.006
LAST_FRAME = 169
PIXEL_CHANGE = 0.05  # a display channel moving by more than this is a visible change


def build(samples):
    """The shot, at the walk's last frame: (scene, camera)."""
    session.reset()
    terrain = scenes.height_field(40.0, 40, name="Their Sand")
    walker = scenes.keyframed_walker(lambda f: (0.0, -5.0 + 10.0 * (f - 1) / (LAST_FRAME - 1), 0.0),
                                     range(1, LAST_FRAME + 1))
    scenes.footprint_settings(terrain, walker, (1, LAST_FRAME), depth=DEPTH, rim=RIM, resolution=2048)
    bpy.context.view_layer.objects.active = terrain
    assert bpy.ops.sandscape.add_sand_material() == {"FINISHED"}
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    camera = scenes.camera("PERSP", location=(0.0, 8.0, 1.6),
                           rotation=(math.radians(80.0), 0.0, math.radians(180.0)), lens=35.0)
    camera.data.clip_end = 1e5
    scene = bpy.context.scene
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(15.0), math.radians(90.0)
    air.density, air.dust_density = 0.003, 0.002  # the demo's air
    air.set_exposure = True  # as the report suggests for this sky
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    readback.cycles_scene(scene, RESOLUTION, samples)  # a new file renders with EEVEE
    scene.cycles.use_denoising = True
    scene.frame_set(LAST_FRAME)
    return scene, camera


def flatten(scene):
    """The same shot without prints: depth and rim 0, painted again."""
    settings = scene.sandscape_footprints
    settings.depth = settings.rim = 0.0
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    scene.frame_set(LAST_FRAME)


def trail_distance(camera):
    """Each pixel's ground distance from the camera where its ray meets the ground (inf above
    the horizon): (H, W), rows bottom-up."""
    origins, directions = scenes.camera_rays(camera, *RESOLUTION)
    down = directions[..., 2] < 0
    t = -origins[..., 2] / np.where(down, directions[..., 2], -1e-9)
    return np.where(down, t * np.hypot(directions[..., 0], directions[..., 1]), np.inf)


def print_pixels(scene, camera):
    """Each painted print's centre in pixels (column, row from the bottom) and its ground
    distance from the camera: (N, 2), (N,)."""
    obj = next(o for o in scene.objects if o.get("sandscape_object") == "footprints")
    local = np.array([v.co[:] for v in obj.data.vertices], np.float64).reshape(-1, 3)
    world = local @ np.array(obj.matrix_world)[:3, :3].T + np.array(obj.matrix_world.translation)
    column, row = scenes.project(camera, world, *RESOLUTION)
    distance = np.hypot(*(world[:, :2] - np.array(camera.location[:2])).T)
    return np.stack([column, row], axis=1), distance
