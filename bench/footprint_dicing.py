"""Footprint dicing: geometry memory and render time of the adaptive patch against adaptive
subdivision of the whole terrain.

Scene: a 40 m terrain (80 x 80 quads), the 12-print walk of bench/footprints.py painted by
bpy.ops.sandscape.paint_footprints, a perspective camera looking across it, Cycles 1 spp.
  patch:   Sandscape's set-up (adaptive patch over the prints, the rest of the terrain coarse)
  whole:   the cut and the patch switched off, the whole terrain adaptively subdivided
           (the same modifier settings), the same material
Geometry memory comes from Cycles' own statistics (_cycles.enable_print_stats()), read
from the process's stdout. Also compares the rendered heights of both (they must agree).

--quick renders at a quarter of the pixels (dicing follows pixels, so memory drops too).

Run: .venv/bin/python bench/footprint_dicing.py [--quick] [--no-append]
"""

import argparse
import importlib
import os
import pathlib
import re
import sys
import tempfile
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (480, 270)


def captured_render(readback):
    """Render; return (seconds, pixels, everything Cycles printed to stdout)."""
    sys.stdout.flush()
    with tempfile.TemporaryFile(mode="w+b") as sink:
        saved = os.dup(1)
        os.dup2(sink.fileno(), 1)
        try:
            started = time.perf_counter()
            pixels = readback.render()
            seconds = time.perf_counter() - started
        finally:
            os.dup2(saved, 1)
            os.close(saved)
        sink.seek(0)
        text = sink.read().decode(errors="replace")
    return seconds, pixels, text


def geometry_memory(text):
    """Cycles' mesh geometry memory in MiB (total), and its per-object lines, from print_stats."""
    block = text.split("Mesh statistics:")[-1].split("Image statistics:")[0]
    total = re.search(r"Total memory:\s*([\d.]+)([KMG])", block)
    scale = {"K": 1 / 1024, "M": 1.0, "G": 1024.0}
    objects = re.findall(r"^\s{8}(\S.*?)\s+([\d.]+[KMG]) \(", block, flags=re.MULTILINE)
    return float(total.group(1)) * scale[total.group(2)], objects


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a quarter of the pixels")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    resolution = (RESOLUTION[0] // 2, RESOLUTION[1] // 2) if args.quick else RESOLUTION
    root = session.isolate()
    import bpy

    cycles_module = importlib.import_module("_cycles")  # Blender's own module, there once bpy is

    session.install_dev_extension(root)
    session.reset()
    from devtools import readback, scenes

    frames = (1, 120)
    length = 0.7 * 11
    terrain = scenes.height_field(40.0, 80, name="Sand")
    walker = scenes.keyframed_walker(lambda f: (-length / 2 + length * (f - 1) / 119, 0.0, 0.0),
                                     range(frames[0], frames[1] + 1))
    scenes.footprint_settings(terrain, walker, frames, resolution=2048)
    bpy.ops.sandscape.paint_footprints()
    scene = readback.cycles_scene(resolution=resolution, samples=1)
    scene.frame_set(frames[1])
    scenes.camera("PERSP", location=(0.0, -6.0, 2.5), rotation=(np.radians(70), 0.0, 0.0), lens=35.0)
    material = terrain.active_material
    tree = material.node_tree
    # Emit world Z so the two set-ups can be compared pixel by pixel.
    geometry = tree.nodes.new("ShaderNodeNewGeometry")
    split = tree.nodes.new("ShaderNodeSeparateXYZ")
    emission = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(geometry.outputs["Position"], split.inputs[0])
    tree.links.new(split.outputs["Z"], emission.inputs["Color"])
    output = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
    tree.links.new(emission.outputs[0], output.inputs["Surface"])
    cycles_module.enable_print_stats()

    patch = next(o for o in bpy.data.objects if o.get("sandscape_object") == "footprint_patch")
    renders = {}
    renders["patch"] = captured_render(readback)
    cut = next(m for m in terrain.modifiers if m.type == "NODES")
    cut.show_render = False
    patch.hide_render = True
    whole = terrain.modifiers.new("Adaptive Subdivision", "SUBSURF")
    for name in ("subdivision_type", "use_adaptive_subdivision", "adaptive_space", "adaptive_pixel_size",
                 "levels"):
        setattr(whole, name, getattr(patch.modifiers[0], name))
    renders["whole"] = captured_render(readback)

    rows = []
    for name, (seconds, _, text) in renders.items():
        memory, found = geometry_memory(text)
        rows.append((name, seconds, memory, found))
        print(name, f"{seconds:.2f} s", f"{memory:.2f} MiB", found[:4])
    difference = np.abs(renders["patch"][1][..., 0] - renders["whole"][1][..., 0])
    lines = [results.heading("Footprint dicing", ["--quick"] if args.quick else []),
             f"{results.machine()}. 40 m terrain of 80x80 quads, 12 prints, "
             f"{resolution[0]}x{resolution[1]} perspective, 1 spp, "
             "dicing 1 px.\n",
             "| set-up | render s | Cycles geometry memory MiB | per object |", "|---|---|---|---|"]
    for name, seconds, memory, found in rows:
        label = {"patch": "adaptive patch over the prints (Sandscape)",
                 "whole": "whole terrain adaptive"}[name]
        parts = ", ".join(f"{obj} {size}" for obj, size in found)
        lines.append(f"| {label} | {seconds:.2f} | {memory:.2f} | {parts} |")
    lines.append(f"\nRendered world Z, patch vs whole: max difference {difference.max() * 1000:.3f} mm, "
                 f"mean {difference.mean() * 1000:.4f} mm; deepest rendered point "
                 f"{renders['patch'][1][..., 0].min() * 1000:.2f} mm (prints in view).")
    results.publish(lines, append=not args.no_append)



if __name__ == "__main__":
    main()
