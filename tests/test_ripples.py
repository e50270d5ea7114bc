"""Wind ripples against their numpy twin (core/sand.py ripples) by bake, on level ground and on
slopes, and as an artist sees them: a top-down render whose waves (the spectrum's mean about its
peak) run along the scene's wind at the ripple wavelength, turning when Add Atmosphere changes
the wind.
"""

import math

import bpy
import numpy as np
import pytest

from core import sand as twin
from devtools import readback, scenes

RES = 128
PLANE = 2.0
WAVELENGTH, AMPLITUDE = 0.25, 0.05
HEIGHT_TOLERANCE = 2e-6  # metres: float32 phase of positions up to 1.4 m, x amplitude
NORMAL_TOLERANCE = 1e-4  # float32 phase x A (2 pi / wavelength)^2
FRACTION_TOLERANCE = 0.01  # fitted amplitude / expected
DIRECTION_TOLERANCE = 5.0  # degrees, the issue's
WAVELENGTH_TOLERANCE = 0.05  # relative, the issue's


@pytest.fixture
def ripple_group(sandscape):
    return sandscape.node_groups.helper.ensure_group(sandscape.node_groups.ripples)


def bake_ripples(group, wind, output, matrix=None, **values):
    from mathutils import Matrix

    plane = readback.uv_plane(PLANE)
    plane.matrix_world = matrix if matrix is not None else Matrix.Identity(4)
    bpy.context.view_layer.update()
    material = scenes.group_material(
        group, {"Wind": wind, "Wavelength": WAVELENGTH, "Amplitude": AMPLITUDE, **values}, output)
    plane.data.materials.append(material)
    # Where Cycles shaded: off the pixel centres by enough to move the height by 4e-5 alone.
    baked, world = readback.bake_emit_with_positions(plane, material, RES)
    c = readback.pixel_centres(RES, -PLANE / 2, PLANE / 2).astype(np.float64)
    x, y = np.meshgrid(c, c)
    centres = np.stack([x, y, np.zeros_like(x), np.ones_like(x)], axis=-1) @ np.array(plane.matrix_world).T
    assert np.abs(world - centres[..., :3]).max() <= 0.01 * PLANE / RES  # the pixel it belongs to
    normal = np.array(plane.matrix_world.to_3x3() @ plane.data.polygons[0].normal)
    return baked, world, np.broadcast_to(normal / np.linalg.norm(normal), x.shape + (3,))


STRAIGHT = {"Meander": 0.0, "Variation": 0.0, "Defects": 0.0}
MEANDERING = {"Meander": 0.35, "Meander Scale": 0.5, "Variation": 0.5, "Defects": 0.9}


def twin_values(values):
    return {"meander": values["Meander"], "meander_scale": values.get("Meander Scale", 1.0),
            "variation": values["Variation"], "flatten": values.get("Flatten", 0.0),
            "defects": values["Defects"]}


@pytest.mark.parametrize("wind, values", [((3.0, 1.0, 0.0), STRAIGHT), ((0.0, -2.0, 5.0), STRAIGHT),
                                          ((0.0, 0.0, 0.0), STRAIGHT), ((3.0, 1.0, 0.0), MEANDERING),
                                          ((-1.0, 4.0, 0.0), MEANDERING),
                                          ((3.0, 1.0, 0.0), {**MEANDERING, "Flatten": 0.6})])
def test_height_and_normal_are_the_twins_on_level_ground(ripple_group, wind, values):
    """Any wind, its vertical part ignored; no wind at all gives crests along Y; crests straight
    or meandering over a lattice of 0.5 m (four cells across the plane); partly trampled."""
    height, positions, normals = bake_ripples(ripple_group, wind, "Height", **values)
    expected_height, expected_normal = twin.ripples(positions, normals, wind, WAVELENGTH, AMPLITUDE,
                                                    **twin_values(values))
    assert np.abs(height[..., 0] - expected_height).max() <= HEIGHT_TOLERANCE
    kept = (1.0 - values["Variation"]) * (1.0 - values.get("Flatten", 0.0))
    assert np.ptp(expected_height) > 1.9 * AMPLITUDE * kept  # the twin is not flat
    normal, _, _ = bake_ripples(ripple_group, wind, "Normal", **values)
    assert np.abs(normal[..., :3] - expected_normal).max() <= NORMAL_TOLERANCE


@pytest.mark.parametrize("variation, tolerance", [(0.0, 0.05), (0.5, 0.25)])
def test_the_twins_normal_is_its_heights_slope(variation, tolerance):
    """The twin against its own height by central differences (an independent reference for the
    formula of the normal), crests splitting and ending included (no seam where a defect's cell
    ends, no spike at a core): exact up to the differences' error without variation (0.03
    degrees); with it, the change of amplitude the normal leaves out costs under a quarter of a
    degree."""
    x = np.linspace(-2.0, 2.0, 401)
    xx, yy = np.meshgrid(x, x)
    positions = np.stack([xx, yy, np.zeros_like(xx)], axis=-1)
    up = np.broadcast_to([0.0, 0.0, 1.0], positions.shape)
    values = {"meander": 0.35, "meander_scale": 0.8, "variation": variation, "defects": 0.9}

    def height(offset):
        return twin.ripples(positions + offset, up, (3.0, 1.0, 0.0), 0.12, 0.004, **values)[0]

    def slope(axis, step):
        offset = np.eye(3)[axis] * step
        return (height(offset) - height(-offset)) / (2 * step)

    # float32 lattice coordinates: a step under 1 mm differences round-off, so two steps are
    # combined (Richardson) to take the step's own error out, largest where the cores flatten.
    step = 1e-3
    slope_x, slope_y = ((4 * slope(axis, step / 2) - slope(axis, step)) / 3 for axis in (0, 1))
    reference = np.stack([-slope_x, -slope_y, np.ones_like(slope_x)], axis=-1)
    reference /= np.linalg.norm(reference, axis=-1, keepdims=True)
    _, normal = twin.ripples(positions, up, (3.0, 1.0, 0.0), 0.12, 0.004, **values)
    apart = np.degrees(np.arccos(np.clip(np.sum(reference * normal, axis=-1), -1.0, 1.0)))
    assert np.degrees(np.arccos(normal[..., 2].min())) > 10.0  # ripples steep enough to tell
    print(f"variation {variation}: normal within {apart.max():.4f} degrees of the height's slope")
    assert apart.max() <= tolerance, apart.max()


def test_every_defect_inserts_one_crest():
    """Crests split and end only at the defects' cores: the ripples' phase winds by one turn (one
    crest more on one side than the other) round two points per pair, each within a centimetre of
    where the cell's noise puts a core (a pair in every cell whose noise is under Defects), and
    nowhere else: not where cells meet, not where the two lattices overlap. Winding summed round
    each 1 cm square of a 6 m field, Meander on."""
    wavelength, share, field = 0.12, 0.9, 3.0
    x = np.arange(-field, field, 0.01)
    xx, yy = np.meshgrid(x, x)
    positions = np.stack([xx, yy, np.zeros_like(xx)], axis=-1)
    direction = np.array([3.0, 1.0]) / np.hypot(3.0, 1.0)
    m, _, _ = twin.ripple_lattice(positions, 0.8)
    phase = 2 * np.pi * (positions[..., :2] @ direction / wavelength + 0.8 * (2.0 * m - 1.0))
    expected = []
    for offset, layer in twin.DEFECT_LAYERS:
        phase = phase + twin.ripple_defects(positions, direction, wavelength, share, offset, layer)[0]
        size = twin.DEFECT_CELL * wavelength
        cells = np.arange(np.floor(-field / size + offset) - 1, np.ceil(field / size + offset) + 1)
        for i in cells:
            for j in cells:
                key = np.array([[i, j, layer]], np.float32)
                draw = float(twin.white_noise_3d(key)[0]) / share
                if draw >= 1.0:
                    continue
                jitter = np.array([twin.white_noise_4d(key, 1.0)[0], twin.white_noise_4d(key, 2.0)[0]], float)
                stray = (2 * jitter - 1) * twin.DEFECT_JITTER * wavelength
                centre = (np.array([i, j]) + 0.5 - offset) * size + stray
                low, high = twin.DEFECT_HALF
                half = wavelength * (low + (high - low) * ((2 * draw) % 1.0))
                along = np.array([-direction[1], direction[0]])
                expected += [centre + half * along, centre - half * along]

    def turn(a, b):
        return np.angle(np.exp(1j * (b - a)))

    winding = (turn(phase[:-1, :-1], phase[:-1, 1:]) + turn(phase[:-1, 1:], phase[1:, 1:]) +
               turn(phase[1:, 1:], phase[1:, :-1]) + turn(phase[1:, :-1], phase[:-1, :-1])) / (2 * np.pi)
    rows, cols = np.nonzero(np.abs(winding) > 0.5)
    found = np.stack([x[cols] + 0.005, x[rows] + 0.005], -1)
    inner = field - 0.05
    expected = np.array([p for p in expected if np.all(np.abs(p) < inner)])
    found_inside = found[np.all(np.abs(found) < inner, axis=-1)]
    apart = np.linalg.norm(found_inside[:, None] - expected[None], axis=-1)
    print(f"{len(expected)} cores expected, {len(found_inside)} found, farthest "
          f"{apart.min(1).max() * 100:.2f} cm off; windings {np.unique(np.round(winding[rows, cols]))}")
    assert len(expected) >= 20
    assert len(found_inside) == len(expected)
    assert apart.min(axis=1).max() <= 0.01 and apart.min(axis=0).max() <= 0.01
    assert np.allclose(np.abs(winding[rows, cols]), 1.0, atol=1e-6)


def fitted_amplitude(height, positions, wind):
    """Least-squares amplitude of the height against sin and cos of the phase along the wind."""
    direction = np.array(wind[:2]) / np.hypot(*wind[:2])
    phase = 2 * np.pi * (positions[..., :2] @ direction) / WAVELENGTH
    basis = np.stack([np.sin(phase).ravel(), np.cos(phase).ravel()], axis=1)
    (a, b), *_ = np.linalg.lstsq(basis, height.ravel(), rcond=None)
    return math.hypot(a, b)


@pytest.mark.parametrize("facing, expected", [("across", 0.2), ("downwind", 0.2 * 0.3), ("upwind", 0.2)])
def test_ripples_fade_on_steep_and_lee_slopes(ripple_group, facing, expected):
    """A plane tilted to the 35 degree angle of repose keeps Steep Fraction (0.2) of its ripples;
    turned away from the wind, Lee Fraction (0.3) of that again. Measured as the amplitude that
    fits the baked height, and the whole bake against the twin."""
    from mathutils import Matrix, Vector

    wind = (2.0, 1.0, 0.0)
    direction = Vector((wind[0], wind[1], 0.0)).normalized()
    axis = direction if facing == "across" else Vector((0.0, 0.0, 1.0)).cross(direction)
    angle = math.radians(35.0) * (-1.0 if facing == "upwind" else 1.0)
    matrix = Matrix.Translation((0.3, -0.2, 1.0)) @ Matrix.Rotation(angle, 4, axis)
    height, positions, normals = bake_ripples(ripple_group, wind, "Height", matrix, **STRAIGHT,
                                              **{"Steep Fraction": 0.2, "Lee Fraction": 0.3})
    downwind = normals[0, 0, :2] @ np.array(direction)[:2]
    assert {"across": abs(downwind) < 1e-6, "downwind": downwind > 0.5, "upwind": downwind < -0.5}[facing]
    measured = fitted_amplitude(height[..., 0], positions, wind) / AMPLITUDE
    print(f"ripples on a 35 degree slope facing {facing}: {measured:.4f} of the amplitude")
    assert abs(measured / expected - 1.0) <= FRACTION_TOLERANCE
    expected_height, _ = twin.ripples(positions, normals, wind, WAVELENGTH, AMPLITUDE, 0.2, 0.3,
                                      **twin_values(STRAIGHT))
    assert np.abs(height[..., 0] - expected_height).max() <= HEIGHT_TOLERANCE


# ---------------------------------------------------------------- renders

SIZE, RENDER_RES = 4.0, 256  # 33 wavelengths across, 8 pixels a wavelength


def spectral_peak(image, size):
    """(direction in degrees modulo 180, wavelength) of the ripples in a square image spanning
    `size` metres, as the height's power-weighted mean over the octave either side of its strongest
    frequency (wavelength from the mean spatial frequency, direction from the mean doubled angle).
    A low sun along the wind shades by the slope, whose spectrum is the height's times k: the
    power is divided by k squared (below 2 cycles a metre, far under the ripples', left out).
    Hann window, zero-padded 2x, mean removed. The strongest frequency alone jumps between the
    spikes of a meandering, forking field (in the twin's height, 11.5 and 14.4 cm in two 2 m windows
    5 m apart; 11.4 and 10.6 cm at the origin with two and four defect lattices, the mean 12.1 and
    12.0 cm)."""
    n = image.shape[0]
    window = np.outer(np.hanning(n), np.hanning(n))
    padded = 2 * n
    power = np.abs(np.fft.fft2((image - image.mean()) * window, s=(padded, padded))) ** 2
    frequencies = np.fft.fftfreq(padded, d=size / n)
    fx, fy = np.meshgrid(frequencies, frequencies)
    k = np.hypot(fx, fy)
    height_power = np.where(k >= 2.0, power / np.maximum(k, 2.0) ** 2, 0.0)
    strongest = k.ravel()[np.argmax(height_power)]
    band = height_power * ((k > strongest / 2) & (k < 2 * strongest))
    direction = np.angle(np.sum(band * np.exp(2j * np.arctan2(fy, fx)))) / 2
    return math.degrees(direction) % 180.0, float(np.sum(band) / np.sum(band * k))


def angle_apart(a, b):
    d = abs(a - b) % 180.0
    return min(d, 180.0 - d)


def rippled_ground(wind_angle):
    """Sand with ripples (no glints) on a plane seen from above, the sun low along the wind so
    the crests shade; the wind set by Add Atmosphere (no dust)."""
    settings = bpy.context.scene.sandscape_atmosphere
    settings.wind = (4.0 * math.cos(math.radians(wind_angle)), 4.0 * math.sin(math.radians(wind_angle)), 0.0)
    settings.sun_elevation, settings.sun_azimuth = math.radians(20.0), math.radians(90.0 - wind_angle)
    settings.density, settings.use_wind, settings.use_haze = 0.0, False, False
    bpy.ops.sandscape.add_atmosphere()


@pytest.mark.parametrize("look", ["PHYSICAL", "JOURNEY"])
def test_rendered_ripples_run_across_the_wind_and_turn_with_it(sandscape, look):
    bpy.ops.mesh.primitive_plane_add(size=SIZE + 1.0)
    ground = bpy.context.active_object
    rippled_ground(20.0)
    bpy.context.view_layer.objects.active = ground
    bpy.ops.sandscape.add_sand_material(look=look, threshold=1.0, ripples=True)
    readback.cycles_scene(resolution=(RENDER_RES, RENDER_RES), samples=4)
    scenes.camera("ORTHO", location=(0.0, 0.0, 10.0), ortho_scale=SIZE)
    for wind_angle in (20.0, 135.0):
        if wind_angle != 20.0:
            rippled_ground(wind_angle)  # Add Atmosphere again: the ripples turn with the new wind
        image = readback.render()[..., :3].mean(-1)
        assert np.isfinite(image).all()
        direction, wavelength = spectral_peak(image, SIZE)
        print(f"{look} ripples, wind at {wind_angle:.0f} degrees: the waves at {direction:.1f} "
              f"degrees, {wavelength * 100:.2f} cm")
        assert angle_apart(direction, wind_angle) <= DIRECTION_TOLERANCE
        assert abs(wavelength / 0.12 - 1.0) <= WAVELENGTH_TOLERANCE


def test_ripple_lengths_follow_the_scene_units(sandscape):
    """Unit scale 0.01 (centimetres): 12 cm apart and 4 mm high are 12 and 0.4 scene units."""
    bpy.context.scene.unit_settings.scale_length = 0.01
    bpy.ops.mesh.primitive_plane_add(size=300.0)
    bpy.ops.sandscape.add_sand_material()  # a script's call: no invoke, the defaults in metres
    wave = sandscape.addon.sand.ripple_node(sandscape.addon.sand.find_sand_material(
        bpy.context.active_object))
    assert wave.inputs["Wavelength"].default_value == pytest.approx(12.0, rel=1e-6)
    assert wave.inputs["Amplitude"].default_value == pytest.approx(0.4, rel=1e-6)
    assert wave.inputs["Meander Scale"].default_value == pytest.approx(80.0, rel=1e-6)


def test_no_ripples_builds_no_ripple_group(sandscape):
    bpy.ops.mesh.primitive_plane_add()
    bpy.ops.sandscape.add_sand_material(ripples=False)
    material = sandscape.addon.sand.find_sand_material(bpy.context.active_object)
    assert sandscape.addon.sand.ripple_node(material) is None
    bpy.ops.sandscape.add_sand_material(ripples=True)
    assert sandscape.addon.sand.ripple_node(material) is not None
    assert len([m for m in bpy.data.materials if m.get("sandscape_structure")]) == 1


def test_prints_trample_the_ripples_they_land_on(sandscape):
    """Painted prints flatten the ripples under them (the Footprint Height group's Pressed into the
    Ripples' Flatten), whichever came first, prints or ripples, and still after the sand is
    updated; sand without ripples has nothing to flatten."""
    sand = sandscape.addon.sand
    terrain = scenes.height_field(6.0, 24, lambda x, y: 0.0 * x, "Flat")
    walker = scenes.keyframed_walker(lambda f: (-1.5 + 0.1 * (f - 1), 0.3, 1.0), range(1, 32))
    scenes.footprint_settings(terrain, walker, (1, 31), resolution=128)
    bpy.context.view_layer.objects.active = terrain
    bpy.ops.sandscape.add_sand_material(ripples=False)
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}
    material = sand.find_sand_material(terrain)

    def trampled():
        wave, prints = sand.ripple_node(material), sand.footprint_node(material)
        links = wave.inputs["Flatten"].links
        return len(links) == 1 and links[0].from_node == prints and links[0].from_socket.name == "Pressed"

    assert sand.ripple_node(material) is None
    bpy.ops.sandscape.add_sand_material(ripples=True)  # ripples after the prints
    assert trampled()
    bpy.ops.sandscape.add_sand_material(ripples=True, strength=20.0)  # the sand updated
    assert trampled()
    assert bpy.ops.sandscape.paint_footprints() == {"FINISHED"}  # painted again
    assert trampled()
