#!/usr/bin/env python3
"""Mutation testing of dflab: does the suite fail when the code is wrong?

usage: mutate.py MODULE [--only NAME] [--work DIR] [--timeout S]     (make mutate MODULE=pht)

Each mutant of tests/mutate/mutants/MODULE.ini is one small semantic change
of the kind real bugs make (a sign, a bound, a dropped term, a constant):

    [pht/tmesh: ties go to the lowest axis]
    file = src/pht/tmesh.c
    find = len > best          (must occur exactly once in file)
    replace = len >= best
    suites = tmesh pht_fit     (Criterion suites that should kill it)
    equivalent = why           (optional: the change cannot alter behaviour)

The mutants are applied to a private copy of the tracked files under
build-mutate/tree/ (never to the working tree: a kill leaves the user's
sources untouched), built there with its own object cache, and each mutant's
suites are run.  Killed = one of its suites fails (non-zero
exit of the suites, or a timeout); stillborn = the mutant does not compile
(reported, not counted); survived = every suite passed.  Prints one line per
mutant, the diff of each survivor, and the score; exit 1 when a survivor is
not marked equivalent, 2 on a malformed mutant file.
"""
import argparse
import configparser
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
# --work DIR (default build-mutate/): runs with different folders do not
# share a tree, so two modules can be tested at once
WORK = os.path.join(ROOT, "build-mutate")
TREE = os.path.join(WORK, "tree")


def die(msg, code=2):
    print(f"mutate: error: {msg}", file=sys.stderr)
    sys.exit(code)


def load(module):
    path = os.path.join(ROOT, "tests", "mutate", "mutants", module + ".ini")
    if not os.path.isfile(path):
        have = sorted(f[:-4] for f in os.listdir(os.path.dirname(path)) if f.endswith(".ini"))
        die(f"{path}: no such mutant list (modules: {' '.join(have)})")
    cp = configparser.ConfigParser(interpolation=None)
    cp.optionxform = str
    try:
        cp.read(path, encoding="utf-8")
    except configparser.Error as e:
        die(f"{path}: {e}")
    out = []
    for name in cp.sections():
        s = cp[name]
        for k in ("file", "find", "replace", "suites"):
            if not s.get(k):
                die(f"{path}: [{name}]: key '{k}' missing (expected file, find, replace, suites)")
        src = os.path.join(ROOT, s["file"])
        try:
            text = open(src, encoding="utf-8").read()
        except OSError as e:
            die(f"{path}: [{name}]: file = {s['file']}: {e.strerror}")
        n = text.count(s["find"])
        if n != 1:
            die(f"{path}: [{name}]: find = {s['find']!r} occurs {n} times in {s['file']} "
                "(expected exactly once)")
        out.append(dict(name=name, file=s["file"], find=s["find"], replace=s["replace"],
                        suites=s["suites"].split(), equivalent=s.get("equivalent", "")))
    return out


def sync_tree():
    """A private copy of the tracked files (the object cache in TREE/build is
    kept between runs; make rebuilds what changed).  A new tree's object
    cache starts as a copy of the working tree's build/ (timestamps kept), so
    only what differs is compiled."""
    if not os.path.isdir(os.path.join(TREE, "build")) and os.path.isdir(os.path.join(ROOT, "build")):
        os.makedirs(TREE, exist_ok=True)
        subprocess.run(["cp", "-a", os.path.join(ROOT, "build"), os.path.join(TREE, "build")],
                       check=True)
    files = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, check=True,
                           capture_output=True).stdout.split(b"\0")
    for f in files:
        if not f:
            continue
        rel = f.decode()
        s, d = os.path.join(ROOT, rel), os.path.join(TREE, rel)
        if not os.path.isfile(s):
            continue
        if os.path.exists(d):
            if open(s, "rb").read() == open(d, "rb").read():
                continue
            # a changed file gets the time of the copy: its source may be
            # older than the object the tree built from the last copy
            shutil.copy(s, d)
            os.utime(d)
            continue
        os.makedirs(os.path.dirname(d), exist_ok=True)
        shutil.copy2(s, d)  # a new tree: times kept, so the seeded objects hold


def build(log):
    r = subprocess.run(["make", "-s", "-j2", "build/dflab", "build/dflab-tests"], cwd=TREE,
                       stdout=log, stderr=subprocess.STDOUT)
    return r.returncode == 0


def run_suites(suites, timeout):
    env = dict(os.environ, DFL_PYTHON=sys.executable,
               DFL_DFLAB=os.path.join(TREE, "build", "dflab"))
    for s in suites:
        try:
            r = subprocess.run([os.path.join(TREE, "build", "dflab-tests"), "--filter", s + "/*",
                                "-j2", "--timeout", str(timeout)], cwd=TREE, env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                               timeout=timeout * 4)
        except subprocess.TimeoutExpired:
            return "killed (timeout)"
        if r.returncode != 0:
            return f"killed by {s}"
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("module")
    ap.add_argument("--only")
    ap.add_argument("--timeout", type=int, default=300)
    ap.add_argument("--work", help="private folder of the mutated tree (default build-mutate)")
    a = ap.parse_args()
    if a.work:
        global WORK, TREE
        WORK = os.path.abspath(a.work)
        TREE = os.path.join(WORK, "tree")
    muts = load(a.module)
    if a.only:
        muts = [m for m in muts if a.only in m["name"]]
    os.makedirs(TREE, exist_ok=True)
    sync_tree()
    log = open(os.path.join(WORK, "build.log"), "w")
    if not build(log):
        die(f"the unmutated tree does not build (see {WORK}/build.log)", 1)
    bad = run_suites(sorted({s for m in muts for s in m["suites"]}), a.timeout)
    if bad:
        die(f"the unmutated tree fails its suites ({bad}); fix that first", 1)
    killed = survived = stillborn = equiv = 0
    survivors = []
    for m in muts:
        path = os.path.join(TREE, m["file"])
        orig = open(path, encoding="utf-8").read()
        t0 = time.time()
        try:
            open(path, "w", encoding="utf-8").write(orig.replace(m["find"], m["replace"], 1))
            if not build(log):
                verdict = "stillborn (does not compile)"
                stillborn += 1
            else:
                verdict = run_suites(m["suites"], a.timeout)
                if verdict:
                    killed += 1
                elif m["equivalent"]:
                    verdict = f"equivalent: {m['equivalent']}"
                    equiv += 1
                else:
                    verdict = "SURVIVED"
                    survived += 1
                    survivors.append(m)
        finally:
            open(path, "w", encoding="utf-8").write(orig)
            os.utime(path)
        print(f"{m['name']}: {verdict} ({time.time() - t0:.0f} s)", flush=True)
    build(log)
    for m in survivors:
        print(f"\n--- survivor [{m['name']}] {m['file']}\n-{m['find']}\n+{m['replace']}")
    live = killed + survived
    score = 100.0 * killed / live if live else 100.0
    print(f"\n{a.module}: {killed} killed, {survived} survived, {equiv} equivalent, "
          f"{stillborn} stillborn; score {score:.0f} % of {live}")
    sys.exit(1 if survived else 0)


if __name__ == "__main__":
    main()
