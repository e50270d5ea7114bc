"""The ground's colour in EEVEE's light from below: the lighting world's lower hemisphere and
the clouds' light at their base (cloud_sunlight.py) take the colour of the scene's ground.

Cycles bounces the light off whatever ground there is; EEVEE bounces none without a baked
probe, so the world stands in for the lit ground, and with the sand's colour over an artist's
olive grass it lit the clouds' bases and the walker's legs too warm. The ground is the opaque
surface below the camera (straight down, else along its view; what renders and is not ours),
else the Sandscape sand last added or updated: its shader's colour (a Principled BSDF's Base
Color, a Diffuse BSDF's Color, our sand's look's Color). Each follows that colour through
simple-expression drivers, so an artist's later change to it carries to both, with no Python on
a farm. A colour from an image (an Image Texture on the colour input, through reroutes) gives the
image's mean in linear light, fixed when an operator runs (core/image_mean.py; a driver cannot
read an image). Any other texture or node cannot be read: the sand's colour stands in. The
operator says which.

Under the clouds' bases the lit ground's light is the lamp's let through the layer plus the
sky's: the share let through is the mean of EEVEE's cloud-shadow map (cloud_shadows.py), set
when it is made (with the lamp's whole light the ground under broken cloud lit the bases too
brightly). The world's lower hemisphere keeps the lamp's whole light: it stands for the ground
round what it lights, a walker in the sun, and one mean over the layer darkened the demo's
walker further (README).
"""

import bpy
import numpy as np
from mathutils import Vector

from ..core import image_mean
from ..core import sand as core_sand
from ..node_groups import helper as h
from . import drivers, evaluation
from . import ownership as own

NODE = "Sandscape EEVEE Ground Colour"  # a Combine Color in the world and in each cloud material
LOOK = "Sandscape Look"  # the sand material's look node (addon/sand.py), whose Color the ground takes
SHADER_COLOUR = {"ShaderNodeBsdfPrincipled": "Base Color", "ShaderNodeBsdfDiffuse": "Color"}
SEE_THROUGH = {"ShaderNodeBsdfGlass", "ShaderNodeBsdfRefraction", "ShaderNodeBsdfTransparent",
               "ShaderNodeHoldout"}
SUN_LET_THROUGH = "Sandscape EEVEE Ground Sun Let Through"  # a Value node beside each NODE
UPRIGHT_SHARE = "Sandscape EEVEE Ground Is Our Sand"  # a Value node in the world: 1 our sand, 0 not
HITS = 8  # surfaces passed through looking for the ground (volume boxes, glass); reroutes followed
IMAGE_KEY, FOLLOWED_KEY = "sandscape_ground_image", "sandscape_ground_material"  # on NODE: an image's mean
MEAN_PIXELS = 1 << 24  # a larger image (past 4k) is read from a copy scaled down to about this many


def _surface_shader(material):
    """The node on the material's EEVEE output's Surface, or None."""
    tree = material.node_tree if material is not None else None
    output = tree.get_output_node("EEVEE") if tree is not None else None
    surface = output.inputs["Surface"] if output is not None else None
    return surface.links[0].from_node if surface is not None and surface.is_linked else None


def colour_input(material):
    """(node, input name) giving the material's surface its colour, or None: our sand's look,
    else the shader on the EEVEE output's Surface."""
    if material is not None and material.get(own.MATERIAL_KEY) == own.SAND and material.node_tree:
        look = material.node_tree.nodes.get(LOOK)
        return (look, "Color") if look is not None and "Color" in look.inputs else None
    shader = _surface_shader(material)
    name = SHADER_COLOUR.get(shader.bl_idname) if shader is not None else None
    return (shader, name) if name is not None else None


def see_through(material):
    """Whether the material's surface lets the view through (glass, a transmissive or cut-out
    Principled, a transparent shader): not a ground, whatever lies behind it."""
    shader = _surface_shader(material)
    if shader is None:
        return False
    if shader.bl_idname in SEE_THROUGH:
        return True
    if shader.bl_idname != "ShaderNodeBsdfPrincipled":
        return False
    transmission, alpha = shader.inputs["Transmission Weight"], shader.inputs["Alpha"]
    return ((not transmission.is_linked and transmission.default_value >= 0.5)
            or (not alpha.is_linked and alpha.default_value < 0.5))


def _surface_material(scene, depsgraph, origin, direction):
    """The material first met from origin along direction on an opaque surface that renders and
    is not ours (the dust box, the clouds, the haze are volumes in mesh boxes; the walker stands
    on the ground), else None."""
    for _ in range(HITS):
        hit, location, _normal, index, obj, _matrix = scene.ray_cast(depsgraph, origin, direction)
        if not hit:
            return None
        origin = location + direction * 1e-4 * max(1.0, location.length)
        original = obj.original
        if original.hide_render or original.get(own.OBJECT_KEY) not in (None, *own.SCENERY):
            continue
        # The face index is the evaluated mesh's (a Subdivision modifier makes more of them).
        evaluated = original.evaluated_get(depsgraph)
        mesh = evaluated.data if evaluated.type == "MESH" else None
        inside = mesh is not None and 0 <= index < len(mesh.polygons)
        slot = mesh.polygons[index].material_index if inside else 0
        slots = original.material_slots
        material = slots[slot].material if slot < len(slots) else None
        if material is None or material.get(own.MATERIAL_KEY) in (own.DUST, own.CLOUD_MATERIAL):
            continue
        if not see_through(material):
            return material
    return None


def below_camera(scene):
    """The material of the opaque surface below the scene's camera (straight down, else along
    its view, else through the middle of the frame's lower edge), or None."""
    camera = scene.camera
    if camera is None:
        return None
    depsgraph = evaluation.scene_depsgraph(scene)  # once: every ray and the camera's place
    evaluated = camera.evaluated_get(depsgraph)
    matrix = evaluated.matrix_world
    origin, turn = matrix.translation, matrix.to_3x3()
    ahead = -(turn @ Vector((0.0, 0.0, 1.0))).normalized()
    rays = [(origin, Vector((0.0, 0.0, -1.0))), (origin, ahead)]
    if camera.type == "CAMERA":  # a camera standing just off the ground's edge sees it low in the frame
        corners = sorted(evaluated.data.view_frame(scene=scene), key=lambda corner: corner.y)[:2]
        edge = (corners[0] + corners[1]) / 2
        if evaluated.data.type == "ORTHO":
            rays.append((matrix @ Vector((edge.x, edge.y, 0.0)), ahead))
        elif (turn @ edge).length > 0:
            rays.append((origin, (turn @ edge).normalized()))
    for start, direction in rays:
        material = _surface_material(scene, depsgraph, start, direction)
        if material is not None:
            return material
    return None


def ground_material(scene, followed=None):
    """The material whose colour the ground takes: the surface below (or ahead of) the camera,
    else the followed sand while the scene still shows it, else a Sandscape sand in the scene."""
    below = below_camera(scene)
    if below is not None:
        return below
    sands = [own.slot_material(obj, own.SAND) for obj in scene.objects]
    sands = [material for material in sands if material is not None]
    if followed is not None and followed in sands:
        return followed
    return sands[0] if sands else None


def image_behind(socket):
    """The image an Image Texture node's Color gives the socket (through reroutes), or None."""
    for _ in range(HITS):
        if not socket.is_linked:
            return None
        link = socket.links[0]
        node = link.from_node
        if node.bl_idname == "NodeReroute":
            socket = node.inputs[0]
            continue
        if node.bl_idname == "ShaderNodeTexImage" and link.from_socket.name == "Color":
            return node.image
        return None
    return None


def _decoded_as_srgb(image):
    """Whether the image's pixels hold sRGB-like codes: a byte image in a display space. Float
    images are held in linear light, and data (Non-Color) is taken as it is, as a shader takes it."""
    space = image.colorspace_settings
    return not (image.is_float or space.is_data or "Linear" in space.name or "ACES" in space.name)


def _associated(image):
    """Whether the ground reflects its byte image's colour times its alpha: as Cycles shades the
    Color of a straight-alpha byte image in a colour space with the node's Alpha output unused,
    and as a ground made transparent by that alpha reflects (used, Cycles gives the colour alone,
    but lets the light through where the alpha is low). Float images and other alpha modes are
    taken as their pixels hold them (not compared with Cycles)."""
    return (image.channels == 4 and not image.is_float and image.alpha_mode == "STRAIGHT"
            and not image.colorspace_settings.is_data)


def mean_colour(image):
    """The image's mean colour in linear light (times its alpha where _associated), or None when it
    has no pixels (a missing file)."""
    width, height = image.size
    if width * height == 0:
        return None
    source = image
    # Memory: a file past 4k is read from a copy scaled down (it averages codes, so a grainy image
    # comes out darker); an image edited since it was loaded is read whole, as a copy loses edits.
    if width * height > MEAN_PIXELS and image.source == "FILE" and not image.is_dirty:
        shrink = (MEAN_PIXELS / (width * height)) ** 0.5
        source = image.copy()
        source.scale(max(1, int(width * shrink)), max(1, int(height * shrink)))
    try:
        pixels = np.empty(len(source.pixels), dtype=np.float32)
        source.pixels.foreach_get(pixels)
    finally:
        if source is not image:
            bpy.data.images.remove(source)
    if len(pixels) == 0:
        return None
    return image_mean.mean_colour(pixels, image.channels, _decoded_as_srgb(image), _associated(image))


def set_colour(node, colour):
    """The Combine Color node's colour fixed (its drivers removed)."""
    for index in range(3):
        node.inputs[index].driver_remove("default_value")
        node.inputs[index].default_value = colour[index]


def colour_image(material):
    """The image the material's colour comes from (an Image Texture, through reroutes), or None."""
    found = colour_input(material)
    return image_behind(found[0].inputs[found[1]]) if found is not None else None


def image_colour(material):
    """(image, its mean colour) when the material's colour comes from an image it can read, else
    None."""
    image = colour_image(material)
    colour = mean_colour(image) if image is not None else None
    return (image, colour) if colour is not None else None


def _record(node, material=None, image=None):
    """Which material's image the node's fixed colour is the mean of (a driver records the rest)."""
    for key, value in ((FOLLOWED_KEY, material), (IMAGE_KEY, image)):
        if value is not None:
            node[key] = value
        elif key in node:
            del node[key]


def recorded_image(tree):
    """(material, image) whose mean the tree's ground colour holds, or None."""
    node = own.node(tree, NODE) if tree is not None else None
    image = node.get(IMAGE_KEY) if node is not None else None
    return (node.get(FOLLOWED_KEY), image) if image is not None else None


_NOT_READ = object()  # drive(): the image not read yet (None: read, and nothing to take from it)


def drive(node, material, imaged=_NOT_READ):
    """Drive the Combine Color node's channels from the material's colour input; where that is
    linked, the mean of its image (imaged: image_colour(material), if already read), else the
    sand's colour, fixed. Whether it took the material's colour."""
    found = colour_input(material)
    _record(node)
    if found is not None and found[0].inputs[found[1]].is_linked:
        imaged = image_colour(material) if imaged is _NOT_READ else imaged
        set_colour(node, imaged[1] if imaged is not None else core_sand.SAND_COLOR)
        if imaged is not None:
            _record(node, material, imaged[0])
        return imaged is not None
    if found is None:
        set_colour(node, core_sand.SAND_COLOR)
        return False
    shader, name = found
    for index in range(3):
        path = f'node_tree.nodes["{shader.name}"].inputs["{name}"].default_value[{index}]'
        drivers.drive(node.inputs[index], "default_value", "colour", [("colour", "MATERIAL", material, path)])
    return True


def match(node, tree):
    """The Combine Color node takes what the tree's ground colour takes: the same material's colour
    followed, else the same fixed colour (an image's mean, read once; or the sand's)."""
    source = own.node(tree, NODE) if tree is not None else None
    driven = drivers.driven_by(tree, NODE)
    if driven is not None or source is None:
        drive(node, driven)
        return
    set_colour(node, [source.inputs[index].default_value for index in range(3)])
    _record(node, *(recorded_image(tree) or ()))


def followed(tree):
    """The material the tree's ground colour follows (by drivers, or an image's mean), or None."""
    driven = drivers.driven_by(tree, NODE)
    recorded = recorded_image(tree)
    return driven if driven is not None else recorded[0] if recorded is not None else None


def _trees(scene):
    """The world's tree (ours) and our cloud materials' trees in the scene."""
    world = own.scene_world(scene)
    trees = [world.node_tree] if world is not None and world.node_tree is not None else []
    for obj in own.scene_objects(scene, own.CLOUDS):
        material = own.slot_material(obj, own.CLOUD_MATERIAL)
        if material is not None and material.node_tree is not None and material.node_tree not in trees:
            trees.append(material.node_tree)
    return trees


def sun_let_through_node(tree):
    """A Value node, 1 until set_sun_let_through: the share of the lamp's light that reaches the
    ground under the cloud layer, on the whole."""
    node = h.add_node(tree, "ShaderNodeValue", name=SUN_LET_THROUGH,
                      label="Sun Let Through to the Ground (mean)")
    node.outputs[0].default_value = 1.0
    return node


def upright_share_node(tree):
    """A Value node: how much of our sand's upright gain (sky_eevee.py) the world's ground takes:
    0 (a Lambert ground) until refresh() finds our Physical Sand."""
    node = h.add_node(tree, "ShaderNodeValue", name=UPRIGHT_SHARE, label="Ground Is Our Sand (1) or Not (0)")
    node.outputs[0].default_value = 0.0
    return node


def set_sun_let_through(scene, share):
    """The share of the lamp's light the cloud layer lets through to the ground, on the whole (the
    mean of EEVEE's cloud-shadow map; 1 without one): the lit ground's light the clouds' bases
    take from below. Cycles shadows the ground through the clouds themselves."""
    for tree in _trees(scene):  # the world has none: see the module's docstring
        node = own.node(tree, SUN_LET_THROUGH)
        if node is not None:
            node.outputs[0].default_value = float(share)


def refresh(scene):
    """Point every ground colour in the scene (the world's, the clouds') at ground_material().
    The material followed, the image its colour comes from (or None), and whether its colour
    could be read (False: a texture or a node other than an image, an image without pixels, or no
    ground found; the sand's colour stands in)."""
    trees = [tree for tree in _trees(scene) if own.node(tree, NODE) is not None]
    world = own.scene_world(scene)
    material = ground_material(scene, followed(world.node_tree) if world is not None else None)
    imaged = image_colour(material)  # read once for every tree
    read = True
    for tree in trees:
        read = drive(own.node(tree, NODE), material, imaged)
    ours = material is not None and material.get(own.MATERIAL_KEY) == own.SAND and \
        str(material.get(own.STRUCTURE_KEY, "PHYSICAL")).startswith("PHYSICAL")
    share = own.node(world.node_tree, UPRIGHT_SHARE) if world is not None and world.node_tree else None
    if share is not None:  # measured on Physical Sand; any other ground (or none found) as Lambert
        share.outputs[0].default_value = 1.0 if ours else 0.0
    return material, colour_image(material), read and material is not None
