"""Quality presets benchmark: render time against error for the demo at many settings.

The demo frame at 240x135 against a reference at REFERENCE_SPP samples (unbiased volumes, no
denoising, no adaptive sampling). Rows: a grid over samples, denoising and volume ray
marching; the preview preset with one other setting changed (adaptive threshold, dicing rate,
bounces, volume step rate); Blender's 5.0 defaults; and each Sandscape preset. Writes the curves to
bench/quality.png (matplotlib, from requirements-bench.txt) and appends the table to
bench/RESULTS.md.

Run: .venv/bin/python bench/quality.py [--quick] [--no-append]
"""

import argparse
import pathlib
import sys
import time

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

RESOLUTION = (240, 135)
FRAME = 150
# Knobs besides samples, denoising and volume sampling, each swept alone around the preview preset.
AXES = (("adaptive_threshold", (0.01, 0.05, 0.1)), ("dicing_rate", (0.5, 2.0, 4.0)),
        ("max_bounces", (2, 4, 8)), ("volume_step_rate", (0.5, 2.0, 4.0)))


def render(readback, scene, settings, presets):
    presets.apply(scene, settings)
    started = time.perf_counter()
    pixels = readback.render(scene)[..., :3]
    return time.perf_counter() - started, pixels


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="a smaller grid and a lower reference")
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    root = session.isolate()
    import importlib

    import bpy

    session.install_dev_extension(root)
    presets = importlib.import_module(f"{session.MODULE}.blender.presets")
    from devtools import readback

    session.reset()
    bpy.ops.sandscape.build_demo_scene()
    scene = bpy.context.scene
    scene.render.resolution_x, scene.render.resolution_y = RESOLUTION
    scene.frame_set(FRAME)
    reference_spp = 512 if args.quick else 2048
    base = dict(presets.BLENDER_DEFAULTS, samples=reference_spp, use_adaptive_sampling=False,
                use_denoising=False)
    _, reference = render(readback, scene, base, presets)

    white = 2.0 ** -scene.view_settings.exposure

    def rmse(pixels):
        return results.display_rmse(pixels, reference, scene.view_settings.exposure)

    counts = (4, 16, 64) if args.quick else (4, 8, 16, 32, 64, 128, 256)
    rows = []
    # Blender's default recipe (adaptive 0.01, OIDN, unbiased volumes) at fewer samples: the
    # time the defaults need for a preset's error is read off this curve.
    for samples in (16, 64, 256) if args.quick else (16, 32, 64, 128, 256, 512, 1024):
        seconds, pixels = render(readback, scene, dict(presets.BLENDER_DEFAULTS, samples=samples), presets)
        label = f"{samples} spp, adaptive 0.01, OIDN, unbiased"
        rows.append(("defaults curve", label, seconds, rmse(pixels)))
        print(rows[-1], flush=True)
    for denoise, biased in ((False, False), (False, True), (True, True)):
        for samples in counts:
            settings = dict(presets.BLENDER_DEFAULTS, samples=samples, use_adaptive_sampling=False,
                            use_denoising=denoise, volume_biased=biased)
            seconds, pixels = render(readback, scene, settings, presets)
            volumes = "ray march" if biased else "unbiased"
            label = f"{samples} spp, {'OIDN' if denoise else 'raw'}, {volumes}"
            rows.append(("grid", label, seconds, rmse(pixels)))
            print(rows[-1], flush=True)
    # One setting at a time away from the preview preset: the other knobs a preset sets.
    for key, values in AXES:
        for value in values:
            settings = dict(presets.PRESETS["PREVIEW"], **{key: value})
            if key == "adaptive_threshold":
                settings["use_adaptive_sampling"] = True
            seconds, pixels = render(readback, scene, settings, presets)
            rows.append(("preview with", f"{key}={value}", seconds, rmse(pixels)))
            print(rows[-1], flush=True)
    seconds, pixels = render(readback, scene, presets.BLENDER_DEFAULTS, presets)
    rows.append(("Blender defaults", "4096 spp, adaptive 0.01, OIDN, unbiased", seconds, rmse(pixels)))
    print(rows[-1], flush=True)
    for name, settings in presets.PRESETS.items():
        seconds, pixels = render(readback, scene, settings, presets)
        rows.append((f"preset {name.lower()}", ", ".join(f"{k}={v}" for k, v in settings.items()), seconds,
                     rmse(pixels)))
        print(rows[-1], flush=True)
    defaults = next(r for r in rows if r[0] == "Blender defaults")
    curve = sorted((s, e) for kind, _, s, e in rows if kind in ("defaults curve", "Blender defaults"))
    lines = [results.heading("Quality", ["--quick"] if args.quick else []),
             f"{results.machine()}. Demo frame {FRAME} at {RESOLUTION[0]}x{RESOLUTION[1]}; "
             f"reference {reference_spp} spp raw, unbiased volumes; RMSE of linear pixels clipped at "
             f"the display's white ({white:g} at exposure {scene.view_settings.exposure:g}).\n",
             "| kind | settings | render s | RMSE | vs Blender defaults |", "|---|---|---|---|---|"]
    for kind, label, seconds, error in rows:
        versus = f"{defaults[2] / seconds:.1f}x faster, RMSE {error / defaults[3]:.2f}x"
        if kind.startswith("preset"):
            equal = time_for_error(curve, error)
            versus += (f"; the defaults need {equal:.1f} s for this RMSE: {equal / seconds:.1f}x faster"
                       if equal else "; outside the measured defaults curve")
        lines.append(f"| {kind} | {label} | {seconds:.2f} | {error:.5f} | {versus} |")
    results.publish(lines, append=not args.no_append)
    plot(rows, REPO / "bench" / "quality.png")


def time_for_error(curve, error):
    """Seconds the curve [(seconds, rmse)] needs for `error`, interpolated log-log; None if never."""
    for (t0, e0), (t1, e1) in zip(curve, curve[1:], strict=False):
        if e1 <= error <= e0 and e1 < e0:
            share = np.log(e0 / error) / np.log(e0 / e1)
            return float(np.exp(np.log(t0) + share * np.log(t1 / t0)))
    return None


def plot(rows, path):
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("quality: matplotlib missing (pip install -r requirements-bench.txt); no plot")
        return
    figure, axes = plt.subplots(figsize=(7, 4.5), dpi=120)
    for denoise in ("raw", "OIDN"):
        for volumes in ("unbiased", "ray march"):
            curve = [(s, e) for kind, label, s, e in rows
                     if kind == "grid" and denoise in label and volumes in label]
            if curve:
                axes.plot(*zip(*curve, strict=True), marker="o", label=f"{denoise}, {volumes}")
    defaults = sorted((s, e) for kind, _, s, e in rows if kind in ("defaults curve", "Blender defaults"))
    axes.plot(*zip(*defaults, strict=True), marker="s", color="black",
              label="Blender defaults, fewer samples")
    axis_rows = [(s, e, label) for kind, label, s, e in rows if kind == "preview with"]
    if axis_rows:
        # Unlabelled: they crowd round the preview star; the table in RESULTS.md names each.
        axes.scatter([s for s, _, _ in axis_rows], [e for _, e, _ in axis_rows], marker="x", color="grey",
                     label="preview, one other setting changed")
    for kind, _, seconds, error in rows:
        if kind not in ("grid", "preview with", "defaults curve"):
            axes.scatter([seconds], [error], marker="*", s=160, zorder=5)
            axes.annotate(kind, (seconds, error), textcoords="offset points", xytext=(6, 4))
    axes.set_xscale("log")
    axes.set_yscale("log")
    axes.set_xlabel("render time, s (2 cores)")
    axes.set_ylabel("RMSE to reference")
    axes.set_title("Sandscape demo: time against error")
    axes.legend(fontsize=8)
    path.parent.mkdir(parents=True, exist_ok=True)
    figure.tight_layout()
    figure.savefig(path)
    print(f"quality: plot -> {path}")


if __name__ == "__main__":
    main()
