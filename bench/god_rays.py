"""God rays: the one group of geometric taps against the seed's unrolled N-sample group.

On a 640x360 sun disc, the compositor's time for the God Rays group (Samples 32 and 1024, the
same nodes) and for the group as it was built before (one node chain per sample, from git
commit OLD), and each one's difference from the seed's own sum at N = 1024 (core.post.
god_rays_seed, as smooth as the seed gets), as a share of its brightest pixel. The compositor
time is a render of an empty scene at 1 sample with the group composited, minus the same render
without it. Appends the table to bench/RESULTS.md.

Run: .venv/bin/python bench/god_rays.py [--no-append]
"""

import argparse
import importlib.util
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from devtools import results, session  # noqa: E402

OLD = "7065e44"  # the last commit with "Sandscape God Rays N"
SIZE = (640, 360)
SUN, RADIUS = (0.62, 0.58), 0.08
REPEATS = 3


def disc():
    width, height = SIZE
    v, u = (np.indices((height, width)) + 0.5) / np.array([height, width])[:, None, None]
    distance = np.hypot((u - SUN[0]) * width / height, v - SUN[1])
    image = np.ones((height, width, 4))
    image[..., :3] = np.clip((RADIUS - distance) * height + 0.5, 0.0, 1.0)[..., None]
    return image


def old_builder(sandscape):
    """The unrolled group's builder module, from git, loaded inside the installed package."""
    source = subprocess.run(["git", "-C", str(REPO), "show", f"{OLD}:node_groups/god_rays.py"],
                            check=True, capture_output=True, text=True).stdout
    path = pathlib.Path(tempfile.mkdtemp(prefix="sandscape-old-rays-")) / "old_god_rays.py"
    path.write_text(source)
    name = f"{sandscape.__name__}.node_groups.old_god_rays"
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-append", action="store_true")
    args = parser.parse_args(argv)
    sandscape = session.start()
    from core import post
    from devtools import readback

    helper, new = sandscape.node_groups.helper, sandscape.node_groups.god_rays
    old = old_builder(sandscape)
    session.reset()
    occlusion = disc()
    settings = {"Density": 0.9, "Weight": 0.1, "Decay": 0.97, "Exposure": 1.0, "Intensity": 1.0}
    reference = post.god_rays_seed(occlusion[..., :3], SUN, 1024, 0.9, 0.1 * 32 / 1024, 0.97 ** (32 / 1024))
    readback.composite_group(helper.ensure_group(new), {"Occlusion": occlusion}, "Rays", SIZE)  # a camera
    scene = readback.cycles_scene(resolution=SIZE)
    scene.render.use_compositing = False
    base, _ = results.median_seconds(lambda: readback.render(scene), REPEATS)
    rows = []
    for label, group, samples in (("one group, Samples 32", helper.ensure_group(new), 32),
                                  ("one group, Samples 1024", helper.ensure_group(new), 1024),
                                  ("unrolled, 32 samples", helper.ensure_group(old.Builder(32)), 32),
                                  ("unrolled, 128 samples", helper.ensure_group(old.Builder(128)), 128)):
        values = {**settings, "Occlusion": occlusion, "Sun": (*SUN, 0.0)}
        if "Samples" in group.interface.items_tree:
            values["Samples"] = float(samples)
        values["Weight"], values["Decay"] = 0.1 * 32 / samples, 0.97 ** (32 / samples)  # one look
        seconds, image = results.median_seconds(
            lambda g=group, v=values: readback.composite_group(g, v, "Rays", SIZE), REPEATS)
        error = np.abs(image[..., :3] - reference).max() / reference.max()
        rows.append((label, len(group.nodes), seconds - base, error))
        print(f"god rays: {label}: {len(group.nodes)} nodes, {seconds - base:.2f} s, error {error:.4f}",
              flush=True)
    lines = [results.heading("God rays: one group against the unrolled samples"),
             f"{results.machine()}. A {SIZE[0]}x{SIZE[1]} sun disc (radius {RADIUS} frame heights), Density "
             "0.9, the default look (Weight 0.1 and Decay 0.97 at 32 samples, the same falloff at every "
             f"count). Time: the compositor with the group, median of {REPEATS} renders of an empty scene "
             f"(less the {base:.2f} s of the same render without it). Error: the largest difference from "
             "the seed's own sum at 1024 samples, as a share of its brightest pixel.\n",
             "| group | nodes | s | error |", "|---|---|---|---|"]
    lines += [f"| {label} | {nodes} | {seconds:.2f} | {error:.4f} |" for label, nodes, seconds, error in rows]
    results.publish(lines, append=not args.no_append)


if __name__ == "__main__":
    main()
