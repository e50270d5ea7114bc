"""What the scene camera sees over the frame range: the views the clouds and the dust box are
fitted to."""

import numpy as np

from . import evaluation, units

FRAME_SAMPLES = 16  # camera positions sampled over the frame range
# Clip End over Clip Start past which EEVEE's picture breaks down: a helper's view rendered alike
# at 1:10^6 and 1:10^7 and brighter, its haze and clouds blocky, at 1:10^8 (whether 1 mm to 100 km
# or 1 cm to 1000 km: the ratio, not the units; README). Between the two.
MOST_DEPTH_RATIO, SAFE_DEPTH_RATIO = 2e7, 1e7


def frames_per_second(scene):
    return scene.render.fps / scene.render.fps_base


def scene_camera(scene):
    """The scene's camera object when it is a camera (an empty or a light can be the scene
    camera), else None."""
    camera = scene.camera
    return camera if camera is not None and camera.type == "CAMERA" else None


def eevee_depth_warning(scene):
    """Why an EEVEE render of the scene's camera breaks down, and what to change; or None."""
    camera = scene_camera(scene)
    if scene.render.engine != "BLENDER_EEVEE" or camera is None:
        return None
    start, end = camera.data.clip_start, camera.data.clip_end
    if start <= 0 or end / start <= MOST_DEPTH_RATIO:
        return None
    ratio = float(f"{end / start:.2g}")  # 1 : 100,000,000, not 99,999,999 from a float's 0.1
    return (f"Camera '{camera.name}' sees from {units.length_text(scene, start)} to "
            f"{units.length_text(scene, end)} (Clip Start to Clip End, 1 : {ratio:,.0f}): past "
            f"1 : {MOST_DEPTH_RATIO:,.0f} EEVEE renders the haze and clouds brighter and blocky. Raise its "
            f"Clip Start (Camera ▸ Lens) to {units.length_text(scene, end / SAFE_DEPTH_RATIO)}")


def camera_views(scene, camera):
    """The camera's world matrix and frame at up to FRAME_SAMPLES frames of the scene's range
    (one when nothing animates it), as core.clouds.frame_rays wants them."""
    animated = any(o.animation_data is not None or o.constraints for o in _chain(camera))
    animated = animated or camera.data.animation_data is not None
    frames = [scene.frame_current]
    if animated:
        sampled = np.linspace(scene.frame_start, scene.frame_end, FRAME_SAMPLES)
        frames = sorted({int(round(f)) for f in sampled} | {scene.frame_current})
    views = []
    for _ in evaluation.stepped_frames(scene, frames):
        corners = [tuple(v) for v in camera.data.view_frame(scene=scene)]
        views.append({"matrix": np.array(camera.matrix_world), "ortho": camera.data.type == "ORTHO",
                      "corners": corners})
    return views


def _chain(obj):
    while obj is not None:
        yield obj
        obj = obj.parent


def reach_points(views, reach):
    """World points that bound every view out to `reach` scene units: the camera positions and
    the frame corners pushed out that far (core.clouds' view conventions)."""
    points = []
    for view in views:
        matrix = view["matrix"]
        corners = np.asarray(view["corners"], np.float64)
        if view["ortho"]:
            far = np.c_[corners[:, :2], np.full(len(corners), -reach)]
            near = np.c_[corners[:, :2], np.zeros(len(corners))]
            local = np.r_[near, far]
        else:
            far = corners / np.linalg.norm(corners, axis=1, keepdims=True) * reach
            local = np.r_[np.zeros((1, 3)), far]
        points.append(local @ matrix[:3, :3].T + matrix[:3, 3])
    return np.concatenate(points)
