#!/usr/bin/env python3
"""ISA determinism: runs configs once per instruction set this CPU runs
(DFL_ISA=sse2, avx2, avx512: core/isa.h) and compares every output file
with the sse2 run byte for byte, with the comparison of check_threads.py
(in manifest.json only wall times, the date, the command line and the
recorded ISA may differ; in CSV tables the wall-clock columns are left out).

    check_isa.py DFLAB [--quick] [--keep DIR] [CONFIG.ini ...]

Without configs: every configs/paper/*/*.ini, the study folders' configs
(configs/<folder>/*.ini, e.g. configs/compare/) and configs/smoke/*.ini
(`make check-isa`, as check_threads.py); --quick: a fast subset (part of
`make test`): the paper configs that run in a few seconds, the comparison
study's quick.ini (every method's kernels), paper configs of the PHT and
proxy kernels with their sizes cut down by --set (QUICK_SET), and the
smoke configs.  Also checks that DFL_ISA=bogus is exit 2 with one line.
Prints one line per difference and a summary; exit 0 when all agree."""
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_threads import every_config, judge, parse_argv, stem  # noqa: E402

ISAS = ["sse2", "avx2", "avx512"]
# paper configs that run in a few seconds at full size
QUICK = ["bs04_corrected", "bs04_fields", "bs04_gradbounds", "bs04_hetero",
         "bs04_normalization", "bs04_polygonization", "bs04_triangle", "bs04_triedge",
         "hvb25_full217", "hvb25_peers_sphere", "hvb25_peers_torus", "smoke", "smoke3d",
         "quick"]
# paper configs cut down: (config stem, --set overrides)
QUICK_SET = {
    "sjp10_fig1": ["fit.eps=1e-2", "fit.max_level=5", "study.val_n=41", "study.image_n=21",
                   "study.graph_n=11"],
    "sjp10_3d": ["fit.max_level=3", "study.eps=1e-1", "study.uniform_levels=2",
                 "sphere_case.val_n=17", "torus_case.val_n=17", "torus_case.eps=1e-1",
                 "torus_implicit_case.val_n=17", "torus_implicit_case.eps=1e-1",
                 "genus2_case.val_n=9", "genus2_case.eps=1e-1", "goursat_case.val_n=9"],
    "hvb25_storage": ["eval.n=33"],
}


def runs_isa(dflab, isa):
    env = dict(os.environ, DFL_ISA=isa)
    return subprocess.run([dflab, "--version"], env=env, stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL).returncode == 0


def run(dflab, cfg, sets, out, isa):
    env = dict(os.environ, DFL_ISA=isa)
    args = [dflab, "run", cfg, "--out", out, "--quiet", "--threads", "2"]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    if p.returncode != 0:
        return "exit %d: %s" % (p.returncode, p.stderr.decode(errors="replace").strip()[-300:])
    return None


def bad_value(dflab):
    """DFL_ISA=bogus: exit 2, one line on stderr naming the variable."""
    env = dict(os.environ, DFL_ISA="bogus")
    p = subprocess.run([dflab, "list"], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    err = p.stderr.decode(errors="replace")
    if p.returncode != 2 or err.count("\n") != 1 or "DFL_ISA" not in err or p.stdout:
        return "DFL_ISA=bogus: exit %d, stderr %r" % (p.returncode, err)
    return None


def main():
    args = parse_argv(sys.argv[1:], __doc__)
    if args is None:
        return 2
    dflab, quick, keep, given = args
    cfgs = [(a, []) for a in given]
    if not cfgs:
        every = every_config()
        if quick:
            cfgs = [(c, []) for c in every if stem(c) in QUICK]
            cfgs += [(c, QUICK_SET[stem(c)]) for c in every if stem(c) in QUICK_SET]
        else:
            cfgs = [(c, []) for c in every]
    isas = [i for i in ISAS if runs_isa(dflab, i)]
    bad = 0
    e = bad_value(dflab)
    if e:
        print("FAIL " + e)
        bad += 1
    base = keep or tempfile.mkdtemp(prefix="dfl_isa_")
    files = 0
    for cfg, sets in cfgs:
        outs = {i: os.path.join(base, i, stem(cfg)) for i in isas}
        errs = [run(dflab, cfg, sets, outs[i], i) for i in isas]
        n, b = judge(cfg, errs, outs[isas[0]],
                     [("DFL_ISA=%s vs %s" % (isas[0], i), outs[i]) for i in isas[1:]])
        files, bad = files + n, bad + b
    if not keep:
        subprocess.run(["rm", "-rf", base])
    print("check-isa: %d configs under %s, %d files compared, %d differ"
          % (len(cfgs), "|".join(isas), files, bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
