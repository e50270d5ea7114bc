"""The view-dependent glint, rendered: an orthographic camera on a true sphere gives a
known hit point and N·V = z / r at every pixel centre."""

import numpy as np
import pytest

from core import glints as twin
from devtools import readback, scenes

RES = 64
RADIUS = 1.0
SCALE = 2.2  # orthographic view width in metres
RENDER_TOLERANCE = 1e-3
SIZE = 0.25
COLOR = (1.0, 0.6, 0.3)


def sphere_hits(res=RES):
    """Hit points on the sphere and N·V at the pixel centres; rows bottom-up like Blender's."""
    c = readback.pixel_centres(res, -SCALE / 2, SCALE / 2).astype(np.float64)
    x, y = np.meshgrid(c, c)
    z = np.sqrt(np.clip(RADIUS**2 - x**2 - y**2, 0.0, None))
    return np.stack([x, y, z], axis=-1), z / RADIUS


def render_sphere(group, values):
    readback.cycles_scene(resolution=(RES, RES), samples=1)
    scenes.sharp_pixels()
    material = scenes.group_material(group, values, output="Emission")
    scenes.analytic_sphere(material, RADIUS)
    scenes.camera("ORTHO", location=(0.0, 0.0, 10.0), ortho_scale=SCALE)
    return readback.render()[..., :3]


def comparable_pixels(positions, n_dot_v):
    """Away from the silhouette (N·V > 0.2) and more than 1 mm from a cell edge, where the
    ±0.005 px sample jitter (about 0.2 mm here) cannot change the cell."""
    frac = positions / SIZE + 0.5
    clear_of_edges = np.all(np.abs(frac - np.round(frac)) * SIZE > 1e-3, axis=-1)
    return (n_dot_v > 0.2) & clear_of_edges


@pytest.mark.parametrize("power", [0.0, 1.0, 4.0, 32.0])
def test_rendered_glint_matches_twin(glints_group, power):
    values = {"Threshold": 0.4, "Glint Size": SIZE, "Facing Power": power,
              "Color": (*COLOR, 1.0), "Strength": 2.0, "Seed": 3.0}
    rendered = render_sphere(glints_group, values)
    positions, n_dot_v = sphere_hits()
    _, expected = twin.glints(positions.astype(np.float32), n_dot_v, 0.4, SIZE, power, COLOR, 2.0, 3)
    keep = comparable_pixels(positions, n_dot_v)
    assert keep.sum() > 1500
    lit = expected[..., 0] > 0
    assert 0.3 < lit[keep].mean() < 0.9  # both lit and dark cells are compared
    # Per unit strength: the 1e-3 tolerance is on the glint term itself.
    error = np.abs(rendered - expected)[keep] / 2.0
    assert error.max() <= RENDER_TOLERANCE, f"max error {error.max():.2e}"
    background = (np.linalg.norm(positions[..., :2], axis=-1) > RADIUS * 1.02)
    assert np.abs(rendered[background]).max() <= 1e-6


def test_facing_power_falls_off_towards_the_rim(glints_group):
    """The mission's rule: glints only where the view lines up with the normal."""
    values = {"Threshold": 0.0, "Glint Size": SIZE, "Facing Power": 8.0,
              "Color": (1.0, 1.0, 1.0, 1.0), "Strength": 1.0, "Seed": 0.0}
    rendered = render_sphere(glints_group, values)[..., 0]
    _, n_dot_v = sphere_hits()
    centre = rendered[n_dot_v > 0.98].mean()
    rim = rendered[(n_dot_v > 0.2) & (n_dot_v < 0.5)].mean()
    assert centre > 0.85 and rim < 0.01
