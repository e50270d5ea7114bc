"""Glint benchmark: what the glint term costs, and how many samples it needs.

1. Render time of the demo view with and without the glint term (median of 3).
2. Glint RMSE against a high-sample reference per sample count, with and without
   OpenImageDenoise. "Glint RMSE" is measured on the glint coverage alone (the group's
   Mask through an emission of strength 1, so 1 = a fully lit, facing pixel), in linear units.

Prints the table and appends it to bench/RESULTS.md with the command that made it.
Run: .venv/bin/python bench/glints.py [--quick]
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


def timed_render(readback):
    started = time.perf_counter()
    pixels = readback.render()
    return time.perf_counter() - started, pixels


def material_without_glints(material):
    """Principled straight into the output: the scene as it would be without the glint term."""
    tree = material.node_tree
    bsdf = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
    out = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
    tree.links.new(bsdf.outputs["BSDF"], out.inputs["Surface"])


def material_glint_coverage(material, glint_node):
    tree = material.node_tree
    emission = tree.nodes.new("ShaderNodeEmission")
    tree.links.new(glint_node.outputs["Mask"], emission.inputs["Color"])
    out = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
    tree.links.new(emission.outputs[0], out.inputs["Surface"])


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="smaller frames, fewer samples")
    parser.add_argument("--no-append", action="store_true", help="do not write bench/RESULTS.md")
    args = parser.parse_args(argv)

    root = session.isolate()
    import bpy
    import numpy as np

    from devtools import demo, readback

    sandscape = session.install_dev_extension(root)
    width, height = (96, 54) if args.quick else (160, 90)
    timing_size = (160, 90) if args.quick else (320, 180)
    ref_spp = 512 if args.quick else 2048
    counts = [1, 2, 4, 8, 16, 32, 64, 128, 256] if not args.quick else [1, 4, 16, 64]

    rows, means = [], []
    # 1. Cost of the glint term in the full material; "as a mesh light" is Cycles' default
    # emission sampling (AUTO), which Sandscape switches off for the sand.
    variants = ("full material", "full material, glints as a mesh light", "without glint term")
    for variant in variants:
        session.reset()
        scene = demo.build_scene(timing_size, 64)
        scene.cycles.use_denoising = False
        material = bpy.data.objects["Sand"].active_material
        if variant == variants[1]:
            material.cycles.emission_sampling = "AUTO"
        if variant == variants[2]:
            material_without_glints(material)
        runs = [timed_render(readback) for _ in range(3)]
        means.append(float(np.mean(runs[-1][1][..., :3])))
        rows.append((variant, f"{timing_size[0]}x{timing_size[1]}", 64, "off",
                     statistics.median(r[0] for r in runs), None))
        print(rows[-1], "mean pixel", means[-1])

    # 2. Samples needed for the glint coverage.
    session.reset()
    scene = demo.build_scene((width, height), ref_spp)
    scene.cycles.use_denoising = False
    scene.view_settings.view_transform = "Standard"
    material = bpy.data.objects["Sand"].active_material
    material_glint_coverage(material, sandscape.blender.sand.glint_node(material))
    ref_time, reference = timed_render(readback)
    rows.append(("glint coverage reference", f"{width}x{height}", ref_spp, "off", ref_time, None))
    print(rows[-1])
    needed = {}
    for denoise in (False, True):
        scene.cycles.use_denoising = denoise
        for spp in counts:
            scene.cycles.samples = spp
            seconds, pixels = timed_render(readback)
            rmse = float(np.sqrt(np.mean((pixels[..., :3] - reference[..., :3]) ** 2)))
            flag = "on" if denoise else "off"
            rows.append(("glint coverage", f"{width}x{height}", spp, flag, seconds, rmse))
            print(rows[-1])
            if rmse < TARGET_RMSE and denoise not in needed:
                needed[denoise] = (spp, seconds)

    lines = [results.heading("Glints", ["--quick"] if args.quick else []),
             f"{results.machine()}, Cycles CPU. Reference: {ref_spp} spp, no denoising.\n",
             "| case | frame | spp | denoise | render s | glint RMSE |", "|---|---|---|---|---|---|"]
    for case, frame, spp, denoise, seconds, rmse in rows:
        lines.append(f"| {case} | {frame} | {spp} | {denoise} | {seconds:.3f} | "
                     f"{'' if rmse is None else f'{rmse:.4f}'} |")
    full, as_light, bare = rows[0][4], rows[1][4], rows[2][4]
    def extra(seconds):
        return f"{(seconds / bare - 1) * 100:+.1f} %"

    lines.append(f"\nGlint term cost: {full:.3f} s vs {bare:.3f} s without it ({extra(full)}); "
                 f"with Cycles' default emission sampling {as_light:.3f} s ({extra(as_light)}).")
    lines.append(f"Mean linear pixel value: {means[0]:.4f} (Sandscape), {means[1]:.4f} (glints as a mesh "
                 f"light), {means[2]:.4f} (no glints): switching emission sampling off keeps the image.")
    for denoise in (False, True):
        label = "with" if denoise else "without"
        if denoise in needed:
            spp, seconds = needed[denoise]
            lines.append(f"Samples for glint RMSE < {TARGET_RMSE} {label} denoising: {spp} "
                         f"({seconds:.3f} s).")
        else:
            lines.append(f"Glint RMSE < {TARGET_RMSE} {label} denoising: not reached up to {counts[-1]} spp.")
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
