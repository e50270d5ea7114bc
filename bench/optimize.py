"""Optimizer benchmark: the demo with parts that add nothing, rendered before and after
bpy.ops.sandscape.optimize_scene, against a high-sample reference of the optimized scene.

The wasteful variant adds what real scenes collect: an empty fog volume (density 0), a flat slab
with adaptive subdivision but no displacement, the sun moved behind the camera while god rays
stay on, a depth pass nothing reads, and volume bounces.

Run: .venv/bin/python bench/optimize.py [--quick] [--no-append]
"""

import argparse
import math
import pathlib
import statistics
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (320, 180)
SAMPLES = 16
FRAME = 150


def wasteful_demo(bpy):
    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    from devtools import scenes  # here, not at the top: it imports bpy, which must follow isolate()

    scenes.empty_fog(30, (0, 0, 5))
    bpy.ops.mesh.primitive_plane_add(size=6, location=(0, 0, 2.5))
    slab = bpy.context.active_object
    slab.modifiers.new("Subdivision", "SUBSURF").use_adaptive_subdivision = True
    scene.sandscape_atmosphere.sun_azimuth = math.radians(270.0)
    bpy.ops.sandscape.add_atmosphere()
    bpy.ops.sandscape.add_post_effects()
    scene.view_layers[0].use_pass_z = True
    scene.cycles.volume_bounces = 2
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.cycles.samples = SAMPLES
    scene.frame_set(FRAME)
    return scene


def timed_render(readback, scene, repeats):
    times, pixels = [], None
    for _ in range(repeats):
        started = time.perf_counter()
        pixels = readback.render(scene)[..., :3]
        times.append(time.perf_counter() - started)
    return statistics.median(times), pixels


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="one render each and a lower reference")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    session.install_dev_extension(root)
    from devtools import readback

    repeats = 1 if args.quick else 3
    scene = wasteful_demo(bpy)
    before, before_pixels = timed_render(readback, scene, repeats)
    operator = bpy.types.SANDSCAPE_OT_optimize_scene
    found = []
    fake = type("Reporter", (), {"dry_run": False, "report": lambda self, kind, text: found.append(text)})()
    operator.execute(fake, bpy.context)
    after, after_pixels = timed_render(readback, scene, repeats)
    scene.cycles.samples = 64 if args.quick else 256
    _, reference = timed_render(readback, scene, 1)

    def rmse(pixels):
        return results.display_rmse(pixels, reference, scene.view_settings.exposure)

    saving = 1.0 - after / before
    lines = [results.heading("Optimizer", ["--quick"] if args.quick else []),
             f"{results.machine()}. Demo frame {FRAME}, {RESOLUTION[0]}x{RESOLUTION[1]}, "
             f"{SAMPLES} spp, "
             f"median of {repeats}; reference: the optimized scene at {scene.cycles.samples} spp; "
             "RMSE clipped at the display's white.\n",
             "| scene | render s | RMSE to reference |", "|---|---|---|",
             f"| wasteful demo | {before:.2f} | {rmse(before_pixels):.5f} |",
             f"| after optimize_scene | {after:.2f} | {rmse(after_pixels):.5f} |",
             f"\nRender time saved: {saving * 100:.1f} % (goal: at least 30 %). Decisions:"]
    lines += [f"- {message}" for message in found]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
