"""Evaluate node outputs and renders numerically: bake into numpy, render into numpy."""

import pathlib
import tempfile

import bpy
import numpy as np


def cycles_scene(scene=None, resolution=(64, 64), samples=1):
    """Cycles on the CPU, exact pixels: no denoiser, no dithering, Standard view, 1 sample."""
    scene = scene or bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False  # on by default in 5.0, and it smears per channel
    scene.render.dither_intensity = 0.0
    scene.view_settings.view_transform = "Standard"
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    return scene


def uv_plane(size=2.0, name="Bake Plane"):
    """A plane of `size` metres centred on the origin, UV 0..1, selected and active."""
    bpy.ops.mesh.primitive_plane_add(size=size)
    obj = bpy.context.active_object
    obj.name = name
    return obj


def pixel_centres(resolution, low=-1.0, high=1.0):
    """Coordinates of pixel centres along one axis of a [low, high] span, in float32."""
    return (low + (np.arange(resolution) + 0.5) / resolution * (high - low)).astype(np.float32)


def bake_emit(obj, material, resolution):
    """Bake the material's emission on obj at 1 sample (the pixel centre); (res, res, 4), rows bottom-up."""
    scene = cycles_scene(bpy.context.scene, samples=1)
    scene.cycles.bake_type = "EMIT"
    scene.render.bake.target = "IMAGE_TEXTURES"
    scene.render.bake.margin = 0
    image = bpy.data.images.new("Sandscape Bake", resolution, resolution, float_buffer=True, alpha=False)
    image.colorspace_settings.name = "Non-Color"
    target = material.node_tree.nodes.new("ShaderNodeTexImage")
    target.image = image
    material.node_tree.nodes.active = target
    for other in bpy.context.view_layer.objects:
        other.select_set(False)
    obj.select_set(True)
    bpy.context.view_layer.objects.active = obj
    try:
        bpy.ops.object.bake(type="EMIT")
        pixels = np.empty(resolution * resolution * 4, np.float32)
        image.pixels.foreach_get(pixels)
    finally:
        material.node_tree.nodes.remove(target)
        bpy.data.images.remove(image)
    return pixels.reshape(resolution, resolution, 4)


def bake_emit_with_positions(obj, material, resolution):
    """bake_emit, and the world position of every baked pixel: Cycles' bake points sit up to a
    few thousandths of a pixel off the pixel centres, so twins are evaluated where it shaded.
    Leaves obj with a Position material in its first slot."""
    baked = bake_emit(obj, material, resolution)
    position = bpy.data.materials.new("Position")
    tree = position.node_tree
    tree.nodes.clear()
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    emission = tree.nodes.new("ShaderNodeEmission")
    out = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(geometry.outputs["Position"], emission.inputs["Color"])
    tree.links.new(emission.outputs[0], out.inputs["Surface"])
    obj.data.materials[0] = position
    world = bake_emit(obj, position, resolution)[..., :3].astype(np.float64)
    return baked, world


def render(scene=None):
    """Render the scene's camera into numpy: (H, W, 4) float32, rows bottom-up (Blender's order).

    Background mode keeps no Render Result pixels, so the frame goes through a 32-bit EXR.
    """
    scene = scene or bpy.context.scene
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_depth = "32"
    with tempfile.TemporaryDirectory(prefix="sandscape-render-") as tmp:
        return _render_and_read(scene, pathlib.Path(tmp) / "frame.exr")


def render_display(scene, path):
    """Render to a 16-bit PNG at `path` (the view transform applied) and read back the display
    values as written: (H, W, 3), rows bottom-up."""
    settings = scene.render.image_settings
    settings.file_format, settings.color_depth, settings.color_mode = "PNG", "16", "RGB"
    return _render_and_read(scene, pathlib.Path(path), "Non-Color")[..., :3]


def _render_and_read(scene, path, colorspace=None):
    scene.render.filepath = str(path)
    bpy.ops.render.render(write_still=True, scene=scene.name)
    return read_image(path, colorspace)


def read_image(path, colorspace=None):
    """An image file's pixels: (H, W, 4) float32, rows bottom-up (`colorspace`: read it as that)."""
    image = bpy.data.images.load(str(path), check_existing=False)
    if colorspace:
        image.colorspace_settings.name = colorspace
    try:
        width, height = image.size
        pixels = np.empty(width * height * 4, np.float32)
        image.pixels.foreach_get(pixels)
    finally:
        bpy.data.images.remove(image)
    return pixels.reshape(height, width, 4)


def data_snapshot():
    """Names of every data-block in every bpy.data collection, to show nothing changed."""
    snapshot = {}
    for attr in dir(bpy.data):
        collection = getattr(bpy.data, attr, None)
        if isinstance(collection, bpy.types.bpy_prop_collection) and attr != "window_managers":
            try:
                snapshot[attr] = sorted(item.name_full for item in collection)
            except (AttributeError, TypeError):
                continue
    return snapshot


def float_image(pixels, name="Probe Image"):
    """A Non-Color float image holding (H, W, 4) pixels, rows bottom-up."""
    height, width = pixels.shape[:2]
    image = bpy.data.images.new(name, width, height, alpha=True, float_buffer=True)
    image.colorspace_settings.name = "Non-Color"
    image.pixels.foreach_set(np.ascontiguousarray(pixels, dtype=np.float32).ravel())
    return image


def composite_group(group, values, output, resolution):
    """Run one compositor group through the real compositor; numpy arrays become Image nodes.

    values: input name -> (H, W, 4) array or a plain value. Returns (H, W, 4), rows bottom-up.
    """
    tree = bpy.data.node_groups.new("Compositor Probe", "CompositorNodeTree")
    tree.interface.new_socket("Image", in_out="OUTPUT", socket_type="NodeSocketColor")
    node = tree.nodes.new("CompositorNodeGroup")
    node.node_tree = group
    for name, value in values.items():
        if isinstance(value, np.ndarray):
            source = tree.nodes.new("CompositorNodeImage")
            source.image = float_image(value, f"Probe {name}")
            tree.links.new(source.outputs["Image"], node.inputs[name])
        else:
            node.inputs[name].default_value = value
    out = tree.nodes.new("NodeGroupOutput")
    tree.links.new(node.outputs[output], out.inputs[0])
    try:
        return composite_tree(tree, resolution)
    finally:
        bpy.data.node_groups.remove(tree)


def composite_tree(tree, resolution):
    """Render with `tree` as the compositor of a scene with nothing in it but a camera (the tree's
    Image nodes are all there is). Returns (H, W, 4), rows bottom-up."""
    scene = cycles_scene(resolution=resolution, samples=1)
    if scene.camera is None:
        camera = bpy.data.objects.new("Compositor Camera", bpy.data.cameras.new("Compositor Camera"))
        scene.collection.objects.link(camera)
        scene.camera = camera
    kept = scene.compositing_node_group
    scene.compositing_node_group = tree
    scene.render.use_compositing = True
    try:
        return render(scene)
    finally:
        scene.compositing_node_group = kept


def _probe_tree(name):
    tree = bpy.data.node_groups.new(name, "GeometryNodeTree")
    tree.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    tree.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    return tree


def _read_on_points(tree, value, points):
    """Store `value` (a field socket of tree) on a mesh of points (n, 3) and read it back."""
    nodes, links = tree.nodes, tree.links
    group_in, group_out = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    store = nodes.new("GeometryNodeStoreNamedAttribute")
    store.inputs["Name"].default_value = "sampled"
    links.new(group_in.outputs[0], store.inputs["Geometry"])
    links.new(value, store.inputs["Value"])
    links.new(store.outputs[0], group_out.inputs[0])
    mesh = bpy.data.meshes.new("Probe Points")
    mesh.from_pydata([tuple(p) for p in np.asarray(points, float)], [], [])
    probe = bpy.data.objects.new("Probe Points", mesh)
    bpy.context.scene.collection.objects.link(probe)
    probe.modifiers.new("Probe", "NODES").node_group = tree
    depsgraph = bpy.context.evaluated_depsgraph_get()
    depsgraph.update()
    evaluated = probe.evaluated_get(depsgraph).data
    values = np.empty(len(evaluated.vertices), np.float32)
    evaluated.attributes["sampled"].data.foreach_get("value", values)
    bpy.data.objects.remove(probe)
    bpy.data.meshes.remove(mesh)
    bpy.data.node_groups.remove(tree)
    return values.astype(np.float64)


def grid_values(volume_object, points, grid="density"):
    """A volume object's grid (as geometry nodes make it, in the object's own space) sampled at
    points (n, 3), trilinear."""
    tree = _probe_tree("Grid Probe")
    nodes, links = tree.nodes, tree.links
    info = nodes.new("GeometryNodeObjectInfo")
    info.transform_space = "ORIGINAL"
    info.inputs["Object"].default_value = volume_object
    named = nodes.new("GeometryNodeGetNamedGrid")
    named.inputs["Name"].default_value = grid
    links.new(info.outputs["Geometry"], named.inputs["Volume"])
    sample = nodes.new("GeometryNodeSampleGrid")
    links.new(named.outputs["Grid"], sample.inputs["Grid"])
    links.new(nodes.new("GeometryNodeInputPosition").outputs[0], sample.inputs["Position"])
    return _read_on_points(tree, sample.outputs[0], points)


def field_values(chain, points, output):
    """Blender's own evaluation of a chain of geometry-node groups at points (n, 3): chain is a
    list of (group, inputs, links into the next group by output name); the last group's output
    named `output` is read."""
    tree = _probe_tree("Field Probe")
    previous, links_on = None, ()
    for group, inputs, links_next in chain:
        node = tree.nodes.new("GeometryNodeGroup")
        node.node_tree = group
        for name, value in inputs.items():
            node.inputs[name].default_value = value
        for name in links_on:
            tree.links.new(previous.outputs[name], node.inputs[name])
        previous, links_on = node, links_next
    return _read_on_points(tree, previous.outputs[output], points)
