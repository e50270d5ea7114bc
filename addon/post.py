"""The scene's compositor tree: Render Layers -> gated blur of the scattered light -> god rays ->
the sun's glow, with the render's alpha kept.

Not a shared group but the tree on scene.compositing_node_group, one per scene, rebuilt from the
settings on every run (an effect switched off is absent, not bypassed). Its parts are the
versioned groups Sandscape Gated Blur and Sandscape God Rays.

The god rays need the sun's place on screen on every frame: simple-expression drivers give it
(sun_screen.py), and the display white follows the exposure the same way, so the tree follows
any camera, sun or exposure with no handler and a render farm without Sandscape renders it.
"""

import types

import bpy

from ..node_groups import gated_blur, god_rays
from ..node_groups import helper as h
from . import atmosphere, drivers, evaluation, sand, sun_screen
from . import ownership as own
from . import post_passes as passes
from .post_glow import add_glow
from .post_sparkles import keep_sparkles

SUN_COLOR = (1.0, 0.93, 0.8, 1.0)
DENOISE, DENOISE_VOLUME = "Sandscape Denoise", "Sandscape Denoise Scattered"
WHITE = "Sandscape Display White"
GLINT_AOV = sand.GLINT_AOV  # the sand material writes where grains can glint


def display_white(scene):
    """The linear value the view shows as white: 2^-exposure (drivers.WHITE_EXPRESSION)."""
    return 2.0 ** -scene.view_settings.exposure


def _clear_animation(tree):
    """The tree's drivers go with its nodes; so does the action of sun keys older files hold."""
    action = tree.animation_data.action if tree.animation_data is not None else None
    tree.animation_data_clear()
    if action is not None and action.users == 0:
        bpy.data.actions.remove(action)


def build(tree, settings, white=1.0, image_denoised=False, scene=None, engine=passes.CYCLES, layer=None):
    """(Re)build the tree for the settings: use_denoise, use_blur, blur_threshold, use_god_rays, ...

    image_denoised: Cycles denoises the combined image (not the passes), so the gated blur
    denoises the scattered light it swaps in, and the sparkles come from its Noisy Image. scene:
    whose render layers the tree reads (default: the context's); layer: which of its view layers.
    engine: whose passes there are (EEVEE has no indirect volume light and no denoising data)."""
    tree.nodes.clear()
    _clear_animation(tree)
    if not tree.interface.items_tree:
        h.add_output(tree, "Image", "NodeSocketColor", "The composited frame")
    tree.description = ("Sandscape post effects: denoising of all but the glints, gated blur of the "
                        "scattered light, god rays, the sun's glow")
    layers = h.add_node(tree, "CompositorNodeRLayers", name="Sandscape Render Layers")
    if scene is not None:  # a scene not shown: its own layers, not the shown scene's
        layers.scene = scene
    if layer is not None:
        layers.layer = layer.name
    output = h.add_node(tree, "NodeGroupOutput", name="Sandscape Composite")
    image = layers.outputs["Image"]
    if passes.denoises(settings, engine):
        image = _denoised(tree, layers, settings, image_denoised)
    elif settings.use_blur:
        volume = _scattered(tree, layers, image, engine)
        if image_denoised:
            # Raw passes swapped into Cycles' denoised image put their noise back (seed to seed
            # 0.55 against 0.148 for the denoised image alone, tests/test_denoise_but_glints.py).
            volume = _denoise(tree, volume, name=DENOISE_VOLUME)
        image = _with_blurred(tree, layers, image, volume, settings)
    if settings.use_god_rays:
        rays = h.add_node(tree, "CompositorNodeGroup", name=sun_screen.RAYS, label="God Rays",
                          node_tree=h.ensure_group(god_rays),
                          inputs={"Samples": float(settings.samples), "Density": settings.ray_density,
                                  "Weight": settings.ray_weight, "Decay": settings.ray_decay,
                                  "Exposure": settings.ray_exposure})
        # The driven sun place sets both the disc and the rays: one source of truth per frame.
        place = sun_screen.add_nodes(tree, settings.fade)
        h.link(tree, place.outputs["Sun"], rays.inputs["Sun"])
        h.link(tree, place.outputs["Intensity"], rays.inputs["Intensity"])
        h.link(tree, _occlusion(tree, layers, place.outputs["Sun"], settings.disc_radius),
               rays.inputs["Occlusion"])
        # In display units: Exposure 1 gives the same rays at any scene exposure (the demo's
        # -2.7 had left the default rays at a mean change of 0.0006).
        scale = h.add_node(tree, "ShaderNodeValue", name=WHITE, label="Display White (driven)")
        scale.outputs[0].default_value = white
        if scene is not None:  # 2^-exposure, whatever the exposure becomes
            drivers.drive(scale.outputs[0], "default_value", drivers.WHITE_EXPRESSION,
                          [("exposure", "SCENE", scene, "view_settings.exposure")])
        shown = h.vector_math(tree, "SCALE", rays.outputs["Rays"], label="× Display White")
        h.link(tree, scale.outputs[0], shown.inputs["Scale"])
        total = h.add_node(tree, "ShaderNodeVectorMath", label="+ God Rays", operation="ADD")
        h.link(tree, image, total.inputs[0])
        h.link(tree, shown.outputs[0], total.inputs[1])
        image = total.outputs[0]
    if settings.use_sun_glow:
        image = add_glow(tree, image, settings.glow_strength, white, scene)
    # Vector maths leave alpha at 1: the render's own alpha goes back on (Film > Transparent).
    alpha = h.add_node(tree, "CompositorNodeSetAlpha", name="Sandscape Keep Alpha", label="Keep Alpha",
                       inputs={"Type": "Replace Alpha"})
    h.link(tree, image, alpha.inputs["Image"])
    h.link(tree, layers.outputs["Alpha"], alpha.inputs["Alpha"])
    h.link(tree, alpha.outputs[0], output.inputs[0])
    h.arrange(tree, set_widths=False)
    return tree


def _scattered(tree, layers, image, engine=passes.CYCLES):
    """The volume passes' light, at most the image's own (per channel)."""
    light = layers.outputs["Volume Direct"]  # EEVEE's Volume Light: it has no indirect pass
    if engine == passes.CYCLES:
        light = h.vector_math(tree, "ADD", light, layers.outputs["Volume Indirect"],
                              label="Volume Passes").outputs[0]
    # The passes can exceed the combined image in a pixel (751 negative pixels in a demo
    # frame; indirect sample clamping is a likely cause): never take out more than it holds.
    return h.vector_math(tree, "MINIMUM", light, image, label="Scattered Light").outputs[0]


def _with_blurred(tree, layers, image, volume, settings):
    """The image with its scattered light swapped for the gated blur of it: the blur's change
    is added, so geometry stays sharp; guided by the sky seen (the environment pass), so cloud
    light is not smeared over the sky round a cloud."""
    blur = h.add_node(tree, "CompositorNodeGroup", name="Sandscape Gated Blur", label="Gated Blur",
                      node_tree=h.ensure_group(gated_blur), inputs={"Threshold": settings.blur_threshold})
    h.link(tree, volume, blur.inputs["Image"])
    h.link(tree, layers.outputs["Environment"], blur.inputs["Guide"])
    change = h.vector_math(tree, "SUBTRACT", blur.outputs["Image"], volume, label="Blur's Change")
    return h.vector_math(tree, "ADD", image, change.outputs[0], label="+ Blur's Change").outputs[0]


def _denoise(tree, image, layers=None, name=None):
    node = h.add_node(tree, "CompositorNodeDenoise", name=name, label="Denoise (OIDN)")
    h.link(tree, image, node.inputs["Image"])
    if layers is not None:  # albedo and normal keep edges and textures: Cycles' denoising data
        h.link(tree, layers.outputs["Denoising Albedo"], node.inputs["Albedo"])
        h.link(tree, layers.outputs["Denoising Normal"], node.inputs["Normal"])
    return node.outputs["Image"]


def _denoised(tree, layers, settings, image_denoised=False):
    """The image denoised with albedo and normal, the gated blur's change to its scattered light,
    and the sparkling pixels taken raw.

    Raw pixels, not denoised (image − glint light) + glint light: while a glinting grain replaced
    the sand it covered (Glint Facet before v4), the rest of its pixel was a dark hole that the
    denoiser filled with the sand around it, and the glint added back on top came out 30 % too
    bright (σ 0.0100 against 0.0086 in the demo at 16 samples). Not measured again since the
    mirror came on top of the sand.
    """
    image = layers.outputs["Image"]
    denoised = None
    if image_denoised:  # Cycles denoised the image: its raw samples are the Noisy Image
        denoised, image = image, layers.outputs["Noisy Image"]
    if not settings.use_blur:
        clean = denoised if denoised is not None else _denoise(tree, image, layers, DENOISE)
    else:
        # The whole image denoised with albedo and normal, then the blur's change to the scattered
        # light denoised on its own. Denoised apart from the guides, the scattered light itself
        # left blotches in the sky (σ 0.007 there against 0.0053; issue 14 measured 0.019 with
        # the raw passes swapped back in).
        volume = _denoise(tree, _scattered(tree, layers, image), name=DENOISE_VOLUME)
        if denoised is None:
            denoised = _denoise(tree, image, layers, DENOISE)
        clean = _with_blurred(tree, layers, denoised, volume, settings)
    return keep_sparkles(tree, layers, image, clean)


def _occlusion(tree, layers, sun, radius):
    """Sun colour inside a soft disc of `radius` (frame heights) around the sun, where sky is seen."""
    coordinates = h.add_node(tree, "CompositorNodeImageCoordinates")
    h.link(tree, layers.outputs["Image"], coordinates.inputs["Image"])
    # The frame's size in pixels as a float vector: (1, 1) relative to each dimension. Not Image
    # Info's Dimensions, an integer vector in 5.2 whose link Blender 5.0 drops when it opens the file.
    info = h.add_node(tree, "CompositorNodeRelativeToPixel", label="Frame Size", data_type="VECTOR",
                      reference_dimension="PER_DIMENSION")
    info.inputs["Vector Value"].default_value = (1.0, 1.0)
    h.link(tree, layers.outputs["Image"], info.inputs["Image"])
    size = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, info.outputs["Vector Value"], size.inputs[0])
    aspect = h.math(tree, "DIVIDE", size.outputs["X"], size.outputs["Y"], label="Aspect")
    offset = h.add_node(tree, "ShaderNodeVectorMath", operation="SUBTRACT")
    h.link(tree, coordinates.outputs["Normalized"], offset.inputs[0])
    h.link(tree, sun, offset.inputs[1])
    split = h.add_node(tree, "ShaderNodeSeparateXYZ")
    h.link(tree, offset.outputs[0], split.inputs[0])
    wide = h.math(tree, "MULTIPLY", split.outputs["X"], aspect.outputs[0], label="dx × aspect")
    square = h.add_node(tree, "ShaderNodeCombineXYZ")
    h.link(tree, wide.outputs[0], square.inputs["X"])
    h.link(tree, split.outputs["Y"], square.inputs["Y"])
    distance = h.add_node(tree, "ShaderNodeVectorMath", operation="LENGTH")
    h.link(tree, square.outputs[0], distance.inputs[0])
    disc = h.add_node(tree, "ShaderNodeMapRange", label="Sun Disc", interpolation_type="SMOOTHSTEP",
                      inputs={"From Min": radius, "From Max": radius * 0.5, "To Min": 0.0, "To Max": 1.0})
    h.link(tree, distance.outputs["Value"], disc.inputs["Value"])
    sky = h.add_node(tree, "CompositorNodeRGBToBW")
    h.link(tree, layers.outputs["Environment"], sky.inputs[0])
    seen = h.math(tree, "GREATER_THAN", sky.outputs[0], 0.0, label="Sky Seen")
    both = h.math(tree, "MULTIPLY", seen.outputs[0], disc.outputs["Result"], label="Disc × Sky")
    tint = h.add_node(tree, "ShaderNodeVectorMath", label="Sun Colour", operation="SCALE",
                      inputs={0: SUN_COLOR[:3]})
    h.link(tree, both.outputs[0], tint.inputs["Scale"])
    return tint.outputs[0]


# ---------------------------------------------------------------- the operator's work

def any_effect(settings):
    return settings.use_denoise or settings.use_blur or settings.use_god_rays or settings.use_sun_glow


def route(scene, settings):
    """What the tree is built for: the engine and, where the tree depends on it, whether Cycles
    denoises the image."""
    engine = scene.render.engine
    reads_denoiser = engine == passes.CYCLES and (settings.use_denoise or settings.use_blur)
    return f"{engine} denoised" if reads_denoiser and scene.cycles.use_denoising else engine


def apply_post_effects(scene, settings, rebuild_only=False):
    """This scene's compositor tree, built for the settings in the engine the scene renders with;
    a user's tree is kept aside. Returns what was done and, under "changes", what of the
    artist's settings changed. rebuild_only: a handler's rebuild for another engine or denoiser,
    which leaves the scene's Compositing switch as the artist set it."""
    current = scene.compositing_node_group
    ours = own.scene_compositor(scene)
    replaced = None
    changes = []
    if current is not None and ours is None:
        replaced = current
        current.use_fake_user = True
    elif ours is not None and any(other.compositing_node_group == ours for other in bpy.data.scenes
                                  if other != scene):
        ours = None  # shared with another scene: this scene gets its own
    layer = rendered_layer(scene)
    engine = scene.render.engine
    if not any_effect(settings):
        if ours is not None:
            _, off = passes.update(ours, scene, layer, None, engine, GLINT_AOV)
            changes += _pass_changes(layer, [], off)
            previous = bpy.data.node_groups.get(ours.get("replaced_tree", ""))
            scene.compositing_node_group = previous
            bpy.data.node_groups.remove(ours)
        return {"tree": None, "replaced": replaced, "changes": changes, "skipped": []}
    if ours is None:
        ours = own.mark(bpy.data.node_groups.new("Sandscape Post Effects", "CompositorNodeTree"),
                        own.TREE_KEY, True)
    if replaced is not None:
        ours["replaced_tree"] = replaced.name
        changes.append(f"compositor '{replaced.name}' replaced (kept with a fake user)")
    on, off = passes.update(ours, scene, layer, settings, engine, GLINT_AOV)
    changes += _pass_changes(layer, on, off)
    # Cycles' own denoiser is the artist's: when it is on, the tree takes its Noisy Image for
    # the sparkles and its denoised image for the rest.
    build(ours, settings, display_white(scene), engine == passes.CYCLES and scene.cycles.use_denoising,
          scene, engine, layer)
    ours["built_for"] = route(scene, settings)
    scene.compositing_node_group = ours
    if not scene.render.use_compositing and not rebuild_only:
        changes.append("compositing turned on (Output properties > Post Processing)")
        scene.render.use_compositing = True
    if settings.use_god_rays:
        sun_screen.attach(ours, scene, atmosphere.scene_sun(scene))
    skipped = []
    if settings.use_denoise and not passes.denoises(settings, engine):
        skipped.append(f"denoising all but the glints (Cycles only; left out in "
                       f"{passes.ENGINE_NAMES.get(engine, engine)})")
    return {"tree": ours, "replaced": replaced, "changes": changes, "skipped": skipped}


def rendered_layer(scene):
    """The view layer the tree reads: the one worked on when it renders, else the first that does."""
    layer = evaluation.scene_view_layer(scene)
    return layer if layer.use else next((v for v in scene.view_layers if v.use), layer)


def _pass_changes(layer, on, off):
    changes = []
    if on:
        changes.append(f"passes on in view layer '{layer.name}': {', '.join(on)}")
    if off:
        changes.append(f"passes Sandscape had turned on, off again: {', '.join(off)}")
    return changes


def set_denoise(scene, on):
    """Switch the tree's denoising of all but the glints on or off (a quality preset's choice).

    A scene without our tree gets one that only denoises; its blur, god rays and glow stay as set.
    """
    settings = scene.sandscape_post
    settings.use_denoise = on
    if own.scene_compositor(scene) is not None:
        return apply_post_effects(scene, settings)
    if not on:
        return None
    names = [p.identifier for p in settings.bl_rna.properties if p.identifier not in ("rna_type", "name")]
    only = types.SimpleNamespace(**{name: getattr(settings, name) for name in names})
    only.use_blur = only.use_god_rays = only.use_sun_glow = False
    return apply_post_effects(scene, only)


def stale_for_denoiser(scene):
    """True when the engine, or Cycles' denoising, was switched since our tree was built."""
    tree, settings = own.scene_compositor(scene), scene.sandscape_post
    if tree is None or scene.compositing_node_group != tree:
        return False
    if "built_for" in tree:
        return tree["built_for"] != route(scene, settings)
    # A tree from before the record: its blur denoised the scattered light when Cycles denoised.
    if settings.use_denoise or not settings.use_blur:
        return False
    return (own.node(tree, DENOISE_VOLUME) is not None) != scene.cycles.use_denoising
