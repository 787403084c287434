#!/usr/bin/env python3
"""Writes results/REPORT.md from the results directories of `make reproduce`.

Each results/<name>/ holding a manifest.json is one study run.  Its section
comes from the first paper folder sections/<paper>/ (see scripts/README.md)
holding a module <study>.py: render(ctx) -> markdown, with tables beside the
paper's values (ctx.ref("bs04_facts.csv")) and figures as PNG
(ctx.figure(fig, stem)); an optional list ASSUMPTIONS names the settings the
paper leaves open, gathered per paper; an optional verdicts(ctx) returns
rows (claim, paper's value, ours, best peer, verdict, why) with verdict one
of VERDICTS, gathered into one table at the top of its paper's section.
The report opens with a table of contents.  A study no folder knows gets its CSV
as a table under "Other studies" (a module without render: under its paper).
A section that fails (its module or its folder does not import, render
raises) shows its traceback in place and makes the exit status 1.
Every figure and table names the config it came from."""
import argparse
import importlib
import importlib.util
import os
import sys
import traceback

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dflio  # noqa: E402
import web_section  # noqa: E402

SECTIONS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "sections")
OTHER = "other"
VERDICTS = ("reproduced", "differs", "not reproducible", "not comparable")


def slug(title):
    """The anchor a Markdown renderer (GitHub's rule) gives a heading: lower
    case, punctuation other than '-' and '_' dropped, spaces to '-'."""
    out = []
    for ch in title.strip().lower():
        if ch.isalnum() or ch in "-_":
            out.append(ch)
        elif ch == " ":
            out.append("-")
    return "".join(out)


def verdict_rows(mod, ctx):
    """The module's verdict rows for run ctx (none without verdicts());
    a verdict outside VERDICTS is an error of the section."""
    fn = getattr(mod, "verdicts", None) if mod else None
    rows = list(fn(ctx)) if fn else []
    for r in rows:
        if len(r) != 6 or r[4] not in VERDICTS:
            raise ValueError(f"{ctx.name}: verdict row {r!r}: expected (claim, paper, ours, "
                             f"peer, verdict, why) with verdict in {VERDICTS}")
    return rows


class Paper:
    """One paper folder root/<folder>/ of section modules: the package it
    imports as, its TITLE and RANK, and why it cannot be used (None when its
    __init__.py imports)."""

    def __init__(self, root, folder):
        self.dir = os.path.join(root, folder)
        self.pkg = f"{os.path.basename(root)}.{folder}"
        self.folder = folder
        self.title = folder
        self.rank = 50
        self.error = None
        if not os.path.isfile(os.path.join(self.dir, "__init__.py")):
            self.error = f"sections folder {folder}/ has no __init__.py (TITLE, RANK)\n"
            return
        try:
            mod = importlib.import_module(self.pkg)
        except Exception:  # reported as a failed section, the others still render
            self.error = traceback.format_exc()
            return
        self.title = getattr(mod, "TITLE", folder)
        self.rank = getattr(mod, "RANK", 50)

    def has(self, study):
        return os.path.isfile(os.path.join(self.dir, study + ".py"))


def papers(root=SECTIONS):
    """The paper folders under root (every subfolder not starting with '_' or
    '.'), in RANK order.  root is imported as a package named after its base
    name, so its parent goes on sys.path."""
    root = os.path.abspath(root)
    parent = os.path.dirname(root)
    if parent not in sys.path:
        sys.path.insert(0, parent)
    spec = importlib.util.find_spec(os.path.basename(root))
    where = [os.path.abspath(d) for d in (spec.submodule_search_locations or [])] if spec else []
    if root not in where:
        raise ValueError(f"{root}: its name is taken by another package ({where or spec}); "
                         "give the sections folder another name")
    found = [Paper(root, d) for d in sorted(os.listdir(root))
             if os.path.isdir(os.path.join(root, d)) and not d.startswith(("_", "."))]
    return sorted(found, key=lambda p: (p.rank, p.folder))


def paper_of(study, found):
    """The first paper whose folder holds <study>.py, else None."""
    return next((p for p in found if p.has(study)), None)


class Ctx:
    def __init__(self, result_dir, manifest, ref_dir, fig_dir):
        self.dir = result_dir
        self.name = os.path.basename(result_dir.rstrip("/"))
        parent = os.path.dirname(os.path.normpath(result_dir))
        if os.path.basename(os.path.dirname(parent)) == "runs":  # runs/<config>/<set>
            self.name = os.path.basename(parent) + "_" + self.name
        self.manifest = manifest
        self.study = manifest["study"]
        # the config as figure titles name it: the file, and the values a
        # --set run changed (so a figure of a sweep point says which)
        self.config_file = manifest["config"]
        ov = dflio.overrides(manifest)
        self.config = self.config_file + "".join(f" --set {o}" for o in ov)
        self.ref_dir = ref_dir
        self.fig_dir = fig_dir

    def path(self, name):
        return os.path.join(self.dir, name)

    def csv(self, name=None):
        return dflio.read_csv(self.path(name or self.study + ".csv"))

    def ref(self, name):
        """Rows of results/reference/<name> (comment lines skipped)."""
        import csv
        with open(os.path.join(self.ref_dir, name), newline="") as fp:
            lines = [ln for ln in fp if not ln.startswith("#")]
        return list(csv.DictReader(lines))

    def figure(self, fig, stem):
        """Saves a matplotlib figure as results/figures/<run>_<stem>.png and
        returns the markdown image line (path relative to REPORT.md).  A
        figure that breaks the figure rules (sections/common/plot.py,
        figure_problems: axis labels and colour bars on field images, no
        label over a neighbouring panel, legible legends) is not saved: the
        section fails, naming what is wrong."""
        from sections.common.plot import figure_problems
        probs = figure_problems(fig)
        if probs:
            import matplotlib.pyplot as plt
            plt.close(fig)
            raise ValueError(f"figure {stem}: " + "; ".join(probs))
        os.makedirs(self.fig_dir, exist_ok=True)
        fn = f"{self.name}_{stem}.png"
        fig.savefig(os.path.join(self.fig_dir, fn), dpi=110, bbox_inches="tight")
        import matplotlib.pyplot as plt
        plt.close(fig)
        rel = os.path.relpath(os.path.join(self.fig_dir, fn), os.path.dirname(self.report_path))
        return f"![{self.name} {stem}]({rel})"


def generic(ctx):
    rows = ctx.csv()
    if not rows:
        return "(empty table)\n"
    header = list(rows[0].keys())
    body = [[dflio.num(r[h]) if dflio.num(r[h]) is not None else r[h] for h in header] for r in rows]
    return dflio.md_table(header, body) + "\n"


def section(r, paper, assumptions, verdicts):
    """Markdown of run r's section (its module's render, else the generic
    table); collects the module's ASSUMPTIONS into assumptions and its
    verdict rows (with the run's name) into verdicts."""
    mod = importlib.import_module(f"{paper.pkg}.{r.study}") if paper else None
    for line in getattr(mod, "ASSUMPTIONS", []):
        if line not in assumptions:
            assumptions.append(line)
    md = (getattr(mod, "render", None) or generic)(r)
    verdicts += [[f"[{r.name}](#{slug(r.heading)})"] + list(v) for v in verdict_rows(mod, r)]
    return md


def result_dirs(results, only):
    """The results folders a report looks at: results/<run>/ (the whole
    report); with --only also the --set runs, results/runs/<config>/<set>/,
    and only itself when it is the path of a folder elsewhere."""
    def under(root):
        if not os.path.isdir(root):
            return []
        return [os.path.join(root, d) for d in sorted(os.listdir(root))
                if os.path.isdir(os.path.join(root, d)) and d not in ("reference", "figures", "runs")
                and ".stage." not in d and not d.endswith((".points", ".logs"))]
    dirs = under(results)
    if only:
        for c in under(os.path.join(results, "runs")):
            dirs += under(c)
        if os.path.isfile(os.path.join(only, "manifest.json")) and not any(
                os.path.realpath(only) == os.path.realpath(d) for d in dirs):
            dirs.append(only)
    return dirs


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--results", default="results")
    ap.add_argument("--out", default=None,
                    help="default results/REPORT.md, with --only results/REPORT_<SECTION>.md")
    ap.add_argument("--only", metavar="SECTION",
                    help="redraw one section: a results folder name, a study name, a --set "
                         "run's folder (results/runs/CONFIG/OVERRIDES, by that path or its "
                         "name) or the path of any results folder")
    ap.add_argument("--sections", default=SECTIONS,
                    help="folder of the paper folders (default: scripts/sections)")
    a = ap.parse_args(argv)
    if a.out is None:
        tag = os.path.basename(os.path.normpath(a.only)) if a.only else None
        a.out = os.path.join(a.results, f"REPORT_{tag}.md" if tag else "REPORT.md")
    ref_dir = os.path.join(a.results, "reference")
    fig_dir = os.path.join(a.results, "figures")
    runs = []
    for full in result_dirs(a.results, a.only):
        man = dflio.read_manifest(full)
        d = os.path.basename(full)
        if man and (not a.only or a.only in (d, man.get("study")) or
                    os.path.realpath(a.only) == os.path.realpath(full)):
            runs.append(Ctx(full, man, ref_dir, fig_dir))
    if a.only and not runs:
        print(f"report: error: --only {a.only}: no results folder or study of that name "
              f"under {a.results}", file=sys.stderr)
        return 2
    try:
        found = papers(a.sections)
    except ValueError as e:
        print(f"report: error: --sections {e}", file=sys.stderr)
        return 2
    groups = {}
    for r in runs:
        r.report_path = a.out
        paper = paper_of(r.study, found)
        groups.setdefault(paper.folder if paper else OTHER, (paper, []))[1].append(r)

    out = ["# dflab report", "",
           "Generated by `make reproduce` (scripts/report.py) from the results directories below. "
           "Each section names the config that produced it; paper values come from "
           "`results/reference/` (transcribed from the papers). Signed distance is negative "
           "inside everywhere in dflab.", ""]
    out += web_section.lines(a.out)
    failures = 0
    toc = ["## Contents", ""]
    parts = []
    for p in found + [None]:
        key = p.folder if p else OTHER
        if key not in groups and not (p and p.error):
            continue
        title = p.title if p else "Other studies"
        head = [f"## {title}", ""]
        toc.append(f"- [{title}](#{slug(title)})")
        if p and p.error:  # a broken folder is never silent, with or without runs
            failures += 1
            head += [f"Section folder `{p.folder}` failed:", "", "```", p.error, "```", ""]
        assumptions, verdicts = [], []
        body = []
        for r in groups.get(key, (p, []))[1]:
            r.heading = f"{r.name} (`{r.config_file}`, study `{r.study}`)"
            toc.append(f"  - [{r.name}](#{slug(r.heading)})")
            body += [f"### {r.heading}", "", dflio.overrides_md(r.manifest), ""]
            try:
                body.append(section(r, p, assumptions, verdicts))
            except Exception:  # a broken section must not hide the others
                failures += 1
                body += ["```", traceback.format_exc(), "```"]
            body.append(f"Wall time: {r.manifest.get('total_wall_seconds', 0):.2f} s; "
                        f"dflab {r.manifest.get('version')} ({r.manifest.get('git_revision')}).\n")
        if verdicts:
            head += ["### Verdicts", "",
                     "Each claim of the paper a run checks, the paper's value beside ours and the "
                     "best peer's; verdict: " + " / ".join(VERDICTS) + ", with why.", "",
                     dflio.md_table(["run", "claim", "paper", "ours", "best peer", "verdict",
                                     "why"], verdicts), ""]
        if assumptions:
            head += ["### Assumptions (settings the paper leaves open)", ""]
            head += [f"- {a}" for a in assumptions] + [""]
        parts += head + body
    out += toc + [""] + parts
    tmp = a.out + ".tmp"
    with open(tmp, "w") as fp:
        fp.write("\n".join(out) + "\n")
    os.replace(tmp, a.out)
    print(f"report: wrote {a.out} ({len(runs)} runs, {failures} failed sections)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
