"""The haze's scattered sunlight (core/haze_light.py) and EEVEE's lighting world that holds it
(addon/sky_eevee_haze.py): the twin against the physics of a thin slab and against Cycles' own
volume, and the world's nodes against the twin. Cycles renders of a white plane seen from above
with the lamp's direct light turned off (its diffuse visibility): the plane shows only the light
that reached it by way of the haze."""

import math

import bpy
import numpy as np
import pytest

from core import haze_light
from devtools import readback, scenes

# Twin against Cycles' volume: single scattering (the twin) against Cycles' every bounce. When
# written: -4.4 % (sun at 6 degrees, 20 km visibility) and +10.6 % (30 degrees, 10 km). Denser
# haze is where the twin falls short: Cycles' multiple scattering, about a third more at 4 km
# visibility under a 6 degree sun (a box 5 km wide, 0.5 km high; not a test).
CYCLES_TOLERANCE = 0.15
NODES_TOLERANCE = 0.03  # the world's nodes, integrated by Cycles, against the twin's integral


def test_thin_haze_over_a_wide_floor_sends_down_its_phase_share_of_its_optical_depth():
    """A thin slab wider than any ray: each scattering sends the phase's downward share to the
    floor, so E = tau x that share for a sun anywhere (isotropic: a half; Henyey-Greenstein 0.6
    under a sun overhead: its forward share, (1 - g^2) / 2g (1/(1 - g) - 1/sqrt(1 + g^2)))."""
    tau, height = 1e-4, 500.0
    for sine in (0.1, 0.5, 1.0):
        got = haze_light.scattered_irradiance(tau / height, 0.0, height, 1e9, sine)
        assert got == pytest.approx(tau / 2, rel=0.01)
    g = 0.6
    forward = (1 - g * g) / (2 * g) * (1 / (1 - g) - 1 / math.sqrt(1 + g * g))
    assert haze_light.scattered_irradiance(tau / height, g, height, 1e9, 1.0) == pytest.approx(tau * forward,
                                                                                               rel=0.01)
    assert haze_light.scattered_irradiance(0.0, g, height, 1e9, 0.5) == 0.0
    assert haze_light.scattered_irradiance(tau, g, height, 1e9, 0.0) == 0.0  # the sun set
    thicker = [haze_light.scattered_irradiance(s, g, height, 2000.0, 0.1) for s in (1e-4, 2e-4, 4e-4)]
    assert thicker == sorted(thicker)


def _plane_under_haze(sandscape, elevation, visibility):
    """A white plane under Add Atmosphere's haze alone (no air, no dust), the lamp lighting only
    the haze, seen by a camera looking at the horizon (so the box rises hundreds of metres, as
    over the demo: a camera looking down gets a box a few metres high); returns (scene, lamp)."""
    bpy.ops.mesh.primitive_plane_add(size=100.0)
    bpy.context.active_object.data.materials.append(scenes.single_node_material(
        "White", "ShaderNodeBsdfDiffuse", Color=(1.0, 1.0, 1.0, 1.0)))
    scene = bpy.context.scene
    scenes.camera("PERSP", location=(0.0, 0.0, 1.5), rotation=(math.radians(90.0), 0.0, 0.0), lens=35.0)
    air = scene.sandscape_atmosphere
    air.sun_elevation, air.sun_azimuth = math.radians(elevation), 0.4
    air.density, air.dust_density, air.use_wind = 0.0, 0.0, False
    air.use_haze, air.visibility = True, visibility
    assert bpy.ops.sandscape.add_atmosphere() == {"FINISHED"}
    lamp = sandscape.addon.atmosphere.scene_sun(scene)
    lamp.visible_diffuse = False  # the plane gets no direct light; the haze still scatters it
    readback.cycles_scene(scene, (16, 16), 256)
    return scene, lamp


def _light_per_unit_sun(scene, lamp):
    """pi x the plane's radiance (its irradiance) over the lamp's, summed over the channels: the
    frame's four lowest rows, the plane 3-5 m off (the haze between adds well under 1 %)."""
    radiance = readback.render(scene)[:4, :, :3].astype(np.float64).mean((0, 1))
    return math.pi * radiance.sum() / (lamp.data.energy * sum(lamp.data.color))


def _twin(sandscape, scene):
    extinction, anisotropy, height, radius = sandscape.addon.sky_eevee_haze.held(scene.world)
    sine = sandscape.addon.atmosphere.scene_sun(scene).matrix_world.col[2].normalized().z
    return haze_light.scattered_irradiance(extinction, anisotropy, height, radius, sine)


@pytest.mark.parametrize("elevation,visibility", [(6.0, 20000.0), (30.0, 10000.0)])
def test_the_twin_holds_the_light_cycles_haze_scatters_down(sandscape, elevation, visibility):
    """Cycles' own dust box (its world dark): the light on the plane against the twin at the
    haze's extinction, anisotropy and the box's size the world holds."""
    scene, lamp = _plane_under_haze(sandscape, elevation, visibility)
    world = scene.world
    held = sandscape.addon.sky_eevee_haze.held(world)
    assert held[0] == pytest.approx(3.912 / visibility, rel=1e-3) and held[2] > 100.0
    world.use_fake_user = True
    scene.world = None
    cycles = _light_per_unit_sun(scene, lamp)
    scene.world = world
    twin = _twin(sandscape, scene)
    print(f"haze light at {elevation:g}°, {visibility:g} m: Cycles {cycles:.4f}, twin {twin:.4f} "
          f"({twin / cycles - 1:+.1%})")
    assert twin == pytest.approx(cycles, rel=CYCLES_TOLERANCE)


def test_eevees_lighting_world_holds_the_twins_haze_light(sandscape):
    """The world's EEVEE output rendered by Cycles (which integrates it exactly), the dust box
    hidden: with the haze set, less without, is the twin's light times the lamp's."""
    scene, lamp = _plane_under_haze(sandscape, 6.0, 20000.0)
    own = sandscape.addon.ownership
    own.scene_object(scene, own.DUST_VOLUME).hide_render = True
    tree = scene.world.node_tree
    tree.nodes.remove(tree.nodes["Sandscape World Output"])
    tree.nodes["Sandscape EEVEE World Output"].target = "ALL"
    held = sandscape.addon.sky_eevee_haze.held(scene.world)
    with_haze = _light_per_unit_sun(scene, lamp)
    sandscape.addon.sky_eevee_haze.follow(scene.world)
    without = _light_per_unit_sun(scene, lamp)
    sandscape.addon.sky_eevee_haze.follow(scene.world, held[0], held[1], held[2], held[3])
    twin = _twin(sandscape, scene)
    print(f"world's haze light {with_haze - without:.4f}, twin {twin:.4f}")
    assert with_haze - without == pytest.approx(twin, rel=NODES_TOLERANCE)
