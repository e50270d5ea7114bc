"""EEVEE beside Cycles on an artist's trail shot (devtools/print_shot.py: flat sand, a painted
10 m walk, a sun 15 degrees up from the side, eye level): time per frame, the sand's mean display
colour per distance band against Cycles', and how many pixels the prints change in each engine.
EEVEE is also timed with the sand's displacement unlinked (issue 27: within 2x of it), and the
sand's brightness is compared at other sun elevations, with the sand's EEVEE output (balanced to
Cycles) and without it. EEVEE runs on software OpenGL here (the bpy wheel's EGL context): its
times are a CPU's, not a GPU's.
Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/eevee.py [--width W --height H] [--suns 15 45 70] [--no-append]
"""

import argparse
import pathlib
import sys
import tempfile
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

BANDS = ((3.0, 6.0), (6.0, 13.0), (13.0, 40.0))  # metres of ground from the camera
TAA_SAMPLES, CYCLES_SAMPLES = 16, 16


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=180)
    parser.add_argument("--suns", type=float, nargs="*", default=[15.0, 45.0, 70.0],
                        help="sun elevations (degrees) for the brightness table")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import bpy

    sandscape = session.install_dev_extension(root)
    from devtools import print_shot as shot
    from devtools import readback

    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-eevee-"))
    shot.RESOLUTION = (args.width, args.height)
    scene, camera = shot.build(CYCLES_SAMPLES)

    def render(name):
        started = time.perf_counter()
        pixels = readback.render_display(scene, out / f"{name}.png")
        seconds = time.perf_counter() - started
        print(f"eevee bench: {name} {seconds:.1f} s", flush=True)
        return pixels, seconds

    frames, seconds = {}, {}
    frames["cycles"], seconds["cycles"] = render("cycles")
    scene.render.engine = "BLENDER_EEVEE"
    scene.eevee.taa_render_samples = TAA_SAMPLES
    _, seconds["eevee first"] = render("eevee-first")  # shaders compiled
    frames["eevee"], seconds["eevee"] = render("eevee")
    material = bpy.data.materials["Sandscape Sand"]
    output = material.node_tree.nodes["Sandscape EEVEE Output"]
    link = output.inputs["Displacement"].links[0]
    source = link.from_socket
    material.node_tree.links.remove(link)
    render("eevee-undisplaced-first")
    _, seconds["eevee undisplaced"] = render("eevee-undisplaced")
    material.node_tree.links.new(source, output.inputs["Displacement"])
    shot.flatten(scene)
    frames["eevee flat"], _ = render("eevee-flat")
    scene.render.engine = "CYCLES"
    frames["cycles flat"], _ = render("cycles-flat")
    dust = next(obj for obj in scene.objects if obj.get("sandscape_object") == "dust_volume")
    dust.hide_render = True  # what the dusty air adds, in each engine
    frames["cycles clear"], _ = render("cycles-clear")
    scene.render.engine = "BLENDER_EEVEE"
    frames["eevee clear"], _ = render("eevee-clear")
    scene.render.engine = "CYCLES"
    dust.hide_render = False

    distance = shot.trail_distance(camera)
    suns = sun_table(bpy, sandscape, scene, args.suns, distance, render)
    hazes = []
    for low, high in (*BANDS, (40.0, np.inf)):
        band = (distance >= low) & (distance < high)
        added = [frames[f"{k} flat"][band][:, :3].mean() - frames[f"{k} clear"][band][:, :3].mean()
                 for k in ("cycles", "eevee")]
        hazes.append((f"{low:g}-{high:g} m" if np.isfinite(high) else f"beyond {low:g} m", *added))
    rows = []
    for low, high in BANDS:
        band = (distance >= low) & (distance < high)
        cycles, eevee = (frames[k][band][:, :3].mean(0) for k in ("cycles", "eevee"))
        rows.append((f"{low:g}-{high:g} m", cycles, eevee, eevee.mean() / cycles.mean() - 1))
    changed = {k: int((np.abs(frames[k] - frames[f"{k} flat"])[..., :3].max(-1) > shot.PIXEL_CHANGE).sum())
               for k in ("cycles", "eevee")}
    for row in rows:
        print("eevee bench:", row, flush=True)
    print(f"eevee bench: prints change {changed}", flush=True)

    def colour(c):
        return "(" + ", ".join(f"{v:.3f}" for v in c) + ")"

    size = (args.width, args.height)
    flags = [f"--width {args.width} --height {args.height}"] if size != (320, 180) else []
    lines = [results.heading("EEVEE beside Cycles", flags),
             f"{results.machine()}. The trail shot of bench/print_visibility.py at {size[0]}x{size[1]}: "
             f"Cycles {CYCLES_SAMPLES} spp denoised, EEVEE {TAA_SAMPLES} samples on software OpenGL (EGL, "
             "llvmpipe). Display values (AgX), ground bands by distance from the camera.\n",
             "| render | s |", "|---|---|",
             f"| Cycles | {seconds['cycles']:.1f} |",
             f"| EEVEE, first frame (shaders compiled) | {seconds['eevee first']:.1f} |",
             f"| EEVEE | {seconds['eevee']:.1f} |",
             f"| EEVEE, sand displacement unlinked | {seconds['eevee undisplaced']:.1f} |", "",
             "| ground | Cycles mean colour | EEVEE mean colour | EEVEE brightness against Cycles |",
             "|---|---|---|---|"]
    lines += [f"| {band} | {colour(c)} | {colour(e)} | {ratio:+.1%} |" for band, c, e, ratio in rows]
    lines += ["", f"Prints against the same shot flattened: {changed['cycles']} pixels change in Cycles, "
              f"{changed['eevee']} in EEVEE (of {args.width * args.height}; a display channel moving by "
              f"more than {shot.PIXEL_CHANGE})."]
    lines += ["", "What the dusty air adds to the ground's display value (the shot against the same without "
              "its dust box):", "", "| ground | Cycles | EEVEE |", "|---|---|---|"]
    lines += [f"| {band} | {c:+.3f} | {e:+.3f} |" for band, c, e in hazes]
    lines += ["", "The sand's brightness in EEVEE against Cycles (display means per band) as the sun "
              "climbs, with the sand's EEVEE output (balanced to Cycles by the driven sun) and without it:",
              "", "| sun | " + " | ".join(f"{lo:g}-{hi:g} m" for lo, hi in BANDS) + " |",
              "|---|" + "---|" * len(BANDS)]
    for sun, (balanced, plain) in suns:
        cells = (f"{b:+.1%} ({p:+.1%} without)" for b, p in zip(balanced, plain, strict=True))
        lines.append(f"| {sun:g}° | " + " | ".join(cells) + " |")
    results.publish(lines, append=not args.no_append)


def sun_table(bpy, sandscape, scene, elevations, distance, render):
    """[(elevation, (balanced ratios per band, ratios without the balance))]."""
    import math

    from devtools import print_shot as shot

    table = []
    material = bpy.data.materials["Sandscape Sand"]
    for elevation in elevations:
        scene.sandscape_atmosphere.sun_elevation = math.radians(elevation)
        assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
        scene.frame_set(shot.LAST_FRAME)
        frames = {}
        for key, engine in (("cycles", "CYCLES"), ("eevee", "BLENDER_EEVEE")):
            scene.render.engine = engine
            frames[key], _ = render(f"{key}-sun-{elevation:g}")
        look = sandscape.addon.sand.look_node(material)
        sandscape.addon.sand_eevee.attach(material, scene, look, None)  # one output for both
        frames["plain"], _ = render(f"eevee-plain-sun-{elevation:g}")
        sandscape.addon.sand_eevee.attach(material, scene, look, "PHYSICAL")
        balanced, plain = [], []
        for low, high in BANDS:
            band = (distance >= low) & (distance < high)
            cycles = frames["cycles"][band][:, :3].mean()
            balanced.append(frames["eevee"][band][:, :3].mean() / cycles - 1)
            plain.append(frames["plain"][band][:, :3].mean() / cycles - 1)
        print(f"eevee bench: sun {elevation:g}: {balanced} balanced, {plain} without", flush=True)
        table.append((elevation, (balanced, plain)))
    return table


if __name__ == "__main__":
    main()
