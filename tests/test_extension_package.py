"""Blender validates and builds the extension, installs the zip, and the installed copy works."""

import json
import os
import pathlib
import subprocess
import sys

import bpy

SCRIPT = pathlib.Path(__file__).with_name("install_check.py")


def test_validate_build_install_and_run():
    env = {k: v for k, v in os.environ.items()
           if k not in ("BLENDER_USER_RESOURCES", "XDG_CACHE_HOME")}
    run = subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, text=True, env=env,
                         timeout=300)
    lines = [line for line in run.stdout.splitlines() if line.startswith("RESULT ")]
    assert run.returncode == 0 and lines, run.stdout[-3000:] + run.stderr[-3000:]
    result = json.loads(lines[-1][len("RESULT "):])
    assert result["validate"] == 0 and result["build"] == 0, result
    assert result["zips"] == ["sandscape-0.1.0.zip"]
    files = result["files"]
    assert "blender_manifest.toml" in files and "__init__.py" in files
    assert "core/glints.py" in files and "node_groups/glints.py" in files
    leaked = [f for f in files if f.split("/")[0] in
              ("tests", "bench", "devtools", ".venv", ".venv-5.0", "out", ".git", ".ci", "Makefile",
               "requirements.txt", "requirements-5.0.txt")]
    assert not leaked, leaked
    assert result["install"] == ["FINISHED"]
    assert "user_default" in result["module_file"]
    assert result["operator"] == ["FINISHED"] and result["material"] == "sand"
    # The installed zip runs on the Blender under test (each suite run tests its own version),
    # footprints included: their geometry-nodes modifier inputs are where 5.0 and 5.2 differ.
    assert result["blender"] == bpy.app.version_string
    assert result["paint"] == ["FINISHED"] and result["cut_faces"] > 0
