"""Where the quality bench's reference noise comes from: two seeds of a demo frame rendered as
bench/quality.py renders its reference (raw, unbiased volumes, 128 bounces), then again with
one thing taken away at a time: the compositor, volume bounces, the clouds, the dusty air, the
glints, the grains' normals, diffuse bounces, the sky's light. The noise of a pair is the clipped
RMSE of their difference / 2; what a part takes away is what it added, in quadrature.

Run: .venv/bin/python devtools/noise_sources.py [--frame 120] [--samples 128]
"""

import argparse
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path[:0] = [str(REPO), str(REPO / "bench")]

from devtools import results, session  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frame", type=int, default=120)
    parser.add_argument("--samples", type=int, default=128, help="samples of each seed's render")
    args = parser.parse_args(argv)
    sandscape, scene = session.demo_scene()
    presets, sand, own = sandscape.addon.presets, sandscape.addon.sand, sandscape.addon.ownership
    import quality  # its resolution and light paths: the reference's

    from devtools import readback

    scene.render.resolution_x, scene.render.resolution_y = quality.RESOLUTION
    scene.frame_set(args.frame)
    white = 2.0 ** -scene.view_settings.exposure
    base = dict(presets.BLENDER_DEFAULTS, **quality.LIGHT_PATHS, samples=args.samples,
                use_adaptive_sampling=False, use_denoising=False)
    material = sand.find_sand_material(scene.sandscape_footprints.terrain)
    glints = sand.glint_node(material)

    compositing = {"on": True}
    presets.apply(scene, {presets.DENOISE: False})  # the reference's tree: blur and god rays

    def render(settings, seed):
        presets.apply(scene, settings)
        scene.cycles.seed = seed
        scene.render.use_compositing = compositing["on"]
        return readback.render(scene)[..., :3]

    def set_inputs(tree, name, value):
        for node in tree.nodes:
            if name in node.inputs and not node.inputs[name].is_linked:
                node.inputs[name].default_value = value

    def hide(kind):
        for obj in own.scene_objects(scene, kind):
            obj.hide_render = True

    steps = [
        ("as the reference", lambda: None, {}),
        ("compositor off", lambda: compositing.update(on=False), {}),
        ("and no volume bounces", lambda: None, {"volume_bounces": 0}),
        ("and no clouds", lambda: hide(own.CLOUDS), {"volume_bounces": 0}),
        ("and no dusty air", lambda: hide(own.DUST_VOLUME), {"volume_bounces": 0}),
        ("and no glints", lambda: setattr(glints.inputs["Threshold"], "default_value", 1.0),
         {"volume_bounces": 0}),
        ("and no grain normals", lambda: set_inputs(material.node_tree, "Grain Strength", 0.0),
         {"volume_bounces": 0}),
        ("and no diffuse bounces", lambda: None, {"volume_bounces": 0, "diffuse_bounces": 0}),
        ("and no sky light", lambda: set_inputs(scene.world.node_tree, "Strength", 0.0),
         {"volume_bounces": 0, "diffuse_bounces": 0}),
    ]
    previous = None
    table = []
    for label, change, extra in steps:
        change()
        started = time.perf_counter()
        pair = [render(dict(base, **extra), seed) for seed in (0, 1)]
        a, b = (np.minimum(p, white) for p in pair)
        noise = results.clipped_rmse(*pair, white) / 2
        squared = ((a - b) ** 2).sum(axis=-1)
        top = squared > np.quantile(squared, 0.95)
        mean = (a + b).mean(axis=-1) / 2
        line = (f"{label}: noise {noise:.5f}; the noisiest 5 % of pixels hold "
                f"{squared[top].sum() / squared.sum():.0%} of it, mean {mean[top].mean():.3f} against "
                f"{mean.mean():.3f} for the frame")
        if previous is not None:
            line += f"; took away {np.sqrt(max(previous ** 2 - noise ** 2, 0.0)):.5f} in quadrature"
        print(f"{line} ({time.perf_counter() - started:.0f} s)", flush=True)
        rows = np.nonzero(top)[0]
        print(f"    noisiest rows (0 = bottom of {squared.shape[0]}): median {np.median(rows):.0f}, "
              f"quartiles {np.quantile(rows, 0.25):.0f}-{np.quantile(rows, 0.75):.0f}", flush=True)
        took = f"{np.sqrt(max(previous ** 2 - noise ** 2, 0.0)):.5f}" if previous is not None else "-"
        table.append(f"| {label} | {noise:.5f} | {took} |")
        previous = noise
    flags = [f"--frame {args.frame}"] * (args.frame != 120)
    flags += [f"--samples {args.samples}"] * (args.samples != 128)
    width, height = quality.RESOLUTION
    results.publish([results.heading("Reference noise sources", flags),
                     f"{results.machine()}. Demo frame {args.frame} at {width}x{height}, two seeds at "
                     f"{args.samples} spp each, the quality reference's settings; noise = clipped RMSE of "
                     "the pair's difference / 2; each row takes one more thing away.\n",
                     "| render | noise | took away (quadrature) |", "|---|---|---|", *table])

if __name__ == "__main__":
    main()
