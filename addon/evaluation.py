"""The evaluated depsgraph of the scene being worked on, not of whatever the context shows.

bpy.context.evaluated_depsgraph_get() is the context's view layer: under
`context.temp_override(scene=other)`, or for a scene passed in by a script while another is
shown, it evaluates the wrong scene, and objects of the scene passed in come back unevaluated.
"""

import bpy
import numpy as np

from . import drivers


def scene_view_layer(scene):
    """The view layer worked on in this scene: the context's when it shows this scene, else the
    first layer that renders (else the first)."""
    context_layer = getattr(bpy.context, "view_layer", None)
    if bpy.context.scene == scene and context_layer is not None and context_layer in scene.view_layers[:]:
        return context_layer
    return next((layer for layer in scene.view_layers if layer.use), scene.view_layers[0])


def scene_depsgraph(scene):
    """That view layer's depsgraph, evaluated."""
    layer = scene_view_layer(scene)
    if layer == getattr(bpy.context, "view_layer", None):
        return bpy.context.evaluated_depsgraph_get()
    depsgraph = layer.depsgraph
    if depsgraph is None:  # never evaluated yet: the context makes it, without stepping a frame
        with bpy.context.temp_override(scene=scene, view_layer=layer):
            return bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    return depsgraph


def world_matrix(scene, obj):
    """The object's world matrix as the scene evaluates it: an object's own matrix_world is only
    brought up to date by the shown scene's depsgraph."""
    return obj.evaluated_get(scene_depsgraph(scene)).matrix_world.copy()


def mesh_triangles(mesh):
    """A mesh's vertex positions (V, 3) and its render triangles (T, 3) as numpy arrays."""
    local = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", local)
    mesh.calc_loop_triangles()
    triangles = np.empty(len(mesh.loop_triangles) * 3, np.int32)
    mesh.loop_triangles.foreach_get("vertices", triangles)
    return local.reshape(-1, 3).astype(np.float64), triangles.reshape(-1, 3)


def stepped_frames(scene, frames):
    """Step the scene through the frames, yielding each, and back to the frame it was on after
    (also when the caller stops early or raises)."""
    kept = scene.frame_current
    try:
        for frame in frames:
            scene.frame_set(int(frame))  # also the current one: unkeyed edits give way to the keys
            yield frame
    finally:
        scene.frame_set(kept)


def drive_by_frame(socket):
    """Drive a socket's value by the scene frame: a simple expression, which runs without Python
    auto-run (a farm, or a file opened with scripts off)."""
    return drivers.drive(socket, "default_value", "frame", [])
