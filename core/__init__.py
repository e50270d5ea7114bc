"""Pure numpy logic: no bpy, no mathutils (a test enforces this)."""
