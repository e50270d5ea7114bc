"""Developer tooling, not shipped: an isolated Blender session with the working tree installed,
bake and render read-back, test scenes, operator stand-ins, snapshots of node groups, the
benchmarks' output, the demo script and the command line."""
