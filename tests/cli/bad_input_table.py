#!/usr/bin/env python3
"""The bad-input table: every case runs the real dflab binary in a fresh
directory and checks the exit-status contract (2 for input, 1 for machine
failures), exactly one final line `dflab: error: ...` on stderr holding the
expected words (file, line, key), nothing on stdout (unless the case says
stdout goes elsewhere) and no file left behind besides the inputs.

usage: bad_input_table.py DFLAB [--list]   (run by tests/cli/test_bad_input_table.c)
Prints one line per failing case and a summary; exit 0 when all pass.
"""
import os
import shutil
import subprocess
import sys
import tempfile

HEAD = b"[study]\nname = smoke\n"
SHAPE = b"[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n"
FIELD = b"[field]\nkind = exact\n"
GRID = b"[grid]\nn = 8\n"
GOOD = HEAD + SHAPE + FIELD + GRID          # 10 lines
SPHERE = b"[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 1\n"
PTS = b"x,y\n0.1,0.2\n"
RUN = ["run", "{D}/bad.ini", "--out", "{D}/o", "--quiet"]
PROBE = ["probe", "{D}/bad.ini", "--points", "{D}/pts.csv"]

CASES = []


def case(name, args, want=(), ini=None, pts=None, rc=2, files=None, stdout_to=None, env=None,
         shell_prefix=None, keep=()):
    """keep: names the run must leave (the outputs of a run that exits 1
    after writing them, the non-finite rule); each must exist."""
    CASES.append(dict(name=name, args=args, want=list(want), ini=ini, pts=pts, rc=rc,
                      files=files or {}, stdout_to=stdout_to, env=env or {},
                      shell_prefix=shell_prefix, keep=set(keep)))


def runc(name, ini, *want, rc=2, extra=()):
    case(name, RUN + list(extra), want, ini=ini, rc=rc)


def probec(name, pts, *want, ini=GOOD, extra=(), rc=2):
    case(name, PROBE + list(extra), want, ini=ini, pts=pts, rc=rc)


# ---- the readers: bytes that are not text --------------------------------
runc("NUL in a value", HEAD + b"[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\0garbage\n" + FIELD + GRID,
     "bad.ini:6", "NUL byte at column 13")
runc("NUL at start", b"\0" + GOOD, "bad.ini:1", "NUL byte")
runc("NUL in a key", GOOD + b"\0n = 3\n", "bad.ini:11", "NUL")
runc("NUL in a section name", HEAD + b"[sha\0pe]\n", "bad.ini:3", "NUL")
for c in [1, 7, 8, 0x0b, 0x0c, 0x1b, 0x1f, 0x7f]:
    runc("control 0x%02x" % c, GOOD + b"[output]\nvti = tr" + bytes([c]) + b"ue\n",
         "bad.ini:12", "control character 0x%02x" % c)
runc("CR inside a line", GOOD.replace(b"n = 8", b"n = 8\rX"), "bad.ini:10", "0x0d")
runc("escape sequence in a key", GOOD + b"\x1b[2Jkey = 1\n", "bad.ini:11", "0x1b")
runc("C1 control U+009B", GOOD + b"[output]\nvti = \xc2\x9b\n", "bad.ini:12", "U+009B")
for nm, b in [("lone continuation", b"\x80"), ("truncated 2-byte", b"\xc3"),
              ("overlong slash", b"\xc0\xaf"), ("overlong 3-byte", b"\xe0\x80\xaf"),
              ("surrogate", b"\xed\xa0\x80"), ("above U+10FFFF", b"\xf4\x90\x80\x80"),
              ("byte 0xff", b"\xff"), ("byte 0xfe", b"\xfe"), ("truncated 4-byte", b"\xf0\x9f\x98")]:
    runc("invalid UTF-8: " + nm, GOOD + b"[output]\nvti = x" + b + b"\n", "bad.ini:12", "invalid UTF-8")
runc("binary garbage", bytes(range(256)) * 4, "bad.ini:1")
runc("line too long", GOOD + b"[output]\nvti = " + b"1" * 70000 + b"\n", "bad.ini:12", "longer than 65534")
runc("endless line without newline", GOOD + b"x" * 200000, "bad.ini:11", "longer than")
runc("section name too long", GOOD + b"[" + b"s" * 60 + b"]\nx = 1\n", "bad.ini:11", "section name longer")
runc("key name too long", GOOD + b"k" * 60 + b" = 1\n", "bad.ini:11", "key name longer")
runc("BOM then duplicate section", b"\xef\xbb\xbf" + GOOD + b"[grid]\nlo = 0 0\n", "bad.ini:11", "duplicate section", "first at line 9")
runc("duplicate section", GOOD + b"[shape]\nradius = 0.2\n", "bad.ini:11", "[shape]: duplicate section", "first at line 3")
runc("duplicate empty section", GOOD + b"[study]\n", "bad.ini:11", "duplicate section")
runc("BOM not at start", GOOD + b"\xef\xbb\xbf[output]\nvti = true\n", "bad.ini:11", "syntax")
case("config /dev/zero", ["run", "/dev/zero", "--out", "{D}/o"], ["/dev/zero:1", "NUL byte"])
case("config is a directory", ["run", "{D}", "--out", "{D}/o"], ["a directory"])
case("config /dev/null", ["run", "/dev/null", "--out", "{D}/o"], ["[study] name", "missing"])
runc("more than 100000 lines", b"\n" * 100001, "bad.ini:100001", "more than 100000 lines")
# ---- INI syntax and keys ---------------------------------------------------
runc("syntax error", GOOD + b"not ini\n", "bad.ini:11", "syntax")
runc("unterminated section", GOOD + b"[output\n", "bad.ini:11", "syntax")
runc("duplicate key", GOOD + b"n = 9\n", "bad.ini:11", "duplicate key")
runc("key outside section", b"n = 3\n" + GOOD, "bad.ini:1", "outside")
runc("unknown key", GOOD + b"nn = 5\n", "bad.ini:11", "[grid] nn")
runc("unknown section", GOOD + b"[gird]\nn = 5\n", "bad.ini:12", "[gird] n")
runc("empty value", HEAD + SHAPE.replace(b"0.3", b"") + FIELD + GRID, "bad.ini:6", "radius")
runc("missing study", SHAPE + FIELD + GRID, "[study] name", "missing")
runc("unknown study", b"[study]\nname = nosuch\n" + SHAPE + FIELD + GRID, "bad.ini:2", "unknown study")
runc("study name sweep", b"[study]\nname = smoke, smoke\n" + SHAPE + FIELD + GRID, "study", "sweep")
runc("empty list item", HEAD + SHAPE + FIELD + b"[grid]\nn = 8,,16\n", "bad.ini:10", "empty item")
runc("trailing comma", HEAD + SHAPE + FIELD + b"[grid]\nn = 8,\n", "bad.ini:10", "empty item")
runc("bad sweep point", HEAD + SHAPE + FIELD + b"[grid]\nn = 8, 1\n", "sweep point 1", "[grid] n")
runc("sweep too large", GOOD + b"[perturb]\nscale = " + b",".join([b"0.01"] * 1000) + b"\noffset = " + b",".join([b"0"] * 1000) + b"\n[metrics]\nband = " + b",".join([b"0.1"] * 1000) + b"\n",
     "more than 100000000 points")
runc("include a directory", GOOD.replace(SHAPE, b"") + b"[shape]\ninclude = .\n", "include", "a directory")
runc("include /dev/zero", GOOD.replace(SHAPE, b"") + b"[shape]\ninclude = /dev/zero\n", "bad.ini:8", "/dev/zero", "not a regular file (a device)")
runc("include /dev/stdin", GOOD.replace(SHAPE, b"") + b"[shape]\ninclude = /dev/stdin\n", "bad.ini:8", "/dev/stdin", "not a regular file")
runc("include missing", GOOD.replace(SHAPE, b"") + b"[shape]\ninclude = nope.ini\n", "bad.ini:8", "nope.ini")
# ---- typed values --------------------------------------------------------
for v in [b"abc", b"1.5", b"0x10", b"99999999999999999999", b"8 8", b"-3", b"1", b"5000", b"1e3"]:
    runc("grid n = " + v.decode(), HEAD + SHAPE + FIELD + b"[grid]\nn = " + v + b"\n", "bad.ini:10", "[grid] n")
for v in [b"nan", b"inf", b"-inf", b"1e999", b"-1", b"0", b"abc", b"0.3 0.2", b"1e151"]:
    runc("radius = " + v.decode(), HEAD + b"[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = " + v + b"\n" + FIELD + GRID, "bad.ini:6", "radius")
for v in [b"0.5", b"0.5 0.5 0.5", b"inf 0.5", b"1e200 0", b"0.5 nan", b"a b", b"1e-400x 0"]:
    runc("center = " + v.decode(), HEAD + b"[shape]\nkind = circle\ncenter = " + v + b"\nradius = 0.3\n" + FIELD + GRID, "bad.ini:5", "center")
runc("bad bool", GOOD + b"[output]\nvti = maybe\n", "bad.ini:12", "boolean")
runc("unknown field kind", HEAD + SHAPE + b"[field]\nkind = magic\n" + GRID, "bad.ini:8", "exact")
runc("unknown shape kind", HEAD + b"[shape]\nkind = blob\n" + FIELD + GRID, "bad.ini:4", "[shape] kind")
runc("hi below lo", GOOD + b"lo = 0 0\nhi = 1 -1\n", "bad.ini:12", "hi > lo")
runc("lo beyond the domain", GOOD + b"lo = -1e200 0\n", "bad.ini:11", "1e150")
runc("3D grid over the memory budget", HEAD + SPHERE + FIELD + b"[grid]\nn = 512\n", "[grid] n", "memory budget")
runc("small memory budget", HEAD + SHAPE + FIELD + b"[grid]\nn = 4096\nmemory_budget = 0.01\n", "[grid] n", "memory_budget")
runc("memory budget zero", GOOD + b"memory_budget = 0\n", "bad.ini:11", "memory_budget")
# every study's estimate against [study] memory_budget / work_budget (issue 21),
# refused before anything is built: the dominating key, the estimate, the budget
ACC = b"[study]\nname = hvb25_accuracy\n"
REN = b"[study]\nname = hvb25_render\n"
runc("proxy grid 2048^3 order 2 over the memory budget",
     ACC + b"memory_budget = 100\n" + SPHERE + b"[field]\nkind = proxy\norder = 2\nres = 2048\nstorage = double\n",
     "bad.ini:11", "[field] res", "needs about 558 GB", "2048^3 cells", "memory budget of 100 GB")
runc("proxy grid over the default memory budget",
     ACC + SPHERE + b"[field]\nkind = proxy\norder = 2\nres = 2048\nstorage = double\n",
     "bad.ini:10", "needs about 558 GB", "the default")
runc("grid peer 1024^3 over the memory budget",
     ACC + b"memory_budget = 10\n" + SPHERE + b"[field]\nkind = gridpeer\nres = 1024\n",
     "bad.ini:10", "[field] res", "needs about 34.4 GB", "memory budget of 10 GB")
# [field] kind = gridpeer: the kinds of field/gridpeer.h, tricubic's not-a-knot minimum
GP = HEAD + SPHERE + b"[field]\nkind = gridpeer\n"
runc("grid peer unknown method", GP + b"method = tricubic5\n" + GRID, "bad.ini:9", "[field] method",
     "trilinear0|taylor1|taylor2|tricubic")
runc("grid peer tricubic below res 4", GP + b"method = tricubic\nres = 3\n" + GRID, "bad.ini:10",
     "[field] res", "res >= 4 for tricubic")
# [field] kind = openvdb (field/vdb.h): its keys and its bound from the box
VDB = HEAD + b"memory_budget = 10\n" + SPHERE.replace(b"radius = 1", b"radius = 0.5") + b"[field]\nkind = openvdb\n"
VGRID = b"[grid]\nn = 8\nlo = -1 -1 -1\nhi = 1 1 1\n"
runc("openvdb voxel zero", VDB + b"voxel = 0\n" + VGRID, "bad.ini:10", "[field] voxel", "voxel size > 0")
runc("openvdb voxel negative", VDB + b"voxel = -0.1\n" + VGRID, "bad.ini:10", "[field] voxel", "below")
runc("openvdb band zero", VDB + b"band = 0\n" + VGRID, "bad.ini:10", "[field] band", "[1, 1000]")
runc("openvdb unknown sampler", VDB + b"sampler = cubic\n" + VGRID, "bad.ini:10", "[field] sampler",
     "box|quadratic|staggered")
runc("openvdb unknown build", VDB + b"build = marching\n" + VGRID, "bad.ini:10", "[field] build",
     "direct|mesh")
runc("openvdb voxel 1e-4 over the memory budget", VDB + b"voxel = 1e-4\n" + VGRID, "bad.ini:10",
     "[field] voxel", "OpenVDB grid", "memory budget of 10 GB")
runc("openvdb mesh build over the memory budget", VDB + b"voxel = 1e-3\nbuild = mesh\n" + VGRID,
     "bad.ini:10", "[field] voxel", "marching-cubes lattice", "memory budget of 10 GB")
runc("openvdb of a 2D shape", HEAD + SHAPE + b"[field]\nkind = openvdb\n" + GRID, "[field] shape",
     "3D shape")
runc("pht mesh at max_level 30 over the memory budget",
     HEAD + SHAPE + b"[field]\nkind = pht\neps = 1e-300\nmax_level = 30\n" + GRID,
     "bad.ini:10", "[field] max_level", "1.15e+18 cells", "memory budget")
runc("frame of 268 Mpixel over the memory budget",
     REN + b"memory_budget = 10\n" + SPHERE + b"[field]\nkind = proxy\n[camera]\nwidth = 16384\nheight = 16384\n",
     "bad.ini:11", "[camera] width", "needs about 53.7 GB", "16384x16384")
runc("renderer max_steps = 1e6 over the work budget",
     REN + SPHERE + b"[field]\nkind = proxy\n[trace]\nmax_steps = 1000000\n",
     "bad.ini:10", "[trace] max_steps", "54.6 h on 1 thread", "work budget of 24 h",
     extra=["--threads", "1"])
runc("eval.n = 1024 over a small work budget",
     ACC + b"work_budget = 0.1\n" + SPHERE + b"[field]\nkind = proxy\n[eval]\nn = 1024\n",
     "bad.ini:11", "[eval] n", "1.07e+09 nodes", "work budget of 6 min", extra=["--threads", "1"])
runc("sjp10_3d validation cache of 1001^3 over the memory budget",
     b"[study]\nname = sjp10_3d\ncases = c\nmemory_budget = 10\n[c]\nshape = s\nlo = -1 -1 -1\n"
     b"hi = 1 1 1\nval_n = 1001\ncache = true\nmidpoints = true\n" + SPHERE.replace(b"[shape]", b"[s]"),
     "bad.ini:9", "[c] val_n", "needs about 128 GB", "1001^3 nodes")
runc("study memory_budget zero", ACC + b"memory_budget = 0\n" + SPHERE + b"[field]\nkind = proxy\n",
     "bad.ini:3", "memory_budget")
runc("study work_budget negative", ACC + b"work_budget = -1\n" + SPHERE + b"[field]\nkind = proxy\n",
     "bad.ini:3", "work_budget")
runc("perturb scale out of range", GOOD + b"[perturb]\nscale = 2\n", "bad.ini:12", "[perturb] scale")
runc("metrics band nan", GOOD + b"[metrics]\nband = nan\n", "bad.ini:12", "band")
runc("grid too large 3D", HEAD + SPHERE + FIELD + b"[grid]\nn = 100000\n", "[grid] n", "[2, 512]")
# accepted-but-uncomputable ranges, tightened (a repository config, by
# absolute path, so that its includes resolve)
REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
POLYCFG = os.path.join(REPO, "configs/paper/bs04/bs04_polygonization.ini")
for v in ["1e-300", "1e-13", "0"]:
    case("polygonization eps = " + v, ["run", POLYCFG, "--set", "study.eps=" + v, "--out", "{D}/o"],
         ["study.eps", "[1e-12, "])
case("polygonization fit_eps tiny", ["run", POLYCFG, "--set", "study.fit_eps=1e-3 1e-300", "--out", "{D}/o"],
     ["study.fit_eps", ">= 1e-12"])
RF = (HEAD.replace(b"smoke", b"smoke") + b"[field]\nkind = rfunc\ncurve = C\neps = 1e-300\n"
      b"[C]\nkind = bspline_curve\norder = 2\ncontrol = 0 0; 1 0; 1 1\n" + GRID)
probec("rfunc curve eps = 1e-300", PTS, "bad.ini:6", "[field] eps", ini=RF)
# ---- --set ---------------------------------------------------------------
case("malformed --set", RUN + ["--set", "grid.n"], ["--set grid.n", "section.key=value"], ini=GOOD)
case("--set without dot", RUN + ["--set", "n=3"], ["section.key=value"], ini=GOOD)
case("--set empty value", RUN + ["--set", "grid.n="], ["empty value"], ini=GOOD)
case("--set unknown key", RUN + ["--set", "grid.foo=1"], ["grid.foo", "unknown key"], ini=GOOD)
case("--set out of range", RUN + ["--set", "grid.n=0"], ["grid.n", "[2, 4096]"], ini=GOOD)
case("--set include", RUN + ["--set", "shape.include=x.ini"], ["include"], ini=GOOD)
case("--set group missing", RUN + ["--set", "field=@{D}/none.ini"], ["--set field=@", "none.ini"],
     ini=GOOD)
case("--set group without its section", RUN + ["--set", "field=@{D}/bad.ini"],
     ["--set field=@", "has no [field] section"], ini=HEAD + SHAPE + GRID)
case("--set group empty name", RUN + ["--set", "=@x.ini"], ["section.key=value or section=@FILE"],
     ini=GOOD)
case("--set group unknown key", RUN + ["--set", "shape=@{D}/g.ini"], ["g.ini:2", "[shape] radiu",
     "unknown key"], ini=GOOD, files={"g.ini": b"[shape]\nradiu = 1\nkind = circle\ncenter = 0 0\nradius = 1\n"})
case("--set kind switch: the new kind's missing key", RUN + ["--set", "shape.kind=sphere"],
     ["[shape] center", "missing key"], ini=GOOD)
case("--set control char", RUN + ["--set", "grid.n=8\x01"], ["grid.n", "\\x01"], ini=GOOD)
case("--set with newline", RUN + ["--set", "grid.n=8\nX"], ["\\x0a"], ini=GOOD)
case("--set 1e200 vector", RUN + ["--set", "shape.center=1e200 0"], ["center", "1e150"], ini=GOOD)
# ---- options and --out ---------------------------------------------------
case("unknown run option", ["run", "{D}/bad.ini", "--frobnicate"], ["--frobnicate", "unknown option"], ini=GOOD)
case("--threads 0", RUN + ["--threads", "0"], ["--threads 0", "[1, 1024]"], ini=GOOD)
case("--threads abc", RUN + ["--threads", "abc"], ["--threads abc"], ini=GOOD)
case("--threads 99999", RUN + ["--threads", "99999"], ["[1, 1024]"], ini=GOOD)
case("--threads missing value", ["run", "{D}/bad.ini", "--threads"], ["--threads needs a value"], ini=GOOD)
case("--out missing value", ["run", "{D}/bad.ini", "--out"], ["--out needs a value"], ini=GOOD)
case("--out empty", ["run", "{D}/bad.ini", "--out", ""], ["--out", "empty"], ini=GOOD)
case("--out /", ["run", "{D}/bad.ini", "--out", "/"], ["--out /", "root"], ini=GOOD)
case("--out ///", ["run", "{D}/bad.ini", "--out", "///"], ["root"], ini=GOOD)
case("--out a file", ["run", "{D}/bad.ini", "--out", "{D}/bad.ini"], ["exists and is not a directory"], ini=GOOD)
case("--out under a file", ["run", "{D}/bad.ini", "--out", "{D}/bad.ini/sub/o"], ["is not a directory"], ini=GOOD)
case("--out /proc/x", ["run", "{D}/bad.ini", "--out", "/proc/x"], ["--out /proc/x", "cannot create"], ini=GOOD)
case("--out /proc/x/y", ["run", "{D}/bad.ini", "--out", "/proc/x/y"], ["cannot create"], ini=GOOD)
case("--out /dev/null", ["run", "{D}/bad.ini", "--out", "/dev/null"], ["not a directory"], ini=GOOD)
case("--out control char", ["run", "{D}/bad.ini", "--out", "{D}/bad.ini/\x1b[2J"], ["\\x1b"], ini=GOOD)
case("failed run leaves no parent", ["run", "{D}/bad.ini", "--out", "{D}/new/deeper/o"], ["bad.ini:11"], ini=GOOD + b"nn = 1\n")
# a results folder is never '.', '..' or a folder reached through a missing one
case("--out .", ["run", "{D}/bad.ini", "--out", "."], ["--out .", "cannot be named '.' or '..'"], ini=GOOD)
case("--out ..", ["run", "{D}/bad.ini", "--out", ".."], ["--out ..", "cannot be named"], ini=GOOD)
case("--out D/.", ["run", "{D}/bad.ini", "--out", "{D}/."], ["cannot be named"], ini=GOOD)
case("--out res/.", ["run", "{D}/bad.ini", "--out", "res/."], ["--out res/.", "cannot be named"], ini=GOOD)
case("--out res/..", ["run", "{D}/bad.ini", "--out", "res/.."], ["--out res/..", "cannot be named"], ini=GOOD)
case("--out nonexist/../y", ["run", "{D}/bad.ini", "--out", "nonexist/../y"], ["'..' follows nonexist"], ini=GOOD)
case("--out D/nonexist/../y", ["run", "{D}/bad.ini", "--out", "{D}/nonexist/../y"], ["'..' follows"], ini=GOOD)
case("merge .", ["merge", "."], ["merge .", "cannot be named"])
case("merge ..", ["merge", ".."], ["merge ..", "cannot be named"])
case("config stem ..", ["run", "{D}/...ini"], ["...ini", "name '..' cannot name its results folder"],
     files={"...ini": GOOD})
case("config stem .", ["run", "{D}/..ini"], ["..ini", "name '.' cannot name"], files={"..ini": GOOD})
case("config stem .. with --set", ["run", "{D}/...ini", "--set", "grid.n=8"], ["name '..'"],
     files={"...ini": GOOD})
case("plan config stem ..", ["plan", "{D}/...ini"], ["name '..'"], files={"...ini": GOOD})
QUICK = os.path.join(REPO, "configs/compare/quick.ini")
WUSON_PATH = "/usr/share/assimp/models/AC/Wuson.ac"
# the validation pass reads every method section through its kind's factory
# (nothing built), so a typo in the last method is named before the first
# method is built, by plan as by run
case("compare: a typo in the last method is named at plan", ["plan", QUICK, "--set",
     "m_vdb.samplr=box"], ["m_vdb", "samplr", "unknown key"])
case("compare: a bad value of a method key is named at plan", ["plan", QUICK, "--set",
     "m_vdb.sampler=cubic"], ["m_vdb.sampler", "box|quadratic|staggered"])
case("compare: an unknown shape kind in skip_kinds is named", ["plan", QUICK, "--set",
     "m_gp_tri.skip_kinds=spheer"], ["m_gp_tri.skip_kinds", "unknown shape kind 'spheer'"])
case("compare: an unknown shape kind in shape_kinds is named", ["plan", QUICK, "--set",
     "m_rfunc.shape_kinds=bspline"], ["m_rfunc.shape_kinds", "unknown shape kind 'bspline'"])
case("missing config", ["run", "{D}/nope.ini", "--out", "{D}/o"], ["nope.ini", "cannot open"])
case("missing CONFIG", ["run"], ["missing CONFIG.ini"])
case("two configs", ["run", "{D}/bad.ini", "{D}/bad.ini"], ["unexpected argument"], ini=GOOD)
case("unknown command", ["frobnicate"], ["unknown command"], rc=2)
case("config name with escape", ["run", "{D}/\x1b]0;x\x07.ini"], ["\\x1b", "\\x07", "cannot open"])
# ---- machine failures: exit 1 -------------------------------------------
case("list into /dev/full", ["list"], ["cannot write to standard output"], rc=1, stdout_to="/dev/full")
case("help into /dev/full", ["help"], ["cannot write"], rc=1, stdout_to="/dev/full")
case("help run into /dev/full", ["help", "run"], ["cannot write"], rc=1, stdout_to="/dev/full")
case("--version into /dev/full", ["--version"], ["cannot write"], rc=1, stdout_to="/dev/full")
case("probe into /dev/full", PROBE, ["cannot write"], ini=GOOD, pts=PTS, rc=1, stdout_to="/dev/full")
case("out of memory", RUN, ["out of memory"], ini=HEAD + SHAPE + FIELD + b"[grid]\nn = 4096\n", rc=1,
     shell_prefix="ulimit -v 600000;")
# ---- numbers at the ends of the double range -------------------------------
case("pht eps 5e-324: below the smallest eps accepted",
     ["run", os.path.join(REPO, "configs/paper/sjp10/sjp10_fig1.ini"), "--set", "fit.eps=5e-324",
      "--out", "{D}/o"], ["fit.eps", "got '5e-324' (below the smallest value accepted, 1e-300)"])
runc("offset 1e-400 rounds to zero", GOOD + b"[perturb]\noffset = 1e-400\n", "bad.ini:12",
     "out of range", "below the smallest double")
runc("offset 1e400 overflows", GOOD + b"[perturb]\noffset = 1e400\n", "bad.ini:12",
     "out of range", "beyond the largest double")
runc("offset 2 above the range", GOOD + b"[perturb]\noffset = 2\n", "bad.ini:12",
     "above the largest value accepted, 1")
# ---- wrong answers accepted before: now input errors -----------------------
RENDER = os.path.join(REPO, "configs/paper/hvb25/hvb25_table4_render_sphere.ini")
for k, v, want in [("camera.target", "1.6 -2.2 1.4", "camera"), ("trace.max_steps", "0", "trace.max_steps"),
                   ("trace.box", "maybe", "trace.box"), ("study.reps", "0", "study.reps"),
                   ("trace.eps", "0", "trace.eps"), ("camera.fov", "nan", "camera.fov")]:
    # every error path of the renderer's key reader (steps and box were read
    # uninitialised there: exit 1 and no error line under the sanitizer)
    case("hvb25_render %s = %s" % (k, v), ["run", RENDER, "--set", k + "=" + v, "--out", "{D}/o"],
         [want])
PX = (b"[study]\nname = hvb25_accuracy\n[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"
      b"[field]\nkind = proxy\norder = 2\nres = 4\ninput = sdf\ncurvature = fit\n[eval]\nn = 5\n")
runc("proxy lo = -1e200 beyond |x| <= 1e150", PX, "field.lo", "[-1e+150, 1e+150]",
     extra=["--set", "field.lo=-1e200"])
for h in ["1e-300", "1e300", "1e-8", "1e6"]:
    runc("fit_spacing = " + h + " is input (not a singular design)", PX, "field.fit_spacing",
         "[1e-06, 10000]", extra=["--set", "field.fit_spacing=" + h])
# order 2 on a triangle mesh with the SDF's analytic curvature: a mesh has
# none at its edges and vertices (the old run built needle proxies that
# flipped the sign of whole cells); refused, naming the key to change
MESHPX = (b"[study]\nname = hvb25_accuracy\n[shape]\nkind = mesh\nfile = " +
          WUSON_PATH.encode() + b"\nfit = box\n[field]\nkind = proxy\norder = 2\nres = 4\n[eval]\nn = 5\n")
runc("proxy order 2 on a mesh needs curvature = fit", MESHPX, "[field] curvature",
     "triangle mesh", "curvature = fit")
runc("proxy clip = nope names the kinds", PX, "field.clip", "bound|paper|off",
     extra=["--set", "field.clip=nope"])
runc("proxy clip = off with a clip_radius", PX.replace(b"[eval]", b"clip = off\nclip_radius = 1\n[eval]"), "[field] clip_radius",
     "clip = off takes no radius")
runc("hvb25_render false_hit_tol = 0", PX.replace(b"hvb25_accuracy", b"hvb25_render"),
     "study.false_hit_tol", extra=["--set", "study.false_hit_tol=0"])
BZ = os.path.join(REPO, "configs/shapes/hvb25_bezier_single.ini").encode()
runc("signed open surface names its input", b"[study]\nname = hvb25_accuracy\n[shape]\ninclude = " + BZ +
     b"\n[field]\nkind = proxy\norder = 1\nres = 4\ninput = parametric\nsigned = true\n[eval]\nn = 5\n",
     "bad.ini:10", "[field] signed", "the parametric input of this shape has no inside")
# ---- the non-finite rule: outputs written, then exit 1 -------------------
# A proxy whose footpoints are moved 1e300 (double storage holds it; the
# decode's |x - p|^2 overflows) is non-finite at every one of the 17^3 = 4913
# evaluation points.  (Half storage clamps what it cannot hold: proxy/store.h.)
NF = (b"[study]\nname = hvb25_accuracy\nband = 0.05\n"
      b"[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n"
      b"[field]\nkind = proxy\norder = 1\nres = 8\ninput = sdf\nstorage = double\nseed = 1\n"
      b"[eval]\nn = 17\n")
OUTS = ["o", "o.points"]
case("noise 1e300: non-finite is exit 1", RUN + ["--set", "field.noise=1e300"],
     ["hvb25_accuracy.csv", "row 1", "point 0", "nonfinite", "4913 non-finite points",
      "allow_nonfinite"], ini=NF, rc=1, keep=OUTS)
case("non-finite in a sweep names the point", RUN + ["--set", "field.noise=0,1e300"],
     ["row 2", "point 1", "4913 non-finite points"], ini=NF, rc=1, keep=OUTS)
case("allow_nonfinite swept: the point that does not allow it", RUN + [
     "--set", "field.noise=1e300", "--set", "study.allow_nonfinite=true,false"],
     ["row 2", "point 1"], ini=NF, rc=1, keep=OUTS)
case("--point run: non-finite is exit 1", RUN + ["--set", "field.noise=1e300", "--point", "0"],
     ["row 1", "4913 non-finite points"], ini=NF, rc=1, keep=["o.points"])
case("merge: non-finite is exit 1 as the run's", ["merge", "{D}/o"],
     ["row 1", "point 0", "4913 non-finite points", "allow_nonfinite"], ini=NF, rc=1,
     keep=OUTS, shell_prefix='"$DFL_TABLE_DFLAB" run bad.ini --set field.noise=1e300 '
     '--point 0 --out o --quiet 2>/dev/null;')
runc("allow_nonfinite not a bool", NF, "allow_nonfinite",
     "boolean", extra=["--set", "study.allow_nonfinite=maybe"])

# ---- probe and the points reader ----------------------------------------
case("probe missing points", ["probe", "{D}/bad.ini", "--points", "{D}/none.csv"], ["none.csv", "cannot open"], ini=GOOD)
case("probe no --points", ["probe", "{D}/bad.ini"], ["--points", "missing"], ini=GOOD)
case("probe points a directory", ["probe", "{D}/bad.ini", "--points", "{D}"], ["a directory"], ini=GOOD)
case("probe points /dev/zero", ["probe", "{D}/bad.ini", "--points", "/dev/zero"], ["/dev/zero:1", "NUL"], ini=GOOD)
probec("probe wrong field count", b"x,y\n0.1,0.2\n0.3\n", "pts.csv:3", "expected 2 fields")
probec("probe nan", b"x,y\n0.1,nan\n", "pts.csv:2", "finite")
probec("probe inf", b"x,y\ninf,0\n", "pts.csv:2", "finite")
probec("probe 1e999", b"x,y\n1e999,0\n", "pts.csv:2", "finite")
probec("probe not a number", b"x,y\n0.1,abc\n", "pts.csv:2", "column 'y'")
probec("probe trailing junk", b"x,y\n0.1,0.2x\n", "pts.csv:2", "column 'y'")
probec("probe empty cell", b"x,y\n0.1,\n", "pts.csv:2", "column 'y'")
probec("probe NUL in a row", b"x,y\n0.1,0.2\0 9\n", "pts.csv:2", "NUL byte at column 8")
probec("probe NUL in header", b"x,\0y\n0.1,0.2\n", "pts.csv:1", "NUL")
probec("probe CR inside", b"x,y\n0.1,\r0.2\n", "pts.csv:2", "0x0d")
probec("probe control char", b"x,y\n0.1,0.2\x1b\n", "pts.csv:2", "0x1b")
probec("probe invalid UTF-8", b"x,y\n0.1,0.2\xff\n", "pts.csv:2", "invalid UTF-8")
probec("probe line too long", b"x,y\n" + b"1" * 5000 + b",2\n", "pts.csv:2", "longer than 4095")
probec("probe endless line", b"x,y\n" + b"1" * 100000, "pts.csv:2", "longer than 4095")
probec("probe unknown column", b"x,y,w\n0.1,0.2,3\n", "pts.csv:1", "unknown column 'w'")
probec("probe duplicate column", b"x,x\n0.1,0.2\n", "pts.csv:1", "duplicate column")
probec("probe missing column", b"x\n0.1\n", "pts.csv:1", "missing column 'y'")
probec("probe z for 2D", b"x,y,z\n0.1,0.2,0.3\n", "pts.csv:1", "'z'")
probec("probe too many columns", b",".join([b"x"] * 20) + b"\n", "pts.csv:1", "too many columns")
probec("probe empty file", b"", "pts.csv", "empty")
probec("probe only BOM", b"\xef\xbb\xbf", "pts.csv", "empty")
probec("probe no rows", b"x,y\n", "pts.csv", "no points")
probec("probe point beyond the domain", b"x,y\n1e155,0.5\n", "point 1", "outside dflab's range")
probec("probe point -1e200", b"x,y\n0.5,0.5\n0.5,-1e200\n", "point 2", "y = -1e+200")
probec("probe jet no direction", b"x,y\n0.1,0.2\n", "pts.csv:1", "missing column 'dx'", extra=["--jet", "2"])
probec("probe jet zero direction", b"x,y,dx,dy\n0.1,0.2,0,0\n", "point 1", "direction is zero", extra=["--jet", "2"])
probec("probe jet -0 direction", b"x,y,dx,dy\n0.1,0.2,-0,0.0\n", "point 1", "direction is zero", extra=["--jet", "1"])
probec("probe jet nan direction", b"x,y,dx,dy\n0.1,0.2,nan,1\n", "pts.csv:2", "column 'dx'", extra=["--jet", "2"])
probec("probe jet huge direction", b"x,y,dx,dy\n0.1,0.2,1e200,1\n", "point 1", "direction dx", extra=["--jet", "2"])
probec("probe jet too high", b"x,y,dx,dy\n0.1,0.2,1,0\n", "--jet 99", "[0, 24]", extra=["--jet", "99"])
probec("probe jet negative", b"x,y,dx,dy\n0.1,0.2,1,0\n", "--jet -1", extra=["--jet", "-1"])
probec("probe jet text", b"x,y,dx,dy\n0.1,0.2,1,0\n", "--jet x", extra=["--jet", "x"])
probec("probe sweep config", b"x,y\n0.1,0.2\n", "shape.radius", "sweep",
       ini=HEAD + b"[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3, 0.2\n" + FIELD + GRID)
probec("probe unknown field key", b"x,y\n0.1,0.2\n", "bad.ini:9", "[field] foo",
       ini=HEAD + SHAPE + b"[field]\nkind = exact\nfoo = 1\n" + GRID)
probec("probe 3D field 2D points", b"x,y\n0.1,0.2\n", "pts.csv:1", "missing column 'z'", ini=HEAD + SPHERE + FIELD)
probec("probe bad config", PTS, "bad.ini:1", "NUL", ini=b"\0")

# ---- mesh shapes: bad files name the file and what is wrong ----------------
P3 = b"x,y,z\n0.1,0.2,0.3\n"
TRI = b"v 0 0 0\nv 1 0 0\nv 0 1 0\n"


def meshc(name, fname, data, *want, keys=b""):
    """A probe of [shape] kind = mesh, file = fname (written with data
    beside bad.ini unless data is None)."""
    ini = HEAD + b"[shape]\nkind = mesh\nfile = " + fname.encode() + b"\n" + keys + FIELD
    case(name, PROBE, want, ini=ini, pts=P3, files={} if data is None else {fname: data})


meshc("mesh file missing", "nope.obj", None, "bad.ini:5", "[shape] file", "nope.obj", "cannot open")
meshc("mesh file empty", "e.obj", b"", "bad.ini:5", "e.obj", "empty file")
meshc("mesh file not a mesh", "junk.stl", b"solid x\n garbage\n", "bad.ini:5", "junk.stl", "not a mesh")
meshc("mesh file too small to be OBJ", "junk.obj", b"hello\n", "junk.obj", "not a mesh")
meshc("mesh file text without faces", "junk.obj", b"hello world\nthis is not\n", "junk.obj", "no triangles")
meshc("mesh file NaN vertex", "nan.obj", b"v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "nan.obj",
      "non-finite coordinate")
meshc("mesh file beyond float range", "big.obj", b"v 1e300 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
      "big.obj", "non-finite coordinate")
meshc("mesh file lines only", "l.obj", TRI + b"l 1 2\n", "l.obj", "no triangles", "1 point or line faces")
meshc("mesh file degenerate triangle", "d.obj", TRI + b"v 2 0 0\nf 1 2 3\nf 1 2 4\n", "d.obj",
      "triangle 1 is degenerate (zero area)")
meshc("mesh file a directory", ".", None, "bad.ini:5", "a directory")
meshc("mesh center without fit", "t.obj", TRI + b"f 1 2 3\n", "bad.ini:6", "[shape] center",
      "only read with fit = box", keys=b"center = 0 0 0\n")
meshc("mesh size zero", "t.obj", TRI + b"f 1 2 3\n", "bad.ini:7", "[shape] size", "> 0",
      keys=b"fit = box\nsize = 0\n")
meshc("mesh distance unknown", "t.obj", TRI + b"f 1 2 3\n", "bad.ini:6", "[shape] distance",
      keys=b"distance = both\n")
case("mesh file and polygonize", PROBE, ["bad.ini", "exactly one of file"], pts=P3,
     ini=HEAD + b"[shape]\nkind = mesh\nfile = t.obj\npolygonize = s\n" + FIELD)
case("mesh polygonize missing section", PROBE, ["bad.ini:5", "[shape] polygonize", "no such section"],
     pts=P3, ini=HEAD + b"[shape]\nkind = mesh\npolygonize = s\n" + FIELD)
case("mesh polygonize 2D shape", PROBE, ["[shape] polygonize", "not a 3D shape"], pts=P3,
     ini=HEAD + b"[shape]\nkind = mesh\npolygonize = s\n" + FIELD +
     b"[s]\nkind = circle\ncenter = 0 0\nradius = 0.5\n")
case("mesh polygonize empty level set", PROBE, ["[shape] polygonize", "does not cross the grid"],
     pts=P3, ini=HEAD + b"[shape]\nkind = mesh\npolygonize = s\nresolution = 8\n" + FIELD +
     b"[s]\nkind = sphere\ncenter = 5 5 5\nradius = 0.5\n")


def run_case(c, dflab, base):
    d = tempfile.mkdtemp(prefix="dfl_bad_", dir=base)
    try:
        inputs = {"out.txt", "err.txt"}
        if c["ini"] is not None:
            open(os.path.join(d, "bad.ini"), "wb").write(c["ini"])
            inputs.add("bad.ini")
        for name, data in c["files"].items():   # further inputs, by name
            open(os.path.join(d, name), "wb").write(data)
            inputs.add(name)
        if c["pts"] is not None:
            open(os.path.join(d, "pts.csv"), "wb").write(c["pts"])
            inputs.add("pts.csv")
        args = [a.replace("{D}", d) for a in c["args"]]
        env = dict(os.environ, DFL_TABLE_DFLAB=dflab, **c["env"])  # for shell prefixes
        out_path = c["stdout_to"] or os.path.join(d, "out.txt")
        with open(out_path, "wb") as out, open(os.path.join(d, "err.txt"), "wb") as err:
            if c["shell_prefix"]:
                cmd = c["shell_prefix"] + " exec " + " ".join("'" + a.replace("'", "'\\''") + "'" for a in [dflab] + args)
                p = subprocess.run(["/bin/sh", "-c", cmd], stdout=out, stderr=err, cwd=d, env=env, timeout=60)
            else:
                p = subprocess.run([dflab] + args, stdout=out, stderr=err, cwd=d, env=env, timeout=60,
                                   stdin=subprocess.DEVNULL)
        if not c["stdout_to"]:
            open(os.path.join(d, "out.txt"), "ab").close()
        msg = open(os.path.join(d, "err.txt"), "rb").read()
        stdout = b"" if c["stdout_to"] else open(os.path.join(d, "out.txt"), "rb").read()
        problems = []
        if p.returncode != c["rc"]:
            problems.append("exit status %d, expected %d" % (p.returncode, c["rc"]))
        lines = msg.split(b"\n")
        if not msg.endswith(b"\n") or not lines[-2].startswith(b"dflab: error: "):
            problems.append("stderr does not end with one 'dflab: error:' line")
        if msg.count(b"dflab: error: ") != 1:
            problems.append("%d error lines" % msg.count(b"dflab: error: "))
        if any(b < 0x20 and b != 0x0a for b in msg) or b"\x7f" in msg:
            problems.append("control bytes on stderr (not escaped)")
        text = msg.decode("utf-8", "replace")
        for w in c["want"]:
            if w not in text:
                problems.append("message lacks %r" % w)
        if stdout:
            problems.append("stdout not empty: %r" % stdout[:80])
        missing = c["keep"] - set(os.listdir(d))
        if missing:
            problems.append("outputs missing: %s" % sorted(missing))
        left = set(os.listdir(d)) - inputs - c["keep"]
        if left:
            problems.append("files left behind: %s" % sorted(left))
        return problems, text.strip()
    finally:
        shutil.rmtree(d, ignore_errors=True)


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    dflab = os.path.abspath(sys.argv[1])
    if "--list" in sys.argv:
        for c in CASES:
            print(c["name"])
        return 0
    base = tempfile.mkdtemp(prefix="dfl_badtable_")
    bad = 0
    try:
        for c in CASES:
            if c["shell_prefix"] and os.environ.get("DFL_SANITIZE"):
                continue  # ulimit -v and AddressSanitizer's shadow memory do not mix
            problems, text = run_case(c, dflab, base)
            if problems:
                bad += 1
                print("FAIL [%s]: %s\n    stderr: %s" % (c["name"], "; ".join(problems), text[-300:]))
            elif "-v" in sys.argv:
                print("ok   [%s]: %s" % (c["name"], text[-160:]))
    finally:
        shutil.rmtree(base, ignore_errors=True)
    print("bad-input table: %d cases, %d failing" % (len(CASES), bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
