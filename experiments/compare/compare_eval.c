/* The comparison protocol (compare_eval.h).  The points depend only on the
 * shape and the options (seeded splitmix draws in a fixed order, the exact
 * SDF batched), so every method of a shape is measured on the same points
 * and the results are the same at any thread count. */
#include "compare/compare_eval.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "core/rng.h"
#include "pht/validate.h"

#define CHUNK 4096
#define PLANE_LEVEL 10      /* pair planes: 2^10 per axis */
#define PAIR_DELTA 1e-9     /* half separation, in box lengths */

void cmp_points_free(cmp_points *p)
{
    if (!p) return;
    free(p->x);
    free(p->d);
    free(p->g);
    free(p->band);
    free(p->off);
    free(p->xp);
    free(p->xm);
    free(p->pa);
    memset(p, 0, sizeof *p);
}

/* The exact SDF and gradient at m points, in parallel chunks. */
static void exact_eval(const dfl_shape *s, size_t m, const double *x, double *d, double *g)
{
    const int dim = s->dim;
    const size_t nch = (m + CHUNK - 1) / CHUNK;
#pragma omp parallel for schedule(dynamic, 1) if (nch > 1)
    for (size_t c = 0; c < nch; c++) {
        const size_t i0 = c * CHUNK, n = m - i0 < CHUNK ? m - i0 : CHUNK;
        dfl_shape_eval(s, n, x + i0 * dim, d + i0, g + i0 * dim);
    }
}

static void draw_box(uint64_t *rng, int dim, const double *lo, const double *hi, double *x)
{
    for (int a = 0; a < dim; a++) x[a] = dfl_rng_splitmix(rng, lo[a], hi[a]);
}

static int in_box(int dim, const double *lo, const double *hi, const double *x)
{
    for (int a = 0; a < dim; a++)
        if (!(x[a] >= lo[a] && x[a] <= hi[a])) return 0;
    return 1;
}

/* Near-surface points: footpoint of a random point, moved along the normal
 * by t in [-band, band]; one point at a time (the draws stay in order). */
static size_t surface_points(const dfl_shape *s, const cmp_points_opts *o, uint64_t *rng,
                             double *out)
{
    const int dim = s->dim;
    size_t k = 0;
    for (size_t i = 0; i < o->surface; i++) {
        for (int tries = 0; tries < 64; tries++) {
            double x[3], g[3], y[3];
            draw_box(rng, dim, o->lo, o->hi, x);
            const double t = dfl_rng_splitmix(rng, -o->band, o->band);
            const double d = dfl_shape_eval1(s, x, g);
            if (!isfinite(d)) continue;
            for (int a = 0; a < dim; a++) y[a] = x[a] - d * g[a] + t * g[a];
            if (!in_box(dim, o->lo, o->hi, y)) continue;
            memcpy(out + k * dim, y, sizeof(double) * dim);
            k++;
            break;
        }
    }
    return k;
}

/* Continuity pairs: a random point, an axis, snapped onto the nearest plane
 * of that axis's 2^PLANE_LEVEL grid, moved by +-delta. */
static void pairs(int dim, const cmp_points_opts *o, uint64_t *rng, double *xp, double *xm,
                  unsigned char *pa)
{
    const double planes = (double)(1 << PLANE_LEVEL);
    for (size_t i = 0; i < o->pairs; i++) {
        double x[3];
        draw_box(rng, dim, o->lo, o->hi, x);
        int a = (int)floor(dfl_rng_splitmix(rng, 0.0, (double)dim));
        if (a >= dim) a = dim - 1;
        const double len = o->hi[a] - o->lo[a];
        double j = round((x[a] - o->lo[a]) / len * planes);
        if (j < 1) j = 1;
        if (j > planes - 1) j = planes - 1;
        x[a] = o->lo[a] + j * len / planes;
        pa[i] = (unsigned char)a;
        memcpy(xp + i * dim, x, sizeof(double) * dim);
        memcpy(xm + i * dim, x, sizeof(double) * dim);
        xp[i * dim + a] += PAIR_DELTA * len;
        xm[i * dim + a] -= PAIR_DELTA * len;
    }
}

dfl_status cmp_points_build(const dfl_shape *shape, const cmp_points_opts *o, cmp_points *out,
                            dfl_err *err)
{
    const int dim = shape->dim;
    memset(out, 0, sizeof *out);
    for (int a = 0; a < dim; a++)
        if (!(o->lo[a] < o->hi[a]))
            return dfl_err_set(err, DFL_E_INPUT, "compare: box lo >= hi on axis %d", a);
    const int n = dim == 2 ? o->grid2d : o->grid3d;
    if (n < 2 || !(o->band > 0) || !(o->medial_band > 0))
        return dfl_err_set(err, DFL_E_INPUT, "compare: grid < 2 nodes or band <= 0");
    size_t ngrid = 1;
    for (int a = 0; a < dim; a++) ngrid *= (size_t)n;
    const size_t cap = ngrid + o->surface + o->medial_draws;
    out->dim = dim;
    out->x = malloc(sizeof(double) * dim * cap);
    double *cand = malloc(sizeof(double) * dim * (o->medial_draws ? o->medial_draws : 1));
    const size_t nnear = o->medial_draws > o->pairs ? o->medial_draws : o->pairs;
    unsigned char *near = malloc(nnear ? nnear : 1);
    out->xp = malloc(sizeof(double) * dim * (o->pairs ? o->pairs : 1));
    out->xm = malloc(sizeof(double) * dim * (o->pairs ? o->pairs : 1));
    out->pa = malloc(o->pairs ? o->pairs : 1);
    if (!out->x || !cand || !near || !out->xp || !out->xm || !out->pa) goto nomem;

    for (size_t i = 0; i < ngrid; i++) {
        size_t r = i;
        for (int a = 0; a < dim; a++) {
            const size_t ia = r % (size_t)n;
            r /= (size_t)n;
            out->x[i * dim + a] = o->lo[a] + (o->hi[a] - o->lo[a]) * (double)ia / (n - 1);
        }
    }
    uint64_t rng = o->seed;
    const size_t ns = surface_points(shape, o, &rng, out->x + ngrid * dim);
    for (size_t i = 0; i < o->medial_draws; i++) draw_box(&rng, dim, o->lo, o->hi, cand + i * dim);
    dfl_status st = dfl_pht_medial_band(shape, o->medial_draws, cand, o->medial_band, near, err);
    if (st) goto fail;
    size_t nm = 0;
    for (size_t i = 0; i < o->medial_draws; i++)
        if (near[i])
            memcpy(out->x + (ngrid + ns + nm++) * dim, cand + i * dim, sizeof(double) * dim);
    pairs(dim, o, &rng, out->xp, out->xm, out->pa);
    /* pairs across the medial band are left out: there the SDF itself has
     * a gradient jump (its kink), which says nothing of the method */
    size_t kept = 0;
    if (o->pairs) {
        if ((st = dfl_pht_medial_band(shape, o->pairs, out->xp, o->medial_band, near, err)))
            goto fail;
        for (size_t i = 0; i < o->pairs; i++) {
            if (near[i]) continue;
            memmove(out->xp + kept * dim, out->xp + i * dim, sizeof(double) * dim);
            memmove(out->xm + kept * dim, out->xm + i * dim, sizeof(double) * dim);
            out->pa[kept] = out->pa[i];
            kept++;
        }
    }
    free(cand);
    cand = NULL;
    free(near);
    near = NULL;

    const size_t m = ngrid + ns + nm;
    out->m = m;
    out->ngrid = ngrid;
    out->nsurface = ns;
    out->nmedial = nm;
    out->npairs = kept;
    out->bandw = o->band;
    memcpy(out->lo, o->lo, sizeof out->lo);
    memcpy(out->hi, o->hi, sizeof out->hi);
    out->d = malloc(sizeof(double) * m);
    out->g = malloc(sizeof(double) * m * dim);
    out->band = malloc(m);
    out->off = malloc(m);
    if (!out->d || !out->g || !out->band || !out->off) goto nomem;
    exact_eval(shape, m, out->x, out->d, out->g);
    for (size_t i = 0; i < m; i++)
        if (!isfinite(out->d[i])) {
            st = dfl_err_set(err, DFL_E_NUMERIC, "compare: exact SDF not finite at point %zu", i);
            goto fail;
        }
    if ((st = dfl_pht_medial_band(shape, m, out->x, o->medial_band, out->off, err))) goto fail;
    for (size_t i = 0; i < m; i++) {
        out->off[i] = !out->off[i];
        out->band[i] = fabs(out->d[i]) <= o->band;
    }
    return DFL_OK;
nomem:
    st = dfl_err_set(err, DFL_E_NOMEM, "compare: out of memory for the error points");
fail:
    free(cand);
    free(near);
    cmp_points_free(out);
    return st;
}

/* u and grad u at m points, in parallel chunks (the field is thread-safe). */
static void field_eval(const dfl_field *f, size_t m, const double *x, double *u, double *g)
{
    const int dim = f->dim;
    const size_t nch = (m + CHUNK - 1) / CHUNK;
#pragma omp parallel for schedule(dynamic, 1) if (nch > 1)
    for (size_t c = 0; c < nch; c++) {
        const size_t i0 = c * CHUNK, n = m - i0 < CHUNK ? m - i0 : CHUNK;
        f->ops->eval(f->ctx, n, x + i0 * dim, u + i0, g + i0 * dim);
    }
}

static double vdiff(int dim, const double *a, const double *b)
{
    double s = 0;
    for (int j = 0; j < dim; j++) s += (a[j] - b[j]) * (a[j] - b[j]);
    return sqrt(s);
}

static int finite_vec(int dim, const double *v)
{
    for (int j = 0; j < dim; j++)
        if (!isfinite(v[j])) return 0;
    return 1;
}

/* The largest value and gradient jumps over n pairs. */
static void jumps(const dfl_field *f, size_t n, const double *xp, const double *xm, double *up,
                  double *um, double *gp, double *gm, double *c0, double *c1)
{
    const int dim = f->dim;
    field_eval(f, n, xp, up, gp);
    field_eval(f, n, xm, um, gm);
    for (size_t i = 0; i < n; i++) {
        const double j0 = fabs(up[i] - um[i]);
        const double j1 = vdiff(dim, gp + i * dim, gm + i * dim);
        *c0 = isfinite(j0) ? fmax(*c0, j0) : INFINITY;
        *c1 = isfinite(j1) ? fmax(*c1, j1) : INFINITY;
    }
}

/* The pairs of p moved along their axes onto the nearest plane of pl. */
static void moved_pairs(const cmp_points *p, const cmp_planes *pl, double *xp, double *xm)
{
    const int dim = p->dim;
    for (size_t i = 0; i < p->npairs; i++) {
        const int a = p->pa[i];
        const double mid = 0.5 * (p->xp[i * dim + a] + p->xm[i * dim + a]);
        const double half = 0.5 * (p->xp[i * dim + a] - p->xm[i * dim + a]);
        const double c = pl->origin[a] + round((mid - pl->origin[a]) / pl->step[a]) * pl->step[a];
        memcpy(xp + i * dim, p->xp + i * dim, sizeof(double) * dim);
        memcpy(xm + i * dim, p->xm + i * dim, sizeof(double) * dim);
        xp[i * dim + a] = c + half;
        xm[i * dim + a] = c - half;
    }
}

dfl_status cmp_measure(const dfl_field *f, const cmp_points *p, int unsigned_ref, int repeats,
                       const cmp_planes *planes, cmp_result *out, dfl_err *err)
{
    const int dim = p->dim;
    const size_t m = p->m;
    memset(out, 0, sizeof *out);
    double *u = malloc(sizeof(double) * m), *gu = malloc(sizeof(double) * m * dim);
    double *ref = malloc(sizeof(double) * m), *gref = malloc(sizeof(double) * m * dim);
    const size_t np = p->npairs ? p->npairs : 1;
    double *up = malloc(sizeof(double) * np), *um = malloc(sizeof(double) * np);
    double *gp = malloc(sizeof(double) * np * dim), *gm = malloc(sizeof(double) * np * dim);
    double *mp = malloc(sizeof(double) * np * dim), *mm = malloc(sizeof(double) * np * dim);
    dfl_status st = DFL_OK;
    if (!u || !gu || !ref || !gref || !up || !um || !gp || !gm || !mp || !mm) {
        st = dfl_err_set(err, DFL_E_NOMEM, "compare: out of memory for field values");
        goto done;
    }
    out->eval_seconds = INFINITY;
    for (int r = 0; r < (repeats < 1 ? 1 : repeats); r++) {
        const double t0 = omp_get_wtime();
        field_eval(f, m, p->x, u, gu);
        const double t = omp_get_wtime() - t0;
        if (t < out->eval_seconds) out->eval_seconds = t;
    }
    for (size_t i = 0; i < m; i++) {
        const double s = unsigned_ref && p->d[i] < 0 ? -1.0 : 1.0;
        ref[i] = unsigned_ref ? fabs(p->d[i]) : p->d[i];
        for (int j = 0; j < dim; j++) gref[i * dim + j] = s * p->g[i * dim + j];
    }
    if ((st = dfl_metrics_compute(m, dim, u, gu, ref, 0.0, &out->whole, err))) goto done;
    if ((st = dfl_metrics_compute(m, dim, u, gu, ref, p->bandw, &out->band, err))) goto done;
    if ((st = dfl_metrics_compute_masked(m, dim, u, gu, ref, p->off, &out->off, err))) goto done;
    double gl = 0;
    size_t nf = 0;
    for (size_t i = 0; i < m; i++) {
        if (!isfinite(u[i]) || !finite_vec(dim, gu + i * dim)) {
            nf++;
            gl = INFINITY;
            continue;
        }
        const double e = vdiff(dim, gu + i * dim, gref + i * dim);
        if (e > gl) gl = e;
    }
    out->grad_linf = gl;
    out->nonfinite = nf;
    if (p->npairs) {
        double c0 = 0, c1 = 0;
        jumps(f, p->npairs, p->xp, p->xm, up, um, gp, gm, &c0, &c1);
        if (planes) {
            moved_pairs(p, planes, mp, mm);
            jumps(f, p->npairs, mp, mm, up, um, gp, gm, &c0, &c1);
        }
        out->c0_jump = c0;
        out->c1_jump = c1;
    }
done:
    free(u);
    free(gu);
    free(ref);
    free(gref);
    free(up);
    free(um);
    free(gp);
    free(gm);
    free(mp);
    free(mm);
    return st;
}
