"""The README's dune pictures: fields grown by Add Dunes with their defaults (and scarce sand, and
two winds), seen from the ground and from above, in a 2 x 2 sheet (docs/dunes.png).

Each field is Add Dunes' own, lit by Add Atmosphere (a low sun from the side, thin air), rendered
in Cycles with its denoiser. Nothing here is the demo: these are the scenes a new artist gets.

Run: .venv/bin/python devtools/dune_pictures.py [--samples N] [--output docs/dunes.png]
"""

import argparse
import math
import pathlib
import sys
import tempfile
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (480, 270)
GROUND = {"location": (-30.0, 10.0), "height": 1.7, "rotation": (86.0, 0.0, 90.0), "lens": 24.0}
ABOVE = {"location": (-110.0, -110.0, 55.0), "rotation": (58.0, 0.0, -45.0), "lens": 28.0}
SUN = (10.0, 200.0)  # elevation, azimuth in degrees: low and from the side of the default wind
AIR_DENSITY = 0.0003  # per metre at 550 nm: a clear desert day (visibility about 13 km)
VIEWS = (
    ("Transverse ridges from the ground (defaults)", {}, GROUND),
    ("The same field from 55 m up", {}, ABOVE),
    ("Scarce sand (0.8 %): barchans", {"sand_supply": 0.8}, ABOVE),
    ("A second wind at 120°: linear dunes",
     {"use_second_wind": True, "second_wind_angle": math.radians(120.0)}, ABOVE),
)


def render_view(bpy, values, view, samples, path):
    from mathutils import Vector

    from devtools import readback

    session.reset()
    scene = bpy.context.scene
    assert bpy.ops.sandscape.add_dunes(**values) == {"FINISHED"}
    field = bpy.context.active_object
    camera = bpy.data.objects.new("Camera", bpy.data.cameras.new("Camera"))
    scene.collection.objects.link(camera)
    scene.camera = camera
    camera.data.lens, camera.data.clip_end = view["lens"], 40000.0
    if "height" in view:
        x, y = view["location"]
        depsgraph = bpy.context.evaluated_depsgraph_get()
        down = Vector((0.0, 0.0, -1.0))
        hit, ground, *_ = field.evaluated_get(depsgraph).ray_cast(Vector((x, y, 100.0)), down)
        camera.location = (x, y, (ground.z if hit else 0.0) + view["height"])
    else:
        camera.location = view["location"]
    camera.rotation_euler = tuple(math.radians(a) for a in view["rotation"])
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = (math.radians(a) for a in SUN)
    air.density, air.use_wind = AIR_DENSITY, False
    air.set_exposure = True
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scene.view_settings.look = "AgX - Punchy"
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    scene.cycles.samples, scene.cycles.use_denoising = samples, True
    return readback.render_display(scene, path)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=24)
    parser.add_argument("--output", default=str(REPO / "docs" / "dunes.png"))
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-dunes-"))
    pictures = []
    for index, (label, values, view) in enumerate(VIEWS):
        started = time.perf_counter()
        pictures.append((label, render_view(bpy, values, view, args.samples, out / f"{index}.png")))
        print(f"dune pictures: {label}: {time.perf_counter() - started:.1f} s", flush=True)
    plt = results.pyplot("dune pictures: no sheet")
    if plt is None:
        return
    figure, axes = plt.subplots(2, 2, figsize=(9.6, 5.8), dpi=100)
    for axis, (label, pixels) in zip(axes.ravel(), pictures, strict=True):
        axis.imshow(pixels[::-1, :, :3].clip(0.0, 1.0))
        axis.set_title(label, fontsize=9)
        axis.axis("off")
    figure.tight_layout()
    figure.savefig(args.output)
    print(f"dune pictures -> {args.output}")


if __name__ == "__main__":
    main()
