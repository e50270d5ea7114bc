"""The Sandscape sand material: a rough sand-coloured base plus the glint emission.

The material is ours when it carries MATERIAL_KEY; a user's material, even one named
like ours, is never looked at. Re-running updates our material in place.
"""

import bpy

from . import glint_shade, glints
from . import helper as h

MATERIAL_KEY = "sandscape_material"
KIND = "sand"
SAND_COLOR = (0.62, 0.45, 0.27, 1.0)
SAND_ROUGHNESS = 0.9
GLINT_INPUTS = ("Threshold", "Glint Size", "Facing Power", "Color", "Strength", "Seed")


def find_sand_material(obj):
    """Our sand material in one of the object's slots, or None."""
    for slot in getattr(obj, "material_slots", ()):
        if slot.material is not None and slot.material.get(MATERIAL_KEY) == KIND:
            return slot.material
    return None


def glint_node(material):
    """The group node (procedural or image glints) inside our material, or None."""
    if material is None or material.node_tree is None:
        return None
    for node in material.node_tree.nodes:
        tree = getattr(node, "node_tree", None)
        if tree is not None and tree.get(h.GROUP_KEY) in (glints.NAME, glint_shade.NAME):
            return node
    return None


def image_node(material):
    node = glint_node(material)
    if node is None or "Noise" not in node.inputs or not node.inputs["Noise"].is_linked:
        return None
    return node.inputs["Noise"].links[0].from_node


def assign_new_material(obj):
    """A new sand material on the object; the user's materials keep their slots and data."""
    material = bpy.data.materials.new("Sandscape Sand")
    material[MATERIAL_KEY] = KIND
    mesh = obj.data
    had_slots = len(mesh.materials) > 0
    mesh.materials.append(material)
    if had_slots:
        index = len(mesh.materials) - 1
        mesh.polygons.foreach_set("material_index", [index] * len(mesh.polygons))
        mesh.update()
    obj.active_material_index = len(obj.material_slots) - 1
    return material


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
        node = _build_tree(material, image)
    if image is not None:
        image_node(material).image = image
    for name in GLINT_INPUTS:
        if name in node.inputs and name in values:
            node.inputs[name].default_value = values[name]
    return node


def _build_tree(material, image):
    tree = material.node_tree
    tree.nodes.clear()
    output = h.add_node(tree, "ShaderNodeOutputMaterial", (600, 0))
    base = h.add_node(tree, "ShaderNodeBsdfPrincipled", (0, 250), "Sand",
                      inputs={"Base Color": SAND_COLOR, "Roughness": SAND_ROUGHNESS})
    if image is None:
        glint = h.add_node(tree, "ShaderNodeGroup", (0, -250), node_tree=h.ensure_group(glints))
    else:
        glint = h.add_node(tree, "ShaderNodeGroup", (0, -250), node_tree=h.ensure_group(glint_shade))
        uv = h.add_node(tree, "ShaderNodeTexCoord", (-500, -250))
        texture = h.add_node(tree, "ShaderNodeTexImage", (-300, -250), "Glint Noise",
                             interpolation="Closest", extension="REPEAT", image=image)
        h.link(tree, uv.outputs["UV"], texture.inputs["Vector"])
        h.link(tree, texture.outputs["Color"], glint.inputs["Noise"])
    glint.label = "Glints"
    add = h.add_node(tree, "ShaderNodeAddShader", (350, 0))
    h.link(tree, base.outputs["BSDF"], add.inputs[0])
    h.link(tree, glint.outputs["Emission"], add.inputs[1])
    h.link(tree, add.outputs[0], output.inputs["Surface"])
    return glint
