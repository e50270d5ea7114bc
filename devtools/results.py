"""Benchmark output: print the table, and append it to bench/RESULTS.md unless told not to."""

import pathlib

RESULTS = pathlib.Path(__file__).resolve().parent.parent / "bench" / "RESULTS.md"


def publish(lines, append=True):
    text = "\n".join(lines) + "\n"
    print(text)
    if append:
        with open(RESULTS, "a") as results:
            results.write(text)
