#!/usr/bin/env python3
"""The reading of hvb25's "L2" (scripts/sections/hvb25/hvb25_common.py):
printed intervals and the MSE / RMS / norm-over-N bounds on hand-derived
cells of the paper's Table 1.  Exit 0 when all hold."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "scripts"))
from sections.hvb25 import hvb25_common as C  # noqa: E402

bad = []


def check(what, got, want):
    if got != want:
        bad.append(f"{what}: got {got}, want {want}")


def close(a, b):
    return all(math.isclose(x, y, rel_tol=1e-12, abs_tol=0) for x, y in zip(a, b))


check("interval 0.000001", close(C.printed_interval("0.000001"), (5e-7, 1.5e-6)), True)
check("interval 1.5e-3", close(C.printed_interval("1.5e-3"), (1.45e-3, 1.55e-3)), True)
check("interval 0.29", close(C.printed_interval("0.29"), (0.285, 0.295)), True)
check("interval 0", C.printed_interval("0"), (0.0, 5e-7))
N = 217 ** 3
# Sphere, order 1, 16^3, SDF nearest: L1 0.0017, "L2" 0.000001, Linf 0.05.
# MSE >= 0.00165^2 = 2.72e-6 > 1.5e-6; RMS >= 0.00165 > 1.5e-6; norm/N lies in
# [0.00165, sqrt(0.00175 * 0.055)] / 3196.6 = [5.2e-7, 3.1e-6], which holds it.
check("sdf sphere 1/16", C.l2_admits("0.0017", "0.000001", "0.05", N),
      {"MSE": False, "RMS": False, "‖e‖₂/N": True})
# Sphere, order 1, 16^3, parametric nearest: 9.3e-6 in [3.4e-6, 1.36e-4].
check("parametric sphere 1/16", C.l2_admits("0.0019", "0.0000093", "0.069", N),
      {"MSE": True, "RMS": False, "‖e‖₂/N": False})
# Torus, order 1, 16^3, parametric Hermite: 0.35 > L1 Linf = 0.165 * 0.315.
check("parametric torus hermite", C.l2_is_mse("0.16", "0.35", "0.31"), False)
# An RMS: L1 0.1, RMS 0.2, Linf 0.5 (0.2 <= sqrt(0.05) = 0.224).
check("an rms", C.l2_admits("0.1", "0.2", "0.5", 4)["RMS"], True)
# The edges: an MSE equal to L1^2 (all errors equal) is possible, one just
# below the interval is not.
check("mse at L1^2", C.l2_is_mse("0.1", "0.01", "0.1"), True)
# "0.10" is [0.095, 0.105]: no MSE below 0.095^2 = 0.009025; "0.0080" is [0.00795, 0.00805].
check("mse below L1^2", C.l2_is_mse("0.10", "0.0080", "0.10"), False)
rows = [dict(norm=n, k="a", c=v) for n, v in (("L1", "0.0017"), ("L2", "0.000001"), ("Linf", "0.05"))]
body, head, cells = C.l2_reading_table(rows, ["c"], lambda r: r["k"], N)
check("table counts", body, [["c", 1, 0, 0, 1]])
check("table names the impossible cell", len(cells), 1)
for b in bad:
    print(b)
sys.exit(1 if bad else 0)
