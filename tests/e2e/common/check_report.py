#!/usr/bin/env python3
"""Checks how scripts/report.py finds and renders sections, on a results tree
and a sections folder made up here (in DIR, which must exist and be empty):

- a study whose module renders gets that text and its ASSUMPTIONS, under its
  paper's TITLE, papers in RANK order;
- a study no folder knows gets the generic table under "Other studies";
- a module without render gets the generic table under its paper;
- a module that does not import, a render that raises, a folder whose
  __init__.py does not import and a folder without __init__.py each show as
  a failed section (their traceback or reason), never as a generic table, and
  the exit status is 1 with the failures counted;
- a module's verdicts(ctx) rows make one "Verdicts" table at the top of its
  paper (linked to the run's heading); a verdict outside report.VERDICTS is
  a failed section;
- the table of contents lists every paper and run, each link the anchor of
  its heading;
- a sections folder whose name another package already takes is refused
  (exit 2).

usage: check_report.py DIR.  Prints "ok" and exits 0, or what failed and 1."""
import json
import os
import subprocess
import sys

REPORT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts",
                      "report.py")

SECTIONS = {
    "papa/__init__.py": 'TITLE = "Paper A"\nRANK = 20\n',
    "papa/tp_good.py": 'ASSUMPTIONS = ["assume x"]\n\n\ndef render(ctx):\n'
                       '    return f"GOOD {ctx.study} {ctx.csv()[0][\'a\']}\\n"\n\n\n'
                       'def verdicts(ctx):\n'
                       '    return [("claim x", "1", ctx.csv()[0]["b"], "-", "differs", "why x")]\n',
    "papa/tp_badverdict.py": 'def render(ctx):\n    return "BADV\\n"\n\n\n'
                             'def verdicts(ctx):\n    return [("c", "1", "2", "-", "maybe", "w")]\n',
    "papa/tp_broken.py": "import no_such_module_dflab\n",
    "papa/tp_norender.py": 'ASSUMPTIONS = ["only assumptions"]\n',
    "papa/tp_raises.py": 'def render(ctx):\n    raise RuntimeError("render boom")\n',
    "papz/__init__.py": 'TITLE = "Paper Z"\nRANK = 10\n',
    "papz/tp_first.py": 'def render(ctx):\n    return "FIRST\\n"\n',
    "papz/tp_title.py": 'def render(ctx):\n    return f"TITLE {ctx.name} [{ctx.config}]\\n"\n',
    "papb/__init__.py": 'raise ImportError("papb init boom")\n',
    "papc/tp_lost.py": 'def render(ctx):\n    return "LOST\\n"\n',
}
STUDIES = ["tp_good", "tp_broken", "tp_norender", "tp_raises", "tp_first", "tp_nomodule",
           "tp_badverdict"]


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as fp:
        fp.write(text)


def section(text, heading):
    """The text from `### heading` to the next heading of level 2 or 3."""
    start = text.index(f"### {heading} ")
    ends = [i for i in (text.find("\n## ", start + 1), text.find("\n### ", start + 1)) if i >= 0]
    return text[start:min(ends) if ends else len(text)]


def main():
    d = sys.argv[1]
    secs = os.path.join(d, "dfl_report_test_sections")
    res = os.path.join(d, "res")
    for rel, text in SECTIONS.items():
        write(os.path.join(secs, rel), text)
    for s in STUDIES:
        write(os.path.join(res, s, "manifest.json"),
              json.dumps({"study": s, "config": f"configs/{s}.ini", "total_wall_seconds": 0.5,
                          "version": "0", "git_revision": "x"}))
        write(os.path.join(res, s, s + ".csv"), "a,b\n1,2.5\n")
    out = os.path.join(d, "REPORT.md")
    run = subprocess.run([sys.executable, REPORT, "--results", res, "--out", out,
                          "--sections", secs], capture_output=True, text=True)
    bad = []

    def want(cond, what):
        if not cond:
            bad.append(what)

    want(run.returncode == 1, f"exit status {run.returncode}, expected 1: {run.stderr}")
    want("(7 runs, 5 failed sections)" in run.stdout, f"summary: {run.stdout!r}")
    text = open(out).read() if os.path.exists(out) else ""
    heads = [ln for ln in text.splitlines() if ln.startswith("## ")]
    want(heads == ["## Contents", "## Paper Z", "## Paper A", "## papb", "## papc", "## Other studies"],
         f"paper headings {heads}")
    table = "| a | b |\n|---|---|\n| 1 | 2.5 |"
    try:
        want("GOOD tp_good 1" in section(text, "tp_good"), "tp_good: render text")
        want("- assume x" in text and "- only assumptions" in text, "ASSUMPTIONS gathered")
        want(text.index("## Paper Z") < text.index("FIRST") < text.index("## Paper A"),
             "tp_first under Paper Z")
        s = section(text, "tp_broken")
        want("no_such_module_dflab" in s and table not in s, "tp_broken: traceback, no table")
        s = section(text, "tp_raises")
        want("render boom" in s and table not in s, "tp_raises: traceback, no table")
        want(table in section(text, "tp_norender"), "tp_norender: generic table")
        s = section(text, "tp_nomodule")
        want(table in s and text.index("## Other studies") < text.index("### tp_nomodule"),
             "tp_nomodule: generic table under Other studies")
        want("papb init boom" in text, "papb: its import error")
        want("papc/ has no __init__.py" in text, "papc: missing __init__.py")
        a = text.index("## Paper A")
        v = text.find("### Verdicts", a)
        want(0 < v < text.index("### tp_good") and
             "| [tp_good](#" in text[v:] and "| claim x | 1 | 2.5 | - | differs | why x |" in text,
             "tp_good's verdict row at the top of Paper A")
        want("maybe" in section(text, "tp_badverdict") and "BADV" not in section(text, "tp_badverdict"),
             "tp_badverdict: a failed section naming the verdict")
        sys.path.insert(0, os.path.dirname(REPORT))
        import report
        toc = text[text.index("## Contents"):text.index("## Paper Z")]
        targets = [ln.split("](#", 1)[1].rstrip(")") for ln in toc.splitlines() if "](#" in ln]
        anchors = {report.slug(ln.lstrip("#").strip()) for ln in text.splitlines()
                   if ln.startswith(("## ", "### "))}
        want(len(targets) == 5 + 7 and all(t in anchors for t in targets),
             f"contents: {len(targets)} links, missing {[t for t in targets if t not in anchors]}")
    except ValueError as e:
        bad.append(f"section missing: {e}")
    # --only finds a --set run under runs/ (by name or path) and a results
    # folder anywhere; its figure titles (ctx.config) carry the overrides
    setrun = os.path.join(res, "runs", "tp_title", "grid.n=16")
    far = os.path.join(d, "elsewhere", "myrun")
    for folder, ov in ((setrun, ["grid.n=16"]), (far, [])):
        write(os.path.join(folder, "manifest.json"),
              json.dumps({"study": "tp_title", "config": "configs/tp_title.ini", "overrides": ov,
                          "total_wall_seconds": 0.5, "version": "0", "git_revision": "x"}))
        write(os.path.join(folder, "tp_title.csv"), "a,b\n1,2.5\n")
    for only, name, title, rep in (
            ("grid.n=16", "tp_title_grid.n=16", "configs/tp_title.ini --set grid.n=16",
             "REPORT_grid.n=16.md"),
            (setrun, "tp_title_grid.n=16", "configs/tp_title.ini --set grid.n=16",
             "REPORT_grid.n=16.md"),
            (far, "myrun", "configs/tp_title.ini", "REPORT_myrun.md")):
        run = subprocess.run([sys.executable, REPORT, "--results", res, "--only", only,
                              "--sections", secs], capture_output=True, text=True)
        rp = os.path.join(res, rep)
        got = open(rp).read() if os.path.exists(rp) else ""
        want(run.returncode in (0, 1) and f"TITLE {name} [{title}]" in got,  # 1: papb, papc
             f"--only {only}: exit {run.returncode} {run.stderr!r}, report {got[-300:]!r}")
    subprocess.run([sys.executable, REPORT, "--results", res, "--out", out, "--sections", secs],
                   capture_output=True, text=True)
    want("TITLE tp_" not in open(out).read() and "TITLE my" not in open(out).read(),
         "the whole report holds no --set run or far folder")
    # a folder named like an importable package is refused, nothing written
    taken = os.path.join(d, "json")
    os.makedirs(os.path.join(taken, "papq"))
    out2 = os.path.join(d, "REPORT2.md")
    run = subprocess.run([sys.executable, REPORT, "--results", res, "--out", out2,
                          "--sections", taken], capture_output=True, text=True)
    want(run.returncode == 2 and "name is taken" in run.stderr and not os.path.exists(out2),
         f"--sections json: exit {run.returncode}, {run.stderr!r}")
    print("\n".join(bad) if bad else "ok")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
