"""Measure the sky model's sun: for each elevation, the irradiance of the Multiple Scattering Sky
Texture's sun disc (normal to the sun) and of the rest of its sky (on level ground), written as
core/sun_table.py. Add Atmosphere reads it to give the sun lamp the sky's own sun.

The disc: a camera looking at the sun with a 1.7 degree field, the sky with and without its
disc rendered, the difference summed over the pixels' solid angles. The sky: a white diffuse
plane seen from above, lit by the disc-less sky alone (radiance = albedo / pi x irradiance).

Run: .venv/bin/python devtools/sun_table.py   (about a minute; rewrites core/sun_table.py)
"""

import math
import pathlib
import sys

REPO = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO))

ELEVATIONS = (-1, 0, 1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 40, 50, 60, 70, 80, 90)  # degrees
FIELD = 0.03  # radians: the disc (0.545 degrees) and its filter footprint fit well inside
PIXELS, DISC_SAMPLES, SKY_SAMPLES = 64, 16, 1024


def sky_world(bpy):
    world = bpy.data.worlds.new("Sky Probe")
    tree = world.node_tree
    tree.nodes.clear()
    sky = tree.nodes.new("ShaderNodeTexSky")
    sky.sky_type = "MULTIPLE_SCATTERING"
    background = tree.nodes.new("ShaderNodeBackground")
    output = tree.nodes.new("ShaderNodeOutputWorld")
    tree.links.new(sky.outputs[0], background.inputs[0])
    tree.links.new(background.outputs[0], output.inputs[0])
    return world, sky


def disc_irradiance(bpy, np, readback, scene, sky, camera, elevation):
    from mathutils import Vector

    scene.cycles.samples = DISC_SAMPLES
    scene.render.resolution_x = scene.render.resolution_y = PIXELS
    camera.data.type, camera.data.angle = "PERSP", FIELD
    camera.location = (0.0, 0.0, 0.0)
    camera.rotation_mode = "QUATERNION"
    towards = Vector((0.0, math.cos(elevation), math.sin(elevation)))  # the sky's sun at rotation 0
    camera.rotation_quaternion = towards.to_track_quat("-Z", "Y")
    sky.sun_disc = True
    with_disc = readback.render(scene)[..., :3].astype(np.float64)
    sky.sun_disc = False
    without = readback.render(scene)[..., :3].astype(np.float64)
    distance = 0.5 / math.tan(FIELD / 2)  # image plane of width 1 at this distance
    u = (np.arange(PIXELS) + 0.5) / PIXELS - 0.5
    x, y = np.meshgrid(u, u)
    solid_angle = distance / (x * x + y * y + distance * distance) ** 1.5 / PIXELS ** 2
    disc = with_disc - without
    border = np.abs(np.concatenate([disc[0], disc[-1], disc[:, 0], disc[:, -1]])).max()
    assert border < 1e-6 * max(disc.max(), 1.0), "the disc is not inside the field"
    return (disc * solid_angle[..., None]).sum((0, 1))


def sky_irradiance(bpy, np, readback, scene, sky, camera, ground):
    scene.cycles.samples = SKY_SAMPLES
    scene.render.resolution_x = scene.render.resolution_y = 8
    camera.data.type, camera.data.ortho_scale = "ORTHO", 0.5
    camera.location, camera.rotation_mode, camera.rotation_euler = (0.0, 0.0, 5.0), "XYZ", (0.0, 0.0, 0.0)
    sky.sun_disc = False
    ground.hide_render = False
    try:
        radiance = readback.render(scene)[..., :3].astype(np.float64).mean((0, 1))
    finally:
        ground.hide_render = True
    return radiance * math.pi  # white Lambertian ground: radiance = irradiance / pi


def main():
    from devtools import session

    root = session.isolate()
    import bpy
    import numpy as np

    session.install_dev_extension(root)
    session.reset()
    from devtools import readback, scenes

    scene = readback.cycles_scene(resolution=(PIXELS, PIXELS), samples=DISC_SAMPLES)
    scene.world, sky = sky_world(bpy)
    camera = scenes.camera("PERSP")
    # A huge white diffuse ground, lit by nothing but the sky (one bounce: the light itself).
    ground = readback.uv_plane(1e4, "Ground")
    ground.data.materials.append(scenes.single_node_material("White", "ShaderNodeBsdfDiffuse",
                                                             Color=(1.0, 1.0, 1.0, 1.0)))
    ground.hide_render = True
    scene.cycles.max_bounces = 1
    rows = []
    for degrees in ELEVATIONS:
        sky.sun_elevation, sky.sun_rotation = math.radians(degrees), 0.0
        disc = disc_irradiance(bpy, np, readback, scene, sky, camera, math.radians(degrees))
        ground_sky = sky_irradiance(bpy, np, readback, scene, sky, camera, ground)
        rows.append((degrees, *disc, *ground_sky))
        print(f"sun_table: {degrees:5.1f} deg: disc {disc.round(3)}, sky on level ground "
              f"{ground_sky.round(3)}", flush=True)
    lines = ['"""The sky model\'s sun, measured in Blender by devtools/sun_table.py (do not edit; run it',
             f"again). Multiple Scattering Sky Texture at its defaults, Blender {bpy.app.version_string}.",
             "",
             "Each row: sun elevation in degrees; the sun disc's irradiance on a surface facing it (R, G, B,",
             "the strength a sun lamp needs per channel); the disc-less sky's irradiance on level ground",
             '(R, G, B)."""',
             "",
             "ROWS = ("]
    lines += [f"    ({d:g}, {', '.join(f'{v:.6g}' for v in values)})," for d, *values in rows]
    lines.append(")")
    (REPO / "core" / "sun_table.py").write_text("\n".join(lines) + "\n")
    print("sun_table: wrote core/sun_table.py")


if __name__ == "__main__":
    main()
