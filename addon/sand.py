"""The Sandscape sand material: a look (PHYSICAL or JOURNEY), glints (LIT mirror facets or
EMISSION sparkles) from object-space cells or an image, wind ripples, and the footprint
displacement when prints are painted (the seeded glint-noise image is glint_noise.py's).

The material is ours when it carries MATERIAL_KEY = "sand"; a user's material, even one named
like ours, is never looked at. Re-running updates our material in place; a change of look,
glints, source or ripples rebuilds its tree and keeps the painted prints. Inside it, group nodes
are found by their group's key and the other nodes by their node names.
"""

import bpy

from ..core import sand as core_sand
from ..node_groups import (
    catalog,
    footprint_height,
    glint_facet,
    glint_shade,
    glints,
    journey_sand,
    lit_glints,
    physical_sand,
    ripples,
    sand_normal,
)
from ..node_groups import helper as h
from . import evaluation, print_lookup, sand_eevee, sky_eevee_ground, sparkle_footprint, units
from . import ownership as own

SAND_COLOR = core_sand.SAND_COLOR
LOOKS = {"PHYSICAL": physical_sand, "JOURNEY": journey_sand}
GLINT_INPUTS = ("Threshold", "Glint Size", "Facing Power", "Color", "Strength", "Roughness", "Seed", "IOR")
# The grains' IOR: the sand's Fresnel and its glint facets take one value from the sand operator
# (the two groups' inputs are each the artist's in the node editor).
IOR = "IOR"
RIPPLE_INPUTS = ("Wavelength", "Amplitude", "Steep Fraction", "Lee Fraction", "Meander", "Meander Scale",
                 "Variation", "Defects")
# The sand operator's ripple settings and the Ripples inputs they set.
RIPPLE_SETTINGS = {"ripple_wavelength": "Wavelength", "ripple_amplitude": "Amplitude",
                   "ripple_meander": "Meander", "ripple_meander_scale": "Meander Scale",
                   "ripple_variation": "Variation", "ripple_defects": "Defects"}
STRUCTURE_KEY = own.STRUCTURE_KEY  # look / glints / source / ripples of the tree built
# Node names inside our material.
PRINT_SPACE, PRINT_REGION = "Sandscape Print Space", "Sandscape Print Region"
PRINT_MAP, PRINT_TEXELS, PRINT_CORNERS, PRINT_BLEND = (
    print_lookup.PRINT_MAP, print_lookup.PRINT_TEXELS, print_lookup.PRINT_CORNERS, print_lookup.PRINT_BLEND)
GLINT_NOISE, GLINTS_ADDED = "Sandscape Glint Noise", "Sandscape Sand + Glints"
RIPPLE_DISPLACEMENT = "Sandscape Ripple Displacement"
GLINT_AOV_NODE = "Sandscape Glint AOV"
GLINT_AOV = "sandscape_glint"  # read by the post-effects tree: where grains can glint


def default_glint_values():
    """The glint groups' own defaults, for a material made without the sand operator."""
    table = {**glints.INPUTS, **lit_glints.INPUTS}
    return {name: table[name][2] for name in GLINT_INPUTS if name in table}


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
    """The glint group node (lit or emission, procedural or image) inside our material, or None."""
    return _group_node(material, (glints.NAME, glint_shade.NAME, lit_glints.NAME, glint_facet.NAME))


def look_node(material):
    return _group_node(material, (physical_sand.NAME, journey_sand.NAME))


def ripple_node(material):
    return _group_node(material, (ripples.NAME,))


def footprint_node(material):
    """The Sandscape Footprint Height group node inside our material, or None."""
    return _group_node(material, (footprint_height.NAME,))


def image_node(material):
    node = glint_node(material)
    if node is None or "Noise" not in node.inputs or not node.inputs["Noise"].is_linked:
        return None
    source = node.inputs["Noise"].links[0].from_node
    return source if source.bl_idname == "ShaderNodeTexImage" else None


def structure(material):
    """(look, glints, source, ripples) of the tree as built, or None for a tree we did not build."""
    text = material.get(STRUCTURE_KEY) if material is not None else None
    if text:
        look, glint_mode, source, rippled = text.split("/")
        return look, glint_mode, source, rippled == "ripples"
    if glint_node(material) is not None:  # built before looks existed: emission glints on Principled
        return "PHYSICAL", "EMISSION", "IMAGE" if image_node(material) else "PROCEDURAL", False
    return None


def read_settings(material):
    """What the material holds now, in the sand operator's terms (its invoke() starts from it)."""
    node = glint_node(material)
    built = structure(material)
    if node is None or built is None:
        return {}
    look, glint_mode, source, rippled = built
    settings = {"look": look, "glints": glint_mode, "source": source, "ripples": rippled}
    for name in GLINT_INPUTS:
        if name in node.inputs and not node.inputs[name].is_linked:
            value = node.inputs[name].default_value
            settings[name.lower().replace(" ", "_")] = tuple(value) if hasattr(value, "__len__") else value
    if "seed" in settings:
        settings["seed"] = int(round(settings["seed"]))
    surface = look_node(material)
    if surface is not None and IOR in surface.inputs and not surface.inputs[IOR].is_linked:
        settings["ior"] = surface.inputs[IOR].default_value  # the sand's, which Update gives the facets
    wave = ripple_node(material)
    if wave is not None:
        for setting, name in RIPPLE_SETTINGS.items():
            if name in wave.inputs:  # a group built by an older version lacks the newer inputs
                settings[setting] = wave.inputs[name].default_value
        settings["ripple_displacement"] = own.node(material.node_tree, RIPPLE_DISPLACEMENT) is not None
    image = image_node(material)
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


def apply(obj, values, image=None, look="PHYSICAL", glint_mode="LIT", ripple_values=None, scene=None):
    """Our sand on the object, added or updated; its sparkles sized to the pixels of scene's
    camera (default: the context's scene). Returns (material, whether it was added)."""
    material = find_sand_material(obj)
    added = material is None
    if added:
        material = assign_new_material(obj)
    update_material(material, values, image, look, glint_mode, ripple_values, scene)
    for unused in [i for i in bpy.data.images if i.get(own.IMAGE_KEY) == own.GLINT_NOISE and i.users == 0]:
        bpy.data.images.remove(unused)  # ours, for another seed or size, and nothing shows it any more
    return material, added


def update_material(material, values, image=None, look="PHYSICAL", glint_mode="LIT", ripple_values=None,
                    scene=None):
    """Build or update the node tree.

    values: GLINT_INPUTS names -> values (those the glint group has are set); image: the glint
    source (None: object-space cells); ripple_values: None for no ripples, else "Wind",
    "Wavelength", "Amplitude" (and optionally the fractions and "Displacement": True for true
    displacement on top of the shading); scene: whose camera's pixel sizes the sparkles (default:
    the context's scene).
    """
    # Glints are tiny highlights: sampling the emissive ground as a light gains nothing and
    # cost +113 % render time instead of +13 % (bench/glints.py). Found by BSDF rays they stay unbiased.
    material.cycles.emission_sampling = "NONE"
    # Journey lights slopes by a normal far from the surface's; the correction's softening would
    # darken them (the contrast at N.L 0.1-0.35 lost a tenth on a sphere). Physical keeps it.
    material.cycles.use_bump_map_correction = look != "JOURNEY"
    wanted = (look, glint_mode, "IMAGE" if image is not None else "PROCEDURAL", ripple_values is not None)
    if structure(material) != wanted:
        kept = _footprint_state(material)
        _build_tree(material, image, look, glint_mode, ripple_values is not None)
        material[STRUCTURE_KEY] = "/".join((*wanted[:3], "ripples" if wanted[3] else "flat"))
        if kept is not None:  # a rebuilt tree keeps the painted footprints
            attach_footprints(material, *kept)
        # The grains' size in this scene's units (a centimetre scene: 0.2 units, not 0.002); set on
        # build only, so an artist's own Grain Size survives a re-run.
        look_node(material).inputs["Grain Size"].default_value = units.to_units(
            scene if scene is not None else bpy.context.scene, sand_normal.GRAIN_SIZE)
    else:
        upgrade_groups(material.node_tree)  # a re-run brings an older file's groups up to date
    node = glint_node(material)
    _glint_aov(material, node)
    sparkle_footprint.attach(node, scene if scene is not None else bpy.context.scene)
    if image is not None:
        image_node(material).image = image
    for name in GLINT_INPUTS:
        if name in node.inputs and name in values and not node.inputs[name].is_linked:
            node.inputs[name].default_value = values[name]
    surface = look_node(material)  # None while an older file's look group stands (it is kept)
    if surface is not None and IOR in values and IOR in surface.inputs and not surface.inputs[IOR].is_linked:
        surface.inputs[IOR].default_value = values[IOR]
    if ripple_values is not None:
        wave = ripple_node(material)
        for name in ("Wind", *RIPPLE_INPUTS):
            if name in ripple_values:
                wave.inputs[name].default_value = ripple_values[name]
        _ripple_displacement(material, bool(ripple_values.get("Displacement")))
    trample_ripples(material)
    scene = scene if scene is not None else bpy.context.scene
    sand_eevee.attach(material, scene, look_node(material), look, node)
    sky_eevee_ground.refresh(scene)  # the lit sand EEVEE's world and clouds bounce, if it is the ground
    return node


def upgrade_groups(tree, seen=None):
    """Ensure every Sandscape group this tree uses, nested ones too, is at this version (or kept:
    a newer one, an artist's edited one; node_groups/versions.py notes which)."""
    seen = set() if seen is None else seen
    for node in tree.nodes:
        group = getattr(node, "node_tree", None)
        name = group.get(h.GROUP_KEY) if group is not None else None
        if name is None or name in seen:
            continue
        seen.add(name)
        builder = catalog.builder_named(name)
        if builder is not None:
            group = h.ensure_group(builder)
        upgrade_groups(group, seen)


def default_ripples(scene):
    """Ripples as a new material gets them: the scene's wind, 12 cm apart, 4 mm high, crests
    bending over 80 cm."""
    return {"Wind": tuple(scene.sandscape_atmosphere.wind),
            "Wavelength": units.to_units(scene, ripples.WAVELENGTH),
            "Amplitude": units.to_units(scene, ripples.AMPLITUDE),
            "Meander Scale": units.to_units(scene, ripples.MEANDER_SCALE)}


def set_wind(scene, wind):
    """The wind of every sand material in the scene: its ripples' and the wind that fills its prints
    (Add Atmosphere changed it)."""
    done = set()
    for obj in scene.objects:
        material = find_sand_material(obj)
        wave = ripple_node(material)
        if wave is not None and material.name not in done:
            wave.inputs["Wind"].default_value = tuple(wind)
            done.add(material.name)
        prints = footprint_node(material) if material is not None else None
        if prints is not None and "Wind" in prints.inputs:  # the wind that fills old prints
            prints.inputs["Wind"].default_value = tuple(wind)
            done.add(material.name)
    return len(done)


def _build_tree(material, image, look, glint_mode, with_ripples):
    tree = material.node_tree
    if tree.animation_data is not None:
        tree.animation_data_clear()  # the footprint driver comes back with attach_footprints
    tree.nodes.clear()
    output = h.add_node(tree, "ShaderNodeOutputMaterial", name="Sandscape Output")
    normal = None
    if with_ripples:
        wave = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Ripples", label="Ripples",
                          node_tree=h.ensure_group(ripples))
        normal = wave.outputs["Normal"]
    surface = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Look", label=look.title(),
                         node_tree=h.ensure_group(LOOKS[look]))
    if normal is not None:
        h.link(tree, normal, surface.inputs["Normal"])
    base = surface.outputs[0]
    lit = glint_mode == "LIT"
    if image is None:
        glint = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Glints",
                           node_tree=h.ensure_group(lit_glints if lit else glints))
    else:
        glint = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Glints",
                           node_tree=h.ensure_group(glint_facet if lit else glint_shade))
        uv = h.add_node(tree, "ShaderNodeTexCoord", name="Sandscape Glint UV")
        texture = h.add_node(tree, "ShaderNodeTexImage", name=GLINT_NOISE, label="Glint Noise",
                             interpolation="Closest", extension="REPEAT", image=image)
        h.link(tree, uv.outputs["UV"], texture.inputs["Vector"])
        h.link(tree, texture.outputs["Color"], glint.inputs["Noise"])
        if lit:  # a facet's tilt from the grain's own value: grains of one value lean alike
            tilt = h.add_node(tree, "ShaderNodeTexWhiteNoise", name="Sandscape Glint Tilt",
                              label="Glint Tilt", noise_dimensions="1D")
            h.link(tree, texture.outputs["Color"], tilt.inputs["W"])
            h.link(tree, tilt.outputs["Color"], glint.inputs["Tilt"])
    glint.label = "Glitter" if look == "JOURNEY" else "Glints"
    if lit:
        h.link(tree, base, glint.inputs["Base"])
        if normal is not None:
            h.link(tree, normal, glint.inputs["Normal"])
        h.link(tree, glint.outputs["Shader"], output.inputs["Surface"])
    else:
        add = h.add_node(tree, "ShaderNodeAddShader", name=GLINTS_ADDED)
        h.link(tree, base, add.inputs[0])
        h.link(tree, glint.outputs["Emission"], add.inputs[1])
        h.link(tree, add.outputs[0], output.inputs["Surface"])
    h.arrange(tree, set_widths=False)
    return glint


def _glint_aov(material, glint):
    """An AOV output of the glint mask, so the compositor can keep the glints out of the denoiser
    (a material built before it existed gets it on its next update)."""
    tree = material.node_tree
    aov = own.node(tree, GLINT_AOV_NODE)
    if aov is None:
        aov = h.add_node(tree, "ShaderNodeOutputAOV", name=GLINT_AOV_NODE, label="Glint AOV")
        aov.location = (glint.location.x, glint.location.y - 300.0)  # under the glints it reads
    aov.aov_name = GLINT_AOV
    if not aov.inputs["Value"].is_linked:
        h.link(tree, glint.outputs["Mask"], aov.inputs["Value"])


def _ripple_displacement(material, wanted):
    """Ripples as true displacement too (where adaptive subdivision dices finely enough: the
    footprint patch), added to the prints' displacement; or shading only."""
    tree = material.node_tree
    existing = own.node(tree, RIPPLE_DISPLACEMENT)
    output = own.node(tree, "Sandscape Output")
    prints = footprint_node(material)
    if existing is not None and not wanted:
        tree.nodes.remove(existing)
        extra = own.node(tree, "Sandscape Prints + Ripples")
        if extra is not None:
            tree.nodes.remove(extra)
        if prints is not None:
            h.link(tree, prints.outputs["Displacement"], output.inputs["Displacement"])
        return
    if existing is None and wanted:
        wave = ripple_node(material)
        displace = h.add_node(tree, "ShaderNodeDisplacement", name=RIPPLE_DISPLACEMENT,
                              label="Ripple Displacement", space="WORLD",
                              inputs={"Midlevel": 0.0, "Scale": 1.0})
        h.link(tree, wave.outputs["Height"], displace.inputs["Height"])
        result = displace.outputs[0]
        if prints is not None:
            both = h.add_node(tree, "ShaderNodeVectorMath", name="Sandscape Prints + Ripples",
                              operation="ADD")
            h.link(tree, prints.outputs["Displacement"], both.inputs[0])
            h.link(tree, result, both.inputs[1])
            result = both.outputs[0]
        h.link(tree, result, output.inputs["Displacement"])
        material.displacement_method = "BOTH"
        h.arrange(tree, set_widths=False)


def _footprint_state(material):
    node = footprint_node(material)
    if node is None or not node.inputs["Print Map"].is_linked:
        return None
    texture = own.node(material.node_tree, PRINT_MAP)
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
        output = own.node(tree, sand_eevee.CYCLES_OUTPUT)
        coords = h.add_node(tree, "ShaderNodeTexCoord", name=PRINT_SPACE, label="Print Space")
        mapping = h.add_node(tree, "ShaderNodeMapping", name=PRINT_REGION, label="Print Region",
                             vector_type="POINT")
        node = h.add_node(tree, "ShaderNodeGroup", name="Sandscape Footprints", label="Footprints",
                          node_tree=h.ensure_group(footprint_height))
        h.link(tree, coords.outputs["Object"], mapping.inputs["Vector"])
        h.link(tree, coords.outputs["Object"], node.inputs["Vector"])
        h.link(tree, node.outputs["Displacement"], output.inputs["Displacement"])
        evaluation.drive_by_frame(node.inputs["Frame"])
        if own.node(tree, RIPPLE_DISPLACEMENT) is not None:  # prints and ripples displace together
            _ripple_displacement(material, False)
            _ripple_displacement(material, True)
    mapping = own.node(tree, PRINT_REGION)
    coords = own.node(tree, PRINT_SPACE)
    if own.node(tree, PRINT_BLEND) is None:  # new, or one Linear lookup (Sandscape before 2026-11-25)
        print_lookup.build(tree, mapping, node)
        h.arrange(tree, set_widths=False)
    coords.object = space_object
    corners = own.node(tree, PRINT_CORNERS)
    corners.inputs["Width"].default_value, corners.inputs["Height"].default_value = image.size
    for name in PRINT_TEXELS:
        own.node(tree, name).image = image
    low, size = image["region_min"], image["region_size"]
    mapping.inputs["Location"].default_value = (-low[0] / size[0], -low[1] / size[1], 0.0)
    mapping.inputs["Scale"].default_value = (1.0 / size[0], 1.0 / size[1], 1.0)
    for name, value in values.items():
        if name in node.inputs and name != "Frame":
            node.inputs[name].default_value = value
    trample_ripples(material)
    # Displacement and bump: the prints are true geometry, and the shading normal stays the
    # smooth one (true displacement alone shades the adaptive patch by its flat base quads).
    material.displacement_method = "BOTH"
    sand_eevee.sync(tree)
    return node


def trample_ripples(material):
    """The prints' Pressed flattens the ripples, as a foot tramples those it lands on (kept out
    where either group is an artist's older one without the sockets)."""
    wave, prints = ripple_node(material), footprint_node(material)
    if wave is not None and prints is not None and "Flatten" in wave.inputs and "Pressed" in prints.outputs:
        h.link(material.node_tree, prints.outputs["Pressed"], wave.inputs["Flatten"])
