"""Benchmark output: print the table, and append it to bench/RESULTS.md unless told not to."""

import pathlib

import numpy as np

RESULTS = pathlib.Path(__file__).resolve().parent.parent / "bench" / "RESULTS.md"


def publish(lines, append=True):
    text = "\n".join(lines) + "\n"
    print(text)
    if append:
        with open(RESULTS, "a") as results:
            results.write(text)


def display_rmse(pixels, reference, exposure):
    """RMSE of linear pixels clipped at the display's white (2^-exposure).

    A sun disc in frame is thousands of times brighter than white; unclipped, the noise of its
    sub-pixel coverage alone made the RMSE (128 at 64 spp in the demo).
    """
    white = 2.0 ** -exposure
    difference = np.minimum(np.asarray(pixels, np.float64), white) - np.minimum(reference, white)
    return float(np.sqrt(np.mean(difference ** 2)))
