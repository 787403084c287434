"""bs04 Sec. 4.2 / Fig. 13a: one field for a region, a segment and a point."""
import dflio
from sections.bs04 import bs04_space_common as sc

ASSUMPTIONS = [
    "Fig. 13a's geometry is not given; ours: the square [0.1, 0.4]², the segment "
    "(0.55, 0.2)–(0.9, 0.75) (disk trim, eq. 4) and the point (0.25, 0.75), on a 199 × 199 grid "
    "(bs04: 99 × 99); R-equivalence with p = 2 (bs04 does not state p for Fig. 13a) and p = 7.",
    "The square's field is rfunc/region.h's: the 2-norm of the violated edge half-plane "
    "distances (exact for a rectangle).",
]


def render(ctx):
    rows = ctx.csv()
    md = ("A square region, a segment and a point, each with its own field, joined by "
          "R-equivalence; u against the exact distance d to the union (band: 0 < d ≤ 0.05, the "
          "set itself left out), and the normalization at regular boundary points (offset "
          "δ = 10⁻⁴ along the normal).\n\n")
    header = ["p", "L1", "RMS", "L∞", "L1 band", "L∞ band", "min |∇u| band", "mean |∇u| band",
              "max |∇u| band", "max |u/δ − 1|", "max ||∇u| − 1| at δ"]
    body = [[int(float(r["p"])), dflio.num(r["l1"]), dflio.num(r["rms"]), dflio.num(r["linf"]),
             dflio.num(r["l1_band"]), dflio.num(r["linf_band"]), dflio.num(r["grad_min_band"]),
             dflio.num(r["grad_mean_band"]), dflio.num(r["grad_max_band"]),
             dflio.num(r["boundary_ratio_err"]), dflio.num(r["boundary_grad_err"])] for r in rows]
    md += dflio.md_table(header, body) + "\n\n"
    md += ("**bs04's claim** (Sec. 4.2): the field is 'normalized everywhere except the joining "
           "points'; here the parts are disjoint, so there are none. Measured: at δ = 10⁻⁴ from "
           "every part u/δ and |∇u| equal 1 to within "
           + ", ".join(f"{max(float(r['boundary_ratio_err']), float(r['boundary_grad_err'])):.1e}"
                       f" (p = {r['p']})" for r in rows)
           + ", as the expansion u = δ(1 + Σ(δ/h_j)^p)^(−1/p) predicts (order (δ/D)^p with D ≈ "
           "0.15 between the parts). Away from the set, u − d < 0 where two part fields are "
           "comparable (between the parts u ≈ 2^(−1/p) d, the bulging of R-equivalence, smaller "
           "for p = 7), and u − d > 0 beyond the segment's ends, where its disk-trimmed field "
           "grows like |x − c|²/d (eq. 3–4).\n\n")
    fig, cols = sc.point_columns(ctx, rows, "hetero", 3, 3.8, 9.5)
    for ax, r, img, ext, lab in cols:
        sc.show(ax[0], fig, img["value"], ext, lab, f"u, p = {r['p']}", iso=img["value"])
        sc.show_grad(ax[1], fig, img, ext, lab)
        sc.show_error(ax[2], fig, img["error"], ext, lab, "u − d")
    fig.suptitle(f"bs04 Fig. 13a analogue: square, segment and point\n{ctx.config}", fontsize=8)
    md += ctx.figure(fig, "field") + "\n\n"
    return md
