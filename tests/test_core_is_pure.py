"""core/ is plain numpy: no module in it may import bpy, mathutils or bmesh."""

import ast
import pathlib

CORE = pathlib.Path(__file__).resolve().parent.parent / "core"
FORBIDDEN = {"bpy", "mathutils", "bmesh", "bpy_extras", "gpu"}


def imported_roots(source):
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            yield from (alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            yield node.module.split(".")[0]


def test_core_imports_no_blender_module():
    files = sorted(CORE.glob("*.py"))
    assert files, "core/ has no modules"
    offenders = {f.name: sorted(set(imported_roots(f.read_text())) & FORBIDDEN) for f in files}
    assert not {name: mods for name, mods in offenders.items() if mods}


def test_the_check_catches_a_bpy_import():
    assert "bpy" in set(imported_roots("import os\nfrom bpy.types import Operator\n"))
    assert "mathutils" in set(imported_roots("import mathutils.noise as n\n"))
