"""Run in a fresh process by test_extension_package.py: validate, build, install, use.

Prints one line 'RESULT <json>' for the test to read.
"""

import json
import pathlib
import sys
import zipfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent))

from devtools import session  # noqa: E402

root = session.isolate()

import bpy  # noqa: E402
from bl_pkg import bl_extension_cli  # noqa: E402

result = {}
out_dir = root / "build"
out_dir.mkdir()
result["validate"] = bl_extension_cli.cli_extension_handler(["validate", str(session.REPO_ROOT)])
result["build"] = bl_extension_cli.cli_extension_handler(
    ["build", "--source-dir", str(session.REPO_ROOT), "--output-dir", str(out_dir)])
zips = sorted(out_dir.glob("*.zip"))
result["zips"] = [z.name for z in zips]
names = zipfile.ZipFile(zips[0]).namelist()
result["files"] = names

bpy.context.preferences.use_preferences_save = False
(root / "blender" / "extensions" / "user_default").mkdir(parents=True, exist_ok=True)
result["install"] = sorted(bpy.ops.extensions.package_install_files(
    filepath=str(zips[0]), repo="user_default", enable_on_install=True))
module = sys.modules.get("bl_ext.user_default.sandscape")
result["module_file"] = getattr(module, "__file__", None)

bpy.ops.wm.read_homefile(use_empty=True)
bpy.ops.mesh.primitive_plane_add()
result["operator"] = sorted(bpy.ops.sandscape.add_sand_material())
material = bpy.context.active_object.active_material
result["material"] = material.get("sandscape_material") if material else None

# Footprints through the installed copy: a walker over a subdivided plane, painted.
bpy.ops.mesh.primitive_grid_add(x_subdivisions=20, y_subdivisions=20, size=10)
terrain = bpy.context.active_object
bpy.ops.sandscape.add_walker()
bpy.context.scene.frame_end = 48
result["paint"] = sorted(bpy.ops.sandscape.paint_footprints())
depsgraph = bpy.context.evaluated_depsgraph_get()
result["cut_faces"] = len(terrain.data.polygons) - len(terrain.evaluated_get(depsgraph).data.polygons)
result["blender"] = bpy.app.version_string
print("RESULT " + json.dumps(result))
