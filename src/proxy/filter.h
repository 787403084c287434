/* Decoding filters (hvb25 Sec. 6): the distance at any point from a proxy
 * grid, by the nearest cell's proxy, or a trilinear or Hermite blend of the
 * 8 neighbouring cells' proxies.
 *
 * Function index
 *   DFL_PROXY_FILTER_LIST         nearest | trilinear | hermite
 *   dfl_proxy_filter_name/parse
 *   DFL_PROXY_CLIP_LIST           bound | paper | off: the clip's formula
 *   dfl_proxy_clip_name/parse
 *   dfl_proxy_filter_opts         filter, clip kind and radius, signed output
 *   dfl_proxy_filter_opts_default the paper's settings for a filter
 *   dfl_proxy_filter_check        options usable with a grid?
 *   dfl_proxy_proxy_dist          one proxy's (clipped) distance and gradient
 *   dfl_proxy_filter_eval         a batch of points: values and gradients
 *
 * The sphere constraint ("clip", radius rho > 0; the paper's Fig. 10: "we
 * constrained the geometries with a sphere around the footpoint", with no
 * formula).  Two readings, chosen by the clip kind:
 *   bound  (dflab's default) each proxy surface is cut to its part inside
 *          the ball B(p, rho) around its footpoint, and its distance is
 *              D(x) = sgn(phi) max(|phi(x)|, |x - p| - rho)
 *          (phi: the proxy's exact signed distance, decode.h).  D equals the
 *          exact distance to the cut patch wherever the nearest point of the
 *          uncut proxy lies in the ball (then |x - p| - rho <= |phi|), and
 *          is a 1-Lipschitz lower bound of it elsewhere (the distance to the
 *          ball), so it never invents a surface far from the footpoint and
 *          sphere tracing stays safe.  Where the max picks the ball term the
 *          gradient is sgn(phi) (x - p)/|x - p|.
 *   paper  the proxy's solid intersected with the ball, the usual SDF
 *          intersection of a shader:  D(x) = max(phi(x), |x - p| - rho),
 *          gradient (x - p)/|x - p| where the ball term wins (ties: phi's).
 *          Outside the proxy's solid it is the bound's value; inside it
 *          and inside the ball it is the larger of two negatives, so the
 *          ball's sphere becomes a second zero set there (the unsigned
 *          output folds it to a surface): only the solid's outside part of
 *          the ball's boundary is no surface.
 *   off    no clip whatever rho is (D = phi).
 * For bound and paper, rho = 0 also means no clip.  The formula's value
 * and gradient are exact for the formula (tests/proxy/test_filter.c).
 * Defaults: the bound kind; nearest clips at one cell size
 * (max_j h_j; the paper's "in practice" choice), trilinear and Hermite do
 * not clip (their 8 neighbours' footpoints lie up to ~2 sqrt(3) h from x,
 * so a one-cell clip would cut the surface itself).
 *
 * Filters (x_c: cell centres; outside the centres' hull the weights clamp
 * to the border layer, the proxies still evaluate at x):
 *   nearest    D of the cell containing x (the nearest centre; x outside
 *              the box takes the nearest border cell).
 *   trilinear  sum_c w_c D_c(x) over the 8 centres around x, tensor weights
 *              (1 - t, t) per axis, t = (x - x_c0) / h.
 *   hermite    the same with the weights (1 - h(t), h(t)), h = h3(t) =
 *              3t^2 - 2t^3 for order 1 and h5(t) = 10t^3 - 15t^4 + 6t^5 for
 *              order 2 grids: h' (and h'' for h5) vanish at t = 0, 1, so at
 *              a cell centre value, gradient (and Hessian) are the centre
 *              proxy's, i.e. those of the surface's distance there.
 * Gradients are exact derivatives of the value (sum w grad D + D grad w).
 * Unsigned output (the paper's) folds each proxy before any blend: D_c is
 * replaced by |D_c| and its gradient by sgn(D_c) grad D_c, so nearest gives
 * |D| and trilinear / hermite give sum_c w_c |D_c(x)| (with the gradient
 * sum w_c sgn(D_c) grad D_c + |D_c| grad w_c), not |sum_c w_c D_c|: each
 * proxy is an unsigned distance of its own, and where neighbouring proxies
 * disagree in sign the blend stays > 0 instead of crossing zero between
 * them.  Signed output (sum_c w_c D_c) needs a grid whose input has an
 * inside (negative inside).  The result at a NaN (failed) proxy is NaN.
 */
#ifndef DFL_PROXY_FILTER_H
#define DFL_PROXY_FILTER_H

#include <stddef.h>

#include "core/names.h"
#include "proxy/proxy.h"

#define DFL_PROXY_FILTER_LIST(X)                                       \
    X(DFL_PROXY_NEAREST, "nearest", "the containing cell's proxy")     \
    X(DFL_PROXY_TRILINEAR, "trilinear", "8 proxies, linear weights")   \
    X(DFL_PROXY_HERMITE, "hermite", "8 proxies, h3 / h5 weights")
typedef enum dfl_proxy_filter { DFL_PROXY_FILTER_LIST(DFL_NAMES_CODE) } dfl_proxy_filter;
enum { DFL_PROXY_FILTER_COUNT = 0 DFL_PROXY_FILTER_LIST(DFL_NAMES_ONE) };
extern const char *const dfl_proxy_filter_names[DFL_PROXY_FILTER_COUNT];
const char *dfl_proxy_filter_name(dfl_proxy_filter f);
dfl_status dfl_proxy_filter_parse(const char *s, dfl_proxy_filter *out, dfl_err *err);

#define DFL_PROXY_CLIP_LIST(X)                                                 \
    X(DFL_PROXY_CLIP_BOUND, "bound", "sgn(phi) max(|phi|, |x - p| - rho)")     \
    X(DFL_PROXY_CLIP_PAPER, "paper", "max(phi, |x - p| - rho): solid and ball") \
    X(DFL_PROXY_CLIP_OFF, "off", "no clip")
typedef enum dfl_proxy_clip { DFL_PROXY_CLIP_LIST(DFL_NAMES_CODE) } dfl_proxy_clip;
enum { DFL_PROXY_CLIP_COUNT = 0 DFL_PROXY_CLIP_LIST(DFL_NAMES_ONE) };
extern const char *const dfl_proxy_clip_names[DFL_PROXY_CLIP_COUNT];
const char *dfl_proxy_clip_name(dfl_proxy_clip c);
dfl_status dfl_proxy_clip_parse(const char *s, dfl_proxy_clip *out, dfl_err *err);

typedef struct dfl_proxy_filter_opts {
    dfl_proxy_filter filter;
    double clip;     /* clip radius rho (length); 0: none */
    int is_signed;   /* 1: signed output, 0: unsigned (|D|) */
    dfl_proxy_clip clip_kind;  /* the formula (0, the default: bound) */
} dfl_proxy_filter_opts;

/* filter f with its default clip for grid g (see above: bound kind),
 * unsigned. */
void dfl_proxy_filter_opts_default(dfl_proxy_filter f, const dfl_proxy_grid *g,
                                   dfl_proxy_filter_opts *o);

/* DFL_E_INPUT when o->filter or o->clip_kind is unknown, o->clip < 0 or
 * not finite, or
 * o->is_signed with a grid whose input has no inside. */
dfl_status dfl_proxy_filter_check(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o,
                                  dfl_err *err);

/* D (signed as above, before the unsigned fold) of cell c's proxy at x
 * under clip kind `kind` and radius clip, gradient into grad when not
 * NULL. */
double dfl_proxy_proxy_dist(const dfl_proxy_grid *g, size_t c, dfl_proxy_clip kind, double clip,
                            const double x[3], double *grad);

/* val[i] (and grad[3i..3i+2] when grad is not NULL) at x[3i..3i+2], i < m.
 * Serial, allocation-free, thread-safe for a shared grid (callers
 * parallelise over chunks of points).  o must pass dfl_proxy_filter_check.
 * A query with a NaN coordinate gets val NaN (its gradient is unspecified)
 * and reads no cell outside the grid: it is located in cell 0 on that axis;
 * infinite coordinates are clamped to the grid like far ones. */
void dfl_proxy_filter_eval(const dfl_proxy_grid *g, const dfl_proxy_filter_opts *o, size_t m,
                           const double *x, double *val, double *grad);

#endif
