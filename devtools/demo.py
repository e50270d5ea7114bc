"""Build the glint demo scene headless and render it (`make demo`).

Until the full desert demo lands, this is a patch of rippled sand with the Sandscape sand
material, a low sun and a sky colour, seen from a little above so slopes face the camera.
"""

import argparse
import math
import pathlib
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent))

from devtools import session  # noqa: E402


def ripple_heights(x, y):
    """Gentle wind ripples plus a long dune swell, in metres."""
    import numpy as np

    swell = 0.6 * np.sin(x * 0.25 + 0.4 * np.sin(y * 0.15))
    ripples = 0.03 * np.sin(x * 3.1 + y * 0.7) + 0.02 * np.sin(x * 5.3 - y * 1.9)
    return swell + ripples


def build_scene(resolution, samples):
    import bpy
    import numpy as np

    bpy.ops.mesh.primitive_grid_add(x_subdivisions=300, y_subdivisions=300, size=40.0)
    ground = bpy.context.active_object
    ground.name = "Sand"
    co = np.empty(len(ground.data.vertices) * 3, np.float32)
    ground.data.vertices.foreach_get("co", co)
    co = co.reshape(-1, 3)
    co[:, 2] = ripple_heights(co[:, 0], co[:, 1])
    ground.data.vertices.foreach_set("co", co.ravel())
    ground.data.shade_smooth()
    ground.data.update()
    bpy.ops.sandscape.add_sand_material(threshold=0.985, glint_size=0.012, facing_power=4.0,
                                        strength=60.0, seed=1)

    sun = bpy.data.objects.new("Sun", bpy.data.lights.new("Sun", "SUN"))
    sun.data.energy = 3.0
    sun.data.color = (1.0, 0.92, 0.8)
    sun.data.angle = math.radians(1.0)
    sun.rotation_euler = (math.radians(60), 0.0, math.radians(200))
    bpy.context.scene.collection.objects.link(sun)

    world = bpy.data.worlds.new("Sky")
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.35, 0.55, 0.9, 1.0)
    background.inputs["Strength"].default_value = 0.6
    scene = bpy.context.scene
    scene.world = world

    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    camera.data.lens = 35.0
    camera.location = (0.0, -9.0, 3.2)
    camera.rotation_euler = (math.radians(68), 0.0, 0.0)
    scene.collection.objects.link(camera)
    scene.camera = camera

    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = True
    scene.render.resolution_x, scene.render.resolution_y = resolution
    scene.render.resolution_percentage = 100
    return scene


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="out/demo.png", help="PNG to write")
    parser.add_argument("--width", type=int, default=640)
    parser.add_argument("--height", type=int, default=360)
    parser.add_argument("--samples", type=int, default=64)
    args = parser.parse_args(argv)

    started = time.perf_counter()
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    session.reset()
    scene = build_scene((args.width, args.height), args.samples)
    built = time.perf_counter()
    output = pathlib.Path(args.output).resolve()
    output.parent.mkdir(parents=True, exist_ok=True)
    scene.render.image_settings.file_format = "PNG"
    scene.render.filepath = str(output)
    bpy.ops.render.render(write_still=True)
    done = time.perf_counter()
    print(f"demo: built in {built - started:.1f} s, rendered {args.width}x{args.height} at "
          f"{args.samples} spp in {done - built:.1f} s -> {output}")


if __name__ == "__main__":
    main()
