"""Find what does not contribute to the image, and switch it off.

Each finding is a Decision: one line for the report and a function that applies it.
Nothing is deleted: objects are hidden from renders, modifiers and passes switched off, links
rerouted, so a decision is easy to undo by hand (and Ctrl+Z undoes the whole operator).
"""

import numpy as np
from mathutils import Vector

from . import atmosphere, evaluation, post, post_glow, sand, sun_screen
from . import ownership as own
from .post_passes import CYCLES, EEVEE

VOLUME_SHADERS = {"ShaderNodeVolumeScatter", "ShaderNodeVolumeAbsorption", "ShaderNodeVolumePrincipled",
                  "ShaderNodeVolumeCoefficients"}


EMPTY_VOLUME, EMPTY_WORLD_VOLUME, IDLE_DICING, DARK_GLINTS, IDLE_RAYS, IDLE_BOUNCES, UNUSED_PASS = (
    "empty volume", "empty world volume", "idle dicing", "dark glints", "idle god rays", "idle bounces",
    "unused pass")


class Decision:
    """A finding: the line for the report, its kind and what it is about (for the checks that
    depend on earlier findings; never read back from the text), and a function that applies it."""
    __slots__ = ("message", "apply", "kind", "target")

    def __init__(self, message, apply, kind, target=None):
        self.message, self.apply, self.kind, self.target = message, apply, kind, target


def decisions(scene):
    """What the scene's render engine spends on and the image does not show. Cycles' settings
    (adaptive dicing, volume bounces, its passes) cost nothing in EEVEE and are left alone there,
    as EEVEE's passes are in Cycles."""
    cycles = not for_eevee(scene)
    checks = (_empty_volumes, _empty_world_volume, *((_idle_adaptive_subdivision,) if cycles else ()),
              _dark_glints, _idle_sun_effects)
    found = [decision for check in checks for decision in check(scene)]
    if cycles:
        found.extend(_idle_volume_bounces(scene, found))
    found.extend(_unused_passes(scene, found))
    return found


def for_eevee(scene):
    return scene.render.engine == EEVEE


def _renderable(scene):
    return [obj for obj in scene.objects if not obj.hide_render and obj.type in {"MESH", "VOLUME", "CURVE"}]


def _volume_output(tree):
    """The active Material/World output's Volume socket when it is linked, else None."""
    if tree is None:
        return None
    for node in tree.nodes:
        if node.bl_idname in {"ShaderNodeOutputMaterial", "ShaderNodeOutputWorld"} and node.is_active_output:
            socket = node.inputs["Volume"]
            return socket if socket.is_linked else None
    return None


def _volume_density_zero(material):
    """True when a volume-only material is fed only by volume shaders of unlinked density 0."""
    tree = material.node_tree if material else None
    volume = _volume_output(tree)
    return volume is not None and not volume.node.inputs["Surface"].is_linked and _scatters_nothing(volume)


def _scatters_nothing(volume):
    """True when a Volume socket is fed only by volume shaders of unlinked density 0."""
    densities = [node.inputs.get("Density") for node in _upstream(volume)
                 if node.bl_idname in VOLUME_SHADERS or node.bl_idname == "ShaderNodeGroup"]
    return bool(densities) and all(
        socket is not None and not socket.is_linked and socket.default_value == 0 for socket in densities)


def _upstream(socket):
    nodes, stack = [], [link.from_node for link in socket.links]
    while stack:
        node = stack.pop()
        nodes.append(node)
        if node.bl_idname in {"ShaderNodeAddShader", "ShaderNodeMixShader"}:
            stack.extend(link.from_node for s in node.inputs for link in s.links)
    return nodes


def _empty_volumes(scene):
    for obj in _renderable(scene):
        material = obj.active_material
        if obj.type == "MESH" and _volume_density_zero(material):
            yield Decision(f"'{obj.name}': a volume of density 0 scatters nothing; hidden from renders",
                           lambda o=obj: setattr(o, "hide_render", True), EMPTY_VOLUME, obj)


def _empty_world_volume(scene):
    # A world volume puts every ray of the scene in a volume: Cycles marches them all.
    world = scene.world
    volume = _volume_output(world.node_tree if world is not None else None)
    if volume is not None and _scatters_nothing(volume):
        message = f"World '{world.name}': a volume of density 0 scatters nothing; unlinked from its output"
        yield Decision(message, lambda v=volume: [v.id_data.links.remove(link) for link in list(v.links)],
                       EMPTY_WORLD_VOLUME, world)


def _displaces(obj):
    for slot in obj.material_slots:
        material = slot.material
        if material is None or material.node_tree is None or material.displacement_method == "BUMP":
            continue
        if any(n.bl_idname == "ShaderNodeOutputMaterial" and n.inputs["Displacement"].is_linked
               for n in material.node_tree.nodes):
            return True
    return False


def _seen_by_camera(scene, obj):
    """Whether the camera may see the object's box at the start, middle or end frame.

    Conservative: a box partly behind the camera counts as seen, and so does any overlap of
    the projected corners' bounds with the frame.
    """
    camera = scene.camera
    if camera is None:
        return True
    frames = sorted({scene.frame_start, (scene.frame_start + scene.frame_end) // 2, scene.frame_end})
    for _ in evaluation.stepped_frames(scene, frames):
        corners = np.array([obj.matrix_world @ Vector(c) for c in obj.bound_box])
        clip = np.c_[corners, np.ones(8)] @ sun_screen.view_projection(scene, camera).T
        w = clip[:, 3]
        if (w > 0).all():
            ndc = clip[:, :2] / w[:, None]
            if (ndc.min(0) <= 1).all() and (ndc.max(0) >= -1).all():
                return True
        elif (w > 0).any():
            return True
    return False


def _idle_adaptive_subdivision(scene):
    for obj in _renderable(scene):
        for modifier in obj.modifiers:
            if modifier.type != "SUBSURF" or not modifier.use_adaptive_subdivision:
                continue
            if not _displaces(obj):
                reason = "its material does not displace"
            elif not _seen_by_camera(scene, obj):
                reason = "the camera never sees it"
            else:
                continue
            yield Decision(f"'{obj.name}': adaptive subdivision off, {reason}",
                           lambda m=modifier: setattr(m, "use_adaptive_subdivision", False), IDLE_DICING, obj)


def _dark_glints(scene):
    seen = set()
    for obj in _renderable(scene):
        material = sand.find_sand_material(obj)
        node = sand.glint_node(material)
        strength = node.inputs.get("Strength") if node is not None else None  # emission glints only
        if strength is None or material.name in seen or strength.default_value != 0:
            continue
        seen.add(material.name)
        tree = material.node_tree
        add = own.node(tree, sand.GLINTS_ADDED)
        if add is None or not add.outputs[0].is_linked:
            continue
        yield Decision(f"'{material.name}': glint strength 0; the glint branch is bypassed",
                       lambda t=tree, a=add: _bypass(t, a), DARK_GLINTS, material)


def _bypass(tree, add):
    """Route the Add Shader's first input straight to where its output went."""
    source = add.inputs[0].links[0].from_socket
    for link in list(add.outputs[0].links):
        tree.links.new(source, link.to_socket)


def _idle_sun_effects(scene):
    """The god rays and the sun's glow, when they cannot show: the sun out of view on every frame
    (found once for both: it may step the frames) or the rays' strength 0."""
    tree = own.scene_compositor(scene)
    rays = sun_screen.rays_node(tree)
    glow = own.node(tree, post_glow.GLOW)
    if rays is None and glow is None:
        return
    zero_strength = rays is not None and (rays.inputs["Exposure"].default_value == 0
                                          or rays.inputs["Weight"].default_value == 0)
    out_of_view = (rays is None or not zero_strength or glow is not None) and _always_zero(scene)
    reason = "their strength is 0" if zero_strength else "the sun is out of view on every frame"
    if rays is not None and (zero_strength or out_of_view):
        yield Decision(f"God rays removed from the compositor: {reason}",
                       lambda s=scene: _switch_off(s, "use_god_rays"), IDLE_RAYS, scene)
    if glow is not None and out_of_view:
        yield Decision("Sun glow removed from the compositor: the sun is out of view on every frame",
                       lambda s=scene: _switch_off(s, "use_sun_glow"), IDLE_RAYS, scene)


def _switch_off(scene, effect):
    setattr(scene.sandscape_post, effect, False)
    post.apply_post_effects(scene, scene.sandscape_post)


def _always_zero(scene):
    """The sun is out of view on every frame: from its keys where they are all that moves the
    camera and the sun, else by stepping the frames."""
    sun = atmosphere.scene_sun(scene)
    if sun is None or scene.camera is None:
        return True
    fade_node = own.node(own.scene_compositor(scene), sun_screen.PLACE)
    fade = fade_node.inputs["Fade"].default_value if fade_node is not None else scene.sandscape_post.fade
    return all(intensity == 0 for *_, intensity in sun_screen.sun_curve(scene, sun, fade))


def _idle_volume_bounces(scene, found):
    if scene.cycles.volume_bounces == 0:
        return
    hidden = {d.target.as_pointer() for d in found if d.kind == EMPTY_VOLUME}
    volumes = [obj for obj in _renderable(scene) if obj.as_pointer() not in hidden
               and obj.active_material is not None
               and _volume_output(obj.active_material.node_tree) is not None]
    world_volume = (scene.world is not None and _volume_output(scene.world.node_tree) is not None
                    and not any(d.kind == EMPTY_WORLD_VOLUME for d in found))
    if not volumes and not world_volume:
        yield Decision(f"Volume bounces {scene.cycles.volume_bounces} -> 0: no volume is left",
                       lambda s=scene: setattr(s.cycles, "volume_bounces", 0), IDLE_BOUNCES, scene)


PASSES = (  # (Render Layers output, owner path, property, the engine it costs in; None: both)
    ("Volume Direct", "cycles", "use_pass_volume_direct", CYCLES),
    ("Volume Indirect", "cycles", "use_pass_volume_indirect", CYCLES),
    ("Volume Direct", "eevee", "use_pass_volume_direct", EEVEE),
    ("Transparent", "eevee", "use_pass_transparent", EEVEE),
    ("Environment", "", "use_pass_environment", None),
    ("Depth", "", "use_pass_z", None),
    ("Mist", "", "use_pass_mist", None),
    ("Normal", "", "use_pass_normal", None),
    ("Position", "", "use_pass_position", None),
    ("Emission", "", "use_pass_emit", None),
    ("Ambient Occlusion", "", "use_pass_ambient_occlusion", None),
    ("Diffuse Direct", "", "use_pass_diffuse_direct", None),
    ("Glossy Direct", "", "use_pass_glossy_direct", None),
)


def _unused_passes(scene, found):
    if any(d.kind == IDLE_RAYS for d in found):
        return  # the rebuilt tree decides its own passes
    tree = scene.compositing_node_group
    used = set()
    if tree is not None and scene.render.use_compositing:
        for node in tree.nodes:
            if node.bl_idname == "CompositorNodeRLayers":
                used |= {socket.name for socket in node.outputs if socket.is_linked}
    if any(node.bl_idname == "CompositorNodeOutputFile" for node in (tree.nodes if tree else ())):
        return  # file outputs may write any pass
    engine = EEVEE if for_eevee(scene) else CYCLES
    for layer in scene.view_layers:
        for name, owner, prop, costs_in in PASSES:
            if costs_in not in (None, engine):
                continue
            holder = getattr(layer, owner) if owner else layer
            if getattr(holder, prop, False) and name not in used:
                yield Decision(f"View layer '{layer.name}': pass '{name}' is rendered but nothing "
                               "reads it; off", lambda h=holder, p=prop: setattr(h, p, False),
                               UNUSED_PASS, layer)

