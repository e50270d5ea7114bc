"""Measure the light the cloud layer sends onto level ground in Cycles, for EEVEE's lighting world
(addon/sky_eevee_clouds.py), written as core/cloud_light_table.py.

The demo's desert at frame 200 with its cumulus layer at each sun elevation and coverage: a
white diffuse plane 30 km square, 400 m up (under the layer's base, over every dune), seen from
above by an orthographic camera, the lamp's direct light kept off it (light linking: the clouds
and the sand still get it), the dust box and the far haze hidden, sand of the demo's colour out
past the layer's edge. The plane shows the sky and the clouds: with the layer against without it, per channel,

    with - without = D x the lamp's irradiance + G x the lamp's x the sand's colour - B x without

(D: the share of the sun's light the clouds send down; G: the sunlit sand's light their bases
send back; B: the share of the clear sky's light they take away, what they hide less what they
pass on, from a third render with the lamp hidden), each by least squares over the channels.
Then D and B at two more densities give their exponents in the optical depth.

Run: .venv/bin/python devtools/cloud_light_table.py   (about 12 minutes; rewrites core/cloud_light_table.py)
     .venv/bin/python devtools/cloud_light_table.py --from-log LOG   (solves a run's printed rows again)
"""

import argparse
import json
import math
import pathlib
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

ELEVATIONS = (2, 6, 12, 20, 30, 45, 70)  # degrees
COVERAGES = (0.2, 0.4, 0.7, 1.0)
DENSITIES = (0.01, 0.05)  # per metre, at DENSITY_POINT, beside the demo's 0.02
DENSITY_POINT = (20, 0.4)  # elevation, coverage
FRAME, PIXELS, SAMPLES = 200, 16, 64
PLANE_SIZE, PLANE_HEIGHT = 30000.0, 400.0  # metres: the mean under some 25 of the map's blobs
GROUND_SIZE = 60000.0  # metres of sand, beyond the layer's 52 km


def probe(bpy, scene, scenes):
    """The white plane and the camera over it (not made the scene's camera here). The plane is
    white to the camera alone and clear to every other ray (light from it would bounce off the
    clouds' bases and back, a white ground 30 km wide), and the lamp does not light it (light
    linking): everything else, the sand too, keeps the sun."""
    from core.sand import SAND_COLOR

    walker = next(o for o in scene.objects if o.get("sandscape_object") == "walker")
    x, y = walker.matrix_world.translation.xy
    # Sand under the whole layer (the demo's land ends 4.2 km out): the sunlit ground's light
    # that the clouds' bases send back down is part of their light on any desert.
    bpy.ops.mesh.primitive_plane_add(size=GROUND_SIZE, location=(x, y, -1.0))
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "Sand Out to the Layer's Edge", "ShaderNodeBsdfDiffuse", Color=SAND_COLOR))
    bpy.ops.mesh.primitive_plane_add(size=PLANE_SIZE, location=(x, y, PLANE_HEIGHT))
    plane = bpy.context.active_object
    material = bpy.data.materials.new("White to the Camera")
    tree = material.node_tree
    tree.nodes.clear()
    path = tree.nodes.new("ShaderNodeLightPath")
    white = tree.nodes.new("ShaderNodeBsdfDiffuse")
    white.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    clear = tree.nodes.new("ShaderNodeBsdfTransparent")
    mix = tree.nodes.new("ShaderNodeMixShader")
    output = tree.nodes.new("ShaderNodeOutputMaterial")
    tree.links.new(path.outputs["Is Camera Ray"], mix.inputs["Fac"])
    tree.links.new(clear.outputs[0], mix.inputs[1])
    tree.links.new(white.outputs[0], mix.inputs[2])
    tree.links.new(mix.outputs[0], output.inputs["Surface"])
    plane.data.materials.append(material)
    camera = scenes.camera("ORTHO", location=(x, y, PLANE_HEIGHT + 10.0), rotation=(0.0, 0.0, 0.0),
                           ortho_scale=PLANE_SIZE * 0.98)
    camera.data.clip_end = 1e5
    camera["probe_plane"] = plane.name
    return camera


def unlit(bpy, lamp, plane):
    """The lamp lights everything but the plane."""
    receivers = bpy.data.collections.get("Not the Probe") or bpy.data.collections.new("Not the Probe")
    if plane.name not in receivers.objects:
        receivers.objects.link(plane)
    lamp.light_linking.receiver_collection = receivers
    for entry in receivers.collection_objects:
        entry.light_linking.link_state = "EXCLUDE"


def measure(bpy, np, readback, scene, camera, elevation, coverage, density):
    """{'sun', 'with', 'without', 'sky with'}: the lamp's irradiance and the plane's, per
    channel (the last with the lamp hidden: the sky's light alone, through the clouds)."""
    scene.sandscape_atmosphere.sun_elevation = math.radians(elevation)
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    scene.sandscape_clouds.coverage, scene.sandscape_clouds.density = coverage, density
    assert bpy.ops.sandscape.add_clouds() == {"FINISHED"}
    own = {o.get("sandscape_object"): o for o in scene.objects if o.get("sandscape_object")}
    for name in ("dust_volume", "far_haze"):
        if name in own:
            own[name].hide_render = True
    lamp, clouds = own["sun"], own["clouds"]
    unlit(bpy, lamp, bpy.data.objects[camera["probe_plane"]])
    shot = scene.camera
    scene.camera = camera
    readback.cycles_scene(scene, (PIXELS, PIXELS), SAMPLES)
    scene.render.use_compositing = False
    row = {"sun": (lamp.data.energy * np.array(lamp.data.color)).tolist()}
    try:
        renders = (("with", False, False), ("without", True, False), ("sky with", False, True))
        for key, hidden, dark in renders:
            clouds.hide_render, lamp.hide_render = hidden, dark
            row[key] = (readback.render(scene)[..., :3].astype(np.float64).mean((0, 1)) * math.pi).tolist()
    finally:
        clouds.hide_render = lamp.hide_render = False
        scene.camera = shot
    return row


def solve(np, row):
    """(D, G, B) from a measured row: B from the sky's light alone (the lamp hidden), the share
    of it the layer takes away; D and G, the rest of the change, in units of the lamp's light
    (D) and of the lamp's light tinted by the sand (G: the sunlit sand's light the bases send
    back down); each by least squares over the channels."""
    from core.sand import SAND_COLOR

    sun, with_, without, sky_with = (np.asarray(row[k]) for k in ("sun", "with", "without", "sky with"))
    b = float(np.dot(without - sky_with, without) / np.dot(without, without))
    basis = np.stack([sun, sun * np.asarray(SAND_COLOR[:3])], 1)
    change = with_ - without + b * without
    (d, g), *_ = np.linalg.lstsq(basis, change, rcond=None)
    if min(d, g) < 0:  # a low sun's red light and the sand's are nearly one colour: neither below 0
        alone = [max(float(np.dot(change, v) / np.dot(v, v)), 0.0) for v in basis.T]
        misses = [np.linalg.norm(change - a * v) for a, v in zip(alone, basis.T, strict=True)]
        d, g = (alone[0], 0.0) if misses[0] <= misses[1] else (0.0, alone[1])
    return float(d), float(g), b


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--from-log", type=pathlib.Path,
                        help="solve the rows a run of this script printed again, rendering nothing")
    args = parser.parse_args(argv)
    if args.from_log:
        import bpy
        import numpy as np

        rows, densities = read_log(args.from_log)
        write_table(np, bpy.app.version_string, rows, densities, 0.02, 1200.0)
        return
    from devtools import session

    _, scene = session.demo_scene()
    import bpy
    import numpy as np

    from devtools import readback, scenes

    scene.frame_set(FRAME)
    camera = probe(bpy, scene, scenes)
    base_density = scene.sandscape_clouds.density
    rows, densities = {}, {}
    for elevation in ELEVATIONS:
        for coverage in COVERAGES:
            row = rows[(elevation, coverage)] = measure(bpy, np, readback, scene, camera, elevation, coverage,
                                                        base_density)
            print(f"cloud_light_table: {elevation:2d} deg, coverage {coverage:.1f}: D, G, B "
                  f"{solve(np, row)} {json.dumps(row)}", flush=True)
    for density in DENSITIES:
        row = densities[density] = measure(bpy, np, readback, scene, camera, *DENSITY_POINT, density)
        print(f"cloud_light_table: density {density}: D, G, B {solve(np, row)} {json.dumps(row)}", flush=True)
    write_table(np, bpy.app.version_string, rows, densities, base_density, scene.sandscape_clouds.thickness)


def read_log(path):
    """The measured rows a run printed: ({(elevation, coverage): row}, {density: row})."""
    rows, densities = {}, {}
    for line in path.read_text().splitlines():
        if not line.startswith("cloud_light_table:") or "{" not in line:
            continue
        head, row = line[:line.index("{")], json.loads(line[line.index("{"):])
        words = head.replace(",", " ").replace(":", " ").split()
        if words[1] == "density":
            densities[float(words[2])] = row
        else:
            rows[(int(words[1]), float(words[4]))] = row
    return rows, densities


def write_table(np, version, rows, densities, base_density, thickness):
    shares = {key: solve(np, row) for key, row in rows.items()}
    base = shares[DENSITY_POINT]
    exponents = []
    for density, row in densities.items():
        ratio = math.log(density / base_density)
        exponents.append([math.log(max(new, 1e-6) / max(old, 1e-6)) / ratio
                          for new, old in zip(solve(np, row), base, strict=True)])
    d_exponent, g_exponent, b_exponent = (float(np.mean(e)) for e in zip(*exponents, strict=True))
    lines = ['"""The cloud layer\'s light on level ground, measured in Cycles by',
             f"devtools/cloud_light_table.py (do not edit; run it again). Blender {version}; the demo's",
             f"cumulus layer, {thickness:g} m thick, at density {base_density:g} per metre (OPTICAL_DEPTH =",
             "density x thickness).",
             "",
             "D: the share of the lamp's irradiance (on a surface facing it) the clouds send onto level",
             "ground; G: the share of it tinted by the sand (the sunlit sand's light their bases send back",
             "down); B: the share of the clear sky's irradiance on level ground they take away. ROWS: sun",
             "elevation in degrees, then (D, G, B) at each of COVERAGES. Each scales with the optical",
             'depth\'s ratio to OPTICAL_DEPTH to the power of its EXPONENT."""',
             "",
             f"OPTICAL_DEPTH = {base_density * thickness:.6g}",
             f"COVERAGES = {COVERAGES!r}",
             f"D_EXPONENT, G_EXPONENT, B_EXPONENT = {d_exponent:.4f}, {g_exponent:.4f}, {b_exponent:.4f}",
             "",
             "ROWS = ("]
    for elevation in ELEVATIONS:
        triples = [f"        ({', '.join(f'{v:.5f}' for v in shares[(elevation, c)])}),  # coverage {c:g}"
                   for c in COVERAGES]
        lines += [f"    ({elevation},", *triples, "    ),"]
    lines.append(")")
    (REPO / "core" / "cloud_light_table.py").write_text("\n".join(lines) + "\n")
    print("cloud_light_table: wrote core/cloud_light_table.py")


if __name__ == "__main__":
    main()
