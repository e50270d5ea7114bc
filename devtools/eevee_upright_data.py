"""Measure how our Physical Sand lights an upright wall in Cycles against EEVEE's lighting world,
and print core.eevee_upright's rows (paste them into core/eevee_upright.py).

A plane of Physical Sand 400 m across under Add Atmosphere's sun and sky (dust off: its box
veils the wall differently in each engine), a grey Lambert wall 2 m square standing 0.5 m above
it, edge-on to the sun, seen square-on through an orthographic camera; the wall's linear mean in
Cycles (256 spp, two bounces), in EEVEE, and in EEVEE with the world's lower hemisphere zeroed.
The world's upright gain is taken out for the measurement (its share set to 0).

Run: .venv/bin/python devtools/eevee_upright_data.py [--json OUT] [--elevations 3 6 ...]
(devtools/eevee_upright.json holds the measurements the rows were taken from.)
"""

import argparse
import contextlib
import json
import math
import pathlib
import sys

import numpy as np

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

from core import eevee_upright as twin  # noqa: E402

ELEVATIONS = (3, 6, 10, 15, 25, 40, 60, 80)


def wall_scene():
    """A session with the wall on the sand; returns (bpy, readback, sandscape, scene)."""
    from devtools import session

    sandscape = session.start()
    import bpy

    from devtools import readback

    session.reset()  # an empty file: no startup cube or lamp beside the wall
    return bpy, readback, sandscape, build_wall(bpy.context.scene)


def build_wall(scene):
    """The wall on the sand in this (empty) scene, its sun and sky not yet added; the scene."""
    import bpy

    from devtools import scenes

    scene.render.resolution_x, scene.render.resolution_y, scene.render.resolution_percentage = 32, 32, 100
    scene.eevee.taa_render_samples = 8
    bpy.ops.mesh.primitive_plane_add(size=400)
    assert bpy.ops.sandscape.add_sand_material(look="PHYSICAL") == {"FINISHED"}
    bpy.ops.mesh.primitive_plane_add(size=2, location=(0.0, 0.0, 1.5), rotation=(math.pi / 2, 0.0, 0.0))
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "Grey", "ShaderNodeBsdfDiffuse", Color=(0.5, 0.5, 0.5, 1.0)))
    scenes.camera("ORTHO", location=(0.0, -5.0, 1.5), rotation=(math.pi / 2, 0.0, 0.0), ortho_scale=0.8)
    scene.cycles.samples, scene.cycles.max_bounces = 256, 2
    scene.eevee.clamp_surface_indirect = 0.0
    scene.sandscape_atmosphere.density = 0.0
    return scene


@contextlib.contextmanager
def _without_ground(tree):
    """The world's lower hemisphere zeroed (its light from below taken out) for the block."""
    mix = tree.nodes["Sandscape EEVEE Two Hemispheres"]
    below = next(i for i in mix.inputs if i.name == "A" and i.is_linked and i.type == "RGBA")
    source = below.links[0].from_socket
    zero = tree.nodes.new("ShaderNodeVectorMath")
    zero.operation, zero.inputs["Scale"].default_value = "SCALE", 0.0
    tree.links.new(source, zero.inputs[0])
    tree.links.new(zero.outputs[0], below)
    try:
        yield
    finally:
        tree.links.new(source, below)
        tree.nodes.remove(zero)


def measure(elevations):
    bpy, readback, sandscape, scene = wall_scene()
    ground = sandscape.addon.sky_eevee_ground

    def mean(engine):
        scene.render.engine = engine
        return readback.render(scene)[..., :3].astype(np.float64).mean((0, 1))

    settings, rows = scene.sandscape_atmosphere, []
    for elevation in elevations:
        settings.sun_elevation, settings.sun_azimuth = math.radians(elevation), math.pi / 2
        scene.render.engine = "CYCLES"
        assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
        scene.frame_set(scene.frame_current)  # the world's drivers read the sun
        tree = scene.world.node_tree
        tree.nodes[ground.UPRIGHT_SHARE].outputs[0].default_value = 0.0  # against the Lambert ground
        cycles, eevee = mean("CYCLES"), mean("BLENDER_EEVEE")
        with _without_ground(tree):
            no_ground = mean("BLENDER_EEVEE")
        row = {"elevation": elevation, "cycles": cycles.tolist(), "eevee": eevee.tolist(),
               "eevee_no_ground": no_ground.tolist()}
        print(row, "gain", twin.measured_gain(cycles, eevee, no_ground).round(3), flush=True)
        rows.append(row)
    return rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--json", type=pathlib.Path, help="write the measurements here")
    parser.add_argument("--elevations", type=float, nargs="+", default=list(ELEVATIONS))
    args = parser.parse_args(argv)
    rows = measure(args.elevations)
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1) + "\n")
    print("ROWS = (")
    for row in rows:
        gain = twin.measured_gain(row["cycles"], row["eevee"], row["eevee_no_ground"])
        print(f"    ({row['elevation']:.1f}, " + ", ".join(f"{g:.3f}" for g in gain) + "),")
    print(")")


if __name__ == "__main__":
    main()
