/* Implicit proxy inputs (hvb25 Sec. 5.3): a polynomial g (geom/implicit.h)
 * with g < 0 inside, not a distance, and two footpoint methods.
 *
 * Function index
 *   DFL_IMPLICIT_FOOT_LIST      paper | robust | paper_against | paper_walk
 *   dfl_implicit_foot_name/parse
 *   dfl_proxy_input_implicit    wrap a dfl_implicit as a proxy input
 *   dfl_proxy_implicit_certify  the robust method's certificate of one answer
 *
 * paper (our reading of the paper's "steps in the opposite direction of
 *   the gradient from our query point ... started the iteration from
 *   different points"): starts p_k = x - (k/4) g(x) grad g(x) / |grad g(x)|^2,
 *   k = 1..4 (fractions of the gradient-Newton step towards g = 0), each
 *   refined by Newton on the square system F(p, t) = (p - x + t grad g(p),
 *   g(p)) = 0 (Jacobian [[I + t Hess g, grad g], [grad g^T, 0]]), 30 steps;
 *   the closest converged result wins.  Newton on F finds any critical point
 *   of the distance (the far side, saddles) and the starts follow grad g,
 *   which is not the direction of the footpoint where g is far from a
 *   distance: the paper's failures.  certified = 1 when some start
 *   converged (the method has no certificate; it claims its answer).
 * The paper's sentence admits other readings of its starts; two more run
 * beside it, each refined and chosen as above:
 * paper_against ("in the opposite direction of the gradient", literally):
 *   p_k = x - (k/4) |g(x)| grad g(x) / |grad g(x)|^2, k = 1..4: outside
 *   (g > 0) the same starts, inside they walk away from g = 0.
 * paper_walk (steps that follow the gradient as it turns): p_0 = x,
 *   p_k = p_{k-1} - g(p_{k-1}) grad g(p_{k-1}) / |grad g(p_{k-1})|^2,
 *   k = 1..4, the iterates of the gradient-Newton projection (a start
 *   where grad g vanishes ends the walk).
 * robust (ours): first a fast path (proxy/input_implicit_fast.h): Newton
 *   on the square system from the nearest surface sample, kept when the
 *   certificate below holds and the cap test shows no other basin among the
 *   samples that could hold a closer point (~97% of a torus' cells); else
 *   geom/implicit.h's full search (surface samples within D0 + 1.5 h of x as
 *   starts, Riemannian Newton with step control), then, for points that
 *   fail the certificate, Ceres LM (solve/lsq.h) on g(p) = 0,
 *   grad g(p) x (p - x) = 0 from the same starts (the hard cases).
 *   certified = dfl_proxy_implicit_certify.
 *
 * Output: p, n = grad g(p) / |grad g(p)| (outward), d = (x - p).n (robust:
 * sign(g(x)) |x - p|), curvature from grad g and Hess g at p (Goldman's
 * formula, geom/curvature.h).  has_inside = 1.
 *
 * Thread safety: read-only after construction (the Ceres context is shared,
 * see solve/lsq.h); the paper method and the Newton path allocate nothing
 * per point (Ceres, for hard cases only, allocates inside).
 */
#ifndef DFL_PROXY_INPUT_IMPLICIT_H
#define DFL_PROXY_INPUT_IMPLICIT_H

#include "core/names.h"
#include "core/status.h"
#include "geom/implicit.h"
#include "proxy/input.h"

#define DFL_IMPLICIT_FOOT_LIST(X)                                                   \
    X(DFL_IMPLICIT_FOOT_PAPER, "paper", "starts on the Newton step towards g = 0")    \
    X(DFL_IMPLICIT_FOOT_ROBUST, "robust", "certified seeds, step control, Ceres LM")  \
    X(DFL_IMPLICIT_FOOT_AGAINST, "paper_against", "starts against grad g, any side") \
    X(DFL_IMPLICIT_FOOT_WALK, "paper_walk", "starts: iterates of the projection")
typedef enum dfl_implicit_foot_method {
    DFL_IMPLICIT_FOOT_LIST(DFL_NAMES_CODE)
} dfl_implicit_foot_method;
enum { DFL_IMPLICIT_FOOT_COUNT = 0 DFL_IMPLICIT_FOOT_LIST(DFL_NAMES_ONE) };
extern const char *const dfl_implicit_foot_names[DFL_IMPLICIT_FOOT_COUNT];
const char *dfl_implicit_foot_name(dfl_implicit_foot_method m);
dfl_status dfl_implicit_foot_parse(const char *s, dfl_implicit_foot_method *out, dfl_err *err);

/* Takes ownership of *imp (set to NULL, also on failure).  DFL_E_INPUT for
 * a NULL surface or a method outside the list, DFL_E_NOMEM. */
dfl_status dfl_proxy_input_implicit(dfl_implicit **imp, dfl_implicit_foot_method method,
                                    dfl_proxy_input *out, dfl_err *err);

/* The certificate of footpoint p (outward unit normal n, signed d) of x on
 * s: 1 when
 *   |g(p)| / |grad g(p)| <= 1e-10 scale                 (on the surface),
 *   |grad g(p) x (x - p)| / |grad g(p)| <= 1e-8 (scale + |x - p|)  (normal),
 *   |(x - p).n - d| <= 1e-8 (scale + |d|)                (d is the offset),
 *   1 + kappa_i d > 0 for both principal curvatures     (a local minimum of
 *                                                        the distance),
 *   sign g(x) = sign d where |d| > 1e-12 scale          (the right side),
 * and the search tried every sample start within its covering radius (it
 * always does; see geom/implicit.h): a point that passes is the closest
 * footpoint provided the samples resolve the surface (spacing below its
 * reach), which the sample grid is chosen for.  0 otherwise. */
int dfl_proxy_implicit_certify(const dfl_implicit *s, const double x[3], const double p[3],
                               double d);

#endif
