"""The Sandscape sand material: a rough sand-coloured base plus the glint emission, and the
footprint displacement when prints are painted; the seeded glint-noise image.

The material is ours when it carries MATERIAL_KEY = "sand"; a user's material, even one named
like ours, is never looked at. Re-running updates our material in place. Inside it, group
nodes are found by their group's key and the other nodes by their node names.
"""

import bpy
import numpy as np

from ..core import glints as glint_twin
from ..node_groups import footprint_height, glint_shade, glints
from ..node_groups import helper as h
from . import ownership as own

SAND_COLOR = (0.62, 0.45, 0.27, 1.0)
SAND_ROUGHNESS = 0.9
GLINT_INPUTS = ("Threshold", "Glint Size", "Facing Power", "Color", "Strength", "Seed")
# Node names inside our material.
PRINT_SPACE, PRINT_REGION = "Sandscape Print Space", "Sandscape Print Region"
PRINT_MAP = "Sandscape Print Map"
GLINT_NOISE, GLINTS_ADDED = "Sandscape Glint Noise", "Sandscape Sand + Glints"


def default_glint_values():
    """The glint group's own defaults, for a material made without the sand operator."""
    return {name: glints.INPUTS[name][2] for name in GLINT_INPUTS}


def find_sand_material(obj):
    """Our sand material in one of the object's slots, or None."""
    return own.slot_material(obj, own.SAND)


def _group_node(material, group_names):
    if material is None or material.node_tree is None:
        return None
    for node in material.node_tree.nodes:
        tree = getattr(node, "node_tree", None)
        if tree is not None and tree.get(h.GROUP_KEY) in group_names:
            return node
    return None


def glint_node(material):
    """The group node (procedural or image glints) inside our material, or None."""
    return _group_node(material, (glints.NAME, glint_shade.NAME))


def footprint_node(material):
    """The Sandscape Footprint Height group node inside our material, or None."""
    return _group_node(material, (footprint_height.NAME,))


def image_node(material):
    node = glint_node(material)
    if node is None or "Noise" not in node.inputs or not node.inputs["Noise"].is_linked:
        return None
    return node.inputs["Noise"].links[0].from_node


def read_settings(material):
    """What the material holds now, in the sand operator's terms (its invoke() starts from it)."""
    node = glint_node(material)
    if node is None:
        return {}
    values = {name: node.inputs[name].default_value for name in GLINT_INPUTS if name in node.inputs}
    image = image_node(material)
    settings = {"source": "IMAGE" if image is not None else "PROCEDURAL"}
    for name, value in values.items():
        settings[name.lower().replace(" ", "_")] = tuple(value) if hasattr(value, "__len__") else value
    if "seed" in settings:
        settings["seed"] = int(round(settings["seed"]))
    if image is not None and image.image is not None:
        settings["image"] = image.image.name
    return settings


def assign_new_material(obj):
    """A new sand material on the object; the user's materials keep their slots and data."""
    material = own.mark(bpy.data.materials.new("Sandscape Sand"), own.MATERIAL_KEY, own.SAND)
    mesh = obj.data
    had_slots = len(mesh.materials) > 0
    mesh.materials.append(material)
    if had_slots:
        index = len(mesh.materials) - 1
        mesh.polygons.foreach_set("material_index", [index] * len(mesh.polygons))
        mesh.update()
    obj.active_material_index = len(obj.material_slots) - 1
    return material


def apply(obj, values, image=None):
    """Our sand on the object, added or updated. Returns (material, whether it was added)."""
    material = find_sand_material(obj)
    added = material is None
    if added:
        material = assign_new_material(obj)
    update_material(material, values, image)
    for unused in [i for i in bpy.data.images if i.get(own.IMAGE_KEY) == own.GLINT_NOISE and i.users == 0]:
        bpy.data.images.remove(unused)  # ours, for another seed or size, and nothing shows it any more
    return material, added


def update_material(material, values, image=None):
    """Build or update the node tree. values: GLINT_INPUTS names -> values; image: glint source.

    With an image, the noise comes from that image through the mesh UVs (one texel, one
    grain) and Glint Size and Seed do not apply; without one, from object-space cells.
    """
    # Glints are tiny highlights: sampling the emissive ground as a light gains nothing and
    # cost +113 % render time instead of +13 % (bench/glints.py). Found by BSDF rays they stay unbiased.
    material.cycles.emission_sampling = "NONE"
    wanted = glint_shade.NAME if image is not None else glints.NAME
    node = glint_node(material)
    if node is None or node.node_tree.get(h.GROUP_KEY) != wanted:
        kept = _footprint_state(material)
        node = _build_tree(material, image)
        if kept is not None:  # switching the glint source keeps the painted footprints
            attach_footprints(material, *kept)
    if image is not None:
        image_node(material).image = image
    for name in GLINT_INPUTS:
        if name in node.inputs and name in values:
            node.inputs[name].default_value = values[name]
    return node


def _build_tree(material, image):
    tree = material.node_tree
    tree.nodes.clear()
    output = h.add_node(tree, "ShaderNodeOutputMaterial", name="Sandscape Output")
    base = h.add_node(tree, "ShaderNodeBsdfPrincipled", name="Sandscape Sand BSDF", label="Sand",
                      inputs={"Base Color": SAND_COLOR, "Roughness": SAND_ROUGHNESS})
    if image is None:
        glint = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Glints", node_tree=h.ensure_group(glints))
    else:
        glint = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Glints",
                           node_tree=h.ensure_group(glint_shade))
        uv = h.add_node(tree, "ShaderNodeTexCoord", name="Sandscape Glint UV")
        texture = h.add_node(tree, "ShaderNodeTexImage", name=GLINT_NOISE, label="Glint Noise",
                             interpolation="Closest", extension="REPEAT", image=image)
        h.link(tree, uv.outputs["UV"], texture.inputs["Vector"])
        h.link(tree, texture.outputs["Color"], glint.inputs["Noise"])
    glint.label = "Glints"
    add = h.add_node(tree, "ShaderNodeAddShader", name=GLINTS_ADDED)
    h.link(tree, base.outputs["BSDF"], add.inputs[0])
    h.link(tree, glint.outputs["Emission"], add.inputs[1])
    h.link(tree, add.outputs[0], output.inputs["Surface"])
    h.arrange(tree, set_widths=False)
    return glint


def _footprint_state(material):
    node = footprint_node(material)
    if node is None or not node.inputs["Print Map"].is_linked:
        return None
    texture = node.inputs["Print Map"].links[0].from_node
    values = {socket.name: socket.default_value for socket in node.inputs
              if not socket.is_linked and socket.name != "Frame" and hasattr(socket, "default_value")}
    values = {name: tuple(v) if hasattr(v, "__len__") else v for name, v in values.items()}
    space = own.node(material.node_tree, PRINT_SPACE)
    return texture.image, space.object if space is not None else None, values


def attach_footprints(material, image, space_object, values):
    """Wire the footprint image into our material's displacement, or update the wiring.

    image: the print map; it carries its region in space_object's X and Y (custom properties
    "region_min" and "region_size"). space_object is the print frame: world-aligned, in world
    units, and a child of the terrain, so the prints stay on the terrain and on the patch that
    shares the material. values: group input defaults. The Frame input gets a driver with the
    simple expression `frame`.
    """
    tree = material.node_tree
    node = footprint_node(material)
    if node is None:
        output = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
        coords = h.add_node(tree, "ShaderNodeTexCoord", name=PRINT_SPACE, label="Print Space")
        mapping = h.add_node(tree, "ShaderNodeMapping", name=PRINT_REGION, label="Print Region",
                             vector_type="POINT")
        texture = h.add_node(tree, "ShaderNodeTexImage", name=PRINT_MAP, label="Print Map",
                             interpolation="Linear", extension="CLIP")
        node = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Footprints", label="Footprints",
                          node_tree=h.ensure_group(footprint_height))
        h.link(tree, coords.outputs["Object"], mapping.inputs["Vector"])
        h.link(tree, mapping.outputs["Vector"], texture.inputs["Vector"])
        h.link(tree, texture.outputs["Color"], node.inputs["Print Map"])
        h.link(tree, coords.outputs["Object"], node.inputs["Vector"])
        h.link(tree, node.outputs["Displacement"], output.inputs["Displacement"])
        driver = node.inputs["Frame"].driver_add("default_value").driver
        driver.type = "SCRIPTED"
        driver.expression = "frame"  # a simple expression: evaluated without Python auto-run
        h.arrange(tree, set_widths=False)
    texture = node.inputs["Print Map"].links[0].from_node
    mapping = texture.inputs["Vector"].links[0].from_node
    coords = mapping.inputs["Vector"].links[0].from_node
    coords.object = space_object
    texture.image = image
    low, size = image["region_min"], image["region_size"]
    mapping.inputs["Location"].default_value = (-low[0] / size[0], -low[1] / size[1], 0.0)
    mapping.inputs["Scale"].default_value = (1.0 / size[0], 1.0 / size[1], 1.0)
    for name, value in values.items():
        if name in node.inputs and name != "Frame":
            node.inputs[name].default_value = value
    # Displacement and bump: the prints are true geometry, and the shading normal stays the
    # smooth one (true displacement alone shades the adaptive patch by its flat base quads).
    material.displacement_method = "BOTH"
    return node


def ensure_noise_image(resolution, seed):
    """The seeded white-noise image for this resolution and seed (8-bit, Non-Color, packed).

    One image per (resolution, seed): two materials with other seeds never share, and so never
    rewrite, each other's image.
    """
    image = own.image(own.GLINT_NOISE, seed=seed, resolution=resolution)
    if image is not None and image.packed_file:
        return image
    if image is None:
        image = bpy.data.images.new("Sandscape Glint Noise", resolution, resolution, alpha=False)
        own.mark(image, own.IMAGE_KEY, own.GLINT_NOISE, seed=seed, resolution=resolution)
        # Before the pixels: changing the colour space of a generated image regenerates it.
        image.colorspace_settings.name = "Non-Color"
    values = glint_twin.byte_to_unit(glint_twin.noise_image(resolution, seed))
    rgba = np.repeat(values[..., None], 4, axis=-1)
    rgba[..., 3] = 1.0
    image.pixels.foreach_set(rgba.ravel())
    image.pack()
    return image
