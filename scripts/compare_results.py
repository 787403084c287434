#!/usr/bin/env python3
"""Compares two results trees (e.g. `make reproduce` before and after a change).

    compare_results.py OLD NEW [--all] [--numeric]

Every CSV under OLD must exist under NEW with the same bytes, and NEW may
hold no CSV that OLD lacks; manifest.json (wall times, revision) and the
generated report and figures and the per-point folders <run>.points/ are
ignored.  --all compares every other file
(VTK, EXR, config.ini) too.  --numeric compares CSVs by value instead of
by bytes: the same columns (NEW may add `point` and swept `section.key`
columns, which dflab writes since sweeps became units of work), the same
rows, and every cell that parses as a double equal bit for bit (so
0.10000000000000001 and 0.1 are the same number); text cells compare as
text.  Prints one line per difference and a summary;
exit status 0 when nothing differs, 1 otherwise, 2 for bad arguments."""
import argparse
import csv
import filecmp
import math
import os
import re
import struct
import sys

IGNORED_DIRS = {"figures"}
IGNORED_FILES = {"manifest.json", "REPORT.md", "README.md"}


def files(root):
    out = set()
    for d, dirs, names in os.walk(root):
        rel = os.path.relpath(d, root)
        dirs[:] = [x for x in dirs if not (rel == "." and x in IGNORED_DIRS) and ".stage." not in x
                   and not x.endswith((".points", ".logs"))]
        for n in names:
            if n in IGNORED_FILES:
                continue
            out.add(os.path.normpath(os.path.join(rel, n)))
    return out


SWEPT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*\.[A-Za-z_][A-Za-z0-9_]*$")


def bits(text):
    """The 64 bits of the double a cell reads as, or None for text."""
    try:
        v = float(text)
    except ValueError:
        return None
    if math.isnan(v):
        return "nan"
    return struct.pack("<d", v)


def same_numbers(old_path, new_path):
    """'' when the two CSVs hold the same values, else what differs."""
    with open(old_path, newline="") as fp:
        old = list(csv.reader(fp))
    with open(new_path, newline="") as fp:
        new = list(csv.reader(fp))
    if not old or not new:
        return "" if old == new else "one file is empty"
    oh, nh = old[0], new[0]
    added = [c for c in nh if c not in oh]
    extra = [c for c in added if c != "point" and not SWEPT.match(c)]
    if extra:
        return f"new columns {extra}"
    missing = [c for c in oh if c not in nh]
    if missing:
        return f"columns missing in new: {missing}"
    if len(old) != len(new):
        return f"{len(old) - 1} rows vs {len(new) - 1}"
    at = [nh.index(c) for c in oh]
    for i, (ro, rn) in enumerate(zip(old[1:], new[1:]), start=2):
        for c, j, a in zip(oh, at, ro):
            b = rn[j] if j < len(rn) else ""
            if a == b:
                continue
            ba, bb = bits(a), bits(b)
            if ba is None or ba != bb:
                return f"row {i} column {c}: {a!r} vs {b!r}"
    return ""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--all", action="store_true", help="compare non-CSV files too")
    ap.add_argument("--numeric", action="store_true",
                    help="compare CSV values as doubles (bit for bit), allowing new point/swept columns")
    a = ap.parse_args()
    for d in (a.old, a.new):
        if not os.path.isdir(d):
            print(f"compare_results: error: {d}: not a directory", file=sys.stderr)
            return 2
    old, new = files(a.old), files(a.new)
    pick = (lambda f: True) if a.all else (lambda f: f.endswith(".csv"))
    old = {f for f in old if pick(f)}
    new = {f for f in new if pick(f)}
    bad = 0
    for f in sorted(old - new):
        print(f"missing in {a.new}: {f}")
        bad += 1
    for f in sorted(new - old):
        print(f"only in {a.new}: {f}")
        bad += 1
    same = 0
    for f in sorted(old & new):
        po, pn = os.path.join(a.old, f), os.path.join(a.new, f)
        if filecmp.cmp(po, pn, shallow=False):
            same += 1
            continue
        why = same_numbers(po, pn) if a.numeric and f.endswith(".csv") else "bytes differ"
        if why:
            print(f"differs: {f}: {why}")
            bad += 1
        else:
            same += 1
    kind = "files" if a.all else "CSV files"
    if a.numeric:
        kind += " (values)"
    print(f"compare_results: {same} {kind} identical, {bad} differences "
          f"({len(old)} in {a.old}, {len(new)} in {a.new})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
