"""The cloud layer's light on level ground, measured in Cycles by
devtools/cloud_light_table.py (do not edit; run it again). Blender 5.2.3 LTS; the demo's
cumulus layer, 1200 m thick, at density 0.02 per metre (OPTICAL_DEPTH =
density x thickness).

D: the share of the lamp's irradiance (on a surface facing it) the clouds send onto level
ground; G: the share of it tinted by the sand (the sunlit sand's light their bases send back
down); B: the share of the clear sky's irradiance on level ground they take away. ROWS: sun
elevation in degrees, then (D, G, B) at each of COVERAGES. Each scales with the optical
depth's ratio to OPTICAL_DEPTH to the power of its EXPONENT."""

OPTICAL_DEPTH = 24
COVERAGES = (0.2, 0.4, 0.7, 1.0)
D_EXPONENT, G_EXPONENT, B_EXPONENT = -0.3511, 0.3149, 0.2577

ROWS = (
    (2,
        (0.00566, 0.01311, 0.11107),  # coverage 0.2
        (0.00293, 0.02507, 0.21138),  # coverage 0.4
        (0.00000, 0.03482, 0.42988),  # coverage 0.7
        (0.00000, 0.04983, 0.76943),  # coverage 1
    ),
    (6,
        (0.00913, 0.02036, 0.12199),  # coverage 0.2
        (0.00906, 0.03342, 0.22602),  # coverage 0.4
        (0.00169, 0.04382, 0.44242),  # coverage 0.7
        (0.00000, 0.02419, 0.77632),  # coverage 1
    ),
    (12,
        (0.01304, 0.03308, 0.12945),  # coverage 0.2
        (0.01379, 0.05408, 0.23512),  # coverage 0.4
        (0.01226, 0.06739, 0.45213),  # coverage 0.7
        (0.00000, 0.03384, 0.78388),  # coverage 1
    ),
    (20,
        (0.01674, 0.04836, 0.13461),  # coverage 0.2
        (0.01856, 0.08034, 0.23776),  # coverage 0.4
        (0.02093, 0.10515, 0.45614),  # coverage 0.7
        (0.00651, 0.04831, 0.78637),  # coverage 1
    ),
    (30,
        (0.02232, 0.04750, 0.13601),  # coverage 0.2
        (0.02557, 0.08668, 0.23870),  # coverage 0.4
        (0.03335, 0.12994, 0.45390),  # coverage 0.7
        (0.02039, 0.07404, 0.78383),  # coverage 1
    ),
    (45,
        (0.02960, 0.04700, 0.13580),  # coverage 0.2
        (0.03838, 0.08987, 0.23610),  # coverage 0.4
        (0.05519, 0.16073, 0.44444),  # coverage 0.7
        (0.04915, 0.13367, 0.77465),  # coverage 1
    ),
    (70,
        (0.03856, 0.04769, 0.13735),  # coverage 0.2
        (0.05715, 0.10251, 0.23572),  # coverage 0.4
        (0.08637, 0.21038, 0.43555),  # coverage 0.7
        (0.09890, 0.24578, 0.76212),  # coverage 1
    ),
)
