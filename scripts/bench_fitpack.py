#!/usr/bin/env python3
"""FITPACK peer of the sjp10 fit row of tests/bench/bench_pht.c
(`sjp10_fit_convex`): the bicubic interpolant (scipy RectBivariateSpline,
s = 0, not-a-knot ends) of exact signed distances on an n x n grid of the
unit square, its fit time and its error off the medial band.

    bench_fitpack.py --dir D --ns 101,151,... [--reps 3]

The bench writes, in D (raw little-endian float64, no header):
  val.bin       the validation points off the medial band, rows (x, y, d):
                d the exact signed distance (negative inside);
  grid_<n>.bin  for each n, the exact distance at the nodes (i, j) / (n - 1),
                i along x fastest: value (x_i, y_j) at index j n + i.
The samples' cost (the exact distances) is the bench's to charge: it times
them itself.  For each n this prints
  n <n> fit <CPU seconds of the fit, best of --reps> off_max <max |s - d|
  over val.bin's points> coefficients <stored coefficients>
and nothing else on success."""
import argparse
import os
import sys
import time

import numpy as np
from scipy.interpolate import RectBivariateSpline


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    ap.add_argument("--ns", required=True)
    ap.add_argument("--reps", type=int, default=3)
    a = ap.parse_args()
    val = np.fromfile(os.path.join(a.dir, "val.bin"), dtype="<f8")
    if val.size == 0 or val.size % 3:
        print(f"bench_fitpack: {a.dir}/val.bin: expected rows of 3 doubles", file=sys.stderr)
        return 2
    val = val.reshape(-1, 3)
    for n in (int(s) for s in a.ns.split(",")):
        z = np.fromfile(os.path.join(a.dir, f"grid_{n}.bin"), dtype="<f8")
        if z.size != n * n:
            print(f"bench_fitpack: grid_{n}.bin: expected {n * n} doubles", file=sys.stderr)
            return 2
        z = z.reshape(n, n).T  # z[i, j] = value at (x_i, y_j)
        t = np.linspace(0.0, 1.0, n)
        best = float("inf")
        for _ in range(a.reps):
            t0 = time.process_time()
            spl = RectBivariateSpline(t, t, z, kx=3, ky=3, s=0)
            best = min(best, time.process_time() - t0)
        err = np.max(np.abs(spl.ev(val[:, 0], val[:, 1]) - val[:, 2]))
        print(f"n {n} fit {best:.6e} off_max {err:.6e} coefficients {len(spl.get_coeffs())}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
