"""The bpy layer: registration, panels and data helpers shared by operators and panels."""
