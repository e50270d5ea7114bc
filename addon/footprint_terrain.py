"""The terrain side of footprints: finding what Sandscape made for a terrain, sampling the walker
or the particles over the frames, the terrain's evaluated render triangles and dropping prints
straight down onto them, and the print frame's place as the scene evaluates it."""

import contextlib

import numpy as np
from mathutils import Vector
from mathutils.bvhtree import BVHTree

from ..node_groups import helper as h
from ..node_groups import region_cut
from . import evaluation
from . import ownership as own


class FootprintError(ValueError):
    """Input that cannot make footprints; the message is for the artist."""


# ---------------------------------------------------------------- finding our data

def find_object(scene, kind, terrain):
    return own.scene_object(scene, kind, **{own.TERRAIN_KEY: terrain})


def find_print_map(terrain):
    return own.image(own.PRINT_MAP, **{own.TERRAIN_KEY: terrain})


def find_cut_modifier(terrain):
    for modifier in terrain.modifiers:
        group = getattr(modifier, "node_group", None)
        if modifier.type == "NODES" and group is not None and group.get(h.GROUP_KEY) == region_cut.NAME:
            return modifier
    return None


@contextlib.contextmanager
def terrain_uncut(terrain):
    """The terrain as the artist made it: our cut modifier off while we sample it."""
    modifier = find_cut_modifier(terrain)
    state = None if modifier is None else (modifier.show_viewport, modifier.show_render)
    if modifier is not None:
        modifier.show_viewport = modifier.show_render = False
    try:
        yield
    finally:
        if modifier is not None:
            modifier.show_viewport, modifier.show_render = state


def terrain_problem(terrain):
    """Why a terrain cannot take prints (not editable, a flat transform), or None."""
    problem = own.not_editable(terrain)
    if problem:
        return problem
    if abs(terrain.matrix_world.to_3x3().determinant()) < 1e-12:
        return (f"'{terrain.name}' has a scale of 0 on an axis: the prints' space would be flat. "
                "Give it a non-zero scale (or apply the scale)")
    return None


# ---------------------------------------------------------------- sampling the scene

def frame_list(frame_start, frame_end):
    if frame_end < frame_start:
        raise FootprintError(f"The frame range {frame_start}..{frame_end} is empty")
    return np.arange(frame_start, frame_end + 1, dtype=np.float64)


def sample_walker(scene, walker, frames, progress=None):
    """World positions of the walker's evaluated matrix_world at each frame: (F, 3)."""
    positions = np.empty((len(frames), 3))
    for index, _ in enumerate(evaluation.stepped_frames(scene, frames)):
        # The evaluated object: only the shown scene's depsgraph writes back to the original.
        evaluated = walker.evaluated_get(evaluation.scene_depsgraph(scene))
        positions[index] = evaluated.matrix_world.translation
        if progress:
            progress(index / len(frames))
    return positions


def sample_particles(scene, emitter, frames):
    """Each particle where it is born: world positions (M, 3), birth frames, directions of travel."""
    found_positions, found_births, found_directions = [], [], []
    previous = None
    for frame in evaluation.stepped_frames(scene, frames):
        depsgraph = evaluation.scene_depsgraph(scene)
        evaluated = emitter.evaluated_get(depsgraph)
        if not evaluated.particle_systems:
            raise FootprintError(f"'{emitter.name}' has no particle system")
        particles = evaluated.particle_systems[0].particles
        count = len(particles)
        state = np.empty(count, np.int32)
        birth = np.empty(count, np.float32)
        location = np.empty(count * 3, np.float32)
        velocity = np.empty(count * 3, np.float32)
        particles.foreach_get("alive_state", state)
        particles.foreach_get("birth_time", birth)
        particles.foreach_get("location", location)
        particles.foreach_get("velocity", velocity)
        # Born during this frame step (the first frame takes everything born so far).
        newborn = (state == 3) & (birth <= frame) & ((birth > frame - 1) | (frame == frames[0]))
        here = np.array(emitter.matrix_world.translation)
        motion = here - previous if previous is not None else np.zeros(3)
        previous = here
        direction = velocity.reshape(-1, 3)[newborn]
        still = np.linalg.norm(direction[:, :2], axis=1) < 1e-9
        direction[still] = motion
        found_positions.append(location.reshape(-1, 3)[newborn])
        found_births.append(birth[newborn])
        found_directions.append(direction)
    return tuple(np.concatenate(found).astype(np.float64)
                 for found in (found_positions, found_births, found_directions))


def evaluated_terrain(scene, terrain):
    """The terrain's evaluated mesh without our cut, in world space: (vertices (V, 3), triangles
    (T, 3)). The triangles are Blender's own split of each face, the ones it renders: a
    non-planar quad split along the other diagonal is another surface (metres apart on an
    elevation model's 90 m cells)."""
    depsgraph = evaluation.scene_depsgraph(scene)
    with terrain_uncut(terrain):
        depsgraph.update()
        evaluated = terrain.evaluated_get(depsgraph)
        world = np.array(evaluated.matrix_world)  # evaluated: a scene not shown has stale originals
        mesh = evaluated.to_mesh()
        try:
            local, triangles = evaluation.mesh_triangles(mesh)
        finally:
            evaluated.to_mesh_clear()
    depsgraph.update()
    vertices = local @ world[:3, :3].T + world[:3, 3]
    return vertices, triangles


def project_down(vertices, triangles, contacts_world, progress=None):
    """Drop each contact straight down (world -Z) onto the terrain's triangles: world hits,
    up-facing unit normals and a hit mask. Rays start above the terrain's top, so the topmost
    surface is found.
    """
    bvh = BVHTree.FromPolygons([Vector(v) for v in vertices], triangles.tolist())
    top = float(vertices[:, 2].max()) + 1.0
    contacts = np.asarray(contacts_world, dtype=np.float64)
    hits = np.full((len(contacts), 3), np.nan)
    normals = np.full((len(contacts), 3), np.nan)
    down = Vector((0.0, 0.0, -1.0))
    for index, (x, y, _) in enumerate(contacts):
        location, normal, _, _ = bvh.ray_cast(Vector((x, y, top)), down)
        if location is not None:
            hits[index] = location
            normals[index] = normal if normal.z >= 0 else -normal
        if progress and index % 4096 == 0:
            progress(index / max(len(contacts), 1))
    return hits, normals, ~np.isnan(hits[:, 0])


def frame_world(scene, frame):
    """The print frame's world matrix from its parent, now (matrix_world waits for an update)."""
    return evaluation.world_matrix(scene, frame.parent) @ frame.matrix_parent_inverse @ frame.matrix_basis
