"""Sand looks benchmark: what each look and its glints cost, and how many samples the glints need.

The demo's dunes, walker and prints under its low sun, without the dusty air, clouds and post
effects (their noise would swamp the sand's), at the demo's frame:

1. Render time at equal samples (median of ROUNDS, taken round robin) of the bare Principled
   BSDF (sand colour, nothing else), PHYSICAL and JOURNEY with lit glints, each without glints
   and without ripples, and PHYSICAL with the emission glints.
2. Samples each look needs for glint RMSE < 0.01. Glints are sub-pixel highlights far brighter
   than the sand, so a reference render would need tens of thousands of samples to be quieter
   than that; instead the RMSE of an N-sample render against the converged image is estimated
   from two renders with different seeds: RMS(a - b) / sqrt 2 (Cycles is unbiased here). It is
   taken on displayed values (linear x 2^exposure through Reinhard's x / (1 + x), so a glint
   counts in full but its peak cannot swamp the measure), over the pixels where glints show
   (a MASK_SPP render with glints differs from one without by more than 0.05) and over the whole
   frame. Where 0.01 is not reached, the samples it needs are extrapolated as 1 / sqrt N.

Prints the table, appends it to bench/RESULTS.md with the command, and saves one PNG per look in
out/ to look at.
Run: .venv/bin/python bench/looks.py [--quick] [--no-append]
"""

import argparse
import pathlib
import statistics
import sys
import time

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

TARGET_RMSE = 0.01
ROUNDS = 5
MASK_SPP = 512
FRAME = 120
GLINT_DIFFERENCE = 0.05  # 4.5 sigma of two MASK_SPP renders' difference without glints


def displayed(pixels, exposure):
    import numpy as np

    exposed = np.asarray(pixels[..., :3], np.float64) * 2.0 ** exposure
    return exposed / (1.0 + exposed)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller frames, fewer samples")
    parser.add_argument("--no-append", action="store_true", help="do not write bench/RESULTS.md")
    args = parser.parse_args(argv)

    root = session.isolate()
    import bpy
    import numpy as np

    from devtools import readback

    sandscape = session.install_dev_extension(root)
    sand = sandscape.addon.sand
    timing_size = (160, 90) if args.quick else (320, 180)
    rmse_size = (96, 54) if args.quick else (160, 90)
    timing_spp, mask_spp = (16, MASK_SPP // 4) if args.quick else (64, MASK_SPP)
    counts = [4, 16, 64] if args.quick else [4, 16, 64, 256, 1024]
    out = REPO / "out"
    out.mkdir(exist_ok=True)

    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    air = scene.sandscape_atmosphere
    air.density = air.dust_density = 0.0
    air.use_haze = False
    air.use_wind = False
    bpy.ops.sandscape.add_atmosphere()  # the same sun and exposure, no dusty air
    for clouds in sandscape.addon.ownership.scene_objects(scene, "clouds"):
        clouds.hide_render = True  # the sand alone: the cloud grid took a render from 5 s to 30 s
    scene.render.use_compositing = False
    scene.cycles.use_denoising = False
    scene.cycles.use_adaptive_sampling = False
    scene.frame_set(FRAME)
    terrain = scene.sandscape_footprints.terrain
    material = sand.find_sand_material(terrain)
    exposure = scene.view_settings.exposure
    glint_values = {**sand.default_glint_values(), **sandscape.addon.demo.SAND}
    no_glints = {**glint_values, "Threshold": 1.0}
    ripple_values = sand.default_ripples(scene)
    bare = bpy.data.materials.new("Bare Principled")
    bsdf = bare.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = sandscape.core.sand.SAND_COLOR

    def use(look, glints="LIT", values=glint_values, waves=True):
        if look == "BARE":
            terrain.material_slots[terrain.active_material_index].material = bare
            return
        terrain.material_slots[terrain.active_material_index].material = material
        sand.update_material(material, values, None, look, glints, ripple_values if waves else None)

    def render(spp, size):
        scene.cycles.samples = spp
        scene.render.resolution_x, scene.render.resolution_y = size
        started = time.perf_counter()
        pixels = readback.render(scene)
        return time.perf_counter() - started, pixels

    variants = [("bare Principled BSDF", "BARE", "LIT", glint_values),
                ("PHYSICAL, lit glints (default)", "PHYSICAL", "LIT", glint_values),
                ("PHYSICAL, no glints", "PHYSICAL", "LIT", no_glints),
                ("PHYSICAL, emission glints", "PHYSICAL", "EMISSION", glint_values),
                ("JOURNEY, lit glints", "JOURNEY", "LIT", glint_values),
                ("JOURNEY, no glints", "JOURNEY", "LIT", no_glints),
                ("PHYSICAL, lit glints, no ripples", "PHYSICAL", "LIT", glint_values, False),
                ("JOURNEY, lit glints, no ripples", "JOURNEY", "LIT", glint_values, False)]
    # Round robin, so that a machine slowing down or speeding up weighs on every variant alike.
    runs = {label: [] for label, *_ in variants}
    for _ in range(ROUNDS):
        for label, look, glints, values, *waves in variants:
            use(look, glints, values, *waves)
            runs[label].append(render(timing_spp, timing_size)[0])
    timings = {label: statistics.median(times) for label, times in runs.items()}
    for label, look, glints, values, *waves in variants:
        print(f"{label}: {timings[label]:.3f} s (of {', '.join(f'{t:.2f}' for t in runs[label])})")
        if values is glint_values and not waves:
            use(look, glints, values)
            scene.render.image_settings.file_format = "PNG"
            scene.render.filepath = str(out / f"bench-look-{look.lower()}-{glints.lower()}.png")
            bpy.ops.render.render(write_still=True)

    def noise(a, b, where=None):
        difference = displayed(a, exposure) - displayed(b, exposure)
        if where is not None:
            difference = difference[where]
        return float(np.sqrt(np.mean(difference ** 2) / 2.0))

    rows, needed = [], {}
    for look, glints in (("PHYSICAL", "LIT"), ("JOURNEY", "LIT"), ("PHYSICAL", "EMISSION")):
        label = f"{look}, {glints.lower()} glints"
        use(look, glints, no_glints)
        _, plain = render(mask_spp, rmse_size)
        use(look, glints, glint_values)
        _, glinting = render(mask_spp, rmse_size)
        glint_added = np.abs(displayed(glinting, exposure) - displayed(plain, exposure))
        where = glint_added.mean(-1) > GLINT_DIFFERENCE
        print(f"{label}: glints show on {where.mean():.2%} of the frame")
        for spp in counts:
            scene.cycles.seed = 0
            seconds, first = render(spp, rmse_size)
            scene.cycles.seed = 1
            _, second = render(spp, rmse_size)
            scene.cycles.seed = 0
            rows.append((label, spp, seconds, noise(first, second, where), noise(first, second),
                         where.mean()))
            print(rows[-1])
        spp, seconds, error = rows[-1][1], rows[-1][2], rows[-1][3]
        reached = [r for r in rows if r[0] == label and r[3] < TARGET_RMSE]
        if reached:
            needed[label] = (f"{reached[0][1]}", reached[0][2])
        else:  # RMSE falls as 1 / sqrt(samples)
            extrapolated = spp * (error / TARGET_RMSE) ** 2
            needed[label] = (f"about {extrapolated:.0f} (extrapolated)", seconds * extrapolated / spp)

    lines = [results.heading("Sand looks", ["--quick"] if args.quick else []),
             f"{results.machine()}, Cycles CPU, no denoising. The demo without dusty air, clouds or post "
             f"effects, frame {FRAME}; glint RMSE on displayed values (x 2^exposure, Reinhard) from two "
             f"seeds, over the pixels where glints show and over the frame.\n",
             "| case | frame | spp | render s | vs PHYSICAL | vs bare Principled |",
             "|---|---|---|---|---|---|"]
    base, bare_seconds = timings[variants[1][0]], timings[variants[0][0]]
    for label, *_ in variants:
        s = timings[label]
        lines.append(f"| {label} | {timing_size[0]}x{timing_size[1]} | {timing_spp} | {s:.3f} | "
                     f"{(s / base - 1) * 100:+.1f} % | {(s / bare_seconds - 1) * 100:+.1f} % |")
    lines += ["", "| look | frame | spp | render s | glint RMSE | frame RMSE | glint pixels |",
              "|---|---|---|---|---|---|---|"]
    for label, spp, seconds, error, frame_error, share in rows:
        lines.append(f"| {label} | {rmse_size[0]}x{rmse_size[1]} | {spp} | {seconds:.3f} | {error:.4f} | "
                     f"{frame_error:.4f} | {share:.2%} |")
    lines.append("")
    for label, (spp, seconds) in needed.items():
        lines.append(f"- {label}: glint RMSE < {TARGET_RMSE} from {spp} spp ({seconds:.1f} s at "
                     f"{rmse_size[0]}x{rmse_size[1]}).")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
