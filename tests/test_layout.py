"""The README's Layout section is the tree: every package it names exists and says in its docstring
what it holds, and every package in the tree is named there."""

import ast
import pathlib
import re

REPO = pathlib.Path(__file__).resolve().parent.parent
PACKAGES = ("core", "addon", "node_groups", "ui", "operators", "devtools")


def layout_block():
    text = (REPO / "README.md").read_text()
    section = text.split("## Layout", 1)[1]
    return section.split("```", 2)[1]


def test_readme_layout_names_every_package_and_only_those():
    named = set(re.findall(r"^([A-Za-z_]+)/", layout_block(), flags=re.MULTILINE))
    named |= set(re.findall(r"^tests/\s+(bench)/", layout_block(), flags=re.MULTILINE))
    on_disk = {p.name for p in REPO.iterdir() if p.is_dir() and not p.name.startswith(".")
               and any(p.glob("*.py"))}
    assert named == on_disk, (named, on_disk)


def test_every_package_says_what_it_holds():
    for name in PACKAGES:
        docstring = ast.get_docstring(ast.parse((REPO / name / "__init__.py").read_text()))
        assert docstring and len(docstring) > 40, name
