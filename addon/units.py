"""The scene's units: Sandscape's settings are physical (a 0.7 m stride), scenes are in their own
units (unit scale 0.01 makes one unit a centimetre). Convert at the edge, report in the
scene's own unit system."""

import math

import bpy

FLOAT_MAX = 3.4028234e38  # where Blender's single-precision properties keep an inf typed into them


def metres_per_unit(scene):
    scale = scene.unit_settings.scale_length
    return scale if math.isfinite(scale) and scale > 0 else 1.0


def to_units(scene, metres):
    """Metres to scene units (a 0.7 m stride is 70 units at unit scale 0.01)."""
    return metres / metres_per_unit(scene)


def length_text(scene, units, precision=3):
    """A length in scene units as the scene shows it ('9.8 mm' for 0.98 units at scale 0.01)."""
    system = scene.unit_settings.system
    if system == "NONE":
        return f"{units:.{precision + 1}g}"
    metres = units * metres_per_unit(scene)
    text = bpy.utils.units.to_string(system, "LENGTH", metres, precision=precision)
    if metres != 0 and not any(digit in text for digit in "123456789"):
        # Below the system's smallest unit it prints "0 m": a limit of 1e-7 m would read as 0.
        return f"{metres:.{precision}g} m" if system == "METRIC" else f"{metres / 0.0254:.{precision}g} in"
    return text


def distinct_length_texts(scene, lengths):
    """length_text of each, with as many digits as it takes for different lengths to read
    differently (1,000 m and 1,004 m are both '1 km' at three)."""
    texts = [length_text(scene, length) for length in lengths]
    for precision in range(4, 8):
        if len(set(texts)) == len(set(lengths)):
            break
        texts = [length_text(scene, length, precision) for length in lengths]
    return texts


def round_up(value, digits=2):
    """The value rounded up to its first `digits` significant digits (1,004 to 1,100): a limit to
    raise to that is past the value, and reads simply."""
    if not (math.isfinite(value) and value > 0):
        return value
    step = 10.0 ** (math.floor(math.log10(value)) - digits + 1)
    return math.ceil(value / step - 1e-9) * step
