"""Keep every scene's post tree built for the engine and denoiser it renders with, and its
sky and rays on the scene's sun.

The sun's place and the display white follow the scene through drivers (sun_screen.py), so
nothing here steps a frame. A tree built for another engine or denoiser, or by an older Sandscape
that keyed the sun, is rebuilt when the scene changes (never while a render runs) and on save;
drivers Blender set aside while a scene had no camera are re-armed once it has one; a sun the
artist swapped in is followed by the sky and the rays.
"""

import bpy
from bpy.app.handlers import persistent

from . import atmosphere, post, sun_screen
from . import ownership as own


def stale(scene):
    """The scene's tree wants rebuilding: another engine or denoiser, or sun keys from before the
    drivers (god rays on, no Sun Place node)."""
    if post.stale_for_denoiser(scene):
        return True
    tree = own.scene_compositor(scene)
    return (tree is not None and scene.compositing_node_group == tree
            and sun_screen.rays_node(tree) is not None and own.node(tree, sun_screen.PLACE) is None)


def refresh(scenes):
    """Point the sky at the artist's sun where it is another now, rebuild the stale trees of these
    scenes, and point the rays' drivers at the scene's sun; how many trees changed."""
    changed = 0
    for scene in scenes:
        if scene.library is not None:
            continue
        atmosphere.follow_scene_sun(scene)
        if stale(scene):
            post.apply_post_effects(scene, scene.sandscape_post, rebuild_only=True)
            changed += 1
            continue
        tree = own.scene_compositor(scene)
        if tree is None or sun_screen.rays_node(tree) is None:
            continue
        sun = atmosphere.scene_sun(scene)
        if sun_screen.driven_sun(tree) != sun:
            sun_screen.attach(tree, scene, sun)
            changed += 1
    return changed


@persistent
def _on_save(*_):
    refresh(bpy.data.scenes)


@persistent
def _on_update(scene, _depsgraph=None):
    if not bpy.app.is_job_running("RENDER"):
        refresh([scene])
        sun_screen.rearm([scene])


def register():
    if _on_save not in bpy.app.handlers.save_pre:
        bpy.app.handlers.save_pre.append(_on_save)
    if _on_update not in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.append(_on_update)


def unregister():
    if _on_save in bpy.app.handlers.save_pre:
        bpy.app.handlers.save_pre.remove(_on_save)
    if _on_update in bpy.app.handlers.depsgraph_update_post:
        bpy.app.handlers.depsgraph_update_post.remove(_on_update)
