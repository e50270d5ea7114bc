"""The bpy layer: all scene logic, one module per capability (sand, walker, footprints,
atmosphere, post, optimize, presets, demo), plus ownership (what is ours, found per scene)
and compat (where Blender 5.0 and 5.2 differ). Builds on core/ and node_groups/; never calls
bpy.ops.sandscape.*."""
