"""Thin operators, one module per capability: validate, call a builder or core, report."""
