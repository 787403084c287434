#!/usr/bin/env python3
"""Compares two results trees (e.g. `make reproduce` before and after a change).

    compare_results.py OLD NEW [--all]

Every CSV under OLD must exist under NEW with the same bytes, and NEW may
hold no CSV that OLD lacks; manifest.json (wall times, revision) and the
generated report and figures are ignored.  --all compares every other file
(VTK, EXR, config.ini) too.  Prints one line per difference and a summary;
exit status 0 when nothing differs, 1 otherwise, 2 for bad arguments."""
import argparse
import filecmp
import os
import sys

IGNORED_DIRS = {"figures"}
IGNORED_FILES = {"manifest.json", "REPORT.md", "README.md"}


def files(root):
    out = set()
    for d, dirs, names in os.walk(root):
        rel = os.path.relpath(d, root)
        dirs[:] = [x for x in dirs if not (rel == "." and x in IGNORED_DIRS) and ".stage." not in x]
        for n in names:
            if n in IGNORED_FILES:
                continue
            out.add(os.path.normpath(os.path.join(rel, n)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--all", action="store_true", help="compare non-CSV files too")
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
        if filecmp.cmp(os.path.join(a.old, f), os.path.join(a.new, f), shallow=False):
            same += 1
        else:
            print(f"differs: {f}")
            bad += 1
    kind = "files" if a.all else "CSV files"
    print(f"compare_results: {same} {kind} identical, {bad} differences "
          f"({len(old)} in {a.old}, {len(new)} in {a.new})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
