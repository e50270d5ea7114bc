"""The EEVEE balances: their fits against the measurements they came from, EEVEE's sand as they make
it against Cycles' per channel, and the node group against its twin (a bake)."""

import json
import pathlib

import numpy as np
import pytest

from core import eevee_balance as twin
from devtools import readback, scenes
from devtools.eevee_balance_data import fit_all, measured_balance, predicted, sheen_excess

DATA = pathlib.Path(__file__).resolve().parent.parent / "devtools" / "eevee_balance.json"
FIT_MEAN_ERROR = 0.06
GOAL = 0.15  # issue 27: EEVEE's sand within 15 % of Cycles' brightness
CHANNEL_LIMIT = 0.25  # each channel under sun and sky: the balance is one factor for all three
SKY_CHANNEL_LIMIT = 0.05  # each channel under the sky alone (the shade): its balance is per channel
LUMINANCE = (0.2126, 0.7152, 0.0722)  # Rec. 709, linear


def rows():
    return json.loads(DATA.read_text())


def test_the_coefficients_are_the_fit_of_the_measurements():
    sheen, balance, ambient, tint = fit_all(rows())
    assert np.allclose(sheen, twin.SHEEN_AMBIENT, atol=1e-3)
    assert np.allclose(balance, twin.COEFFICIENTS, atol=1e-3)
    assert np.allclose(ambient, twin.AMBIENT_COEFFICIENTS, atol=1e-3)
    assert np.allclose(tint, twin.AMBIENT_TINT_COEFFICIENTS, atol=1e-3)


def test_the_fits_follow_what_was_needed():
    """W(v) follows what EEVEE's sand under the sky alone adds to its colour (0.003-0.148) within
    0.01 (0.008 when written). The balance on the sun's light that was needed spans 0.44-6.44 over
    the 108 views and suns, the ambient balance 0.85-1.69; the fits follow them within
    FIT_MEAN_ERROR on average (2.9 % and 0.2 % when written)."""
    measured = rows()
    v, excess = sheen_excess(measured)
    assert np.abs(twin.sheen_ambient(v) - excess).max() <= 0.01
    view, light, balance, ambient = measured_balance(measured)
    up = (0.0, 0.0, 1.0)
    for name, needed, fitted in (("balance", balance, twin.balance(view, light, up)),
                                 ("ambient balance", ambient, twin.ambient_balance(view, light, up))):
        error = fitted / needed - 1.0
        print(f"EEVEE {name}: needed {needed.min():.2f}..{needed.max():.2f}, fit error mean "
              f"{np.abs(error).mean():.1%}, largest {np.abs(error).max():.1%}")
        assert np.abs(error).mean() <= FIT_MEAN_ERROR
    assert balance.max() / balance.min() > 5


def test_eevees_sand_is_within_the_goal_of_cycles():
    """EEVEE's sand as the fitted balances make it (its own surface and the ambient its output
    finds, measured, through core.eevee_balance.surface) against Cycles', over every measured view
    and sun, under sun and sky and under the sky alone: its brightness (luminance) within the
    issue's 15 % everywhere, each channel within CHANNEL_LIMIT (SKY_CHANNEL_LIMIT under the sky
    alone). When written (v9, 216 views): luminance at most 10.7 % (mean 1.4 %; the sky alone
    1.8 %); per channel mean 3.3 %, largest 18.0 %; the sky alone 2.3 % (v8, one ambient balance
    for all channels, 21.6 % on its 108 views: EEVEE's shade bluer than Cycles' at grazing views).
    With 2026-12-05's one balance and one probe on v8's 108 views: luminance up to 59.5 % (22.8 %
    for suns of 10° and more), per channel up to 62.6 %; without a balance, 89.5 % and 104 %."""
    measured = rows()
    view, light, _, _ = measured_balance(measured)
    luminance = np.array(LUMINANCE)
    for part, out, key, channel_limit in zip(("sun and sky", "sky alone"), predicted(measured, view, light),
                                             ("cycles", "cycles_sky"), (CHANNEL_LIMIT, SKY_CHANNEL_LIMIT),
                                             strict=True):
        cycles = np.array([row[key] for row in measured])
        error = out / cycles - 1.0
        brightness = out @ luminance / (cycles @ luminance) - 1.0
        print(f"EEVEE's sand against Cycles', {part}: luminance mean {np.abs(brightness).mean():.1%}, "
              f"largest {np.abs(brightness).max():.1%}; per channel mean {np.abs(error).mean():.1%}, "
              f"largest {np.abs(error).max():.1%}")
        assert np.abs(brightness).max() <= GOAL
        assert np.abs(error).max() <= channel_limit


def test_the_group_bakes_as_its_twin(sandscape):
    """Baked on a plane whose normal points up (the baker looks along it, V = N) with suns
    round about, and with a normal given to the group that the baker's view grazes (N·V = 0.1),
    where the fits change fastest."""
    helper = sandscape.node_groups.helper
    group = helper.ensure_group(sandscape.node_groups.eevee_balance)
    up, grazed = (0.0, 0.0, 1.0), (0.99499, 0.0, 0.1)
    cases = [(sun, up) for sun in ((0.3, 0.2, 0.5), (-0.8, 0.1, 0.3), (0.0, 0.0, 1.0), (0.0, 0.0, 0.0),
                                   (0.9, 0.0, 0.03), (0.5, 0.0, -0.2))]
    cases += [((0.2, 0.3, 0.9), grazed), ((0.9, -0.4, 0.1), grazed)]
    for sun, normal in cases:
        plane = readback.uv_plane(2.0)
        for output, expected in (("Balance", twin.balance), ("Ambient Balance", twin.ambient_balance),
                                 ("Ambient Tint", twin.ambient_tint)):
            values = {"Sun Direction": sun} | ({"Normal": normal} if normal != up else {})
            material = scenes.group_material(group, values, output)
            plane.data.materials.clear()
            plane.data.materials.append(material)
            baked = readback.bake_emit(plane, material, 8)[..., :3]
            wanted = expected(up, sun, normal)  # all 1 without a sun
            assert baked == pytest.approx(np.broadcast_to(wanted, baked.shape), rel=1e-4), (output, sun)


def test_faces_turned_from_the_sun_keep_their_light():
    """The balance corrects the sun's light: a face the sun does not reach gets 1 (the fit had
    brightened shaded slip faces' sky light by up to 2.5x under a low sun ahead), and the ease
    from the fit starts where the fit's own cosine limit does, with no step. The ambient balance
    and its tint, measured on faces the sun reaches, are 1 there too."""
    view = np.array([-0.99, 0.1, 0.09])
    normal = np.array([0.0, 0.0, 1.0])
    for height in (-0.3, -0.01, 0.0):
        assert twin.balance(view, (1.0, 0.0, height), normal) == pytest.approx(1.0)
        assert twin.ambient_balance(view, (1.0, 0.0, height), normal) == pytest.approx(1.0)
        assert twin.ambient_tint(view, (1.0, 0.0, height), normal) == pytest.approx(np.ones(3))
    sine = twin.MIN_COSINE
    fitted = twin.balance(view, (np.sqrt(1 - sine ** 2), 0.0, sine), normal)
    assert fitted > 1.5  # where the ease starts, the fit brightens a lot: the ease matters
    near = twin.balance(view, (np.sqrt(1 - (sine - 1e-4) ** 2), 0.0, sine - 1e-4), normal)
    assert near == pytest.approx(fitted, rel=0.01)
    half = twin.balance(view, (np.sqrt(1 - (sine / 2) ** 2), 0.0, sine / 2), normal)
    assert 1.0 < half < fitted
