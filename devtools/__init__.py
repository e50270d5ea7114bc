"""Developer tooling shared by tests, benchmarks and the demo script (not shipped)."""
