"""Thin operators, one module per capability: poll() through base.SandscapeOperator, value
checks in execute() before anything changes, a call into the bpy layer (addon/), one report."""
