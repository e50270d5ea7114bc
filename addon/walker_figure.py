"""The stand-in walker's body and its cloth: one lathed surface from the poncho's hem to the hood's
peak (the traveller of seed 004, its arms under the cloth), a head in the hood, a scarf wrapped at
the neck whose tail streams behind, a band at the hem, and the three materials its body and
legs wear.

Materials are ours (MATERIAL_KEY "cloak", "walker_trim", "walker_wraps"), found in the walker's and
its limbs' slots, so Add Walker again keeps an artist's edits to them.
"""

import itertools

import bmesh
import bpy
import numpy as np
from mathutils import Matrix

from ..core import scarf
from ..node_groups import helper as h
from . import ownership as own
from . import walker_gait

HEIGHT = 1.7  # metres: a person-sized stand-in
# Linear base colours. A crimson cloak: the low sun's warm light turned the earlier reds burnt
# orange and brick on screen ((0.36, 0.03, 0.02) hue 17 degrees, (0.26, 0.012, 0.022) hue 15 to
# the fourth and seventh reviews); blue in the base keeps it crimson under that light, and some
# green keeps that channel off zero in the shaded frames (at 0.01 Draft clipped it, the eighth
# review).
CLOAK = (0.3, 0.035, 0.11, 1.0)
TRIM = (0.55, 0.3, 0.06, 1.0)  # the golden scarf and hem band of seed 004's traveller
WRAPS = (0.035, 0.025, 0.02, 1.0)  # dark cloth wound round the legs and hands
# A cloak from the neck to the shins over the arms, as the traveller's poncho of seed 004 (the sixth
# review: tube arms with ball hands out of bell sleeves, square shoulders and a trapezoid robe read
# as a garden gnome). Rings from the hem up, (height over the soles, radius, depth against width):
# the shoulders slope from the hood down to their points, the cloth falls from there, flaring.
ROBE = ((0.36, 0.37, 0.8), (0.8, 0.32, 0.77), (1.12, 0.275, 0.72), (1.29, 0.248, 0.68),
        (1.37, 0.226, 0.68), (1.42, 0.19, 0.72))
HEM, SHOULDERS = ROBE[0][0], 1.37  # metres over the soles: the hem, the shoulders' points
HEM_BAND = 0.04  # metres: the golden band's height over the hem (7 cm read as a plank, the eighth review)
# The cloth's folds: FOLDS round the robe, their depth a share of the radius at the hem, fading to
# nothing at the shoulders (a smooth cone with a straight hem read as stiff board; folds 12 % deep
# did not show, the red even across the hem, the eighth review).
FOLDS, FOLD_DEPTH = 8, 0.24
HEM_WAVE = 0.02  # metres the hem rises where a fold goes in
# The cloak darkens into a fold's trough by up to FOLD_SHADE of its colour, from a point attribute
# (1 in the deepest trough): with the low sun ahead the camera sees the robe's back in shade, lit by
# the sky alone, where twice as deep folds still did not show.
FOLD_ATTRIBUTE, FOLD_SHADE = "sandscape_fold", 0.55
# 9: the tail carries a flutter attribute (walker_flutter.py); 8: the scarf's tail streaming
# behind; 7: the hood shorter over a dark face, the scarf's tail
# across the back to one side, folds twice as deep, a narrower hem band; 6: a poncho over the arms
# with sloping shoulders and folds, the hood one smooth taper; 5: the robe down to the shins, the
# hood's peak tall and pointed; 4: a scarf and a hem band in gold, legs and hands wrapped dark; 3:
# the robe and a hood (2: the robe under a bare head on a neck; 1: a torso over the hips)
FIGURE_SHAPE_KEY, FIGURE_SHAPE = "sandscape_figure_shape", 9
HEAD = 0.11  # radius; its top at HEIGHT
HEAD_FORWARD = 0.035  # metres: the face fills the hood's opening, in the dark wraps (the hood's shadow)
# Above the robe, as its rings: a hood narrowing in one curve from the shoulders over the head to
# a tall peak that falls back, the traveller's of seed 004 (a neck narrowing under a rounded crown
# read as a cone on an egg; a short rounded peak, as a child's duffel hood; a peak 17 cm over the
# head, as a capirote, the eighth review).
HOOD = ((1.47, 0.145, 0.84), (1.53, 0.137, 0.94), (1.59, 0.134, 1.0), (1.65, 0.128, 1.0),
        (1.7, 0.113, 1.0), (1.74, 0.088, 1.0), (1.775, 0.052, 1.0), (1.8, 0.012, 1.0))
HOOD_FALL = 0.09  # metres the peak falls back
# The scarf's wrap at the neck, as (height over the soles, metres off the cloth under it: lower, on
# the shoulders, it read as a bar across them). Its tail streams from the nape behind the figure
# and to its left, as the traveller's does in the wind: TAIL_LENGTH along a heading TAIL_SWEEP
# radians off straight back, falling TAIL_DROP by its end, waving TAIL_WAVE (metres, up and down and
# sideways, growing to the end), TAIL_WIDTH (start, end) high, its end cut into two points (hanging
# down the middle it made a "T" with the wrap; glued diagonally across the back, a stiff sash, the
# eighth and ninth reviews).
COLLAR = ((1.45, 0.02), (1.5, 0.016))
TAIL_START = 1.475  # metres over the soles: the tail leaves the wrap at the nape
TAIL_LENGTH, TAIL_SWEEP, TAIL_DROP, TAIL_WAVE = 0.85, 0.75, 0.3, 0.06
# How freely each point of the tail flutters (walker_flutter.py): 0 at the nape, 1 at the end.
FLUTTER_ATTRIBUTE, FLUTTER_GROWTH = scarf.FLUTTER_ATTRIBUTE, scarf.FLUTTER_GROWTH
TAIL_WIDTH = (0.09, 0.06)
ROBE_SEGMENTS = 32
CLOAK_SLOT, TRIM_SLOT, FACE_SLOT = 0, 1, 2  # the body's material slots


def profile():
    """The body's rings from the hem up: (height over the soles, radius, depth against width)."""
    (hem, hem_radius, depth_share), (above, above_radius, _) = ROBE[:2]
    band = hem_radius + (above_radius - hem_radius) * HEM_BAND / (above - hem)
    return [ROBE[0], (hem + HEM_BAND, band, depth_share), *ROBE[1:], *HOOD]


def section(heights):
    """The cloth's elliptic section at `heights` (metres over the soles), its folds aside: (radius,
    depth against width)."""
    at, radii, depths = np.array(profile()).T
    return np.interp(heights, at, radii), np.interp(heights, at, depths)


def fold_depth(heights):
    """How far in (a share of the radius) the folds reach at `heights`: deepest at the hem."""
    return FOLD_DEPTH * fold_reach(heights)


def fold_reach(heights):
    """How far the folds have formed at `heights`: 1 at the hem, 0 at the shoulders (their points),
    where the cloth hangs from."""
    return np.clip((SHOULDERS - np.asarray(heights)) / (SHOULDERS - HEM), 0.0, 1.0)


def fold_trough(turn):
    """How far into a fold's trough the cloth is at `turn` (radians round the figure): 0 on a crest
    (one at the back), 1 in a trough."""
    return (1.0 - np.cos(FOLDS * turn)) / 2


def _ring_points(height, radius, depth, turn, folds=False):
    fall_from, peak = HOOD[-3][0], HOOD[-1][0]  # above the head's top the hood falls back
    fall = HOOD_FALL * max(0.0, (height - fall_from) / (peak - fall_from))
    trough = fold_trough(turn) if folds else np.zeros_like(turn)
    radius = radius * (1.0 - fold_depth(height) * trough)
    lift = HEM_WAVE * trough * (height <= HEM + HEM_BAND + 1e-9)  # the hem and its band rise in a fold
    return np.stack([depth * radius * np.cos(turn) - fall, radius * np.sin(turn), height + lift])


def _lathe(bm, rings_at, material, close_bottom=False, close_top=False, folds=False):
    turn = np.linspace(0.0, 2 * np.pi, ROBE_SEGMENTS, endpoint=False)
    if folds:  # a new layer first: adding one invalidates the verts made before it
        layer = bm.verts.layers.float.get(FOLD_ATTRIBUTE) or bm.verts.layers.float.new(FOLD_ATTRIBUTE)
    rings = [[bm.verts.new(p) for p in _ring_points(*ring, turn, folds).T] for ring in rings_at]
    if folds:
        for ring, verts in zip(rings_at, rings, strict=True):
            shade = np.sqrt(fold_reach(ring[0])) * fold_trough(turn)
            for vert, value in zip(verts, shade, strict=True):
                vert[layer] = value
    faces = [bm.faces.new(rings[0][::-1])] if close_bottom else []
    for low, high in itertools.pairwise(rings):
        for i in range(ROBE_SEGMENTS):
            j = (i + 1) % ROBE_SEGMENTS
            faces.append(bm.faces.new((low[i], low[j], high[j], high[i])))
    if close_top:
        faces.append(bm.faces.new(rings[-1]))
    for face, index in zip(faces, material, strict=True):
        face.material_index = index


TAIL_HEADING = np.array([-np.cos(TAIL_SWEEP), np.sin(TAIL_SWEEP), 0.0])  # level, behind and left


def tail_centre(t):
    """The tail's centre line at `t` (0 at the nape, 1 at its end): (x, y, z) in the figure's space."""
    t = np.asarray(t, float)
    radius, depth = section(TAIL_START)
    heading = TAIL_HEADING
    aside = np.array([heading[1], -heading[0]])  # across the heading, level
    along = TAIL_LENGTH * t
    wave = TAIL_WAVE * t * np.sin(2.5 * np.pi * t)
    x = -(depth * radius + COLLAR[0][1]) + along * heading[0] + wave * aside[0]
    y = along * heading[1] + wave * aside[1]
    z = TAIL_START - TAIL_DROP * t ** 1.5 + TAIL_WAVE * t * np.sin(3.0 * np.pi * t + 1.0)
    return np.stack([x, y, z])


def _tail(bm):
    """The scarf's tail: a ribbon of rows streaming from the nape, its width upright (as a flag's in
    the wind), three points across."""
    steps = np.linspace(0.0, 1.0, 16)
    centres = tail_centre(steps)
    flutter = bm.verts.layers.float[FLUTTER_ATTRIBUTE]
    rows = []
    for row, t in enumerate(steps):
        half = (TAIL_WIDTH[0] + (TAIL_WIDTH[1] - TAIL_WIDTH[0]) * t) / 2
        points = centres[:, row, None] + np.outer([0.0, 0.0, 1.0], [-half, 0.0, half])
        if row == len(steps) - 1:
            points[:, 1] -= 0.06 * TAIL_HEADING  # the end's middle falls back: two points
        rows.append([bm.verts.new(p) for p in points.T])
        for vert in rows[-1]:
            vert[flutter] = t ** FLUTTER_GROWTH  # held at the nape, free at the end
    for upper, lower in itertools.pairwise(rows):
        for k in range(2):
            bm.faces.new((upper[k], upper[k + 1], lower[k + 1], lower[k])).material_index = TRIM_SLOT


def figure_mesh(scale):
    """A low-poly figure's body standing on its origin facing +X: a folded poncho over the arms,
    broader across than deep, with a golden band at its hem, whose shoulders slope into a peaked
    hood; a head in the dark wraps; a scarf at the neck with its tail streaming behind (its legs are
    walker_gait's, swinging inside the robe, the shins showing below it). `scale`: scene units per
    metre. Slots: cloak, trim, face."""
    bm = bmesh.new()
    bm.verts.layers.float.new(FLUTTER_ATTRIBUTE)  # before any vertex (zero off the tail)
    rings = profile()
    bands = [TRIM_SLOT] * ROBE_SEGMENTS + [CLOAK_SLOT] * (ROBE_SEGMENTS * (len(rings) - 2))
    _lathe(bm, rings, [CLOAK_SLOT, *bands, CLOAK_SLOT], close_bottom=True, close_top=True, folds=True)
    heights, lifts = np.array(COLLAR).T
    radii, depths = section(heights)
    collar = zip(heights, radii + lifts, depths, strict=True)
    _lathe(bm, collar, [TRIM_SLOT] * (ROBE_SEGMENTS * (len(COLLAR) - 1)))
    _tail(bm)
    head = bmesh.ops.create_uvsphere(bm, u_segments=12, v_segments=8, radius=HEAD,
                                     matrix=Matrix.Translation((HEAD_FORWARD, 0.0, HEIGHT - HEAD)))
    for face in {face for vert in head["verts"] for face in vert.link_faces}:
        face.material_index = FACE_SLOT
    walker_gait.shade_smooth_but_edges(bm)
    bmesh.ops.scale(bm, vec=(scale, scale, scale), verts=bm.verts)
    mesh = bpy.data.meshes.new("Sandscape Walker")
    bm.to_mesh(mesh)
    bm.free()
    return mesh


# kind: (name, linear base colour, roughness). No sheen: it paled the cloak and rimmed nothing against
# a low sun ahead (README, the fourth review).
MATERIALS = {own.CLOAK: ("Sandscape Walker Cloak", CLOAK, 0.8),
             own.CLOAK_TRIM: ("Sandscape Walker Trim", TRIM, 0.55),
             own.WRAPS: ("Sandscape Walker Wraps", WRAPS, 0.9)}


def _new_material(kind):
    name, colour, roughness = MATERIALS[kind]
    material = own.mark(bpy.data.materials.new(name), own.MATERIAL_KEY, kind)
    material.diffuse_color = colour
    tree = material.node_tree
    nodes = tree.nodes if tree else ()
    shader = next((n for n in nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"), None)
    if shader is not None:
        shader.inputs["Base Color"].default_value = colour
        shader.inputs["Roughness"].default_value = roughness
        if kind == own.CLOAK:
            _shade_folds(tree, shader, colour)
    return material


def _shade_folds(tree, shader, colour):
    """The cloak's colour darkened into its folds' troughs (FOLD_ATTRIBUTE): the artist recolours
    the cloak on the Mix node's A."""
    fold = h.add_node(tree, "ShaderNodeAttribute", (shader.location.x - 400, shader.location.y - 200),
                      label="Fold Trough", attribute_name=FOLD_ATTRIBUTE)
    shade = h.add_node(tree, "ShaderNodeMix", (shader.location.x - 200, shader.location.y),
                       label="Cloak Colour", data_type="RGBA", blend_type="MULTIPLY")
    h.socket(shade.inputs, "A").default_value = colour
    h.socket(shade.inputs, "B").default_value = (1.0 - FOLD_SHADE,) * 3 + (1.0,)
    h.link(tree, fold.outputs["Fac"], h.socket(shade.inputs, "Factor"))
    h.link(tree, h.socket(shade.outputs, "Result"), shader.inputs["Base Color"])


def add_fold_shading(material):
    """A cloak made before its folds were shaded gets the shading, in the colour it has now (its
    Principled Base Color goes to the Mix node's A); one whose Base Color the artist linked (a
    texture) is left as it is. Returns True when added."""
    tree = material.node_tree
    if tree is None or any(n.bl_idname == "ShaderNodeAttribute" and n.attribute_name == FOLD_ATTRIBUTE
                           for n in tree.nodes):
        return False
    shader = next((n for n in tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"), None)
    if shader is None or shader.inputs["Base Color"].is_linked:
        return False
    _shade_folds(tree, shader, tuple(shader.inputs["Base Color"].default_value))
    return True


class Cloth(dict):
    """{kind: material} for a figure: ours found in the walker's and its limbs' slots; a kind not
    found is made when first asked for (none is made that nothing wears)."""

    def __init__(self, walker):
        super().__init__()
        for obj in (walker, *walker.children_recursive):
            for kind in MATERIALS:
                if kind not in self and (found := own.slot_material(obj, kind)) is not None:
                    self[kind] = found

    def __missing__(self, kind):
        self[kind] = material = _new_material(kind)
        return material


def dress(walker, cloth):
    """Give the body's new mesh its slots: cloak, trim, face (`cloth`: a Cloth). Appended to a mesh
    without any: clearing a mesh's slots clears its faces' material indices too."""
    for kind in (own.CLOAK, own.CLOAK_TRIM, own.WRAPS):
        walker.data.materials.append(cloth[kind])
