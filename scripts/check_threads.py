#!/usr/bin/env python3
"""Thread-count determinism: runs configs with `--threads 1`, `--threads 2`
and with OMP_NUM_THREADS=1 (no --threads) and compares every output file
byte for byte; in manifest.json only the wall times, the date, the
thread count, the command line and the ISA the kernels ran may differ, and in CSV tables only the
columns that hold wall-clock measurements (TIMING below: `seconds`,
`*_seconds`, `*_ms`, `t_*`, `*ns_per_*`, `*_s`, `*_per_s`, `*_rss_*` -- the timings of
hvb25's Table 4, of sjp10's fits and of compare_methods), which no two runs share; a CSV's sha256 in the manifest is
then checked through that comparison instead.

    check_threads.py DFLAB [--quick] [--keep DIR] [CONFIG.ini ...]

Without configs: every configs/paper/*/*.ini and configs/smoke/*.ini
(`make check-threads`); --quick: the paper configs that run in about a
second plus the smoke configs (part of `make test`).  Prints one line per
difference and a summary; exit 0 when all agree."""
import csv
import glob
import io
import json
import os
import re
import subprocess
import sys
import tempfile

# configs that run in ~1 s each (results_base wall times), for --quick
QUICK = ["bs04_hetero", "bs04_normalization", "bs04_polygonization", "smoke", "smoke3d"]
VOLATILE = {"date", "wall_seconds", "total_wall_seconds", "threads", "omp_threads", "command_line",
            "isa"}


# Machine measurements: wall-clock times (`*_s` seconds, `*_per_s` rates
# included) and the resident-set growth of a build (`*_rss_*`).
TIMING = re.compile(r"^(seconds|.*_seconds|.*_ms|t_.*|.*ns_per_.*|.*_s|.*_per_s|.*_rss_.*)$")


def strip(o):
    if isinstance(o, dict):
        if str(o.get("path", o.get("name", ""))).endswith(".csv"):
            o = {k: v for k, v in o.items() if k not in ("sha256", "bytes")}
        return {k: strip(v) for k, v in o.items() if k not in VOLATILE}
    if isinstance(o, list):
        return [strip(v) for v in o]
    return o


def csv_rows(path):
    """The table without its wall-clock columns (TIMING)."""
    rows = list(csv.reader(io.StringIO(open(path, encoding="utf-8").read())))
    if not rows:
        return rows
    keep = [i for i, c in enumerate(rows[0]) if not TIMING.match(c)]
    return [[r[i] for i in keep if i < len(r)] for r in rows]


def run(dflab, cfg, out, threads, env_threads):
    env = dict(os.environ)
    env.pop("OMP_NUM_THREADS", None)
    args = [dflab, "run", cfg, "--out", out, "--quiet"]
    if threads:
        args += ["--threads", str(threads)]
    if env_threads:
        env["OMP_NUM_THREADS"] = str(env_threads)
    p = subprocess.run(args, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    if p.returncode != 0:
        return "exit %d: %s" % (p.returncode, p.stderr.decode(errors="replace").strip()[-300:])
    return None


def compare(a, b, label):
    diffs = []
    fa, fb = set(os.listdir(a)), set(os.listdir(b))
    for n in sorted(fa ^ fb):
        diffs.append("%s: %s only in one run" % (label, n))
    for n in sorted(fa & fb):
        pa, pb = os.path.join(a, n), os.path.join(b, n)
        if n == "manifest.json":
            ma, mb = strip(json.load(open(pa))), strip(json.load(open(pb)))
            if ma != mb:
                diffs.append("%s: manifest.json differs beyond wall times" % label)
        elif n.endswith(".csv"):
            if csv_rows(pa) != csv_rows(pb):
                diffs.append("%s: %s differs" % (label, n))
        elif open(pa, "rb").read() != open(pb, "rb").read():
            diffs.append("%s: %s differs" % (label, n))
    return diffs


# The command line and the verdict, shared with check_isa.py (same options,
# same FAIL lines).
def parse_argv(argv, doc):
    """DFLAB [--quick] [--keep DIR] [CONFIG.ini ...] -> (dflab, quick, keep,
    configs); None, after printing doc, without DFLAB."""
    if not argv:
        print(doc)
        return None
    argv = list(argv)
    dflab = os.path.abspath(argv.pop(0))
    quick = "--quick" in argv
    keep = None
    if "--keep" in argv:
        keep = argv[argv.index("--keep") + 1]
        argv.remove("--keep"), argv.remove(keep)
    return dflab, quick, keep, [a for a in argv if not a.startswith("--")]


def stem(cfg):
    return os.path.splitext(os.path.basename(cfg))[0]


def every_config(studies=True):
    """configs/paper/*/*.ini (with studies: and the study configs
    configs/<study>/*.ini) sorted, then configs/smoke/*.ini sorted."""
    study = [c for c in glob.glob("configs/*/*.ini")
             if c.split(os.sep)[1] not in ("shapes", "fields", "smoke", "paper")] if studies else []
    return (sorted(glob.glob("configs/paper/*/*.ini") + study)
            + sorted(glob.glob("configs/smoke/*.ini")))


def judge(cfg, errs, ref, others):
    """One config's verdict: the errors of its runs (None where a run
    worked) or, when all ran, compare() of each (label, dir) in others with
    ref.  Prints one FAIL line per problem; returns (files compared, 1 if it
    failed else 0)."""
    if any(errs):
        print("FAIL %s: %s" % (cfg, [e for e in errs if e]))
        return 0, 1
    d = []
    for label, out in others:
        d += compare(ref, out, "%s (%s)" % (stem(cfg), label))
    for x in d:
        print("FAIL " + x)
    return len(os.listdir(ref)), int(bool(d))


def main():
    args = parse_argv(sys.argv[1:], __doc__)
    if args is None:
        return 2
    dflab, quick, keep, cfgs = args
    if not cfgs:
        cfgs = every_config()
        if quick:
            cfgs = [c for c in cfgs if stem(c) in QUICK]
    base = keep or tempfile.mkdtemp(prefix="dfl_threads_")
    bad, files = 0, 0
    for cfg in cfgs:
        outs = {k: os.path.join(base, k, stem(cfg)) for k in ("t1", "t2", "env1")}
        errs = [run(dflab, cfg, outs["t1"], 1, None), run(dflab, cfg, outs["t2"], 2, None),
                run(dflab, cfg, outs["env1"], None, 1)]
        n, b = judge(cfg, errs, outs["t1"], [("--threads 1 vs 2", outs["t2"]),
                                             ("--threads 1 vs OMP_NUM_THREADS=1", outs["env1"])])
        files, bad = files + n, bad + b
    if not keep:
        subprocess.run(["rm", "-rf", base])
    print("check-threads: %d configs, %d files each compared 3 ways, %d configs differ"
          % (len(cfgs), files, bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
