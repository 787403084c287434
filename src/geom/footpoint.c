/* Footpoint options and what the curve and surface searches share: noise
 * of the squared distance, extents, the top-k list of sampled minima and
 * the ranking of refined candidates (formulas in footpoint.h). */
#include "geom/foot_internal.h"

#include <assert.h>
#include <math.h>

#include "core/vec.h"

void dfl_foot_opts_default(dfl_foot_opts *o)
{
    o->backend = DFL_FOOT_NEWTON;
    o->samples_per_span = 16;
    o->candidates = 4;
    o->max_iter = 100;
    o->tie_rel = 1e-9;
}

dfl_status dfl_foot_opts_check(const dfl_foot_opts *o, dfl_err *err)
{
    if (o->backend != DFL_FOOT_NEWTON && o->backend != DFL_FOOT_CERES)
        return dfl_err_set(err, DFL_E_INPUT, "backend: expected newton or ceres");
    if (o->samples_per_span < 2 || o->samples_per_span > 10000)
        return dfl_err_set(err, DFL_E_INPUT, "samples_per_span = %d: expected 2..10000",
                           o->samples_per_span);
    if (o->candidates < 1 || o->candidates > DFL_FOOT_MAX_CAND)
        return dfl_err_set(err, DFL_E_INPUT, "candidates = %d: expected 1..%d", o->candidates,
                           DFL_FOOT_MAX_CAND);
    if (o->max_iter < 1 || o->max_iter > 100000)
        return dfl_err_set(err, DFL_E_INPUT, "max_iter = %d: expected 1..100000", o->max_iter);
    if (!(o->tie_rel >= 0.0 && o->tie_rel < 1.0))
        return dfl_err_set(err, DFL_E_INPUT, "tie_rel = %g: expected [0, 1)", o->tie_rel);
    return DFL_OK;
}

/* Rounding of g = |P - x|^2 / 2 at the point P (n coordinates): |r| times
 * the rounding of P and x, plus g's own.  The Newton step controls of
 * curves and surfaces accept a step that stays within it. */
double dfl_foot_g_noise(int n, const double *P, const double *x, double g)
{
    const double r = sqrt(2.0 * g);
    const double p = sqrt(dfl_vecn_dot(n, P, P)), q = sqrt(dfl_vecn_dot(n, x, x));
    return 4e-15 * (g + r * (p + q)) + 1e-300;
}

double dfl_foot_extent(int dim, size_t n, const double *cp)
{
    double ext = 0.0;
    for (int j = 0; j < dim; j++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t i = 0; i < n; i++) {
            lo = fmin(lo, cp[i * (size_t)dim + (size_t)j]);
            hi = fmax(hi, cp[i * (size_t)dim + (size_t)j]);
        }
        ext = fmax(ext, hi - lo);
    }
    return ext;
}

void dfl_foot_topk_insert(dfl_foot_topk *t, double g, size_t p, size_t i, size_t j)
{
    if (t->n == t->k && g >= t->g[t->n - 1]) return;
    int pos = t->n < t->k ? t->n++ : t->n - 1;
    while (pos > 0 && t->g[pos - 1] > g) {
        t->g[pos] = t->g[pos - 1];
        t->i[pos] = t->i[pos - 1];
        t->j[pos] = t->j[pos - 1];
        t->p[pos] = t->p[pos - 1];
        pos--;
    }
    t->g[pos] = g;
    t->i[pos] = i;
    t->j[pos] = j;
    t->p[pos] = p;
}

/* the distance and the point of candidate q */
static double cand_dist(const double *dist, size_t stride, int q)
{
    return *(const double *)((const char *)dist + (size_t)q * stride);
}

static const double *cand_point(const double *p, size_t stride, int q)
{
    return (const double *)((const char *)p + (size_t)q * stride);
}

int dfl_foot_rank(int n, int dim, const double *dist, const double *p, size_t stride,
                  double size, double tie_rel,
                  int (*same_basin)(const void *ctx, int kept, int cand, double tol),
                  const void *ctx, int *keep, int *ntied)
{
    assert(n >= 1 && n <= DFL_FOOT_MAX_CAND);
    /* sort by distance (insertion sort of indices, stable, n <= 16) */
    int ord[DFL_FOOT_MAX_CAND];
    for (int a = 0; a < n; a++) {
        int b = a;
        while (b > 0 && cand_dist(dist, stride, ord[b - 1]) > cand_dist(dist, stride, a)) {
            ord[b] = ord[b - 1];
            b--;
        }
        ord[b] = a;
    }
    /* drop duplicates of earlier (closer) footpoints: the same point, or
     * the same basin */
    const double same = 1e-7 * size;
    const double tol = tie_rel * cand_dist(dist, stride, ord[0]) + 1e-14 * size;
    int m = 0;
    for (int a = 0; a < n; a++) {
        int dup = 0;
        for (int b = 0; b < m && !dup; b++)
            if (sqrt(dfl_foot_d2(dim, cand_point(p, stride, ord[a]),
                                 cand_point(p, stride, keep[b]))) <= same ||
                same_basin(ctx, keep[b], ord[a], tol))
                dup = 1;
        if (!dup) keep[m++] = ord[a];
    }
    /* ties with the best: the medial axis */
    const double best = cand_dist(dist, stride, keep[0]);
    int nt = 1;
    while (nt < m && cand_dist(dist, stride, keep[nt]) - best <= tol) nt++;
    *ntied = nt;
    return m;
}
