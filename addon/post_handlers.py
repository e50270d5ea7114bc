"""Save and render start keep every scene's post tree current: the exposure's white, the
denoiser the tree was built for, and the god rays' sun keys (sun_keys.refresh, which steps the
frames only when what the keys depend on changed)."""

import bpy
from bpy.app.handlers import persistent

from . import atmosphere, post, shot, sun_keys
from . import ownership as own


def refresh_sun_keys(scene):
    """Re-key the sun when what the camera sees of it changed; True when the keys were rewritten."""
    tree = own.scene_compositor(scene)
    if tree is None or sun_keys.rays_node(tree) is None or sun_keys.sun_key_node(tree) is None:
        return False
    white = own.node(tree, post.WHITE)
    if white is not None:  # the exposure may have changed since the tree was built
        white.outputs[0].default_value = post.display_white(scene)
    sun = atmosphere.scene_sun(scene)
    if sun is None or shot.scene_camera(scene) is None:
        return False
    return sun_keys.refresh(tree, scene, sun, tree.get("fade", 0.25))


@persistent
def refresh_all(*_):
    for scene in bpy.data.scenes:
        if scene.library is None:
            if post.stale_for_denoiser(scene):
                post.apply_post_effects(scene, scene.sandscape_post, rebuild_only=True)  # keys the sun too
            else:
                refresh_sun_keys(scene)


HANDLERS = (bpy.app.handlers.save_pre, bpy.app.handlers.render_init)


def register():
    for handlers in HANDLERS:
        if refresh_all not in handlers:
            handlers.append(refresh_all)


def unregister():
    for handlers in HANDLERS:
        if refresh_all in handlers:
            handlers.remove(refresh_all)
