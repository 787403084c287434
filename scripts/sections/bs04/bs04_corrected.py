"""bs04 Fig. 14, eq. 20: the corrected R-equivalence beside the plain one."""
import math
import os

import dflio
from sections.bs04 import bs04_common as bc
from sections.common.plot import pyplot

ASSUMPTIONS = [
    "Corrected join (Fig. 14): the angle of Fig. 1(c)'s segments is not given; dflab uses "
    "α = 90°, 135°, 270° for Fig. 14(a) and the collinear pair α = 180° of Fig. 6(a) for "
    "Fig. 14(b), segments of length L = 1, p = 2 (the figures') and 7, 12.",
    "Eq. 20's derivation (h1 = h2 = q in the hatched sector) needs exact segment distances; "
    "dflab measures them (parts = exact) and the trimmed fields of eq. 4 (disk, strip). Each "
    "point runs three joins: eq. 6; bs04's eq. 20 as printed (correction = eq20, NaN where its "
    "radicand ≤ 0); and dflab's guarded form of eq. 20 (correction = guarded: qt = max(q, h1, h2) "
    "and a floor, rfunc/join.h) — a regularisation of ours, not the paper's. The hatched sector "
    "is computed exactly: (x − O)·e1 ≤ 0 and (x − O)·e2 ≤ 0. It is sampled up to 0.5 L from O.",
    "Fig. 14 draws strip-trimmed segments (as Fig. 1(c) and 6(a)) at p = 2; bs04 does not say "
    "which trim its eq. 20 fields use beyond that. dflab runs exact, disk and strip parts.",
    "The onset of eq. 20's undefined region is searched on the hatched sector's bisector "
    "(4000 radii up to 10 L, then bisection). α = 60° is added to show where the reflex-side "
    "exactness of eq. 20 ends (a case point at θ = 80°, r = 0.5 L).",
]


_f = dflio.cell


def _pairs(by, parts, alphas, ps, corr="guarded"):
    """(part, alpha, p, plain row, corrected row) of every point run with both
    joins (the corrected one in form corr), parts slowest, p fastest."""
    for part in parts:
        for a in alphas:
            for p in ps:
                e = by.get((part, a, p, "requiv", "none"))
                c = by.get((part, a, p, "requiv_corrected", corr))
                if e and c:
                    yield part, a, p, e[1], c[1]


G20 = "dflab's guarded eq. 20"
L20 = "bs04 eq. 20"


def _undefined(by, parts, alphas, ps):
    """Rows of eq. 20's undefined region: shares, sector samples, onset."""
    out = []
    for part, a, p, e, c in _pairs(by, parts, alphas, ps, "eq20"):
        out.append([part, a, p, _f(c, "undefined_share"), int(_f(c, "sector_undefined")),
                    int(_f(c, "sector_points")), _f(c, "onset_radius"), _f(c, "onset_radius_theory")])
    return out


def render(ctx):
    plt = pyplot()
    import numpy as np

    rows = ctx.csv()
    paper = bc.quote(bc.facts(ctx), "corrected")
    md = paper + "\n\n" if paper else ""
    by = {}
    for i, r in enumerate(rows):
        by[(r["parts"], _f(r, "alpha"), int(_f(r, "p")), r["join"], r.get("correction", "guarded"))] = (i, r)
    alphas = sorted({_f(r, "alpha") for r in rows})
    ps = sorted({int(_f(r, "p")) for r in rows})
    parts = [p for p in ("exact", "disk", "strip", "disk_smooth", "strip_smooth")
             if any(r["parts"] == p for r in rows)]
    lit = {(pa, a, p): c for pa, a, p, e, c in _pairs(by, parts, alphas, ps, "eq20")}

    md += (f"Two forms of the corrected join are measured: **{L20}** as printed, "
           "u = (h1^−p + h2^−p − q^−p)^(−1/p), undefined (NaN) where the radicand is ≤ 0, and "
           f"**{G20}**, which subtracts max(q, h1, h2)^−p and floors the sum (rfunc/join.h). "
           "With exact parts both are the same function (h_i ≤ q). With trimmed parts the guard "
           "is active almost everywhere off the segments and reduces to min(h1, h2) in the "
           "hatched sector, so its numbers are not the paper's formula.\n\n")

    body = []
    for part, a, p, e, c in _pairs(by, parts, alphas, ps):
        l = lit.get((part, a, p))
        body.append([part, a, p, int(_f(e, "sector_points")), _f(e, "sector_gdef_max"),
                     _f(e, "sector_gdef_min"), 1 - 2 ** (-1 / p),
                     _f(l, "sector_gdef_max") if l else float("nan"), _f(c, "sector_gdef_max"),
                     _f(e, "sector_gdef_at_rmin"), _f(c, "sector_gdef_at_rmin"),
                     _f(c, "sector_part_gdef_max")])
    md += ("**Hatched sector**: | |∇u| − 1 | over the sector samples (exact geometry). Theory for exact "
           "parts: h1 = h2 = q, so eq. 6 gives |∇u| = 2^(−1/p) (defect 1 − 2^(−1/p)) and eq. 20 gives "
           f"u = q (defect 0). The {L20} column is over the samples where it is defined. "
           "*ring*: the innermost ring of samples, r = L/80:\n\n")
    md += dflio.md_table(["parts", "α (°)", "p", "points", "eq. 6 max", "eq. 6 min",
                          "theory 1−2^(−1/p)", f"{L20} max [paper: 0]", f"{G20} max",
                          "eq. 6 ring", f"{G20} ring", "max ||∇h_i|−1|"], body)
    ex = [b for b in body if b[0] == "exact"]
    if ex:
        worst = max(max(b[7], b[8]) for b in ex)
        dev = max(max(abs(b[4] - b[6]), abs(b[5] - b[6])) for b in ex)
        md += (f"\n\nWith exact distances the paper's claim holds to rounding: eq. 20's largest "
               f"sector defect is {worst:.1e} (both forms), and eq. 6's defect equals 1 − 2^(−1/p) "
               f"within {dev:.1e} at every sample. With the disk trim, h_i > q in the sector (behind "
               "an end point t = y·e − |y|²/L only adds to h²): bs04's eq. 20 then becomes "
               f"undefined beyond an onset radius (next table), and {G20} gives u = min(h1, h2), "
               "whose defect is the trim's own, ≤ 2r/L. So eq. 20 repairs the sector only as far "
               "as the parts are exact distances.\n\n")

    und = _undefined(by, parts, alphas, ps)
    if und:
        md += (f"**Where {L20} is undefined** (radicand ≤ 0): share of the grid nodes, hatched-sector "
               "samples, and the onset radius r* on the sector's bisector, measured (first NaN, "
               "bisection) and in closed form. Closed form (disk trim): behind its end point a "
               "disk-trimmed segment has h = q·sqrt(1 + 2aρ + ρ²), ρ = q/L, a = −(x·e)/q; on the "
               "bisector a = cos(α′/2) (α′ = min(α, 360° − α)), and 2(1 + 2aρ + ρ²)^(−p/2) = 1 gives "
               "**r*/L = sqrt(cos²(α′/2) + 2^(2/p) − 1) − cos(α′/2)**. By Jensen's inequality "
               "(the map a ↦ (1 + 2aρ + ρ²)^(−p/2) is convex and decreasing, and a1 + a2 is "
               "largest on the bisector) this is the smallest onset radius in the sector. Exact "
               "parts never make it undefined (h_i ≤ q); — = defined on the whole scan:\n\n")
        md += dflio.md_table(["parts", "α (°)", "p", "undefined share of grid nodes",
                              "undefined sector samples", "of", "onset r*/L measured",
                              "r*/L closed form"],
                             [[b[0], b[1], b[2], f"{100 * b[3]:.1f} %", b[3 + 1], b[5],
                               "—" if math.isnan(b[6]) else b[6],
                               "—" if math.isnan(b[7]) else b[7]] for b in und])
        dk = [b for b in und if b[0] == "disk" and not math.isnan(b[7])]
        if dk:
            dev = max(abs(b[6] - b[7]) for b in dk)
            sh = [b[3] for b in dk if b[1] == 90.0]
            md += (f"\n\nThe measured onset equals the closed form within {dev:.1e} L at every disk "
                   "point. ")
            if sh:
                md += (f"At α = 90° with disk trims bs04's eq. 20 is undefined at "
                       f"{100 * min(sh):.0f}–{100 * max(sh):.0f} % of the 99 × 99 nodes. ")
        st2 = [b for b in und if b[0] == "strip" and b[2] == 2 and 90.0 <= b[1] <= 180.0]
        if st2:
            ok = all(b[3] == 0.0 and math.isnan(b[6]) for b in st2)
            md += ("With strip trims at p = 2 (Fig. 14's setting) the radicand "
                   + ("stays positive on the whole grid and along the bisector up to 10 L for "
                      "α = 90°–180°, so Fig. 14 is reproduced literally there"
                      if ok else "does not stay positive everywhere (see the table)")
                   + ". ")
        st7 = [b for b in und if b[0] == "strip" and b[2] > 2]
        if st7:
            bad = sorted({b[1] for b in st7 if b[3] > 0})
            good = sorted({b[1] for b in st7 if b[3] == 0})
            md += (f"At p = {', '.join(str(p) for p in sorted({b[2] for b in st7}))} strip trims "
                   + (f"become undefined beyond the onset in the table at α = "
                      f"{', '.join(f'{a:g}°' for a in bad)}" if bad else "stay defined")
                   + (f" and stay defined at α = {', '.join(f'{a:g}°' for a in good)}" if bad and good
                      else "")
                   + ".")
        md += "\n\n"

    body = [[part, a, p, _f(e, "band_gdef_max"), _f(c, "band_gdef_max"),
             _f(e, "band_linf"), _f(c, "band_linf"), _f(e, "vertex_gdef_max"),
             _f(c, "vertex_gdef_max"), _f(e, "vertex_linf"), _f(c, "vertex_linf")]
            for part, a, p, e, c in _pairs(by, parts, alphas, ps)]
    md += ("**Elsewhere** (grid nodes; *band*: 0 < d ≤ 0.1 L and |x − O| ≥ 0.25 L, near regular "
           "points; *vertex*: |x − O| < 0.25 L outside the hatched sector; d = exact distance to the "
           "union; max | |∇u| − 1 | and max |u − d|):\n\n")
    md += dflio.md_table(["parts", "α (°)", "p", "band: eq. 6", f"band: {G20}", "band |u−d|: eq. 6",
                          f"band |u−d|: {G20}", "vertex: eq. 6", f"vertex: {G20}",
                          "vertex |u−d|: eq. 6", f"vertex |u−d|: {G20}"], body)
    exb = [b for b in body if b[0] == "exact"]
    never = all(b[4] <= b[3] + 1e-12 for b in exb)
    trb = [b for b in body if b[0] != "exact"]
    md += "\n\n"
    if exb:
        md += (f"With exact parts, {G20}'s defect (here the same function as {L20}) near regular points is "
               + ("never larger than eq. 6's" if never else "sometimes larger than eq. 6's (see table)")
               + ". ")
    if trb:
        md += (f"With trimmed parts both joins have a band defect of at least "
               f"{min(min(b[3], b[4]) for b in trb):.3f}: the trim's own defect beyond the far end "
               "points, which hides the difference between the joins. ")

    # the reflex side: exact for alpha >= 90 only
    refl = [(a, p, _f(c, "reflex_linf"), _f(c, "case_u"), _f(c, "case_d"))
            for part, a, p, e, c in _pairs(by, parts, alphas, ps, "eq20") if part == "exact"]
    if refl:
        big = [r for r in refl if r[0] >= 90.0]
        small = [r for r in refl if r[0] < 90.0]
        md += ("\n\n**Range of the reflex-side exactness.** With exact parts eq. 20 equals the exact "
               "distance on the reflex side (outside the convex sector) where one segment's closest "
               "point is O: that segment's h = q cancels and u is the other distance. Every "
               "reflex-side point has such a segment only when α′ ≥ 90°. ")
        if big:
            md += (f"Measured max |u − d| on the reflex side, α′ ≥ 90°: "
                   f"{max(r[2] for r in big):.1e} (rounding). ")
        for a, p, lin, cu, cd in small:
            if p == 2:
                md += (f"For α = {a:g}° (p = 2) it is {lin:.3g}: at θ = 80°, r = 0.5 L, both "
                       f"closest points are interior, and eq. 20 gives u = {cu:.5f} r against "
                       f"d = {cd:.5f} r. ")
        md += ("So the statement holds for 90° ≤ α′ ≤ 180° only. For collinear segments (α = 180°, "
               "Fig. 14(b)) the corrected field is the exact distance everywhere. In the convex "
               "sector both joins still bulge (vertex columns), because eq. 20 only cancels q where "
               "it equals both h_i. The paper says the same: |∇u| = 1 is neither expected nor wanted "
               "there.\n\n")

    # images: grad_norm of the joins for p = 2 (or the smallest p); eq. 20's
    # undefined region hatched grey
    p0 = ps[0]
    shown = [a for a in (90.0, 180.0) if a in alphas] or alphas[:2]
    cols = [("exact", "requiv", "none"), ("exact", "requiv_corrected", "eq20"),
            ("disk", "requiv_corrected", "eq20"), ("disk", "requiv_corrected", "guarded"),
            ("strip", "requiv_corrected", "eq20")]
    cols = [c for c in cols if c[0] in parts]
    stems = {"none": "requiv", "guarded": "corrected", "eq20": "eq20"}
    npts = len(rows) // 3
    if shown and cols:
        fig, axs = plt.subplots(len(shown), len(cols), figsize=(3.0 * len(cols), 3.0 * len(shown)),
                                squeeze=False)
        im = None
        for i, a in enumerate(shown):
            for j, (part, join, corr) in enumerate(cols):
                ax = axs[i][j]
                hit = by.get((part, a, p0, join, corr))
                if not hit:
                    ax.axis("off")
                    continue
                # three rows (eq. 6, guarded, eq20) per sweep point
                fn = ctx.path(dflio.sweep_name(stems[corr], hit[0] // 3, npts, "vti"))
                if not os.path.exists(fn):
                    ax.axis("off")
                    continue
                x, y, arr = dflio.read_vti_plane(fn)
                g = arr["grad_norm"]
                v = arr["value"]
                ext = [x[0], x[-1], y[0], y[-1]]
                im = ax.imshow(g, origin="lower", extent=ext, vmin=0.5, vmax=1.5, cmap="RdBu_r")
                undef = np.isnan(v)
                if undef.any():
                    ax.imshow(np.where(undef, 1.0, np.nan), origin="lower", extent=ext,
                              cmap="Greys", vmin=0, vmax=2, alpha=0.9, gid="overlay")
                    ax.contourf(x, y, undef.astype(float), levels=[0.5, 1.5], colors="none",
                                hatches=["////"])
                ax.contour(x, y, np.where(undef, np.nan, v), levels=np.linspace(0.1, 1.0, 10),
                           colors="k", linewidths=0.4)
                ar = math.radians(a)
                ax.plot([1, 0, math.cos(ar)], [0, 0, math.sin(ar)], "r-", lw=1.5)
                sg = 1.0 if a <= 180 else -1.0
                edges = [(0.0, -sg), (-sg * math.sin(ar), sg * math.cos(ar))]
                if a == 180:
                    edges = [(0.0, 1.0), (0.0, -1.0)]  # the sector is the line x = 0
                for nx, ny in edges:
                    ax.plot([0, 1.5 * nx], [0, 1.5 * ny], "g--", lw=0.9)
                name = ("eq. 6" if join == "requiv" else L20 if corr == "eq20" else G20)
                ax.set_title(f"{name}, {part},\nα = {a:g}°, p = {p0}", fontsize=7)
                ax.set_xticks([])
                ax.set_yticks([])
                ax.set_xlabel("x", fontsize=6, labelpad=1)
                ax.set_ylabel("y", fontsize=6, labelpad=1)
        if im is not None:
            fig.colorbar(im, ax=axs, shrink=0.7, label="|∇u|")
        fig.suptitle("|∇u| (colour, white = 1), isolines of u (black), hatched-sector edges (green "
                     f"dashed), grey hatched: {L20} undefined (radicand ≤ 0)\n{ctx.config}", fontsize=8)
        md += ctx.figure(fig, "fields") + "\n"
    return md
