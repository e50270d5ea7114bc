"""Small scenes with known geometry, for tests and benchmarks."""

import math

import bpy
import numpy as np
from mathutils import Vector


def group_material(group, values, output="Mask", name="Probe"):
    """A material showing one output of a node group: a shader output as the surface, any other
    emitted (a float becomes a grey colour)."""
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    node = tree.nodes.new("ShaderNodeGroup")
    node.node_tree = group
    for key, value in values.items():
        node.inputs[key].default_value = value
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    if node.outputs[output].type == "SHADER":
        tree.links.new(node.outputs[output], out.inputs["Surface"])
    else:
        emission = tree.nodes.new("ShaderNodeEmission")
        emission.inputs["Strength"].default_value = 1.0
        tree.links.new(node.outputs[output], emission.inputs["Color"])
        tree.links.new(emission.outputs[0], out.inputs["Surface"])
    return material


def analytic_sphere(material, radius=1.0, location=(0.0, 0.0, 0.0)):
    """A true sphere: a one-point point cloud, which Cycles intersects analytically."""
    mesh = bpy.data.meshes.new("Sphere Point")
    mesh.from_pydata([(0.0, 0.0, 0.0)], [], [])
    obj = bpy.data.objects.new("Analytic Sphere", mesh)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    tree = bpy.data.node_groups.new("Point Sphere", "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    group_in = tree.nodes.new("NodeGroupInput")
    group_out = tree.nodes.new("NodeGroupOutput")
    to_points = tree.nodes.new("GeometryNodeMeshToPoints")
    to_points.inputs["Radius"].default_value = radius
    set_material = tree.nodes.new("GeometryNodeSetMaterial")
    set_material.inputs["Material"].default_value = material
    tree.links.new(group_in.outputs[0], to_points.inputs["Mesh"])
    tree.links.new(to_points.outputs[0], set_material.inputs["Geometry"])
    tree.links.new(set_material.outputs[0], group_out.inputs[0])
    obj.modifiers.new("Point Sphere", "NODES").node_group = tree
    return obj


def camera(kind="ORTHO", location=(0.0, 0.0, 10.0), rotation=(0.0, 0.0, 0.0), ortho_scale=2.2,
           lens=50.0):
    data = bpy.data.cameras.new("Probe Camera")
    data.type = kind
    data.ortho_scale = ortho_scale
    data.lens = lens
    data.clip_end = 1000.0
    obj = bpy.data.objects.new("Probe Camera", data)
    obj.location = location
    obj.rotation_euler = rotation
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.scene.camera = obj
    return obj


def sharp_pixels(scene=None):
    """1 sample taken at the pixel centre: the narrowest box filter Cycles allows (0.01 px)."""
    scene = scene or bpy.context.scene
    scene.cycles.pixel_filter_type = "BOX"
    scene.cycles.filter_width = 0.01
    return scene


def camera_rays(camera_obj, width, height, columns=None, rows=None):
    """World-space origins and unit directions of the rays through every pixel centre, or through
    the pixel coordinates given (columns, rows in pixels from the bottom left; centres at +0.5).

    Arrays (height, width, 3) (or the coordinates' shape), rows bottom-up like Blender's pixels.
    """
    depsgraph = bpy.context.evaluated_depsgraph_get()
    projection = np.array(camera_obj.calc_matrix_camera(depsgraph, x=width, y=height))
    view = np.array(camera_obj.matrix_world.inverted())
    inverse = np.linalg.inv(projection @ view)
    if columns is None:
        rows, columns = np.mgrid[0:height, 0:width] + 0.5
    x, y = np.asarray(columns) / width * 2.0 - 1.0, np.asarray(rows) / height * 2.0 - 1.0
    ends = []
    for depth in (-1.0, 1.0):
        clip = np.stack([x, y, np.full_like(x, depth), np.ones_like(x)], axis=-1)
        world = clip @ inverse.T
        ends.append(world[..., :3] / world[..., 3:4])
    direction = ends[1] - ends[0]
    return ends[0], direction / np.linalg.norm(direction, axis=-1, keepdims=True)


def pixel_hits(scene, camera_obj, width, height, to_sun, offset=0.02,
               hidden=("dust_volume", "far_haze", "clouds", "cloud_shadows")):
    """What the ray through each pixel centre hits, volumes' boxes and shells and EEVEE's cloud
    shadow mesh (our objects of the `hidden` kinds) left out: {"hit", "distance", "normal_z", "object",
    "sunlit"} arrays (height, width), rows bottom-up; sunlit: a surface facing `to_sun` (a world
    vector towards the sun) with nothing between (a second ray from `offset` off the surface)."""
    boxes = [o for o in scene.objects if o.get("sandscape_object") in hidden]
    was = [o.hide_viewport for o in boxes]
    for obj in boxes:
        obj.hide_viewport = True
    try:
        depsgraph = bpy.context.evaluated_depsgraph_get()
        origins, directions = camera_rays(camera_obj, width, height)
        to_sun = Vector(to_sun).normalized()
        shape = origins.shape[:2]
        out = {"hit": np.zeros(shape, bool), "distance": np.full(shape, np.inf), "normal_z": np.zeros(shape),
               "object": np.full(shape, None, object), "sunlit": np.zeros(shape, bool)}
        for index in np.ndindex(shape):
            hit, where, normal, _, obj, _ = scene.ray_cast(depsgraph, origins[index], directions[index])
            if not hit:
                continue
            out["hit"][index], out["object"][index], out["normal_z"][index] = True, obj, normal.z
            out["distance"][index] = np.linalg.norm(np.array(where) - origins[index])
            out["sunlit"][index] = normal.dot(to_sun) > 0 and not scene.ray_cast(
                depsgraph, where + normal * offset, to_sun)[0]
    finally:
        for obj, hide in zip(boxes, was, strict=True):
            obj.hide_viewport = hide
    return out


def project(camera_obj, points, width, height):
    """Pixel coordinates (column, row from the bottom, float) of world points seen by a camera."""
    depsgraph = bpy.context.evaluated_depsgraph_get()
    projection = np.array(camera_obj.calc_matrix_camera(depsgraph, x=width, y=height))
    view = np.array(camera_obj.matrix_world.inverted())
    homogeneous = np.concatenate([points, np.ones(points.shape[:-1] + (1,))], axis=-1)
    clip = homogeneous @ (projection @ view).T
    ndc = clip[..., :2] / clip[..., 3:4]
    return (ndc[..., 0] + 1.0) / 2.0 * width, (ndc[..., 1] + 1.0) / 2.0 * height


def _moved_camera_renders(camera_obj, render, width, height):
    """(render before, render after the camera moves 5 cm and turns 1 degree, and for every pixel
    of the first the column and row where its ground point (z = 0) lands in the second)."""
    a = render()
    origins, directions = camera_rays(camera_obj, width, height)
    camera_obj.location.x += 0.05
    camera_obj.rotation_euler.z -= np.radians(1.0)
    bpy.context.view_layer.update()
    b = render()
    t = -origins[..., 2] / directions[..., 2]
    col, row = project(camera_obj, origins + t[..., None] * directions, width, height)
    return a, b, np.floor(col).astype(int), np.floor(row).astype(int)


def glints_kept_after_camera_move(camera_obj, glints_in_render, width, height, enough):
    """Share of the glint pixels of a render that are glint pixels again after the camera moves
    5 cm and turns 1 degree. Each glint pixel of the first render is traced to the ground (z = 0)
    and projected into the second; pixels whose 3 x 3 neighbourhood there straddles a glint edge
    are left out. glints_in_render: () -> boolean (height, width) image; asserts that at least
    `enough` pixels were judged."""
    a, b, col, row = _moved_camera_renders(camera_obj, glints_in_render, width, height)
    inside = a & (col >= 1) & (col < width - 1) & (row >= 1) & (row < height - 1)
    col, row = col[inside], row[inside]
    window = np.stack([b[row + dy, col + dx] for dy in (-1, 0, 1) for dx in (-1, 0, 1)])
    settled = window.all(axis=0) | ~window.any(axis=0)
    assert settled.sum() > enough, "too few glint pixels to judge"
    return b[row, col][settled].mean()


def sparkles_kept_after_camera_move(camera_obj, sparkles_in_render, width, height, enough):
    """For one-pixel sparkles: (share of the sparkle pixels of a render with a sparkle pixel
    within one pixel of where their ground point lands after the camera moves 5 cm and turns 1
    degree, the same share for any pixel: what chance alone gives)."""
    a, b, col, row = _moved_camera_renders(camera_obj, sparkles_in_render, width, height)
    inside = a & (col >= 1) & (col < width - 1) & (row >= 1) & (row < height - 1)
    assert inside.sum() > enough, "too few sparkle pixels to judge"
    near = np.zeros_like(b)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            near[1:-1, 1:-1] |= b[1 + dy:height - 1 + dy, 1 + dx:width - 1 + dx]
    return float(near[row[inside], col[inside]].mean()), float(near[1:-1, 1:-1].mean())


def height_field(size, subdivisions, height=None, name="Terrain"):
    """A square grid mesh of `size` metres centred on the origin, z = height(x, y) (vectorised), UV 0..1."""
    axis = np.linspace(-size / 2, size / 2, subdivisions + 1)
    x, y = np.meshgrid(axis, axis)
    z = np.zeros_like(x) if height is None else height(x, y)
    n = subdivisions + 1
    index = np.arange(n * n).reshape(n, n)
    quads = np.stack([index[:-1, :-1], index[:-1, 1:], index[1:, 1:], index[1:, :-1]], -1).reshape(-1, 4)
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(n * n)
    mesh.vertices.foreach_set("co", np.stack([x, y, z], -1).astype(np.float32).ravel())
    mesh.loops.add(quads.size)
    mesh.loops.foreach_set("vertex_index", quads.ravel().astype(np.int32))
    mesh.polygons.add(len(quads))
    mesh.polygons.foreach_set("loop_start", (np.arange(len(quads)) * 4).astype(np.int32))
    mesh.update(calc_edges=True)
    mesh.validate()
    uv = np.stack([x, y], -1).reshape(-1, 2)[quads.ravel()] / size + 0.5
    mesh.uv_layers.new(name="UVMap").uv.foreach_set("vector", uv.astype(np.float32).ravel())
    obj = bpy.data.objects.new(name, mesh)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def keyframed_walker(path, frames, name="Walker"):
    """An empty keyed at each frame to path(frame) -> (x, y, z): any animated object will do."""
    walker = bpy.data.objects.new(name, None)
    bpy.context.scene.collection.objects.link(walker)
    for frame in frames:
        walker.location = path(frame)
        walker.keyframe_insert("location", frame=frame)
    return walker


def footprint_settings(terrain, walker, frames, **values):
    """The scene's footprint settings for a walk over `frames` (first, last), plus overrides."""
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = frames
    settings = scene.sandscape_footprints
    settings.terrain, settings.walker = terrain, walker
    for key, value in values.items():
        setattr(settings, key, value)
    return settings


def single_node_material(name, shader, output="Surface", **inputs):
    """A material of one shader node (e.g. ShaderNodeVolumeScatter) into the output's `output` socket."""
    material = bpy.data.materials.new(name)
    tree = material.node_tree
    tree.nodes.clear()
    node = tree.nodes.new(shader)
    for key, value in inputs.items():
        node.inputs[key].default_value = value
    tree.links.new(node.outputs[0], tree.nodes.new("ShaderNodeOutputMaterial").inputs[output])
    return material


def empty_fog(size, location):
    """A cube of density-0 Volume Scatter: a volume that scatters nothing."""
    bpy.ops.mesh.primitive_cube_add(size=size, location=location)
    fog = bpy.context.active_object
    fog.name = "Empty Fog"
    fog.data.materials.append(single_node_material("Empty Fog", "ShaderNodeVolumeScatter", "Volume",
                                                   Density=0.0))
    return fog


def world_volume(world, density=0.0):
    """A Volume Scatter of `density` on the world's active output (a default world gets nodes)."""
    tree = world.node_tree
    output = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputWorld" and n.is_active_output)
    scatter = tree.nodes.new("ShaderNodeVolumeScatter")
    scatter.inputs["Density"].default_value = density
    tree.links.new(scatter.outputs[0], output.inputs["Volume"])
    return scatter


def long_keyed_shot(frames=1000):
    """A long shot with the god rays keyed: a dolly camera aimed by Track To at a keyed target, a
    side sun, and one ordinary animated modifier elsewhere (a waving ground). Returns the scene."""
    scene = bpy.context.scene
    scene.frame_start, scene.frame_end = 1, frames
    bpy.ops.mesh.primitive_plane_add(size=40)
    wave = bpy.context.active_object.modifiers.new("Wave", "WAVE")
    for frame, height in ((1, 0.1), (frames, 0.3)):
        wave.height = height
        wave.keyframe_insert("height", frame=frame)
    target = bpy.data.objects.new("Target", None)
    scene.collection.objects.link(target)
    for frame, x in ((1, -2.0), (frames, 2.0)):
        target.location = (x, 0.0, 0.5)
        target.keyframe_insert("location", frame=frame)
    obj = camera("PERSP", location=(0.0, -8.0, 1.5), rotation=(math.radians(85), 0, 0), lens=35)
    for frame, x in ((1, -3.0), (frames, 3.0)):
        obj.location.x = x
        obj.keyframe_insert("location", index=0, frame=frame)
    aim = obj.constraints.new("TRACK_TO")
    aim.target, aim.track_axis, aim.up_axis = target, "TRACK_NEGATIVE_Z", "UP_Y"
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth, air.density = math.radians(10), math.radians(20), 0.0
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scene.sandscape_post.use_blur = scene.sandscape_post.use_denoise = False
    assert bpy.ops.sandscape.add_post_effects() == {"FINISHED"}
    return scene
