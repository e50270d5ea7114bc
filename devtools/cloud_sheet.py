"""The cloud layer from the ground at sunrise, noon and backlit: the default layer over a plain
sand plane, a camera at 2 m looking 10 degrees up. Renders with the code of the tree it sits in,
so a copy in an older checkout renders the layer as it was.

Run: .venv/bin/python devtools/cloud_sheet.py render DIR       (three PNGs into DIR)
     .venv/bin/python devtools/cloud_sheet.py compose BEFORE AFTER [--output docs/clouds.png]
"""

import argparse
import math
import pathlib
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

VIEWS = {  # sun (elevation, azimuth from +Y towards +X); the camera looks along +Y
    "sunrise": (4.0, 70.0),
    "noon": (70.0, 160.0),
    "backlit": (14.0, 8.0),
}
RESOLUTION = (320, 180)
SAMPLES = 32


def render(directory):
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    from devtools import readback, scenes

    directory = pathlib.Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    for name, (elevation, azimuth) in VIEWS.items():
        session.reset()
        scene = bpy.context.scene
        bpy.ops.mesh.primitive_plane_add(size=80000.0)
        sand = bpy.data.materials.new("Plain Sand")
        sand.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (0.56, 0.38, 0.22, 1.0)
        bpy.context.object.data.materials.append(sand)
        camera = scenes.camera("PERSP", location=(0.0, 0.0, 2.0), rotation=(math.radians(100.0), 0.0, 0.0),
                               lens=20.0)
        camera.data.clip_end = 1e6
        air = scene.sandscape_atmosphere
        air.sun_elevation, air.sun_azimuth = math.radians(elevation), math.radians(azimuth)
        air.density, air.use_haze = 0.0, False
        air.set_exposure = True
        readback.cycles_scene(scene, RESOLUTION, SAMPLES)
        scene.cycles.volume_biased = True  # ray marching, as the quality presets set it
        bpy.ops.sandscape.add_atmosphere()
        started = time.perf_counter()
        bpy.ops.sandscape.add_clouds()
        scene.cycles.volume_bounces = 8
        scene.cycles.use_denoising = True
        scene.view_settings.view_transform = "AgX"
        readback.render_display(scene, directory / f"{name}.png")
        print(f"cloud sheet: {name}: {time.perf_counter() - started:.1f} s", flush=True)


def compose(before, after, output):
    plt = results.pyplot("cloud sheet: no sheet")
    if plt is None:
        return
    import matplotlib.image

    figure, axes = plt.subplots(2, len(VIEWS), figsize=(3.2 * len(VIEWS), 4.0), dpi=100, squeeze=False)
    for row, (label, directory) in enumerate((("before", before), ("after", after))):
        for column, name in enumerate(VIEWS):
            axis = axes[row, column]
            axis.axis("off")
            axis.imshow(matplotlib.image.imread(str(pathlib.Path(directory) / f"{name}.png")))
            axis.set_title(f"{name}, {label}", fontsize=8)
    figure.tight_layout()
    figure.savefig(output)
    print(f"cloud sheet -> {output}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=("render", "compose"))
    parser.add_argument("paths", nargs="+")
    parser.add_argument("--output", default=str(REPO / "docs" / "clouds.png"))
    args = parser.parse_args(argv)
    if args.mode == "render":
        render(args.paths[0])
    else:
        compose(*args.paths[:2], args.output)


if __name__ == "__main__":
    main()
