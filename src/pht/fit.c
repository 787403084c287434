/* Adaptive and uniform PHT fits (fit.h).
 *
 * Per level: Hermite data at the base vertices that have none yet (in
 * parallel over vertices), resolution and spline (serial, cheap), then the
 * estimator in two parallel passes over the cells whose polynomial changed:
 * exact distances at the cell's points (timed as footpoints; only where no
 * earlier estimate holds them: the exact distance is most of a curve fit's
 * time), then the spline there (timed as spline).  Every per-cell or per-vertex result goes
 * to its own slot and reductions run in leaf order afterwards, so threads
 * never change a bit. */
#include "pht/fit.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"

DFL_NAMES_DEFINE(dfl_pht_estimator, DFL_PHT_ESTIMATOR_LIST, DFL_PHT_EST_COUNT,
                 dfl_pht_estimator_names, dfl_pht_estimator_name, dfl_pht_estimator_parse,
                 "estimator")

void dfl_pht_fit_opts_default(int dim, dfl_pht_fit_opts *o)
{
    memset(o, 0, sizeof *o);
    for (int j = 0; j < dim && j < 3; j++) o->hi[j] = 1.0;
    o->eps = 1e-3;
    o->max_level = 10;
    o->samples = 16;
    o->split = DFL_PHT_SPLIT_CROSS;
    o->estimator = DFL_PHT_EST_RANDOM;
    o->seed = 1;
    o->grade = 1;
    o->peaks = 1;
}


static int pht_fit_max_level(int dim, dfl_pht_split split)
{
    return split == DFL_PHT_SPLIT_BINARY ? dim * DFL_TMESH_MAX_LEVEL : DFL_TMESH_MAX_LEVEL;
}

dfl_status dfl_pht_fit_opts_check(int dim, const dfl_pht_fit_opts *o, dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "PHT fit: dimension %d (expected 2 or 3)", dim);
    if (!(o->eps > 0) || !isfinite(o->eps))
        return dfl_err_set(err, DFL_E_INPUT, "PHT fit: eps = %g (expected a finite value > 0)",
                           o->eps);
    if ((int)o->split < 0 || (int)o->split >= DFL_PHT_SPLIT_COUNT)
        return dfl_err_set(err, DFL_E_INPUT, "PHT fit: split %d (expected cross or binary)",
                           (int)o->split);
    int maxl = pht_fit_max_level(dim, o->split);
    if (o->max_level < 0 || o->max_level > maxl)
        return dfl_err_set(err, DFL_E_INPUT, "PHT fit: max_level = %d (expected 0..%d for %s)",
                           o->max_level, maxl, dfl_pht_split_name(o->split));
    if (o->samples < 1 || o->samples > 4096)
        return dfl_err_set(err, DFL_E_INPUT, "PHT fit: samples = %d (expected 1..4096)",
                           o->samples);
    if ((int)o->estimator < 0 || (int)o->estimator >= DFL_PHT_EST_COUNT)
        return dfl_err_set(err, DFL_E_INPUT,
                           "PHT fit: estimator %d (expected random, grid or gradient)",
                           (int)o->estimator);
    for (int j = 0; j < dim; j++)
        if (!isfinite(o->lo[j]) || !isfinite(o->hi[j]) || !(o->lo[j] < o->hi[j]))
            return dfl_err_set(err, DFL_E_INPUT,
                               "PHT fit: box side %d is [%g, %g] (expected finite lo < hi)", j,
                               o->lo[j], o->hi[j]);
    return DFL_OK;
}

/* ---- the fit's working state ---- */
typedef struct fitter {
    const dfl_pht_source *src;
    const dfl_pht_fit_opts *o;
    int dim, nd, nc, npts;   /* npts: estimator points per cell */
    int xstride;             /* exact values per cell: npts (+ npts * dim gradients) */
    dfl_tmesh *mesh;
    dfl_pht_spline *spline;
    double *data;            /* nverts * nd */
    unsigned char *have;     /* data computed from the SDF */
    size_t vcap;
    /* per tree node: the last estimate of the node as a leaf, and the exact
     * values at its points (the points are a function of the node alone) */
    double *node_err, *node_sum, *node_coef, *node_exact;
    unsigned char *node_valid;
    size_t ncap;
    size_t medial;
} fitter;

static int grow_vertices(fitter *F)
{
    size_t nv = dfl_tmesh_nverts(F->mesh);
    if (nv <= F->vcap) return 0;
    size_t cap = F->vcap ? F->vcap : 64;
    while (cap < nv) cap *= 2;
    double *d = realloc(F->data, cap * (size_t)F->nd * sizeof *d);
    if (!d) return -1;
    F->data = d;
    unsigned char *h = realloc(F->have, cap);
    if (!h) return -1;
    F->have = h;
    memset(F->have + F->vcap, 0, cap - F->vcap);
    memset(F->data + F->vcap * (size_t)F->nd, 0, (cap - F->vcap) * (size_t)F->nd * sizeof *d);
    F->vcap = cap;
    return 0;
}

static int grow_nodes(fitter *F)
{
    size_t nn = dfl_tmesh_ncells(F->mesh);
    if (nn <= F->ncap) return 0;
    size_t cap = F->ncap ? F->ncap : 64;
    while (cap < nn) cap *= 2;
    double *e = realloc(F->node_err, cap * sizeof *e);
    if (!e) return -1;
    F->node_err = e;
    double *s = realloc(F->node_sum, cap * sizeof *s);
    if (!s) return -1;
    F->node_sum = s;
    double *c = realloc(F->node_coef, cap * (size_t)F->nc * sizeof *c);
    if (!c) return -1;
    F->node_coef = c;
    double *x = realloc(F->node_exact, cap * (size_t)F->xstride * sizeof *x);
    if (!x) return -1;
    F->node_exact = x;
    unsigned char *v = realloc(F->node_valid, cap);
    if (!v) return -1;
    F->node_valid = v;
    memset(F->node_valid + F->ncap, 0, cap - F->ncap);
    F->ncap = cap;
    return 0;
}

/* Hermite data of every base vertex without data. */
static dfl_status compute_base(fitter *F, size_t *nnew, dfl_err *err)
{
    size_t nv = dfl_tmesh_nverts(F->mesh), n = 0;
    size_t *list = malloc((nv ? nv : 1) * sizeof *list);
    if (!list) return dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
    for (size_t v = 0; v < nv; v++) {
        dfl_tmesh_vertex t;
        dfl_tmesh_vertex_get(F->mesh, v, &t);
        if (t.kind == DFL_TMESH_BASE && !F->have[v]) list[n++] = v;
    }
    unsigned char *bad = calloc(n ? n : 1, 1), *med = calloc(n ? n : 1, 1);
    if (!bad || !med) {
        free(list);
        free(bad);
        free(med);
        return dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
    }
#pragma omp parallel for schedule(dynamic, 8) if (n > 64)
    for (size_t i = 0; i < n; i++) {
        dfl_tmesh_vertex t;
        dfl_tmesh_vertex_get(F->mesh, list[i], &t);
        int fl = 0;
        if (dfl_pht_hermite(F->src, t.x, F->data + list[i] * (size_t)F->nd, &fl, NULL) != DFL_OK)
            bad[i] = 1;
        med[i] = (fl & DFL_PHT_HERMITE_MEDIAL) != 0;
    }
    dfl_status st = DFL_OK;
    for (size_t i = 0; i < n; i++) {
        if (bad[i] && st == DFL_OK) {
            dfl_tmesh_vertex t;
            dfl_tmesh_vertex_get(F->mesh, list[i], &t);
            double tmp[DFL_PHT_NDATA_MAX];
            st = dfl_pht_hermite(F->src, t.x, tmp, NULL, err);
            if (st == DFL_OK) st = dfl_err_set(err, DFL_E_NUMERIC, "Hermite data failed");
            dfl_err_prefix(err, "PHT fit: vertex (%g, %g, %g)", t.x[0], t.x[1], t.x[2]);
        }
        F->have[list[i]] = 1;
        F->medial += med[i];
    }
    *nnew = n;
    free(list);
    free(bad);
    free(med);
    return st;
}

static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* The estimator points of a cell: a pure function of (seed, box, level). */
static void cell_points(const fitter *F, const dfl_tmesh_cell *c, double *pts)
{
    const int dim = F->dim;
    if (F->o->estimator == DFL_PHT_EST_GRID) {
        int n = (int)lround(pow((double)F->o->samples, 1.0 / dim));
        if (n < 1) n = 1;
        for (int i = 0; i < F->npts; i++) {
            int r = i;
            for (int j = 0; j < dim; j++) {
                double t = ((r % n) + 0.5) / n;
                r /= n;
                pts[i * dim + j] = c->lo[j] + (c->hi[j] - c->lo[j]) * t;
            }
        }
        return;
    }
    uint64_t s = mix64(F->o->seed + 0x9E3779B97F4A7C15ull * (uint64_t)(c->level + 1));
    for (int j = 0; j < dim; j++) {
        uint64_t b;
        memcpy(&b, &c->lo[j], sizeof b);
        s = mix64(s ^ (b + 0x632BE59BD9B4E019ull * (uint64_t)(j + 1)));
    }
    const int nr = F->o->samples;
    for (int i = 0; i < nr; i++)
        for (int j = 0; j < dim; j++)
            pts[i * dim + j] = dfl_rng_splitmix(&s, c->lo[j], c->hi[j]);
    /* the centre, then the face centres (axis a low, high) */
    for (int q = 0; nr + q < F->npts; q++) {
        double *x = pts + (size_t)(nr + q) * (size_t)dim;
        for (int j = 0; j < dim; j++) x[j] = 0.5 * (c->lo[j] + c->hi[j]);
        if (q > 0) {
            int a = (q - 1) / 2;
            x[a] = (q - 1) % 2 ? c->hi[a] : c->lo[a];
        }
    }
}

/* Face centres shared within one estimator pass.  The random and gradient
 * estimators' peak points include the 2 dim face centres of a cell; two
 * cells of the same size that share a face share that point bit for bit
 * (the centre's other coordinates are 0.5 (lo + hi) of equal lo and hi, the
 * face coordinate is the same lattice position), so its exact value is
 * computed once: the first cell in todo order that has it evaluates it (or
 * already holds it from the node cache), later ones copy.  Keys are the
 * coordinates' bits, so only identical points are ever shared. */
typedef struct shared_pts {
    int on, nf, first;        /* nf = 2 dim face centres at points first.. */
    size_t cap;               /* hash slots (a power of 2) */
    double *key;              /* cap * 3 */
    size_t *slot_k;           /* todo index of the first occurrence; SIZE_MAX empty */
    int *slot_p;
    size_t *src_k;            /* per todo cell and face: the cell to copy from, or SIZE_MAX */
    int *src_p;
} shared_pts;

static int shared_init(const fitter *F, size_t nt, shared_pts *sh)
{
    memset(sh, 0, sizeof *sh);
    sh->on = F->o->estimator != DFL_PHT_EST_GRID && F->o->peaks && nt > 1;
    if (!sh->on) return 0;
    sh->nf = 2 * F->dim;
    sh->first = F->o->samples + 1;
    size_t need = 2 * nt * (size_t)sh->nf;
    sh->cap = 64;
    while (sh->cap < need) sh->cap *= 2;
    sh->key = malloc(sh->cap * 3 * sizeof *sh->key);
    sh->slot_k = malloc(sh->cap * sizeof *sh->slot_k);
    sh->slot_p = malloc(sh->cap * sizeof *sh->slot_p);
    sh->src_k = malloc(nt * (size_t)sh->nf * sizeof *sh->src_k);
    sh->src_p = malloc(nt * (size_t)sh->nf * sizeof *sh->src_p);
    if (!sh->key || !sh->slot_k || !sh->slot_p || !sh->src_k || !sh->src_p) return -1;
    for (size_t i = 0; i < sh->cap; i++) sh->slot_k[i] = SIZE_MAX;
    for (size_t i = 0; i < nt * (size_t)sh->nf; i++) sh->src_k[i] = SIZE_MAX;
    return 0;
}

static void shared_free(shared_pts *sh)
{
    free(sh->key);
    free(sh->slot_k);
    free(sh->slot_p);
    free(sh->src_k);
    free(sh->src_p);
    memset(sh, 0, sizeof *sh);
}


/* Registers the face centres of todo cell k (tree node id), in todo order;
 * a cell that evaluates (no node cache) copies those registered before. */
static void shared_add(const fitter *F, shared_pts *sh, size_t k, size_t id)
{
    if (!sh->on) return;
    const int dim = F->dim, eval = !F->node_valid[id];
    dfl_tmesh_cell c;
    dfl_tmesh_cell_get(F->mesh, id, &c);
    for (int f = 0; f < sh->nf; f++) {
        /* cell_points' face centre q = f + 1 */
        double x[3] = {0, 0, 0};
        for (int j = 0; j < dim; j++) x[j] = 0.5 * (c.lo[j] + c.hi[j]);
        x[f / 2] = f % 2 ? c.hi[f / 2] : c.lo[f / 2];
        uint64_t h = 0;
        for (int j = 0; j < dim; j++) {
            uint64_t b;
            memcpy(&b, &x[j], sizeof b);
            h = mix64(h ^ b);
        }
        size_t i = (size_t)h & (sh->cap - 1);
        while (sh->slot_k[i] != SIZE_MAX &&
               memcmp(sh->key + 3 * i, x, (size_t)dim * sizeof *x) != 0)
            i = (i + 1) & (sh->cap - 1);
        if (sh->slot_k[i] == SIZE_MAX) {
            memcpy(sh->key + 3 * i, x, sizeof x);
            sh->slot_k[i] = k;
            sh->slot_p[i] = sh->first + f;
        } else if (eval) {
            sh->src_k[k * (size_t)sh->nf + (size_t)f] = sh->slot_k[i];
            sh->src_p[k * (size_t)sh->nf + (size_t)f] = sh->slot_p[i];
        }
    }
}

/* Point p of todo cell k is copied from another cell. */
static int shared_copied(const shared_pts *sh, size_t k, int p)
{
    return sh->on && p >= sh->first && p < sh->first + sh->nf &&
           sh->src_k[k * (size_t)sh->nf + (size_t)(p - sh->first)] != SIZE_MAX;
}

/* Copies every shared value (and gradient) from the cell that holds it;
 * sources are first occurrences, never copies themselves. */
static void shared_copy(const shared_pts *sh, size_t nt, int np, int dim, int grad, int stride,
                        double *exact)
{
    if (!sh->on) return;
    for (size_t k = 0; k < nt; k++)
        for (int f = 0; f < sh->nf; f++) {
            size_t sk = sh->src_k[k * (size_t)sh->nf + (size_t)f];
            if (sk == SIZE_MAX) continue;
            int sp = sh->src_p[k * (size_t)sh->nf + (size_t)f], p = sh->first + f;
            double *e = exact + k * (size_t)stride;
            const double *se = exact + sk * (size_t)stride;
            e[p] = se[sp];
            if (grad) memcpy(e + np + p * dim, se + np + sp * dim, (size_t)dim * sizeof *e);
        }
}

/* Estimator over all leaves; per-leaf error into err_out (leaf order), the
 * level's max and mean error into rec.  Times are added to rec->t_foot
 * (exact distances) and rec->t_spline (spline). */
static dfl_status estimate(fitter *F, double *err_out, dfl_pht_level *rec, dfl_err *err)
{
    size_t nl = dfl_tmesh_nleaves(F->mesh);
    const size_t *leaves = dfl_tmesh_leaves(F->mesh);
    const int dim = F->dim, np = F->npts, grad = F->o->estimator == DFL_PHT_EST_GRADIENT;
    const int stride = np * (1 + (grad ? dim : 0));
    size_t *todo = malloc((nl ? nl : 1) * sizeof *todo), nt = 0;
    if (!todo) return dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
    for (size_t i = 0; i < nl; i++) {
        size_t id = leaves[i];
        const double *coef = dfl_pht_spline_cell(F->spline, i, NULL, NULL, NULL);
        if (F->node_valid[id] &&
            memcmp(coef, F->node_coef + id * (size_t)F->nc, (size_t)F->nc * sizeof *coef) == 0)
            continue;
        todo[nt++] = i;
    }
    double *exact = malloc((nt ? nt : 1) * (size_t)stride * sizeof *exact);
    shared_pts sh;
    if (!exact || shared_init(F, nt, &sh) != 0) {
        free(todo);
        free(exact);
        shared_free(&sh);
        return dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
    }
    double t0 = omp_get_wtime();
    /* re-estimated cells take their exact values from the node cache; the
     * others share face centres (first occurrence in todo order evaluates) */
    size_t ncache = 0;
    for (size_t k = 0; k < nt; k++) {
        size_t id = leaves[todo[k]];
        if (F->node_valid[id]) {
            memcpy(exact + k * (size_t)stride, F->node_exact + id * (size_t)stride,
                   (size_t)stride * sizeof *exact);
            ncache++;
        }
        shared_add(F, &sh, k, leaves[todo[k]]);
    }
    (void)ncache;
    /* small levels stay serial: waking threads costs more than they save */
    const int par = (nt - ncache) * (size_t)np > 4096;
#pragma omp parallel if (par)
    {
        double pts[(4096 + 7) * 3], q[(4096 + 7) * 3], v[4096 + 7], g[(4096 + 7) * 3];
        int which[4096 + 7];
#pragma omp for schedule(dynamic, 4)
        for (size_t k = 0; k < nt; k++) {
            size_t id = leaves[todo[k]];
            if (F->node_valid[id]) continue;
            dfl_tmesh_cell c;
            dfl_tmesh_cell_get(F->mesh, id, &c);
            cell_points(F, &c, pts);
            double *e = exact + k * (size_t)stride;
            int n = 0;
            for (int p = 0; p < np; p++) {
                if (shared_copied(&sh, k, p)) continue;
                memcpy(q + n * dim, pts + p * dim, (size_t)dim * sizeof *q);
                which[n++] = p;
            }
            dfl_pht_source_eval(F->src, (size_t)n, q, v, grad ? g : NULL);
            for (int i = 0; i < n; i++) {
                e[which[i]] = v[i];
                if (grad) memcpy(e + np + which[i] * dim, g + i * dim, (size_t)dim * sizeof *g);
            }
        }
    }
    shared_copy(&sh, nt, np, dim, grad, stride, exact);
    shared_free(&sh);
    double t1 = omp_get_wtime();
#pragma omp parallel if (par)
    {
        double pts[(4096 + 7) * 3], val[4096 + 7], g[(4096 + 7) * 3];
#pragma omp for schedule(dynamic, 4)
        for (size_t k = 0; k < nt; k++) {
            size_t i = todo[k], id = leaves[i];
            dfl_tmesh_cell c;
            dfl_tmesh_cell_get(F->mesh, id, &c);
            cell_points(F, &c, pts);
            const double *e = exact + k * (size_t)stride;
            dfl_pht_eval_cell(F->spline, i, (size_t)np, pts, val, grad ? g : NULL, NULL);
            double mx = 0.0, sum = 0.0;
            for (int p = 0; p < np; p++) {
                double ev = fabs(val[p] - e[p]);
                sum += ev;
                if (grad) {
                    double gg = 0.0;
                    for (int j = 0; j < dim; j++) {
                        double dj = g[p * dim + j] - e[np + p * dim + j];
                        gg += dj * dj;
                    }
                    if (sqrt(gg) > ev) ev = sqrt(gg);
                }
                /* a NaN sticks: !(ev <= mx) alone let a later finite point
                 * replace it */
                if (isnan(ev) || ev > mx) mx = ev;
            }
            F->node_err[id] = mx;
            F->node_sum[id] = sum;
            memcpy(F->node_coef + id * (size_t)F->nc,
                   dfl_pht_spline_cell(F->spline, i, NULL, NULL, NULL),
                   (size_t)F->nc * sizeof(double));
            memcpy(F->node_exact + id * (size_t)stride, e, (size_t)stride * sizeof *e);
            F->node_valid[id] = 1;
        }
    }
    double t2 = omp_get_wtime();
    rec->t_foot += t1 - t0;
    rec->t_spline += t2 - t1;
    double mx = 0.0, sum = 0.0;
    for (size_t i = 0; i < nl; i++) {
        err_out[i] = F->node_err[leaves[i]];
        if (isnan(err_out[i]) || err_out[i] > mx) mx = err_out[i]; /* a NaN sticks */
        sum += F->node_sum[leaves[i]];
    }
    rec->max_err = mx;
    rec->mean_err = nl ? sum / ((double)nl * np) : 0.0;
    free(todo);
    free(exact);
    return DFL_OK;
}

/* One level: data, spline, estimate; the record's counts and times. */
static dfl_status level_pass(fitter *F, double **cell_err, dfl_pht_level *rec, dfl_err *err)
{
    dfl_status st;
    if (grow_vertices(F) != 0 || grow_nodes(F) != 0)
        return dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
    double t0 = omp_get_wtime();
    if ((st = compute_base(F, &rec->new_base, err)) != DFL_OK) return st;
    double t1 = omp_get_wtime();
    dfl_pht_resolve(F->mesh, F->data);
    dfl_pht_spline_free(F->spline);
    F->spline = NULL;
    if ((st = dfl_pht_spline_new(F->mesh, F->data, &F->spline, err)) != DFL_OK) return st;
    double t2 = omp_get_wtime();
    rec->t_foot += t1 - t0;
    rec->t_spline += t2 - t1;
    rec->cells = dfl_tmesh_nleaves(F->mesh);
    rec->base_vertices = dfl_tmesh_nbase(F->mesh);
    rec->dofs = rec->base_vertices * (size_t)F->nd;
    double *ce = realloc(*cell_err, (rec->cells ? rec->cells : 1) * sizeof *ce);
    if (!ce) return dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
    *cell_err = ce;
    return estimate(F, ce, rec, err);
}

static dfl_status fitter_init(fitter *F, const dfl_pht_source *src, const dfl_pht_fit_opts *o,
                              dfl_err *err)
{
    memset(F, 0, sizeof *F);
    F->src = src;
    F->o = o;
    F->dim = dfl_pht_source_dim(src);
    F->nd = DFL_PHT_NDATA(F->dim);
    F->nc = DFL_PHT_NCOEF(F->dim);
    dfl_status st = dfl_pht_fit_opts_check(F->dim, o, err);
    if (st != DFL_OK) return st;
    /* an unsigned distance (an open curve) has no inside: refuse it here,
     * once for every caller, rather than fit a function that is not an SDF */
    if ((st = dfl_pht_source_check_signed(src, o->lo, o->hi, err)) != DFL_OK) return st;
    if (o->estimator == DFL_PHT_EST_GRID) {
        int n = (int)lround(pow((double)o->samples, 1.0 / F->dim));
        if (n < 1) n = 1;
        F->npts = F->dim == 2 ? n * n : n * n * n;
    } else {
        F->npts = o->samples + (o->peaks ? 1 + 2 * F->dim : 0);
    }
    F->xstride = F->npts * (1 + (o->estimator == DFL_PHT_EST_GRADIENT ? F->dim : 0));
    return dfl_tmesh_new(F->dim, o->lo, o->hi, &F->mesh, err);
}

static void fitter_finish(fitter *F, dfl_pht_fit *out, double *cell_err, dfl_pht_level *levels,
                          int nlevels, double t_start)
{
    out->dim = F->dim;
    out->mesh = F->mesh;
    out->spline = F->spline;
    out->data = F->data;
    out->cell_err = cell_err;
    out->levels = levels;
    out->nlevels = nlevels;
    out->medial_vertices = F->medial;
    out->t_total = omp_get_wtime() - t_start;
    free(F->have);
    free(F->node_err);
    free(F->node_sum);
    free(F->node_coef);
    free(F->node_exact);
    free(F->node_valid);
}

static void fitter_abort(fitter *F, double *cell_err, dfl_pht_level *levels, dfl_pht_fit *out)
{
    dfl_pht_fit tmp;
    memset(&tmp, 0, sizeof tmp);
    fitter_finish(F, &tmp, cell_err, levels, 0, 0.0);
    dfl_pht_fit_free(&tmp);
    memset(out, 0, sizeof *out);
}

/* Appends to split[0..ns) the owners of the hanging corners of the cells in
 * it that are >= 2 levels coarser and below max_level (once each: the
 * owners are leaves not yet in split, so split needs room for all leaves). */
static size_t add_owners(fitter *F, size_t *split, size_t ns)
{
    size_t n0 = ns, nn = dfl_tmesh_ncells(F->mesh);
    unsigned char *mark = calloc(nn, 1);
    if (!mark) return ns;  /* grading is an improvement, not a requirement */
    for (size_t i = 0; i < n0; i++) mark[split[i]] = 1;
    for (size_t i = 0; i < n0; i++) {
        dfl_tmesh_cell c;
        dfl_tmesh_cell_get(F->mesh, split[i], &c);
        for (int k = 0; k < (1 << F->dim); k++) {
            dfl_tmesh_vertex v;
            dfl_tmesh_vertex_get(F->mesh, c.corner[k], &v);
            if (v.kind == DFL_TMESH_BASE || mark[v.owner]) continue;
            dfl_tmesh_cell o;
            dfl_tmesh_cell_get(F->mesh, v.owner, &o);
            if (o.level > c.level - 2 || o.level >= F->o->max_level) continue;
            mark[v.owner] = 1;
            split[ns++] = v.owner;
        }
    }
    free(mark);
    return ns;
}

dfl_status dfl_pht_fit_run(const dfl_pht_source *src, const dfl_pht_fit_opts *o,
                           dfl_pht_fit *out, dfl_err *err)
{
    double t_start = omp_get_wtime();
    fitter F;
    memset(out, 0, sizeof *out);
    dfl_status st = fitter_init(&F, src, o, err);
    if (st != DFL_OK) {
        dfl_tmesh_free(F.mesh);
        return st;
    }
    double *cell_err = NULL;
    size_t lcap = 16;
    dfl_pht_level *levels = calloc(lcap, sizeof *levels);
    size_t *split = NULL;
    int nlev = 0;
    if (!levels) {
        st = dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
        goto fail;
    }
    /* iterate until no cell above eps is below max_level (with grading a
     * cell may reach max_level after more than max_level iterations) */
    for (int k = 0;; k++) {
        if ((size_t)k + 1 >= lcap) {
            dfl_pht_level *nl = realloc(levels, 2 * lcap * sizeof *nl);
            if (!nl) {
                st = dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
                goto fail;
            }
            memset(nl + lcap, 0, lcap * sizeof *nl);
            levels = nl;
            lcap *= 2;
        }
        dfl_pht_level *rec = &levels[k];
        rec->level = k;
        if ((st = level_pass(&F, &cell_err, rec, err)) != DFL_OK) goto fail;
        nlev = k + 1;
        size_t nl = dfl_tmesh_nleaves(F.mesh), ns = 0;
        const size_t *leaves = dfl_tmesh_leaves(F.mesh);
        size_t *sp = realloc(split, (nl ? 2 * nl : 1) * sizeof *sp);
        if (!sp) {
            st = dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
            goto fail;
        }
        split = sp;
        int all_ok = 1;
        size_t capped = 0;
        for (size_t i = 0; i < nl; i++) {
            if (cell_err[i] <= o->eps) continue;
            all_ok = 0;
            int level;
            dfl_pht_spline_cell(F.spline, i, NULL, NULL, &level);
            if (level < o->max_level) split[ns++] = leaves[i];
            else capped++;
        }
        out->capped = capped;
        if (o->grade && ns) ns = add_owners(&F, split, ns);
        out->converged = all_ok;
        rec->refined = ns;
        if (ns == 0) break;
        double t0 = omp_get_wtime();
        if ((st = dfl_tmesh_refine(F.mesh, ns, split, o->split, err)) != DFL_OK) goto fail;
        levels[k + 1].t_mesh = omp_get_wtime() - t0;
    }
    free(split);
    int conv = out->converged;
    size_t capped = out->capped;
    fitter_finish(&F, out, cell_err, levels, nlev, t_start);
    out->converged = conv;
    out->capped = capped;
    return DFL_OK;
fail:
    free(split);
    fitter_abort(&F, cell_err, levels, out);
    return st;
}

dfl_status dfl_pht_fit_uniform(const dfl_pht_source *src, const dfl_pht_fit_opts *o, int level,
                               dfl_pht_fit *out, dfl_err *err)
{
    double t_start = omp_get_wtime();
    memset(out, 0, sizeof *out);
    if (level < 0 || level > DFL_TMESH_MAX_LEVEL)
        return dfl_err_set(err, DFL_E_INPUT, "PHT uniform fit: level %d (expected 0..%d)", level,
                           DFL_TMESH_MAX_LEVEL);
    dfl_pht_fit_opts u = *o;
    u.split = DFL_PHT_SPLIT_CROSS;
    u.max_level = level;
    if (!(u.eps > 0)) u.eps = 1.0;
    fitter F;
    dfl_status st = fitter_init(&F, src, &u, err);
    double *cell_err = NULL;
    dfl_pht_level *levels = calloc(1, sizeof *levels);
    if (st == DFL_OK && !levels) st = dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
    double t0 = omp_get_wtime();
    for (int k = 0; st == DFL_OK && k < level; k++) {
        size_t nl = dfl_tmesh_nleaves(F.mesh);
        size_t *ids = malloc(nl * sizeof *ids);
        if (!ids) {
            st = dfl_err_set(err, DFL_E_NOMEM, "PHT fit: out of memory");
            break;
        }
        memcpy(ids, dfl_tmesh_leaves(F.mesh), nl * sizeof *ids);
        st = dfl_tmesh_refine(F.mesh, nl, ids, DFL_PHT_SPLIT_CROSS, err);
        free(ids);
    }
    if (st == DFL_OK) {
        levels[0].t_mesh = omp_get_wtime() - t0;
        levels[0].level = level;
        st = level_pass(&F, &cell_err, levels, err);
    }
    if (st != DFL_OK) {
        fitter_abort(&F, cell_err, levels, out);
        return st;
    }
    size_t capped = 0;
    for (size_t i = 0; i < dfl_tmesh_nleaves(F.mesh); i++)
        if (!(cell_err[i] <= u.eps)) capped++;
    fitter_finish(&F, out, cell_err, levels, 1, t_start);
    out->converged = capped == 0;
    out->capped = capped;
    return DFL_OK;
}

void dfl_pht_fit_free(dfl_pht_fit *f)
{
    if (!f) return;
    dfl_tmesh_free(f->mesh);
    dfl_pht_spline_free(f->spline);
    free(f->data);
    free(f->cell_err);
    free(f->levels);
    memset(f, 0, sizeof *f);
}
