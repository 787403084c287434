/* Parametric proxy inputs (hvb25 Sec. 5.1): sphere, torus, cone (lateral
 * surface) and B-spline / Bezier patch sets, single or multi-patch.
 *
 * Function index
 *   dfl_param_input_opts          starts grid and iteration limit
 *   dfl_param_input_opts_default  grid 16, 60 iterations, 3 starts, pruned scans
 *   dfl_proxy_input_param_sphere  S = c + r (cos v rho(u) + sin v w)
 *   dfl_proxy_input_param_torus   S = c + (R + r cos v) rho(u) + r sin v w
 *   dfl_proxy_input_param_cone    S = a + v (b - a) + (ra + v (rb - ra)) rho(u)
 *   dfl_proxy_input_param_surfaces  a dfl_surface_set (takes ownership)
 *
 * rho(u) = cos u e1 + sin u e2 with (e1, e2, w) = dfl_vec3_tangent_basis(w)
 * completed to a right-handed frame, w the unit axis (sphere: w = z).  The
 * analytic parametrizations are periodic in u; S_u x S_v points outward.
 * The sphere is two such charts, with polar axes z and x, so that every
 * footpoint has a regular chart (the better answer of the two wins).
 *
 * Footpoint: the paper's start, the nearest node of a regular grid x grid
 * parameter grid per patch (precomputed), refined by geometric Newton
 * (Kallay 2001) on f(u, v) = |S - x|^2 / 2: the Newton step with the
 * Hessian [E + S_uu.r, F + S_uv.r; F + S_uv.r, G + S_vv.r] (r = S - x) where
 * it is positive definite, else Kallay's tangent-plane step (the first
 * fundamental form [E F; F G]); every step halved until f decreases;
 * non-periodic parameters are clamped with an active set at the domain
 * bounds.  To survive grids whose nearest node lies in the wrong basin the
 * `starts` (default 3; 1 is the paper's) nearest nodes at least two grid
 * steps apart (and the nearest node
 * of every patch none of them is on, up to 8 patches) are refined and the
 * closest result wins (the paper used one).
 *
 * Normal, sign, curvature: n = S_u x S_v / |.| at the footpoint.  Closed
 * shapes (sphere, torus: has_inside = 1) keep the outward n and d = (x - p).n;
 * open ones (cone lateral surface, patches) orient n towards x and d = |x - p|
 * >= 0; a footpoint on the domain boundary gets n = (x - p)/|x - p|.
 * Curvatures: geom/curvature.h's dfl_curvature_parametric w.r.t. that n,
 * i.e. from the fundamental forms with K = (LN - M^2)/(EG - F^2) (hvb25
 * prints LM - N^2) and the principal directions of the Weingarten map.
 * certified = 1 when Newton met its stationarity test |grad f| <= 1e-13
 * |S_u| |S_v| scale (interior; at bounds on the free parameter) and the
 * parametrization is regular there; NAN curvatures where it is singular
 * (a cone's apex).
 *
 * Thread safety: read-only after construction; no allocation per point.
 */
#ifndef DFL_PROXY_INPUT_PARAM_H
#define DFL_PROXY_INPUT_PARAM_H

#include "core/status.h"
#include "geom/surface.h"
#include "proxy/input.h"

typedef struct dfl_param_input_opts {
    int grid;       /* parameter-grid nodes per patch and direction, 4..512 */
    int max_iter;   /* Newton iterations per start, >= 1 */
    int starts;     /* nearest grid nodes refined, 1 (the paper's) .. 3 */
    int prune;      /* 1 (default): the node scans skip a grid row whose
                       bounding box is no nearer than the worst start kept
                       (the same nodes, in the same order, win: every answer
                       is bit for bit the brute-force scan's), and Newton's
                       start evaluations come from a table made once (up to
                       65536 nodes over all patches; the same calls, so the
                       same bits); 0: brute force, for tests */
} dfl_param_input_opts;

void dfl_param_input_opts_default(dfl_param_input_opts *o);

/* opt may be NULL (defaults).  DFL_E_INPUT for degenerate parameters
 * (r <= 0, zero axis, minor >= major, ra, rb < 0 or both 0, a == b, bad
 * options), DFL_E_NOMEM. */
dfl_status dfl_proxy_input_param_sphere(const double c[3], double r,
                                        const dfl_param_input_opts *opt, dfl_proxy_input *out,
                                        dfl_err *err);
dfl_status dfl_proxy_input_param_torus(const double c[3], const double axis[3], double R,
                                       double r, const dfl_param_input_opts *opt,
                                       dfl_proxy_input *out, dfl_err *err);
dfl_status dfl_proxy_input_param_cone(const double a[3], const double b[3], double ra, double rb,
                                      const dfl_param_input_opts *opt, dfl_proxy_input *out,
                                      dfl_err *err);
/* Takes ownership of *set (zeroed on success and on failure). */
dfl_status dfl_proxy_input_param_surfaces(dfl_surface_set *set, const dfl_param_input_opts *opt,
                                          dfl_proxy_input *out, dfl_err *err);

#endif
