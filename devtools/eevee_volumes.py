"""What EEVEE's volumes do with a phase function, measured: a thin slab seen from above, lit by a
sun lamp, scattering with one Henyey-Greenstein lobe or an even mix of two. EEVEE does not dim
the sun inside the slab, so the light scattered to the camera is E p (1 - exp(-sigma d)); the
table gives the measured p beside the lobe's (or the mix's), with the sun's shadows off, and the
slab's light with them on (no surface behind it). Appends the table to bench/RESULTS.md.

Run: .venv/bin/python devtools/eevee_volumes.py [--no-append]
"""

import argparse
import math
import pathlib
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

SIGMA, THICKNESS = 0.5, 1.0  # 1/m, m
CASES = ((0.0, None, 90.0), (0.31, None, 90.0), (-0.31, None, 90.0), (0.31, -0.31, 90.0), (0.31, -0.31, 30.0))


def henyey_greenstein(cosine, g):
    return (1.0 - g * g) / (4.0 * math.pi * (1.0 + g * g - 2.0 * g * cosine) ** 1.5)


def volume(tree, output, lobes):
    for node in [n for n in tree.nodes if n != output]:
        tree.nodes.remove(node)
    shaders = []
    for g in lobes:
        scatter = tree.nodes.new("ShaderNodeVolumeScatter")
        scatter.inputs["Density"].default_value = SIGMA
        scatter.inputs["Anisotropy"].default_value = g
        shaders.append(scatter.outputs[0])
    if len(shaders) == 2:
        mix = tree.nodes.new("ShaderNodeMixShader")
        mix.inputs[0].default_value = 0.5
        tree.links.new(shaders[0], mix.inputs[1])
        tree.links.new(shaders[1], mix.inputs[2])
        shaders = [mix.outputs[0]]
    tree.links.new(shaders[0], output.inputs["Volume"])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    from devtools import readback, scenes

    session.reset()
    scene = bpy.context.scene
    scene.render.engine = "BLENDER_EEVEE"
    scene.render.resolution_x = scene.render.resolution_y = 32
    scene.render.resolution_percentage = 100
    scene.eevee.taa_render_samples = 8
    scene.view_settings.view_transform = "Standard"
    scene.world = None
    bpy.ops.mesh.primitive_cube_add(size=1.0, location=(0.0, 0.0, 0.5 + THICKNESS / 2))
    box = bpy.context.object
    box.scale = (4.0, 4.0, THICKNESS)
    material = bpy.data.materials.new("Slab")
    box.data.materials.append(material)
    tree = material.node_tree
    tree.nodes.clear()
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    scenes.camera("ORTHO", location=(0.0, 0.0, 5.0), ortho_scale=1.0)
    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy, sun.data.angle = 1.0, 0.0
    scene.collection.objects.link(sun)
    rows = []
    for first, second, elevation in CASES:
        lobes = (first,) if second is None else (first, second)
        volume(tree, output, lobes)
        sun.rotation_euler = (math.radians(90.0 - elevation), 0.0, 0.0)
        cosine = -math.sin(math.radians(elevation))  # the light's way against the view's (up)
        expected = np.mean([henyey_greenstein(cosine, g) for g in lobes])
        measured = {}
        for shadows in (False, True):
            sun.data.use_shadow = shadows
            pixels = readback.render(scene)[..., :3].astype(np.float64)
            measured[shadows] = pixels.mean() / (1.0 - math.exp(-SIGMA * THICKNESS))
        label = f"g {first:+g}" if second is None else f"half g {first:+g}, half g {second:+g}"
        rows.append((label, elevation, expected, measured[False], measured[True]))
        print(rows[-1], flush=True)
    lines = [results.heading("EEVEE volumes: phase and sun"),
             f"{results.machine()}, EEVEE on software OpenGL. A {THICKNESS:g} m slab of sigma {SIGMA:g}/m "
             "from above, a sun of strength 1, no world; p measured = mean pixel / (1 - exp(-sigma d)).\n",
             "| volume | sun elevation | p of the lobes | p measured, shadows off | ratio | shadows on |",
             "|---|---|---|---|---|---|",
             *(f"| {label} | {elevation:g}° | {expected:.4f} | {off:.4f} | {off / expected:.3f} | {on:.4f} |"
               for label, elevation, expected, off, on in rows)]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
