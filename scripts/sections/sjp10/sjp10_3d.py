"""sjp10 in 3D: tricubic PHT fits vs the uniform tricubic grid and the peers' Discregrid figures."""
import dflio
from sections.sjp10 import sjp10_common as sc

_f = dflio.cell_nan

ASSUMPTIONS = [
    "3D shapes (sjp10 Fig. 3 shows a torus-like and a genus-2 solid without parameters): the "
    "peers' protocol sphere (r 0.5) and torus (R 0.6, r 0.25, axis z) in [−1, 1]³, fitted from "
    "their analytic SDFs (exact jets) at eps = 1e-2, 3e-3, 1e-3, max_level 7, 16 random estimator "
    "points per cell, cross splits (8 children), validated on the peers' 217³ node grid (L1 = mean "
    "|e|, L∞ = max |e|, no band) and by the per-cell protocol (pht/validate.h: every leaf cell's "
    "27 halving nodes + 4 random points, a 4³ sub-grid and near-medial points in cells next to the "
    "medial set; 'max per cell'); 'met eps' judges eps against the per-cell max (genus 2 and "
    "Goursat: cell_val = false, their implicit footpoints are too slow for it, so the estimator "
    "alone judges).",
    sc.DEPARTURES,
    "Implicit input (sjp10 Sec. 3.3): the torus quartic, geom's genus-2 tube around Bernoulli's "
    "lemniscate (eps 0.1) in [−1.5, 1.5]³ and Goursat's tangle cube (x⁴+y⁴+z⁴−5|x|²+11.8 = 0) in "
    "[−3, 3]³; footpoints by geom's Riemannian Newton from several surface samples (not sjp10's "
    "polygon-mesh starts and tangent-plane projections) cost ~130–280 µs per point here, so these "
    "run at eps = 3e-2 only (Goursat, box side 6: 1e-1; the analytic torus adds 3e-2 for the "
    "comparison) with 4 estimator "
    "points per cell; "
    "the implicit torus is validated against the analytic torus SDF on 217³ nodes, genus 2 and "
    "Goursat against their own implicit SDF on 21³ nodes + 20³ midpoints.",
]


def render(ctx):
    rows = ctx.csv()
    md = ("Tricubic PHT fits (8 data per base vertex: f, fx, fy, fz, fxy, fxz, fyz, fxyz) and the "
          "uniform tricubic Hermite grid (level k: 2^k cells per axis). Errors: L1 = mean |e|, "
          "L∞ = max |e| over the validation grid.\n\n")
    body = []
    for r in rows:
        what = f"eps {_f(r, 'eps'):g}" if r["method"] == "pht" else f"level {int(_f(r, 'uniform_level'))}"
        body.append([r["case"], r["method"] + ("" if r["method"] != "pht" else f" ({sc.rule(r)})"),
                     what, int(_f(r, "cells")), int(_f(r, "dofs")),
                     sc.met(r) if r["method"] == "pht" else "—", _f(r, "val_mean"), _f(r, "val_rms"),
                     _f(r, "val_max"), _f(r, "cv_max"), _f(r, "val_gmax"),
                     f"{int(_f(r, 'val_n'))}³" + (" + mid" if _f(r, "midpoints") == 1 else ""),
                     _f(r, "t_total"), _f(r, "t_val")])
    md += dflio.md_table(["case", "method (rule)", "setting", "cells", "dofs (stored scalars)", "met eps",
                          "L1", "RMS", "L∞ (grid)", "max per cell", "max |∇f − ∇d|", "validation",
                          "fit s", "validation s"],
                         body) + "\n\n"
    pr = sc.peers(ctx, "discregrid3d") + [r for r in sc.peers(ctx, "simple3d") if "taylor2_float64" in r["method"]]
    pbody = [[r["shape"], r["protocol"] + " " + r["method"], r["param"], int(float(r["scalars"])),
              float(r["mean_abs"]), float(r["max_abs"])] for r in pr]
    md += ("**Peers measured on this machine's kind** (results/reference/sjp10_peers_measured.csv; "
           "Discregrid's cubic serendipity cells are C0 across cells, the PHT spline is C1):\n\n")
    md += dflio.md_table(["shape", "method", "N", "stored scalars", "L1", "L∞"], pbody) + "\n\n"
    # the aim on the torus
    sph = sorted([r for r in rows if r["case"].startswith("sphere") and r["method"] == "pht"
                  and sc.rule(r) == "dflab"], key=lambda r: -_f(r, "eps"))
    if len(sph) > 1:
        md += ("**Sphere cell counts are not monotone in eps** ("
               + ", ".join(f"{int(_f(r, 'cells'))} at {_f(r, 'eps'):g}" for r in sph)
               + "). Away from its centre the sphere's SDF is smooth and the level-2 cells already "
               "meet these thresholds; only the 8 cells touching the centre (the kink, a corner of "
               "each) keep splitting, about 56 new cells per level, so every eps ≤ 3e-3 ends at "
               "max_level 7 with ~8 + 56·6 cells, the kink's error (~0.22 h) above eps. At eps = "
               "1e-2 the kink error of levels 4–6 (0.035, 0.015, 0.0083) straddles eps, and the "
               "estimator's random points, which rarely come close to the kink corner, rate only 6 "
               "of the 8 level-4 centre cells above eps: the mesh turns asymmetric, the unsplit "
               "coarse centre cells give the data at their hanging corners (their polynomial, with "
               "its kink error), and the finer neighbours inherit that error and split level after "
               "level to max_level (240 cells at level 7). The count is decided by which of the "
               "symmetric centre cells the estimator catches, not by eps alone (a per-level trace "
               "of the fits: at 1e-2 the level-4 step splits 6 cells, at 3e-3 and 1e-3 all 8). "
               "The paper's rule shows the same ("
               + ", ".join(f"{int(_f(r, 'cells'))} at {_f(r, 'eps'):g}" for r in sorted(
                   [r for r in rows if r["case"].startswith("sphere") and r["method"] == "pht"
                    and sc.rule(r) == "paper"], key=lambda r: -_f(r, "eps")))
               + ").\n\n")
    tor = [r for r in rows if r["case"].startswith("torus") and r["method"] == "pht"
           and sc.rule(r) == "dflab"]
    ok = [r for r in tor if _f(r, "dofs") <= 33000 and _f(r, "val_mean") <= 1.4e-4 and _f(r, "val_max") <= 2.6e-3]
    if tor:
        best = min(tor, key=lambda r: _f(r, "val_max"))
        md += (f"**Torus against the aim** (≤ 33 k stored scalars with L1 ≤ 1.4e-4 and L∞ ≤ 2.6e-3; "
               f"Discregrid at 32,657 scalars: 1.37e-4 / 0.0261): "
               + (f"met by eps = {_f(ok[0], 'eps'):g} ({int(_f(ok[0], 'dofs'))} dofs, L1 "
                  f"{sc.fmt(_f(ok[0], 'val_mean'))}, L∞ {sc.fmt(_f(ok[0], 'val_max'))})"
                  if ok else
                  f"not met; the closest fit is eps = {_f(best, 'eps'):g} with {int(_f(best, 'dofs'))} "
                  f"dofs, L1 {sc.fmt(_f(best, 'val_mean'))}, L∞ {sc.fmt(_f(best, 'val_max'))}")
               + ". The L∞ of every 3D SDF fit sits on the medial set (the torus' core circle and "
               "axis, the sphere's centre), where the SDF has a kink no C1 spline follows: a cell of "
               "size h there errs by ∝ h, which is why L∞ falls only linearly with the finest cell "
               "while L1 falls with the smooth part.\n\n")
    md += sc.SIGN_NOTE + "\n"
    return md
