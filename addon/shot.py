"""What the scene camera sees over the frame range: the views the clouds and the dust box are
fitted to."""

import numpy as np

from . import evaluation

FRAME_SAMPLES = 16  # camera positions sampled over the frame range


def frames_per_second(scene):
    return scene.render.fps / scene.render.fps_base


def scene_camera(scene):
    """The scene's camera object when it is a camera (an empty or a light can be the scene
    camera), else None."""
    camera = scene.camera
    return camera if camera is not None and camera.type == "CAMERA" else None


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
