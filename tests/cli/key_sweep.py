#!/usr/bin/env python3
"""The key sweep: every key every study reads, given one bad value.

usage: key_sweep.py DFLAB [--jobs J] [--only STUDY]   (run by make sanitize)

For each study of `dflab list`, its first config, and each key `dflab help
STUDY CONFIG` lists, one value the key's own "expects" column refuses:

    an integer in [a, b]            b + 1 (a - 1 when b is huge)
    a finite number in [a, b]       2b + 1 when b < 1e300, else nan
    a boolean                       maybe
    one of x|y|z                    nosuch
    N blank-separated numbers       1e200 (one number beyond |v| <= 1e150)
    a value (free text)             not swept (any text may be meant)

is given with --set to `dflab run CONFIG --out DIR` (a key and value an
earlier study already had is skipped unless --all: the same getter of the
same shared reader); it must end with exit
status 2, a last stderr line `dflab: error: ...` naming the key (as
section.key or [section] key), no sanitizer or runtime-error report on
stderr, and nothing left in the case's folder.  Under `make sanitize` the
binary is the ASan + UBSan one, so a key whose refusal path reads
uninitialised memory or leaks fails here.  Prints one line per failing case
and a summary; exit 0 when all hold."""
import argparse
import concurrent.futures
import os
import re
import shutil
import subprocess
import sys
import tempfile

EXPECT = re.compile(
    r"(?P<int>an integer in \[(?P<ia>\S+), (?P<ib>\S+)\])|"
    r"(?P<num>a finite number in \[(?P<na>\S+), (?P<nb>\S+)\])|"
    r"(?P<bool>a boolean)|"
    r"(?P<enum>one of (?P<names>\S+))|"
    r"(?P<vec>(?P<vn>\d) blank-separated finite numbers)")
SANITIZER = ("AddressSanitizer", "LeakSanitizer", "runtime error:", "UndefinedBehaviorSanitizer")


def studies(dflab):
    out = subprocess.run([dflab, "list"], capture_output=True, text=True, check=True).stdout
    res, cur = [], None
    for line in out.splitlines():
        if line and not line.startswith(" "):
            cur = line.split()[0]
        elif cur and line.strip().endswith(".ini"):
            res.append((cur, line.strip()))
            cur = None  # the first config of each study
    return res


def bad_value(m):
    if m.group("int"):
        a, b = float(m.group("ia")), float(m.group("ib"))
        return str(int(b) + 1) if b < 1e15 else str(int(a) - 1)
    if m.group("num"):
        b = float(m.group("nb"))
        return repr(2 * b + 1) if b < 1e300 else "nan"
    if m.group("bool"):
        return "maybe"
    if m.group("enum"):
        return "nosuch"
    if m.group("vec"):
        return " ".join(["1e200"] * int(m.group("vn")))
    return None


def keys(dflab, study, cfg):
    out = subprocess.run([dflab, "help", study, cfg], capture_output=True, text=True).stdout
    res = []
    for line in out.splitlines():
        mk = re.match(r"^  ([a-z_][a-z0-9_]*\.[a-z_][a-z0-9_]*)\s", line)
        if not mk or mk.group(1) == "study.name":
            continue
        m = EXPECT.search(line, mk.end())
        v = bad_value(m) if m else None
        if v is not None:
            res.append((mk.group(1), v))
    return res


def run_case(dflab, repo, study, cfg, key, value):
    d = tempfile.mkdtemp(prefix="dfl_keys_")
    try:
        r = subprocess.run([dflab, "run", os.path.join(repo, cfg), "--set", f"{key}={value}",
                            "--out", os.path.join(d, "o"), "--quiet"], cwd=d,
                           capture_output=True, text=True, timeout=600)
        sec, k = key.split(".", 1)
        lines = r.stderr.strip().splitlines()
        last = lines[-1] if lines else ""
        why = []
        if r.returncode != 2:
            why.append(f"exit {r.returncode}")
        if not last.startswith("dflab: error:") or (key not in last and f"[{sec}] {k}" not in last):
            why.append(f"last line {last!r}")
        if any(s in r.stderr for s in SANITIZER):
            why.append("sanitizer report: " + r.stderr[-600:])
        left = os.listdir(d)
        if left:
            why.append(f"left {left}")
        return f"{study} {cfg}: --set {key}={value}: " + "; ".join(why) if why else None
    except subprocess.TimeoutExpired:
        return f"{study} {cfg}: --set {key}={value}: no answer in 600 s"
    finally:
        shutil.rmtree(d, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dflab")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only")
    ap.add_argument("--all", action="store_true",
                    help="also a key another study already swept with the same expects")
    a = ap.parse_args()
    dflab = os.path.abspath(a.dflab)
    repo = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    cases, seen = [], set()
    for study, cfg in studies(dflab):
        if a.only and study != a.only:
            continue
        ks = keys(dflab, study, os.path.join(repo, cfg))
        if not ks:
            print(f"key sweep: {study}: `dflab help` lists no key to sweep", file=sys.stderr)
            return 1
        for k, v in ks:
            # a key read the same way (same name, same refused value) by an
            # earlier study goes through the same getter and the same shared
            # reader (shape, field, eval, output sections): once is enough
            if not a.all and (k, v) in seen:
                continue
            seen.add((k, v))
            cases.append((study, cfg, k, v))
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as ex:
        bad = [f for f in ex.map(lambda c: run_case(dflab, repo, *c), cases) if f]
    for b in bad:
        print(b)
    print(f"key sweep: {len(cases)} cases, {len(bad)} failing")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
