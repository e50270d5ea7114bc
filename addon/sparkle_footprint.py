"""The render camera's pixel on the glint cells.

Sandscape Glint Cells sizes its cells to a pixel's footprint, and Sandscape Glint Splat puts each
sparkle into its pixel; these drivers keep the glint group's Pixel Angle (perspective), Pixel Size
(orthographic) and Resolution equal to what one pixel of the scene's active camera spans and to the
render's pixels. They are simple expressions: a farm
evaluates them with Python auto-run off, and they follow a new lens, resolution or camera.

A driver evaluated while the scene had no camera is marked invalid and Blender skips it until
the file is reloaded or the driver edited: so the sand would render with one cell per grain in
the session where the camera came after the sand. A depsgraph handler re-arms such drivers once
the scene has a camera (a check of our sand materials' drivers; nothing while a render runs).
"""

import math
import re

import bpy
from bpy.app.handlers import persistent

from . import drivers
from . import ownership as own

SOCKETS = ("Pixel Angle", "Pixel Size", "Resolution X", "Resolution Y")
# The pixels the camera's angle (or orthographic scale) spans: the larger side when the sensor
# fit is Auto, else the side it names.
_SPAN = "((fit == 0) * max(rx, ry) + (fit == 1) * rx + (fit == 2) * ry) * pct / 100"
EXPRESSIONS = {
    "Pixel Angle": f"(kind == 0) * 2 * tan(angle / 2) / ({_SPAN})",
    "Pixel Size": f"(kind == 1) * ortho / ({_SPAN})",
    "Resolution X": "rx * pct / 100",
    "Resolution Y": "ry * pct / 100",
}
VARIABLES = {  # name -> data path on the scene
    "kind": "camera.data.type", "fit": "camera.data.sensor_fit", "angle": "camera.data.angle",
    "ortho": "camera.data.ortho_scale", "rx": "render.resolution_x", "ry": "render.resolution_y",
    "pct": "render.resolution_percentage",
}


# Each expression's variables: a resolution driver needs no camera.
_USED = {name: [variable for variable in VARIABLES if re.search(rf"\b{variable}\b", expression)]
         for name, expression in EXPRESSIONS.items()}


def attach(node, scene):
    """Drive the node's Pixel Angle, Pixel Size and Resolution from the scene's camera (inputs the artist
    linked are left alone). Returns the number of inputs driven."""
    driven = 0
    for name, expression in EXPRESSIONS.items():
        socket = node.inputs.get(name)
        if socket is None or socket.is_linked:
            continue
        variables = [(variable, "SCENE", scene, VARIABLES[variable]) for variable in _USED[name]]
        drivers.drive(socket, "default_value", expression, variables)
        driven += 1
    return driven


def rearm(scenes=None):
    """Re-enable our sparkle drivers that Blender marked invalid while their scene had no camera,
    where it has one now. Returns how many were re-armed."""
    expressions = set(EXPRESSIONS.values())

    def ready(scene):
        return scene is not None and scene.camera is not None and (scenes is None or scene in scenes)

    return sum(drivers.rearm(material.node_tree.animation_data, expressions, ready)
               for material in bpy.data.materials
               if material.get(own.MATERIAL_KEY) == own.SAND and material.node_tree is not None)


@persistent
def _rearm_after_update(scene, _depsgraph=None):
    if not bpy.app.is_job_running("RENDER") and scene.camera is not None:
        rearm([scene])


def register():
    if _rearm_after_update not in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.append(_rearm_after_update)


def unregister():
    if _rearm_after_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(_rearm_after_update)


def pixel_angle(scene):
    """What the Pixel Angle driver gives, in Python (tests and benches)."""
    camera, render = scene.camera.data, scene.render
    fits = {"AUTO": max(render.resolution_x, render.resolution_y), "HORIZONTAL": render.resolution_x,
            "VERTICAL": render.resolution_y}
    span = fits[camera.sensor_fit] * render.resolution_percentage / 100
    return 2 * math.tan(camera.angle / 2) / span if camera.type == "PERSP" else 0.0
