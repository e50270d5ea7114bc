"""What Sandscape made, and how to find it again: one custom-property key per kind of data.

Data we make carries its key with a kind as the value (an object: OBJECT_KEY = "walker",
"sun", ...). Lookups go through the scene the operator runs in, never through all of
bpy.data, so two scenes keep their own sun, sky, dust and compositor. A user's data is never
matched by its name, and nodes inside our trees are found by node.name (labels are the
artist's to change). The key names are those of files saved by earlier versions.
"""

import bpy

from ..node_groups import helper

GROUP_KEY = helper.GROUP_KEY  # node groups: found by this key (the builder's NAME), never by name
OBJECT_KEY = "sandscape_object"
MATERIAL_KEY = "sandscape_material"
STRUCTURE_KEY = "sandscape_structure"  # our sand's look / glints / source / ripples (addon/sand.py)
IMAGE_KEY = "sandscape_image"
WORLD_KEY = "sandscape_world"
TREE_KEY = "sandscape_compositor"
TERRAIN_KEY = "sandscape_terrain"  # on footprint data: the terrain it belongs to

# Kinds of objects
SUN, DUST_VOLUME, CLOUDS = "sun", "dust_volume", "clouds"
CLOUD_SHADOWS = "cloud_shadows"  # EEVEE's shadow of the clouds: an object, its material
FAR_HAZE = "far_haze"  # the haze between the dust box and the clouds: an object, its material
WALKER, WALK_PATH, WALKER_LIMB = "walker", "walk_path", "walker_limb"
FOOTPRINTS, PATCH, PRINT_FRAME = "footprints", "footprint_patch", "print_frame"
DUNES, DUNE_HORIZON = "dunes", "dune_horizon"
SCENERY = (DUNES,)  # ours, yet the scene's ground: counted where the scene's geometry is
# Kinds of materials, images, worlds
SAND, DUST, CLOUD_MATERIAL, CLOAK = "sand", "dust", "clouds", "cloak"
CLOAK_TRIM, WRAPS = "walker_trim", "walker_wraps"  # the walker's golden trim; legs' and hands' cloth
GLINT_NOISE, PRINT_MAP = "glint_noise", "print_map"
SKY = "sky"
CLOUD_GRID = "cloud_grid"  # the cloud layer's own geometry-nodes tree


def mark(block, key, kind, **links):
    """Tag a data-block as ours; links are more custom properties (a terrain, a seed)."""
    block[key] = kind
    for name, value in links.items():
        block[name] = value
    return block


def new_volume_object(scene, name, kind, mesh=None):
    """Our object of a kind, linked to the scene, drawn as its bounds (see through a volume)."""
    obj = mark(bpy.data.objects.new(name, mesh or bpy.data.meshes.new(name)), OBJECT_KEY, kind)
    scene.collection.objects.link(obj)
    obj.display_type = "BOUNDS"
    return obj


def scene_objects(scene, kind, **match):
    """Our objects of a kind in this scene, optionally matching more custom properties."""
    return [obj for obj in scene.objects if obj.get(OBJECT_KEY) == kind
            and all(obj.get(name) == value for name, value in match.items())]


def scene_object(scene, kind, **match):
    found = scene_objects(scene, kind, **match)
    return found[0] if found else None


def slot_material(obj, kind):
    """Our material of a kind in one of the object's slots, or None."""
    for slot in getattr(obj, "material_slots", ()):
        if slot.material is not None and slot.material.get(MATERIAL_KEY) == kind:
            return slot.material
    return None


def image(kind, **match):
    """Our image of a kind (images belong to no scene: match what owns it, a terrain or a seed)."""
    for candidate in bpy.data.images:
        if candidate.get(IMAGE_KEY) == kind and all(candidate.get(k) == v for k, v in match.items()):
            return candidate
    return None


def scene_world(scene):
    """The scene's world when it is ours, else None."""
    world = scene.world
    return world if world is not None and world.get(WORLD_KEY) else None


def scene_compositor(scene):
    """The scene's compositor tree when it is ours, else None."""
    tree = scene.compositing_node_group
    return tree if tree is not None and tree.get(TREE_KEY) else None


def node(tree, name):
    """One of our nodes in a tree we built, by its node name (labels are the artist's)."""
    return tree.nodes.get(name) if tree is not None else None


def remove_with_data(obj):
    """Remove our object, and its mesh and material when nothing else uses them."""
    mesh, material = obj.data, obj.active_material
    bpy.data.objects.remove(obj)
    if mesh is not None and mesh.users == 0:
        bpy.data.meshes.remove(mesh)
    if material is not None and material.users == 0:
        bpy.data.materials.remove(material)


def set_mesh(obj, verts, faces):
    """Give our object a new mesh built from vertices and faces (see replace_mesh)."""
    mesh = bpy.data.meshes.new(obj.data.name)
    mesh.from_pydata([tuple(v) for v in verts], [], faces)
    mesh.validate()
    replace_mesh(obj, mesh)


def replace_mesh(obj, mesh):
    """Give our object a new mesh, with the old one's materials and name (running an operator
    again keeps "Sandscape Clouds", not "….001"); the old one goes when nothing else uses it."""
    old = obj.data
    for material in old.materials:
        mesh.materials.append(material)
    obj.data = mesh
    if old.users == 0:
        name = old.name
        bpy.data.meshes.remove(old)
        mesh.name = name


def not_editable(block):
    """Why a data-block cannot take our changes (linked, overridden, not editable), or None.

    Sandscape adds modifiers, materials and objects next to the artist's data; on linked
    data they would be lost on save, and on a library override they come back half-made
    after reopening. So both are refused before anything changes.
    """
    if block is None:
        return None
    if block.library is not None:
        return (f"'{block.name}' is linked from {block.library.filepath}: make it local first "
                "(Object > Library Override or Make Local)")
    if block.override_library is not None:
        return (f"'{block.name}' is a library override: make it local first (Object > Library "
                "Override > Make Local), Sandscape's changes to it would not be kept")
    if not block.is_editable:
        return f"'{block.name}' cannot be edited"
    data = getattr(block, "data", None)
    if isinstance(data, bpy.types.ID) and data is not block:
        return not_editable(data)
    return None
