"""Pure numpy, no bpy or mathutils (a test enforces this): the footprint painter and walk
planner, dunes, the atmosphere's physics, and a numpy twin of every node group (glints, post
effects, footprint height, region cut) that the tests hold Blender's output against."""
