"""The sun's place on screen for the god rays, driven on every frame.

Simple-expression drivers on the post tree read the scene camera's and the sun's world matrices,
the lens and the render size: whatever moves them (keys, constraints, parents, paths, physics,
a marker that switches cameras) moves the rays, with no handler, no key and no frame stepped,
and a farm with the extension off and Python auto-run off evaluates them the same. The drivers
give the sun's direction in camera space and the lens' scale and shift; the Sandscape Sun Place
group turns them into the place on screen and the rays' fade, in the compositor.

The reference they are tested against is stepped_curve: Blender's own projection
(calc_matrix_camera) of the evaluated camera, frame by frame.
"""

import numpy as np

from ..core import post
from ..node_groups import helper as h
from ..node_groups import sun_place
from . import drivers, evaluation, keyed_motion, shot
from . import ownership as own

RAYS, PLACE = "Sandscape God Rays", "Sandscape Sun Place"  # node names in the post tree
DIRECTION, LENS, SHIFT = "Sandscape Sun Direction", "Sandscape Sun Lens", "Sandscape Sun Shift"


def _cross(a, b):
    """The components of a × b for two camera axes named by letter (xa, xb, xc ...)."""
    return (f"{a}b*{b}c-{a}c*{b}b", f"{a}c*{b}a-{a}a*{b}c", f"{a}a*{b}b-{a}b*{b}a")


def _dot(name, cross):
    return "+".join(f"{name}{'abc'[i]}*({term})" for i, term in enumerate(cross))


# The sun's axis (the lamp's world +Z, towards it) in the camera's space: the inverse of the
# camera's matrix with its axes at unit length, as Blender renders it (Cramer's rule, so a
# sheared camera under a stretched, turned parent comes out right too).
_DETERMINANT = _dot("x", _cross("y", "z"))
# A degenerate camera (no camera: every variable 0) divides by 1, not by 0, so the console stays quiet.
_IN_CAMERA = {axis: f"({_dot('s', _cross(*others))})*sqrt({axis}a*{axis}a+{axis}b*{axis}b+{axis}c*{axis}c)"
                    f"/({_DETERMINANT} if {_DETERMINANT}!=0 else 1)"
              for axis, others in (("x", "yz"), ("y", "zx"), ("z", "xy"))}
# The sensor fit's span in pixels (pixel aspect applied), as Blender fits the sensor.
_SPAN = "((f==0)*max(rx*ax,ry*ay)+(f==1)*rx*ax+(f==2)*ry*ay)"
EXPRESSIONS = {
    (DIRECTION, "X"): _IN_CAMERA["x"], (DIRECTION, "Y"): _IN_CAMERA["y"], (DIRECTION, "Z"): _IN_CAMERA["z"],
    (LENS, "X"): f"{_SPAN}/(rx*ax)/2/max(tan(t/2),1e-9)",
    (LENS, "Y"): f"{_SPAN}/(ry*ay)/2/max(tan(t/2),1e-9)",
    (SHIFT, "X"): f"sx*{_SPAN}/(rx*ax)", (SHIFT, "Y"): f"sy*{_SPAN}/(ry*ay)",
    (PLACE, "Perspective"): "k==0",
}
CAMERA_PATHS = {  # variable -> data path on the scene: its camera now, whichever that is
    **{f"{axis}{'abc'[row]}": f"camera.matrix_world[{column}][{row}]"
       for column, axis in enumerate("xyz") for row in range(3)},
    "t": "camera.data.angle", "k": "camera.data.type", "f": "camera.data.sensor_fit",
    "sx": "camera.data.shift_x", "sy": "camera.data.shift_y",
    "rx": "render.resolution_x", "ry": "render.resolution_y",
    "ax": "render.pixel_aspect_x", "ay": "render.pixel_aspect_y",
}


def rays_node(tree):
    return own.node(tree, RAYS)


def add_nodes(tree, fade):
    """The driven inputs and the Sun Place group in the post tree; the group node (its Sun and
    Intensity outputs place and fade the rays)."""
    place = h.add_node(tree, "CompositorNodeGroup", name=PLACE, label="Sun Place",
                       node_tree=h.ensure_group(sun_place), inputs={"Fade": fade})
    for name, label, socket in ((DIRECTION, "Sun Direction (driven)", "Direction"),
                                (LENS, "Lens Scale (driven)", "Scale"),
                                (SHIFT, "Lens Shift (driven)", "Shift")):
        values = h.add_node(tree, "ShaderNodeCombineXYZ", name=name, label=label)
        h.link(tree, values.outputs[0], place.inputs[socket])
    return place


def _sockets(tree):
    return {key: own.node(tree, key[0]).inputs[key[1]] for key in EXPRESSIONS}


def attach(tree, scene, sun):
    """Drive the tree's sun inputs from the scene's camera and this sun (None: no sun, so no
    rays). Returns the number of values driven."""
    if own.node(tree, PLACE) is None:
        return 0
    sockets = _sockets(tree)
    if sun is None:
        for socket in sockets.values():
            socket.driver_remove("default_value")
        sockets[(PLACE, "Perspective")].default_value = 0.0
        return 0
    # The sun first: rearm() and driven_sun() read the first target.
    variables = drivers.lamp_axis(sun)
    variables += [(name, "SCENE", scene, path) for name, path in CAMERA_PATHS.items()]
    for key, socket in sockets.items():
        drivers.drive(socket, "default_value", EXPRESSIONS[key], variables)
    return len(sockets)


def driven_sun(tree):
    """The sun the tree's drivers follow, or None."""
    animation = tree.animation_data
    for curve in animation.drivers if animation is not None else ():
        if curve.driver.expression == EXPRESSIONS[(DIRECTION, "Z")] and curve.driver.variables:
            return curve.driver.variables[0].targets[0].id
    return None


def rearm(scenes):
    """Re-enable the sun drivers of these scenes' trees that Blender set aside while the scene
    had no camera or sun; how many."""
    rearmed = 0
    for scene in scenes:
        tree = own.scene_compositor(scene)
        if tree is not None and scene.camera is not None:
            rearmed += drivers.rearm(tree.animation_data, set(EXPRESSIONS.values()),
                                     lambda sun, seen=scene.objects: sun is not None and sun.name in seen)
    return rearmed


def driven_place(tree, scene, fade=None, depsgraph=None):
    """(u, v, intensity) the drivers and the Sun Place group (through its twin) give on the
    scene's current frame, read from the scene's own evaluation."""
    depsgraph = depsgraph or evaluation.scene_depsgraph(scene)
    values = {key: socket.default_value for key, socket in _sockets(tree.evaluated_get(depsgraph)).items()}
    place = own.node(tree, PLACE)
    fade = place.inputs["Fade"].default_value if fade is None else fade
    return post.sun_on_screen([values[(DIRECTION, axis)] for axis in "XYZ"],
                              [values[(LENS, axis)] for axis in "XY"],
                              [values[(SHIFT, axis)] for axis in "XY"], values[(PLACE, "Perspective")], fade)


def driven_curve(tree, scene, fade=None):
    """[(frame, u, v, intensity)] stepping the scene's frames."""
    return [(frame, *driven_place(tree, scene, fade))
            for frame in evaluation.stepped_frames(scene, range(scene.frame_start, scene.frame_end + 1))]


# ---------------------------------------------------------------- the reference, in Python

def view_projection(scene, camera, depsgraph=None):
    """World to clip space of the camera as the scene renders it; camera as evaluated in depsgraph
    (default: the scene's own)."""
    depsgraph = depsgraph or evaluation.scene_depsgraph(scene)
    camera = camera.evaluated_get(depsgraph)
    render = scene.render
    width = max(render.resolution_x * render.resolution_percentage // 100, 1)
    height = max(render.resolution_y * render.resolution_percentage // 100, 1)
    projection = np.array(camera.calc_matrix_camera(
        depsgraph, x=width, y=height, scale_x=render.pixel_aspect_x, scale_y=render.pixel_aspect_y))
    return projection @ np.linalg.inv(_unit_axes(np.array(camera.matrix_world, dtype=np.float64)))


def _unit_axes(matrix):
    """The camera's world matrix as Blender renders from it: its axes at unit length (shear kept)."""
    matrix = np.array(matrix, dtype=np.float64)
    matrix[:3, :3] /= np.linalg.norm(matrix[:3, :3], axis=0)
    return matrix


def _frame_place(projection, direction, fade, frame, perspective=True):
    (u, v), in_front = post.screen_position(projection, direction)
    in_front = in_front and perspective
    intensity = post.sun_intensity((u, v), in_front, fade)
    if not in_front or not np.isfinite((u, v)).all():
        u, v = 0.5, 0.5  # any finite place: the intensity is 0
    return (frame, float(u), float(v), float(intensity))


def curve_from_keys(scene, sun, fade):
    """The sun curve read from the keyframes, without stepping a frame; None where more than
    plain keys move the camera or the sun (keyed_motion.py), or markers switch cameras."""
    camera = scene.camera
    if camera is None or any(marker.camera is not None for marker in scene.timeline_markers):
        return None
    if not keyed_motion.still_camera_data(camera):
        return None
    frames = range(scene.frame_start, scene.frame_end + 1)
    cameras = keyed_motion.world_matrices(scene, camera, frames)
    suns = keyed_motion.world_matrices(scene, sun, frames) if cameras is not None else None
    if suns is None:
        return None
    projection = view_projection(scene, camera) @ _unit_axes(np.array(camera.matrix_world))  # the lens alone
    perspective = camera.data.type == "PERSP"
    return [_frame_place(projection @ np.linalg.inv(_unit_axes(view)), lamp[:3, 2], fade, frame, perspective)
            for frame, view, lamp in zip(frames, cameras, suns, strict=True)]


def stepped_curve(scene, sun, fade):
    """The sun curve by stepping every frame: whatever moves the camera and the sun."""
    curve = []
    for frame in evaluation.stepped_frames(scene, range(scene.frame_start, scene.frame_end + 1)):
        depsgraph = evaluation.scene_depsgraph(scene)  # a scene not shown: its own evaluation
        direction = np.array(sun.evaluated_get(depsgraph).matrix_world.col[2][:3])
        camera = shot.scene_camera(scene)
        if camera is None:
            curve.append((frame, 0.5, 0.5, 0.0))
            continue
        curve.append(_frame_place(view_projection(scene, camera, depsgraph), direction, fade, frame,
                                  camera.data.type == "PERSP"))
    return curve


def sun_curve(scene, sun, fade):
    """The sun curve: from the keys where they are all that move the camera and the sun (no
    frame stepped), else by stepping the frames."""
    from_keys = curve_from_keys(scene, sun, fade)
    return from_keys if from_keys is not None else stepped_curve(scene, sun, fade)
