"""The report's link to the teaching page (src/web, `make web`) and the
screenshots its browser test writes (`make test`: build/web-test/web-*.png).
Only links, and only to files that exist: the page and the pictures are not
results, so a report written before they exist says how to make them."""
import os

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
PANELS = (("two", "Two segments"), ("norm", "Normalization order"), ("bulge", "Bulging of a curve"))


def lines(report_path):
    """Markdown lines of the section (a paragraph, no heading: the report's
    headings are its papers), paths relative to report_path's folder."""
    here = os.path.dirname(os.path.abspath(report_path))
    rel = lambda *p: os.path.relpath(os.path.join(ROOT, *p), here)  # noqa: E731
    page = os.path.join(ROOT, "build", "web", "index.html")
    link = (f"[A live page]({rel('build', 'web', 'index.html')})" if os.path.exists(page)
            else "A live page (not built yet: `make web`)")
    out = [f"**Teaching page.** {link} runs dflab's own C library "
           "(core, geom, field, rfunc) in the browser: two segments, normalization order, "
           "bulging of a curve. Build it with `make web`, then open build/web/index.html or "
           "serve it with `python3 -m http.server -d build/web`. Screenshots from `make test`:", ""]
    for key, title in PANELS:
        shot = os.path.join(ROOT, "build", "web-test", f"web-{key}.png")
        out += [f"![{title}]({rel('build', 'web-test', f'web-{key}.png')})" if os.path.exists(shot)
                else f"- {title}: no screenshot yet (run `make test`)"]
    return out + [""]
