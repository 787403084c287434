"""Cross-check of the tricubic grid peer (src/field/gridpeer.h) against SciPy.

Usage: gridpeer_scipy.py FILE, FILE as tests/field/test_gridpeer.c's
tricubic_matches_scipy writes it: n K / lo / hi, the n^3 samples at the
cell centres (index i + n (j + n k)), the (n + 2K)^3 values of the peer at
the centres -K .. n - 1 + K, then query rows x y z u gx gy gz (the peer's
value and gradient).  Checks
  1. the tensor product of make_interp_spline(k=3) (not-a-knot, SciPy's
     default for k = 3; extrapolating its end pieces) on the samples:
     value and gradient at every query;
  2. ndimage.map_coordinates(order=3, prefilter=True, mode='mirror') on the
     padded grid at the queries: its mirror ends lie K centres outside the
     box, where their effect has decayed by (2 - sqrt 3)^K.
Exit 0 when both agree to rounding, 1 otherwise (the worst differences on
stdout either way).
"""
import sys

import numpy as np
from scipy import ndimage
from scipy.interpolate import make_interp_spline


def main(path):
    with open(path) as fp:
        n, K = map(int, fp.readline().split())
        lo = np.array(fp.readline().split(), float)
        hi = np.array(fp.readline().split(), float)
        rest = fp.read().split("\n")
    vals = [line for line in rest if line.strip()]
    M = n + 2 * K
    samples = np.array(vals[:n ** 3], float).reshape(n, n, n)       # [k, j, i]
    padded = np.array(vals[n ** 3:n ** 3 + M ** 3], float).reshape(M, M, M)
    q = np.array([list(map(float, line.split())) for line in vals[n ** 3 + M ** 3:]])
    assert q.shape[1] == 7 and len(q) > 0
    h = (hi - lo) / n
    A = np.transpose(samples, (2, 1, 0))                             # [i, j, k]
    P = np.transpose(padded, (2, 1, 0))
    centres = [lo[a] + (np.arange(n) + 0.5) * h[a] for a in range(3)]
    worst_v = worst_g = worst_m = 0.0
    scale = max(1.0, np.abs(A).max())
    for row in q:
        x, u, g = row[:3], row[3], row[4:]
        sx = make_interp_spline(centres[0], A, k=3, axis=0)
        ax = [sx(x[0]), sx.derivative()(x[0])]                      # (n, n) over j, k
        ref = np.zeros(4)  # value, d/dx, d/dy, d/dz
        for dx in range(2):
            sy = make_interp_spline(centres[1], ax[dx], k=3, axis=0)
            for dy in range(2 - dx):
                by = (sy.derivative() if dy else sy)(x[1])           # (n,) over k
                sz = make_interp_spline(centres[2], by, k=3)
                for dz in range(2 - dx - dy):
                    v = float((sz.derivative() if dz else sz)(x[2]))
                    ref[0 if dx + dy + dz == 0 else 1 + [dx, dy, dz].index(1)] = v
        worst_v = max(worst_v, abs(u - ref[0]))
        worst_g = max(worst_g, np.abs(g - ref[1:]).max())
        coord = (x - lo) / h - 0.5 + K
        m = ndimage.map_coordinates(P, coord.reshape(3, 1), order=3, mode="mirror",
                                    prefilter=True)[0]
        worst_m = max(worst_m, abs(u - m))
    tol_v, tol_g, tol_m = 1e-13 * scale, 1e-12 * scale / h.min(), 1e-11 * scale
    print(f"queries {len(q)}: make_interp_spline value {worst_v:.3g} (tol {tol_v:.3g}), "
          f"gradient {worst_g:.3g} (tol {tol_g:.3g}); map_coordinates value {worst_m:.3g} "
          f"(tol {tol_m:.3g})")
    return 0 if worst_v <= tol_v and worst_g <= tol_g and worst_m <= tol_m else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
