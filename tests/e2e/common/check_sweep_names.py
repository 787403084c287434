#!/usr/bin/env python3
"""Checks the file names of a dflab run against scripts/dflio.py's sweep rule:
DIR must hold exactly the FIXED files and, for every STEM.EXT of PERPOINT,
dflio.sweep_name(STEM, i, NPOINTS, EXT) for i = 0..NPOINTS-1, and each of
those must split back into its stem, point and extension; with more than
one point, the merge's collection STEM.pvd of every .vti / .vtp stem too.

usage: check_sweep_names.py DIR NPOINTS PERPOINT [FIXED...]
PERPOINT is a comma list of STEM.EXT.  Prints "ok" and exits 0, or prints
what differs and exits 1."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "scripts"))
import dflio  # noqa: E402


def main():
    d, n, perpoint, fixed = sys.argv[1], int(sys.argv[2]), sys.argv[3].split(","), sys.argv[4:]
    want = set(fixed)
    bad = []
    for name in perpoint:
        stem, ext = name.rsplit(".", 1)
        for i in range(n):
            f = dflio.sweep_name(stem, i, n, ext)
            want.add(f)
            split = dflio.sweep_split(f)
            if split != (stem, i if n > 1 else None, ext):
                bad.append(f"{f} splits into {split}")
        if n > 1 and ext in ("vti", "vtp"):
            want.add(stem + ".pvd")
    got = set(os.listdir(d))
    bad += [f"missing {f}" for f in sorted(want - got)]
    bad += [f"unexpected {f}" for f in sorted(got - want)]
    for f in fixed:
        if dflio.sweep_point_of(f) is not None:
            bad.append(f"{f} reads as a sweep point")
    print("\n".join(bad) if bad else "ok")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
