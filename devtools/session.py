"""A Blender session for development: an isolated user directory and the working tree
installed the way Blender installs extensions (a local repository holding it).

isolate() must run before the first `import bpy`.
"""

import contextlib
import os
import pathlib
import tempfile

REPO_ROOT = pathlib.Path(__file__).resolve().parent.parent
EXTENSION_ID = "sandscape"
LOCAL_REPO = "local"
MODULE = f"bl_ext.{LOCAL_REPO}.{EXTENSION_ID}"


def isolate(root=None):
    """Point Blender's user resources and caches at a temporary directory; returns it."""
    if "bpy" in __import__("sys").modules:
        raise RuntimeError("isolate() must run before bpy is imported")
    root = pathlib.Path(root or tempfile.mkdtemp(prefix="sandscape-user-"))
    (root / "cache").mkdir(parents=True, exist_ok=True)
    os.environ["BLENDER_USER_RESOURCES"] = str(root / "blender")
    os.environ["XDG_CACHE_HOME"] = str(root / "cache")
    return root


def install_dev_extension(root):
    """Register the working tree as extension `sandscape` of a local repository; returns the module."""
    import addon_utils
    import bpy

    bpy.context.preferences.use_preferences_save = False
    repo_dir = pathlib.Path(root) / "extensions"
    repo_dir.mkdir(parents=True, exist_ok=True)
    link = repo_dir / EXTENSION_ID
    if not link.exists():
        link.symlink_to(REPO_ROOT, target_is_directory=True)
    bpy.context.preferences.extensions.repos.new(
        name="Sandscape dev", module=LOCAL_REPO, custom_directory=str(repo_dir), source="USER")
    bpy.ops.extensions.repo_refresh_all()
    addon_utils.enable(MODULE, default_set=True)
    if not hasattr(bpy.types, "SANDSCAPE_OT_add_sand_material"):
        raise RuntimeError(f"{MODULE} did not register")
    import importlib
    return importlib.import_module(MODULE)


def reset():
    """An empty factory file (the isolated user directory has no startup.blend).

    read_homefile keeps the preferences, so the extension stays enabled;
    read_factory_settings would disable it. Old Python references to data go stale.
    """
    import bpy

    bpy.ops.wm.read_homefile(use_empty=True)
    bpy.context.preferences.use_preferences_save = False


def start():
    """A bench's session: isolated, bpy imported, the working tree installed; the package."""
    root = isolate()
    import bpy  # noqa: F401 (after isolate, before the extension)

    return install_dev_extension(root)


def demo_scene():
    """A bench's session with the desert demo built in it: (the package, its scene at 100 %)."""
    sandscape = start()
    import bpy

    reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    scene.render.resolution_percentage = 100
    return sandscape, scene


@contextlib.contextmanager
def extension_off():
    """Sandscape disabled and Python auto-run off, as on a render farm without the extension."""
    import addon_utils
    import bpy

    preferences = bpy.context.preferences.filepaths
    addon_utils.disable(MODULE, default_set=True)
    preferences.use_scripts_auto_execute = False
    try:
        assert not hasattr(bpy.types, "SANDSCAPE_OT_paint_footprints")
        yield
    finally:
        preferences.use_scripts_auto_execute = True
        addon_utils.enable(MODULE, default_set=True)
