"""Effects benchmark: does each effect read in the demo? Each one removed in turn, same frame, same seed.

The demo at FRAME (none of the frames the tests use), through its compositor, in display values
(the 16-bit PNG the view transform makes). For each effect: the share of 4x4 blocks whose mean
moves by more than BLOCK_CHANGE in any channel when it is removed. And the lit lower half's median
hue and saturation: does the sand read as sand? Writes docs/effects.png, a contact sheet of each
effect on and off, and appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/effects.py [--samples N] [--frame F] [--no-append]
"""

import argparse
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import look, results, session  # noqa: E402

RESOLUTION = (320, 180)
FRAME = 200
BLOCK = 4
BLOCK_CHANGE = 0.05
# Share of blocks each effect must move (issue 14; prints and dusty air: issue 25).
GOALS = {"footprints": 0.02, "god rays": 0.03, "clouds": 0.05, "dusty air": 0.04}
SAND_HUE = (15.0, 50.0)  # degrees
SAND_SATURATION = 0.2


def block_change(on, off, block=BLOCK):
    """Share of block x block tiles whose mean moves by more than BLOCK_CHANGE in any channel."""
    height, width = (on.shape[0] // block) * block, (on.shape[1] // block) * block

    def means(pixels):
        tiles = pixels[:height, :width, :3].reshape(height // block, block, width // block, block, 3)
        return tiles.mean(axis=(1, 3))

    return float(np.mean(np.abs(means(on) - means(off)).max(axis=-1) > BLOCK_CHANGE))


def removals(bpy, scene, modules):
    """Effect name -> a function that removes it from the demo scene (each undone by a rebuild)."""
    footprints, post, clouds, sand = (modules[name] for name in ("footprints", "post", "clouds", "sand"))

    def no_prints():
        steps = scene.sandscape_footprints
        steps.depth = steps.rim = 0.0
        footprints.paint(scene, steps)

    def no_god_rays():
        scene.sandscape_post.use_god_rays = False
        post.apply_post_effects(scene, scene.sandscape_post)

    def no_glow():
        scene.sandscape_post.use_sun_glow = False
        post.apply_post_effects(scene, scene.sandscape_post)

    def no_clouds():
        clouds.remove_layer(scene)

    def no_glints():
        material = sand.find_sand_material(scene.sandscape_footprints.terrain)
        sand.glint_node(material).inputs["Threshold"].default_value = 1.0  # no grain passes it

    def no_dust():
        air = scene.sandscape_atmosphere
        air.density = air.dust_density = 0.0
        air.use_haze = False
        modules["atmosphere"].apply(scene, air)

    def no_far_haze():
        modules["far_haze"].remove(scene)

    return {"footprints": no_prints, "god rays": no_god_rays, "sun glow": no_glow, "clouds": no_clouds,
            "far haze": no_far_haze, "glints": no_glints, "dusty air": no_dust}


def build_demo(bpy, samples, frame):
    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.render.resolution_percentage = 100
    if samples:
        scene.cycles.samples = samples
    scene.frame_set(frame)
    return scene


def contact_sheet(images, path):
    plt = results.pyplot("effects: no contact sheet")
    if plt is None:
        return
    rows = len(images)
    figure, axes = plt.subplots(rows, 2, figsize=(6.4, 1.9 * rows), dpi=110, squeeze=False)
    for row, (label, on, off) in enumerate(images):
        for column, (pixels, state) in enumerate(((on, "on"), (off, "off"))):
            axis = axes[row, column]
            axis.imshow(np.clip(pixels[::-1], 0.0, 1.0))
            axis.set_title(f"{label} {state}", fontsize=8)
            axis.axis("off")
    figure.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.savefig(path)
    print(f"effects: contact sheet -> {path}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, help="instead of the demo's preset")
    parser.add_argument("--frame", type=int, default=FRAME)
    parser.add_argument("--only", nargs="*", help="effects to remove (default: all)")
    parser.add_argument("--sheet", default=str(REPO / "docs" / "effects.png"))
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import importlib
    import tempfile

    import bpy

    session.install_dev_extension(root)
    from devtools import readback

    modules = {name: importlib.import_module(f"{session.MODULE}.addon.{name}")
               for name in ("footprints", "post", "clouds", "sand", "atmosphere", "far_haze")}
    out = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-effects-"))
    scene = build_demo(bpy, args.samples, args.frame)
    started = time.perf_counter()
    full = readback.render_display(scene, out / "full.png")
    seconds = time.perf_counter() - started
    samples = scene.cycles.samples
    hue, saturation = look.lit_lower_half(full)
    rows, sheet = [], []
    for name in args.only or list(removals(bpy, scene, modules)):
        scene = build_demo(bpy, args.samples, args.frame)
        removals(bpy, scene, modules)[name]()
        scene.frame_set(args.frame)
        without = readback.render_display(scene, out / f"no-{name.replace(' ', '-')}.png")
        rows.append((name, block_change(full, without)))
        sheet.append((name, full, without))
        print(rows[-1], flush=True)
    flags = [f"--samples {args.samples}"] if args.samples else []
    flags += [f"--frame {args.frame}"] if args.frame != FRAME else []
    lines = [results.heading("Effects", flags),
             f"{results.machine()}. Demo frame {args.frame}, {RESOLUTION[0]}x{RESOLUTION[1]}, {samples} spp, "
             f"through its compositor ({seconds:.1f} s a render); display values of a 16-bit PNG, same seed "
             f"on and off. A block changes when its {BLOCK}x{BLOCK} mean moves by more than {BLOCK_CHANGE} "
             "in any channel.\n",
             "| effect removed | blocks changed | goal |", "|---|---|---|"]
    for name, share in rows:
        goal = GOALS.get(name)
        verdict = (f"≥ {goal * 100:g} %: {'met' if share >= goal else 'missed'}" if goal else "-")
        lines.append(f"| {name} | {share * 100:.1f} % | {verdict} |")
    sand_ok = SAND_HUE[0] <= hue <= SAND_HUE[1] and saturation >= SAND_SATURATION
    lines.append(f"\nLit lower half (its brighter half): median hue {hue:.1f}°, saturation {saturation:.3f} "
                 f"(goal: hue {SAND_HUE[0]:g}–{SAND_HUE[1]:g}°, saturation ≥ {SAND_SATURATION}: "
                 f"{'met' if sand_ok else 'missed'}).")
    results.publish(lines, append=not args.no_append)
    if sheet:
        contact_sheet(sheet, pathlib.Path(args.sheet))


if __name__ == "__main__":
    main()
