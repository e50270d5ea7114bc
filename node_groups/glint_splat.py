"""Sandscape Glint Splat: each sparkle of the pixel-sized cells put into the pixels round its point,
the same for every sample of a pixel, so glint pixels converge as fast as the sand around them.

A cell's sparkle is a point on the surface, jittered round its lattice point (on a lattice of the
object's plane the normal leans least from) so sparkles scatter rather than line up; the pixel it
falls in takes its light, shared with the next pixels near its edge by a smoothstep (their shares sum
to one, so a sparkle moving across the screen glides rather than jumps). Every sample of a pixel
finds the same cells and shares: the pixel's centre is found on the tangent plane from the Window
coordinate, and the screen offset of a cell's point from it by the pixel's footprint (the derivatives
of the surface point across the screen). Cells are large enough for the pixel's reach and the jitter
that at most two per axis have a point that can fall in the pixel: four candidates. A cell glints as
Sandscape Glint Cells' cells do (one of its grains would) and is mirror over its grains' share, but
no more than a whole pixel of it.
Inactive (no render camera, a panoramic one, or no resolution): Sandscape Lit Glints falls back to
the cells. Twin: core.glint_splat.
"""

from ..core import glint_splat as twin
from ..core import glints as cells_twin
from . import glint_cells
from . import helper as h

NAME = "Sandscape Glint Splat"
VERSION = 4
TREE_TYPE = "ShaderNodeTree"
DESCRIPTION = ("Sparkles as points put into the pixels round them, the same for every sample of a pixel: "
               "the four cells that can reach this pixel, their noise, tilt and share of it")
CANDIDATES = twin.CANDIDATES
MAX_PIXELS = 1e6  # bounds for driven inputs typed by hand: a pixel's angle (radians), ortho size (units)
MAX_PIXEL_SIZE = 1e6

INPUTS = {  # name -> (type, description, default, min, max, subtype); append only
    **{name: glint_cells.INPUTS[name] for name in ("Glint Size", "Seed", "Threshold", "Pixel Angle",
                                                   "Pixel Size")},
    "Resolution X": ("NodeSocketFloat", "Pixels across the render (driven from the scene)",
                     0.0, 0.0, None, None),
    "Resolution Y": ("NodeSocketFloat", "Pixels up the render (driven from the scene)", 0.0, 0.0, None, None),
}
OUTPUTS = {
    "Active": ("NodeSocketFloat", "1 where the render camera's pixel is known (the splat applies)"),
    "Threshold": ("NodeSocketFloat", "Noise above this sparkles at the cells' level"),
    **{f"Noise {k}": ("NodeSocketFloat", f"Candidate {k}'s random value") for k in CANDIDATES},
    **{f"Tilt {k}": ("NodeSocketColor", f"Candidate {k}'s random colour: which way its facet leans")
       for k in CANDIDATES},
    **{f"Amount {k}": ("NodeSocketFloat", f"Share of the pixel that is candidate {k}'s mirror (0 unless "
                       "it glints and reaches this pixel)") for k in CANDIDATES},
}


class _Nodes:
    """Math shorthands that keep the nodes for the frames."""

    def __init__(self, tree):
        self.tree, self.made = tree, []

    def take(self):
        made, self.made = self.made, []
        return made

    def m(self, operation, a=None, b=None, label=None, c=None):
        node = h.math(self.tree, operation, a, b, label=label, c=c)
        self.made.append(node)
        return node.outputs[0]

    def v(self, operation, a=None, b=None, label=None, c=None, **inputs):
        node = h.vector_math(self.tree, operation, a, b, label=label, c=c, **inputs)
        self.made.append(node)
        return node.outputs["Value" if operation in ("DOT_PRODUCT", "LENGTH", "DISTANCE") else "Vector"]

    def node(self, node_type, label=None, **props):
        node = h.add_node(self.tree, node_type, label=label, **props)
        self.made.append(node)
        return node

    def xyz(self, vector, label):
        split = self.node("ShaderNodeSeparateXYZ", label=label)
        h.link(self.tree, vector, split.inputs[0])
        return split.outputs

    def combine(self, x, y, z, label):
        node = self.node("ShaderNodeCombineXYZ", label=label)
        for index, value in enumerate((x, y, z)):
            if isinstance(value, float):
                node.inputs[index].default_value = value
            else:
                h.link(self.tree, value, node.inputs[index])
        return node.outputs[0]


def _pixel_centre(n, inputs):
    """The pixel centre's point on the tangent plane and the derivatives across the screen, in
    camera space (x right, y up, z forward, as Cycles gives it)."""
    tree = n.tree
    coords = n.node("ShaderNodeTexCoord", label="Camera and Window")
    geometry = n.node("ShaderNodeNewGeometry")
    normal = n.node("ShaderNodeVectorTransform", label="Normal in Camera Space", vector_type="NORMAL",
                    convert_from="WORLD", convert_to="CAMERA")
    h.link(tree, geometry.outputs["Normal"], normal.inputs[0])
    window = n.xyz(coords.outputs["Window"], "Window")
    point = coords.outputs["Camera"]
    px = n.xyz(point, "Point")
    # Offset of the sample from its pixel's centre, in pixels.
    offsets = []
    for axis, resolution in ((0, inputs["Resolution X"]), (1, inputs["Resolution Y"])):
        pixel = n.m("MULTIPLY", window[axis], resolution, label="Pixel Coordinate")
        whole = n.m("FLOOR", pixel, label="Pixel")
        inside = n.m("SUBTRACT", pixel, whole, label="In the Pixel")
        offsets.append(n.m("SUBTRACT", inside, 0.5, label="From the Centre"))
    perspective = n.m("GREATER_THAN", inputs["Pixel Angle"], 0.0, label="Perspective")
    ortho = n.m("SUBTRACT", 1.0, perspective, label="Orthographic")
    depth = n.m("MAXIMUM", px[2], twin.MIN_DEPTH, label="Depth > 0")
    # Perspective: the centre's ray at unit depth; orthographic: along z from the centre's origin.
    ray = []
    origin = []
    for axis in (0, 1):
        slope = n.m("DIVIDE", px[axis], depth, label="x / z" if axis == 0 else "y / z")
        back = n.m("MULTIPLY", offsets[axis], inputs["Pixel Angle"], label="Offset × Pixel Angle")
        ray.append(n.m("MULTIPLY", n.m("SUBTRACT", slope, back), perspective, label="Centre's Ray"))
        back_ortho = n.m("MULTIPLY", offsets[axis], inputs["Pixel Size"], label="Offset × Pixel Size")
        origin.append(n.m("MULTIPLY", n.m("SUBTRACT", px[axis], back_ortho), ortho, label="Centre's Origin"))
    direction = n.combine(ray[0], ray[1], 1.0, "Ray")
    start = n.combine(origin[0], origin[1], 0.0, "Origin")
    normal_c = normal.outputs[0]
    facing = n.v("DOT_PRODUCT", normal_c, direction, label="N·Ray")
    # A grazing ray: keep its sign, bound its size (the level then tops out).
    behind = n.m("LESS_THAN", facing, 0.0, label="Facing Away")
    size = n.m("MAXIMUM", n.m("ABSOLUTE", facing), twin.MIN_FACING, label="|N·Ray| ≥ Limit")
    signed = n.m("MULTIPLY", size, n.m("MULTIPLY_ADD", behind, -2.0, c=1.0), label="N·Ray, Bounded")
    reach = n.v("DOT_PRODUCT", normal_c, n.v("SUBTRACT", point, start), label="N·(P − Origin)")
    distance = n.m("DIVIDE", reach, signed, label="Along the Ray")
    centre = n.v("MULTIPLY_ADD", direction, n.combine(distance, distance, distance, "t"), c=start,
                 label="Pixel Centre")
    # d(point)/d(pixel) = pitch (e − ray (N·e) / (N·ray)); pitch = t × angle, or the ortho pixel.
    pitch = n.m("MULTIPLY_ADD", distance, inputs["Pixel Angle"], c=inputs["Pixel Size"], label="Pitch")
    normal_xyz = n.xyz(normal_c, "Normal")
    steps = []
    for axis, unit in ((0, (1.0, 0.0, 0.0)), (1, (0.0, 1.0, 0.0))):
        lean = n.m("DIVIDE", normal_xyz[axis], signed, label="N·e / N·Ray")
        along = n.v("SCALE", direction, label="Ray × Lean")
        h.link(tree, lean, along.node.inputs["Scale"])
        step = n.v("SUBTRACT", unit, along, label="e − Ray × Lean")
        scaled = n.v("SCALE", step, label="× Pitch")
        h.link(tree, pitch, scaled.node.inputs["Scale"])
        steps.append(scaled)
    return centre, steps, n.take()


def build(tree):
    tree.description = DESCRIPTION
    h.add_sockets(tree, INPUTS, INPUTS, OUTPUTS)
    group_in, group_out = h.group_io(tree)
    n = _Nodes(tree)
    inputs = {socket.name: socket for socket in group_in.outputs if socket.name}
    for name, top in (("Resolution X", MAX_PIXELS), ("Resolution Y", MAX_PIXELS), ("Pixel Angle", 1.0),
                      ("Pixel Size", MAX_PIXEL_SIZE)):
        inputs[name], bounds = h.finite(tree, inputs[name], top, f"{name}, Finite")
        n.made += bounds
    centre_c, steps_c, centre_nodes = _pixel_centre(n, inputs)

    # To the object's space, on the lattice of the plane the normal leans least from.
    to_object = []
    for vector, kind in ((centre_c, "POINT"), (steps_c[0], "VECTOR"), (steps_c[1], "VECTOR")):
        node = n.node("ShaderNodeVectorTransform", label="To the Object", vector_type=kind,
                      convert_from="CAMERA", convert_to="OBJECT")
        h.link(tree, vector, node.inputs[0])
        to_object.append(node.outputs[0])
    geometry = n.node("ShaderNodeNewGeometry")
    normal_o = n.node("ShaderNodeVectorTransform", label="Normal in Object Space", vector_type="NORMAL",
                      convert_from="WORLD", convert_to="OBJECT")
    h.link(tree, geometry.outputs["Normal"], normal_o.inputs[0])
    unit = n.v("NORMALIZE", normal_o.outputs[0])
    lean = n.xyz(n.v("ABSOLUTE", unit), "|Normal|")
    below_z = n.m("LESS_THAN", lean[2], n.m("MAXIMUM", lean[0], lean[1]))
    z_up = n.m("SUBTRACT", 1.0, below_z, label="Lattice ⟂ Z")
    x_over_y = n.m("SUBTRACT", 1.0, n.m("LESS_THAN", lean[0], lean[1]))
    x_up = n.m("MULTIPLY", n.m("SUBTRACT", 1.0, z_up), x_over_y, label="Lattice ⟂ X")
    y_up = n.m("SUBTRACT", n.m("SUBTRACT", 1.0, z_up), x_up, label="Lattice ⟂ Y")
    pick_a = n.combine(z_up, x_up, y_up, "First Axis")  # z: x, x: y, y: z
    pick_b = n.combine(y_up, z_up, x_up, "Second Axis")  # z: y, x: z, y: x
    pick_n = n.combine(x_up, y_up, z_up, "Normal Axis")
    plane = []
    for vector in to_object:
        plane.append((n.v("DOT_PRODUCT", vector, pick_a), n.v("DOT_PRODUCT", vector, pick_b)))
    (ca, cb), (ua, ub), (va, vb) = plane
    rise = n.v("DOT_PRODUCT", n.v("ABSOLUTE", unit), pick_n, label="|Normal| on Its Axis")
    axis_code = n.m("MULTIPLY_ADD", y_up, 2.0, c=x_up, label="Axis Code")
    frame_nodes = [*n.take(), geometry]

    # Level: cells at least CELL_REACH x the pixel's reach (one pixel each way) on each lattice axis,
    # so a cell's jittered point reaches the pixel only from the two nearest cells per axis.
    reach_a = n.m("ADD", n.m("ABSOLUTE", ua), n.m("ABSOLUTE", va), label="Reach A")
    reach_b = n.m("ADD", n.m("ABSOLUTE", ub), n.m("ABSOLUTE", vb), label="Reach B")
    reach = n.m("MAXIMUM", reach_a, reach_b, label="Reach")
    log = n.m("LOGARITHM", n.m("DIVIDE", n.m("MULTIPLY", reach, twin.CELL_REACH), inputs["Glint Size"]), 2.0,
              label="log2(Cell Reach / Size)")
    level = n.m("MINIMUM", n.m("MAXIMUM", n.m("CEIL", log), float(cells_twin.LEVELS[0])),
                float(cells_twin.LEVELS[1]), label="Level")
    cell = n.m("MULTIPLY", n.m("POWER", 2.0, level), inputs["Glint Size"], label="Cell Size")
    grains = n.m("POWER", 4.0, level, label="Grains per Cell")
    coarse = n.m("POWER", inputs["Threshold"], grains, label="Threshold^Grains")
    below = n.m("SUBTRACT", inputs["Threshold"], 1.0)
    fine = n.m("MULTIPLY_ADD", grains, below, c=1.0, label="1 − Grains × Share")
    threshold = n.m("MAXIMUM", coarse, fine, label="Threshold of the Level")
    share = n.m("DIVIDE", n.m("SUBTRACT", 1.0, inputs["Threshold"]), n.m("SUBTRACT", 1.0, threshold),
                label="Mirror Share of a Cell")
    pixel_area = n.v("LENGTH", n.v("CROSS_PRODUCT", to_object[1], to_object[2]), label="Pixel's Area")
    cell_area = n.m("DIVIDE", n.m("MULTIPLY", cell, cell), n.m("MAXIMUM", rise, 1e-6), label="Cell's Area")
    mirror = n.m("DIVIDE", n.m("MULTIPLY", share, cell_area), pixel_area, label="Mirror / Pixel")
    mirror = n.m("MINIMUM", mirror, 1.0, label="At Most a Pixel")
    det = n.m("SUBTRACT", n.m("MULTIPLY", ua, vb), n.m("MULTIPLY", ub, va), label="Det")
    det = n.m("ADD", det, n.m("MULTIPLY", n.m("COMPARE", det, 0.0, c=0.0), 1e-30), label="Det ≠ 0")
    spread = n.m("MULTIPLY", cell, twin.JITTER / 2, label="Jitter Each Way")
    lowest = [n.m("SUBTRACT", n.m("MULTIPLY_ADD", far, -twin.TENT_REACH, c=at), spread, label="Lowest Reach")
              for at, far in ((ca, reach_a), (cb, reach_b))]
    starts = [n.m("ADD", n.m("FLOOR", n.m("DIVIDE", low, cell)), 1.0, label="First Cell") for low in lowest]
    seed = n.m("MULTIPLY_ADD", level, cells_twin.LEVEL_SEED, c=inputs["Seed"], label="Seed of the Level")
    jitter_seed = n.m("ADD", seed, twin.JITTER_SEED, label="Seed of the Jitter")
    resolution = n.m("MINIMUM", inputs["Resolution X"], inputs["Resolution Y"])
    pixel = n.m("MAXIMUM", inputs["Pixel Angle"], inputs["Pixel Size"])
    active = n.m("MULTIPLY", n.m("GREATER_THAN", resolution, 0.0), n.m("GREATER_THAN", pixel, 0.0),
                 label="Active")
    level_nodes = n.take()

    raw, noises, candidate_nodes = [], [], []
    for k, (di, dj) in zip(CANDIDATES, twin.OFFSETS, strict=True):
        i = n.m("ADD", starts[0], float(di), label=f"Cell {k} A")
        j = n.m("ADD", starts[1], float(dj), label=f"Cell {k} B")
        cell_vector = n.combine(i, j, axis_code, "Cell")
        jitter = n.node("ShaderNodeTexWhiteNoise", label=f"Jitter {k}", noise_dimensions="4D")
        h.link(tree, cell_vector, jitter.inputs["Vector"])
        h.link(tree, jitter_seed, jitter.inputs["W"])
        jitter_parts = n.node("ShaderNodeSeparateColor")
        h.link(tree, jitter.outputs["Color"], jitter_parts.inputs["Color"])
        points = [n.m("MULTIPLY_ADD", n.m("SUBTRACT", jitter_parts.outputs[c], 0.5), twin.JITTER, c=index,
                      label="Jittered Point") for c, index in ((0, i), (1, j))]
        offsets = [n.m("SUBTRACT", n.m("MULTIPLY", point, cell), at, label="From the Centre")
                   for point, at in ((points[0], ca), (points[1], cb))]
        across = n.m("SUBTRACT", n.m("MULTIPLY", offsets[0], vb), n.m("MULTIPLY", offsets[1], va))
        du = n.m("DIVIDE", across, det, label="Pixels Across")
        up = n.m("SUBTRACT", n.m("MULTIPLY", ua, offsets[1]), n.m("MULTIPLY", ub, offsets[0]))
        dv = n.m("DIVIDE", up, det, label="Pixels Up")
        tents = []
        for offset in (du, dv):
            tent = n.node("ShaderNodeMapRange", label="Tent", interpolation_type="SMOOTHSTEP", clamp=True)
            h.link(tree, n.m("ABSOLUTE", offset), tent.inputs["Value"])
            tent.inputs["From Min"].default_value = 0.5 - twin.SHARE_WIDTH / 2
            tent.inputs["From Max"].default_value = 0.5 + twin.SHARE_WIDTH / 2
            tent.inputs["To Min"].default_value, tent.inputs["To Max"].default_value = 1.0, 0.0
            tents.append(tent.outputs["Result"])
        noise = n.node("ShaderNodeTexWhiteNoise", label=f"Noise {k}", noise_dimensions="4D")
        h.link(tree, cell_vector, noise.inputs["Vector"])
        h.link(tree, seed, noise.inputs["W"])
        lit = n.m("GREATER_THAN", noise.outputs["Value"], threshold, label="Can Glint")
        share_k = n.m("MULTIPLY", n.m("MULTIPLY", tents[0], tents[1]), n.m("MULTIPLY", lit, mirror),
                      label=f"Share {k}")
        raw.append(share_k)
        noises.append(noise)
        candidate_nodes.append(n.take())
    total = raw[0]
    for share_k in raw[1:]:
        total = n.m("ADD", total, share_k, label="Total")
    scale = n.m("DIVIDE", active, n.m("MAXIMUM", total, 1.0), label="At Most the Pixel")
    for k, share_k, noise in zip(CANDIDATES, raw, noises, strict=True):
        h.link(tree, n.m("MULTIPLY", share_k, scale, label=f"Amount {k}"), group_out.inputs[f"Amount {k}"])
        h.link(tree, noise.outputs["Value"], group_out.inputs[f"Noise {k}"])
        h.link(tree, noise.outputs["Color"], group_out.inputs[f"Tilt {k}"])
    h.link(tree, active, group_out.inputs["Active"])
    h.link(tree, threshold, group_out.inputs["Threshold"])
    h.frame(tree, "The Pixel's Centre and Footprint", centre_nodes)
    h.frame(tree, "On the Object's Lattice", frame_nodes)
    h.frame(tree, "Level, Threshold and Mirror", level_nodes)
    for k, nodes in zip(CANDIDATES, candidate_nodes, strict=True):
        h.frame(tree, f"Candidate {k}", nodes)
    h.frame(tree, "Shares", n.take())
    h.arrange(tree)
