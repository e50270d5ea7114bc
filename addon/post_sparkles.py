"""The sparkles through the compositor: kept raw where the denoiser would smear them, and each
gathered into its own pixel.

The sand material writes where grains can glint into an AOV (sand.GLINT_AOV); the glint light is
Cycles' glossy light (and emission, in Emission mode) where a grain was hit.
"""

from ..node_groups import helper as h
from . import sand

GLINT_AOV = sand.GLINT_AOV
# A pixel is taken raw as it passes both (ratios to the ground, weight rising from 0 to 1):
SPARKLE_BAR = (1.5, 3.0)  # its glint light
DENOISED_BAR = (1.1, 1.3)  # its denoised self
# A sparkle gathered into its own pixel: its glint light over the dimmest of the 3x3 to the ground
# (the spread then 0.16-0.32 of the ground beside it, where it starts to show), and its own
# pixel: its glint light to the brightest of the 3x3 around, rising from 0 to 1.
GATHER_BAR = (1.0, 2.0)
# The pixel filter hands a one-pixel sparkle's pixels beside it 0.16 of its light each (Blender's
# 1.5 px Blackman-Harris; diagonals 0.02), and two pixels one sparkle straddles are near alike.
OWN_PIXEL_BAR = (0.3, 0.5)
# Its glint light to the mean of the ring of 16 pixels round its 3x3: a sparkle's ring holds the
# sheen alone (and a straddling twin's arm, 0.01 of it); a silhouette's edge runs through the
# ring, 2 of the 16 pixels like itself (8x), 16x for an edge pixel twice as bright as the rest.
ALONE_BAR = (10.0, 16.0)


def keep_sparkles(tree, layers, image, clean):
    """The denoised image `clean` with the sparkling pixels taken raw from `image`, then each
    sparkle's light gathered into its own pixel."""
    glint = _glint_light(tree, layers)
    weight, glint_level, ground = _sparkle_weight(tree, layers, glint, clean)
    sparkling = h.add_node(tree, "ShaderNodeMix", label="Sparkles Raw", data_type="RGBA")
    h.link(tree, weight, sparkling.inputs["Factor"])
    h.link(tree, clean, h.socket(sparkling.inputs, "A"))
    h.link(tree, image, h.socket(sparkling.inputs, "B"))
    return _gathered(tree, layers, sparkling.outputs["Result"], glint, glint_level, ground)


def _gathered(tree, layers, image, glint, glint_level, ground):
    """The glint light the pixel filter spread round each sparkle taken off the pixels beside it
    and added to the sparkle's own (its light kept, in one pixel).

    Blender's 1.5 px filter hands two in five of the samples that see a one-pixel sparkle to the
    pixels beside it: each sparkle was a plus of four arms, white on screen (the denoiser keeps
    them as it keeps the sparkle: every sample of a sparkle's pixel agrees). A sparkle is a pixel
    where grains were hit whose glint light is the brightest of its 3x3 and stands over its floor
    (the dimmest of the 3x3: the sand's own sheen) by GATHER_BAR times the ground; what the pixels
    beside it hold over their floor moves into it."""
    grains = h.math(tree, "GREATER_THAN", layers.outputs[GLINT_AOV], 0.0, label="Glinting Grains Hit")
    brightest = h.add_node(tree, "CompositorNodeDilateErode", label="Brightest Glint Around",
                           inputs={"Size": 1})
    h.link(tree, glint_level, brightest.inputs["Mask"])
    dimmest = h.add_node(tree, "CompositorNodeDilateErode", label="Dimmest Glint Around", inputs={"Size": -1})
    h.link(tree, glint_level, dimmest.inputs["Mask"])
    peak = h.math(tree, "MAXIMUM", brightest.outputs["Mask"], 1e-9, label="Brightest > 0")
    own_pixel = _ramp(tree, glint_level, peak.outputs[0], OWN_PIXEL_BAR, "Its Own Pixel")
    excess = h.math(tree, "SUBTRACT", glint_level, dimmest.outputs["Mask"], label="Over the Floor")
    over = h.math(tree, "MAXIMUM", excess.outputs[0], 0.0, label="Over the Floor ≥ 0")
    stands = _ramp(tree, over.outputs[0], ground, GATHER_BAR, "Stands Out")
    sparkle = h.math(tree, "MULTIPLY", grains.outputs[0], stands, label="Sparkle")
    # Alone: a sparkle's light falls within its 3x3 (the filter's arms, or the twin pixel of a grain
    # that straddles two), so the ring of 16 pixels round that 3x3 holds only the sand's sheen.
    # A silhouette's edge, where the sheen meets the sky, runs on through the ring; taken for
    # sparkles its pixels left notches along the crest (the fifteenth review). Against the eight
    # neighbours instead, a straddling grain's twin barred it and its arms stayed (the sixteenth).
    inner = h.math(tree, "MULTIPLY", _box_mean(tree, glint_level), 9.0, label="3x3 Glint Sum")
    outer = h.math(tree, "MULTIPLY", _box_mean(tree, glint_level, 2), 25.0, label="5x5 Glint Sum")
    ring = h.math(tree, "SUBTRACT", outer.outputs[0], inner.outputs[0], label="The Ring Round Its 3x3")
    their_mean = h.math(tree, "DIVIDE", ring.outputs[0], 16.0, label="The Ring's Mean")
    safe_mean = h.math(tree, "MAXIMUM", their_mean.outputs[0], 1e-9, label="The Ring's Mean > 0")
    alone = _ramp(tree, glint_level, safe_mean.outputs[0], ALONE_BAR, "Alone in Its 5x5")
    lone = h.math(tree, "MULTIPLY", sparkle.outputs[0], alone, label="A Lone Sparkle")
    core = h.math(tree, "MULTIPLY", lone.outputs[0], own_pixel, label="A Sparkle's Own Pixel")
    near = h.add_node(tree, "CompositorNodeDilateErode", label="Beside a Sparkle", inputs={"Size": 1})
    h.link(tree, core.outputs[0], near.inputs["Mask"])
    beside = h.math(tree, "SUBTRACT", 1.0, own_pixel, label="Not a Sparkle's Own")
    spread = h.math(tree, "MULTIPLY", near.outputs["Mask"], beside.outputs[0], label="Spread Round It")
    # The glint light over the floor, in colour: the glint light × its share over the floor.
    own_level = h.math(tree, "MAXIMUM", glint_level, 1e-9, label="Glint > 0")
    share = h.math(tree, "DIVIDE", over.outputs[0], own_level.outputs[0], label="Share Over the Floor")
    wanted = h.math(tree, "MULTIPLY", share.outputs[0], spread.outputs[0], label="Share to Take")
    # Never more than the pixel stands over the ground: the denoiser may have taken part of the
    # spread already (at Draft's 16 samples the arms came out as dark specks beside a sparkle).
    room = h.math(tree, "SUBTRACT", _luminance(tree, image), ground, label="Over the Ground")
    wanted_level = h.math(tree, "MULTIPLY", wanted.outputs[0], glint_level, label="Light to Take")
    safe_level = h.math(tree, "MAXIMUM", wanted_level.outputs[0], 1e-9, label="Light to Take > 0")
    fits = h.math(tree, "DIVIDE", room.outputs[0], safe_level.outputs[0], label="Room for It")
    capped = h.math(tree, "MINIMUM", fits.outputs[0], 1.0, label="At Most All of It")
    allowed = h.math(tree, "MAXIMUM", capped.outputs[0], 0.0, label="At Least None")
    taken_share = h.math(tree, "MULTIPLY", wanted.outputs[0], allowed.outputs[0], label="Share Taken")
    spilled = h.vector_math(tree, "SCALE", glint, label="Glint Light Spread")
    h.link(tree, taken_share.outputs[0], h.socket(spilled.inputs, "Scale"))
    # Shared among the sparkles beside it (their weights over their sum): one beside two is not
    # gathered twice.
    count = h.math(tree, "MULTIPLY", _box_mean(tree, core.outputs[0]), 9.0, label="Sparkles Beside")
    safe = h.math(tree, "MAXIMUM", count.outputs[0], 1e-6, label="Sparkles Beside > 0")
    each = h.math(tree, "DIVIDE", 1.0, safe.outputs[0], label="A Sparkle's Share")
    shared = h.vector_math(tree, "SCALE", spilled.outputs[0], label="Spread per Sparkle")
    h.link(tree, each.outputs[0], h.socket(shared.inputs, "Scale"))
    gathers = h.math(tree, "MULTIPLY", core.outputs[0], 9.0, label="× 9: the 3x3 Sum")
    back = h.vector_math(tree, "SCALE", _box_mean(tree, shared.outputs[0]), label="Gathered Back")
    h.link(tree, gathers.outputs[0], h.socket(back.inputs, "Scale"))
    taken = h.vector_math(tree, "SUBTRACT", image, spilled.outputs[0], label="Spread Taken Off")
    floor = h.vector_math(tree, "MAXIMUM", taken.outputs[0], (0.0, 0.0, 0.0), label="Not Below Black")
    return h.vector_math(tree, "ADD", floor.outputs[0], back.outputs[0], label="+ Gathered Back").outputs[0]


def _box_mean(tree, value, reach=1):
    """The mean over a square of 2 reach + 1 pixels a side: the Blur node's Flat filter of size
    reach (on 5.0 and 5.2)."""
    side = 2 * reach + 1
    mean = h.add_node(tree, "CompositorNodeBlur", label=f"{side}x{side} Mean",
                      inputs={"Type": "Flat", "Size": (reach, reach)})
    h.link(tree, value, mean.inputs["Image"])
    return mean.outputs["Image"]


def _glint_light(tree, layers):
    """The light the glinting grains send: glossy light where a grain was hit, and the emission
    in Emission mode. A grain's mirror is a Glossy closure on top of the sand."""
    glossy = h.vector_math(tree, "ADD", layers.outputs["Glossy Direct"], layers.outputs["Glossy Indirect"],
                           label="Glossy Light")
    # Cycles' light passes are divided by the closure colour: × Glossy Color gives the light seen.
    seen = h.vector_math(tree, "MULTIPLY", glossy.outputs[0], layers.outputs["Glossy Color"],
                         label="× Glossy Color")
    lit = h.vector_math(tree, "ADD", seen.outputs[0], layers.outputs["Emission"], label="+ Emission")
    return lit.outputs[0]


def _sparkle_weight(tree, layers, glint, clean):
    """How far each pixel sparkles, from the glints' light against the ground around it and what of
    the pixel survives the denoiser (and the glint light's level and the ground, for the gathering).

    The sand material writes where grains can glint into the AOV. OIDN takes a one-pixel sparkle
    for noise and smears it away, so the glint light stays raw; but only where it is a sparkle:
    the sand's own sheen and the facets that catch no sun are dim, and sampled raw they were the
    frame's noise. The ground is the darkest denoised pixel of the 3x3 around, not the rest of
    the raw pixel: a grain that covers most of a pixel leaves little rest, and its dim mirror was
    kept raw as a dark speck. Two ramps (SPARKLE_BAR, DENOISED_BAR), multiplied: the glint light
    alone let through dim grains a few samples caught, raw at two or three times their light in
    one seed and gone in the next. The denoiser takes such a spike out and keeps most of a
    sparkle many samples saw, so the denoised pixel must stand above the ground too. The bars
    were chosen from measured noise and sparkle light: README, "Denoising all but the glints".
    """
    grains = h.math(tree, "GREATER_THAN", layers.outputs[GLINT_AOV], 0.0, label="Glinting Grains Hit")
    glint_level = _luminance(tree, glint)
    # The darkest denoised pixel of the 3x3 around: the ground a sparkle sits on. Not the pixel
    # itself, which keeps most of a bright sparkle through the denoiser.
    clean_level = _luminance(tree, clean)
    around = h.add_node(tree, "CompositorNodeDilateErode", label="Darkest Around", inputs={"Size": -1})
    h.link(tree, clean_level, around.inputs["Mask"])
    ground = h.math(tree, "MAXIMUM", around.outputs["Mask"], 1e-6, label="Ground > 0")
    outshines = _ramp(tree, glint_level, ground.outputs[0], SPARKLE_BAR, "Outshines the Ground")
    # A grain that a few samples caught is a spike the denoiser takes out; one that many caught
    # stays above the ground in the denoised pixel too. Only the second is a sparkle to keep raw.
    survives = _ramp(tree, clean_level, ground.outputs[0], DENOISED_BAR, "Survives the Denoiser")
    both = h.math(tree, "MULTIPLY", outshines, survives, label="Outshines and Survives")
    weight = h.math(tree, "MULTIPLY", grains.outputs[0], both.outputs[0], label="Sparkle Weight")
    return weight.outputs[0], glint_level, ground.outputs[0]


def _ramp(tree, level, ground, bar, label):
    """0 where level / ground is at most bar[0], rising to 1 at bar[1]."""
    ratio = h.math(tree, "DIVIDE", level, ground, label=f"{label}: Ratio")
    ramp = h.add_node(tree, "ShaderNodeMapRange", label=label,
                      inputs={"From Min": bar[0], "From Max": bar[1], "To Min": 0.0, "To Max": 1.0})
    h.link(tree, ratio.outputs[0], ramp.inputs["Value"])
    return ramp.outputs["Result"]


def _luminance(tree, color):
    node = h.add_node(tree, "CompositorNodeRGBToBW", label="Luminance")
    h.link(tree, color, node.inputs[0])
    return node.outputs[0]
