"""Optimizer benchmark: the demo with parts that add nothing, against the same scene built
without them (the ideal), before and after bpy.ops.sandscape.optimize_scene.

Both carry a crate on the sand and a displaced mound behind the camera, each with a Subdivision
Surface modifier. The wasteful scene adds five kinds of waste real scenes collect: an empty fog
volume (density 0), an empty world volume, adaptive subdivision on the crate (its material does
not displace) and on the mound (the camera never sees it), and passes nothing reads (Depth, Mist,
Ambient Occlusion). The goal: the optimized render within 5 % of the ideal's time, at its RMSE.

Run: .venv/bin/python bench/optimize.py [--quick] [--no-append]
"""

import argparse
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
GOAL = 0.05  # the optimized render at most this much slower than the ideal
PASSES = ("use_pass_z", "use_pass_mist", "use_pass_ambient_occlusion")


def ideal_demo(bpy):
    """The demo with a crate in view and a displaced mound behind the camera, neither dicing adaptively."""
    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    from devtools import scenes  # here, not at the top: it imports bpy, which must follow isolate()

    scene.frame_set(FRAME)
    walker = scene.sandscape_footprints.walker.matrix_world.translation
    bpy.ops.mesh.primitive_cube_add(size=0.8, location=(walker.x + 3.0, walker.y - 1.2, walker.z + 0.3))
    crate = bpy.context.active_object
    crate.modifiers.new("Subdivision", "SUBSURF")
    start = scene.sandscape_footprints.terrain.matrix_world.translation
    bpy.ops.mesh.primitive_plane_add(size=8, location=(start.x - 45.0, start.y, walker.z))
    mound = bpy.context.active_object
    mound.modifiers.new("Subdivision", "SUBSURF")
    material = scenes.single_node_material("Mound", "ShaderNodeDisplacement", "Displacement", Height=0.5)
    noise = material.node_tree.nodes.new("ShaderNodeTexNoise")
    displacement = next(n for n in material.node_tree.nodes if n.bl_idname == "ShaderNodeDisplacement")
    material.node_tree.links.new(noise.outputs["Fac"], displacement.inputs["Height"])
    material.displacement_method = "DISPLACEMENT"
    mound.data.materials.append(material)
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    scene.cycles.samples = SAMPLES
    return scene, crate, mound


def add_waste(scene, crate, mound):
    from devtools import scenes

    scenes.empty_fog(30, (0, 0, 5))
    scenes.world_volume(scene.world, density=0.0)
    for obj in (crate, mound):
        obj.modifiers[0].use_adaptive_subdivision = True
    for name in PASSES:
        setattr(scene.view_layers[0], name, True)


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
    scene, crate, mound = ideal_demo(bpy)
    scene.frame_set(FRAME)
    ideal, ideal_pixels = timed_render(readback, scene, repeats)
    scene.cycles.samples = 64 if args.quick else 256
    _, reference = timed_render(readback, scene, 1)
    scene.cycles.samples = SAMPLES
    add_waste(scene, crate, mound)
    before, before_pixels = timed_render(readback, scene, repeats)
    operator = bpy.types.SANDSCAPE_OT_optimize_scene
    found = []
    fake = type("Reporter", (), {"dry_run": False, "report": lambda self, kind, text: found.append(text)})()
    operator.execute(fake, bpy.context)
    after, after_pixels = timed_render(readback, scene, repeats)

    def rmse(pixels):
        return results.display_rmse(pixels, reference, scene.view_settings.exposure)

    over = after / ideal - 1.0
    lines = [results.heading("Optimizer", ["--quick"] if args.quick else []),
             f"{results.machine()}. Demo frame {FRAME}, {RESOLUTION[0]}x{RESOLUTION[1]}, {SAMPLES} spp, "
             f"median of {repeats}; reference: the ideal scene at 64 spp if --quick else 256; "
             "RMSE clipped at the display's white. Five kinds of waste (see the script).\n",
             "| scene | render s | vs ideal | RMSE to reference |", "|---|---|---|---|",
             f"| ideal (built without the waste) | {ideal:.2f} | - | {rmse(ideal_pixels):.5f} |",
             f"| wasteful | {before:.2f} | {before / ideal - 1:+.1%} | {rmse(before_pixels):.5f} |",
             f"| after optimize_scene | {after:.2f} | {over:+.1%} | {rmse(after_pixels):.5f} |",
             f"\nOptimized against ideal: {over:+.1%} (goal: at most +{GOAL:.0%}: "
             f"{'met' if over <= GOAL else 'missed'}). Decisions:"]
    lines += [f"- {message}" for message in found]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
