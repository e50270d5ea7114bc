"""Every node group Sandscape builds, in one table: the node editors' Add menus, the snapshot
tests and the README read it (Molecular Nodes' node_info table is the model).

Each entry: the builder, and the Add-menu category an artist finds it under (None for
groups that only Sandscape itself wires up). The editor follows from the builder's TREE_TYPE.
"""

from . import (
    cloud_density,
    dust_field,
    dust_volume,
    eevee_balance,
    footprint_height,
    gated_blur,
    glint_cells,
    glint_facet,
    glint_shade,
    glint_splat,
    glints,
    god_rays,
    journey_sand,
    lit_glints,
    physical_sand,
    print_markers,
    region_cut,
    ripple_defects,
    ripples,
    sand_normal,
    scarf_wind,
    sun_place,
    texel_blend,
    texel_corners,
    weather_map,
)

GROUPS = (
    (physical_sand, "Sand"),
    (journey_sand, "Sand"),
    (lit_glints, "Sand"),
    (glint_facet, "Sand"),
    (glints, "Sand"),
    (glint_shade, "Sand"),
    (glint_cells, "Sand"),
    (glint_splat, "Sand"),
    (sand_normal, "Sand"),
    (ripples, "Sand"),
    (ripple_defects, None),
    (footprint_height, "Footprints"),
    (dust_volume, "Atmosphere"),
    (dust_field, "Atmosphere"),
    (cloud_density, "Clouds"),
    (weather_map, "Clouds"),
    (cloud_density.GEOMETRY, "Clouds"),
    (weather_map.GEOMETRY, "Clouds"),
    (gated_blur, "Post Effects"),
    (god_rays, "Post Effects"),
    (sun_place, "Post Effects"),
    (region_cut, None),
    (print_markers, None),
    (scarf_wind, None),
    (texel_corners, None),
    (texel_blend, None),
    (eevee_balance, None),
)


def builders():
    return [builder for builder, _ in GROUPS]


def menu_entries(tree_type):
    """(category, builder) for the groups an artist can add in an editor of this tree type."""
    return [(category, builder) for builder, category in GROUPS
            if category is not None and builder.TREE_TYPE == tree_type]


def builder_named(name):
    return next((builder for builder in builders() if builder.NAME == name), None)
