/* The builder keeps the input's work in batches (one query per chunk of
 * cells) and the per-cell work to encoding and rounding, so that an SDF
 * input's order-1 grid costs little more than the SDF evaluations. */
#include "proxy/proxy.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/vec.h"

#define CHUNK 256

void dfl_proxy_build_opts_default(dfl_proxy_build_opts *o)
{
    memset(o, 0, sizeof *o);
    o->order = 1;
    o->res = 16;
    for (int j = 0; j < 3; j++) {
        o->lo[j] = -1.0;
        o->hi[j] = 1.0;
    }
    o->storage = DFL_PROXY_DOUBLE;
    o->position = DFL_PROXY_DISPLACEMENT;
    o->noise_cell = -1;
}

static dfl_status check_opts(const dfl_proxy_build_opts *o, dfl_err *err)
{
    if (!o) return dfl_err_set(err, DFL_E_INPUT, "proxy grid: no options");
    if (o->order != 1 && o->order != 2)
        return dfl_err_set(err, DFL_E_INPUT, "proxy grid: order %d (expected 1 or 2)", o->order);
    if (o->res < 1 || o->res > 2048)
        return dfl_err_set(err, DFL_E_INPUT, "proxy grid: res %d (expected 1..2048)", o->res);
    for (int j = 0; j < 3; j++)
        if (!(o->lo[j] < o->hi[j]) || !isfinite(o->lo[j]) || !isfinite(o->hi[j]))
            return dfl_err_set(err, DFL_E_INPUT, "proxy grid: lo[%d] = %g must be < hi[%d] = %g",
                               j, o->lo[j], j, o->hi[j]);
    if (!(o->noise >= 0) || !isfinite(o->noise))
        return dfl_err_set(err, DFL_E_INPUT, "proxy grid: noise %g (expected >= 0)", o->noise);
    if (o->noise_cell < -1 || (o->noise_cell >= 0 && o->res >= 1 &&
                               (double)o->noise_cell >= (double)o->res * o->res * o->res))
        return dfl_err_set(err, DFL_E_INPUT, "proxy grid: noise cell %ld (expected -1 or < N^3)",
                           o->noise_cell);
    if ((unsigned)o->storage >= DFL_PROXY_STORAGE_COUNT ||
        (unsigned)o->position >= DFL_PROXY_POSITION_COUNT)
        return dfl_err_set(err, DFL_E_INPUT, "proxy grid: bad storage or position");
    return DFL_OK;
}

dfl_status dfl_proxy_grid_alloc(const dfl_proxy_build_opts *o, int has_inside, int with_side,
                                dfl_proxy_grid *g, dfl_err *err)
{
    memset(g, 0, sizeof *g);
    dfl_status st = check_opts(o, err);
    if (st) return st;
    g->order = o->order;
    g->res = o->res;
    g->nscalar = DFL_PROXY_NSCALAR(o->order);
    for (int j = 0; j < 3; j++) {
        g->lo[j] = o->lo[j];
        g->hi[j] = o->hi[j];
        g->h[j] = (o->hi[j] - o->lo[j]) / o->res;
    }
    g->storage = o->storage;
    g->position = o->position;
    g->has_inside = has_inside;
    g->ncells = (size_t)o->res * (size_t)o->res * (size_t)o->res;
    g->data = calloc(g->ncells * (size_t)g->nscalar, dfl_proxy_storage_size(o->storage));
    if (with_side) {
        g->side = malloc(g->ncells);
        if (g->side) memset(g->side, 1, g->ncells);
    }
    if (!g->data || (with_side && !g->side)) {
        dfl_proxy_grid_free(g);
        return dfl_err_set(err, DFL_E_NOMEM, "proxy grid: out of memory (%zu cells)",
                           (size_t)o->res * o->res * o->res);
    }
    return DFL_OK;
}

void dfl_proxy_grid_free(dfl_proxy_grid *g)
{
    if (!g) return;
    free(g->data);
    free(g->side);
    memset(g, 0, sizeof *g);
}

/* The storage's largest finite value, its relative spacing (ulp of 1) and
 * its smallest normal value. */
static double storage_max(dfl_proxy_storage s)
{
    return s == DFL_PROXY_DOUBLE ? DBL_MAX : s == DFL_PROXY_FLOAT ? FLT_MAX : 65504.0;
}

static double storage_eps(dfl_proxy_storage s)
{
    return s == DFL_PROXY_DOUBLE ? 0x1p-52 : s == DFL_PROXY_FLOAT ? 0x1p-23 : 0x1p-10;
}

static double storage_tiny(dfl_proxy_storage s)
{
    return s == DFL_PROXY_DOUBLE ? DBL_MIN : s == DFL_PROXY_FLOAT ? FLT_MIN : 0x1p-14;
}

/* The first move length of cell centre xc (proxy.h): delta_0 = h 2^-40 |
 * 2^-20 | 2^-10, at least the smallest normal value of the storage (a
 * shorter displacement loses its direction in subnormals) and, for
 * absolute footpoints, 2 ulp of the largest coordinate of xc (a shorter
 * move rounds back onto the centre).  Rounding then shortens a move of
 * this length by less than half, so the first try normally survives. */
static double moved_delta(const dfl_proxy_grid *g, const double xc[3])
{
    const dfl_proxy_storage s = g->storage;
    const double e = s == DFL_PROXY_DOUBLE ? 0x1p-40 : s == DFL_PROXY_FLOAT ? 0x1p-20 : 0x1p-10;
    double d = e * dfl_proxy_cell_size(g);
    if (d < storage_tiny(s)) d = storage_tiny(s);
    if (g->position == DFL_PROXY_ABSOLUTE) {
        double m = 0;
        for (int j = 0; j < 3; j++)
            if (fabs(xc[j]) > m) m = fabs(xc[j]);
        if (2.0 * storage_eps(s) * m > d) d = 2.0 * storage_eps(s) * m;
    }
    return d;
}

/* Uniform on the unit sphere (Archimedes: z uniform, angle uniform). */
static void noise_dir(uint64_t seed, size_t c, double w[3])
{
    uint64_t s = seed + (uint64_t)c * 0xD1B54A32D192ED03ull;
    const double z = dfl_rng_splitmix(&s, -1.0, 1.0);
    const double a = dfl_rng_splitmix(&s, 0.0, 2.0 * DFL_PI);
    const double r = sqrt(1.0 - z * z);
    w[0] = r * cos(a);
    w[1] = r * sin(a);
    w[2] = z;
}

/* Centres of cells c0 .. c0 + m - 1, counting (i, j, k) up. */
static void centres(const dfl_proxy_grid *g, size_t c0, size_t m, double *x)
{
    const size_t n = (size_t)g->res;
    size_t i = c0 % n, j = (c0 / n) % n, k = c0 / (n * n);
    for (size_t q = 0; q < m; q++) {
        x[3 * q] = g->lo[0] + ((double)i + 0.5) * g->h[0];
        x[3 * q + 1] = g->lo[1] + ((double)j + 0.5) * g->h[1];
        x[3 * q + 2] = g->lo[2] + ((double)k + 0.5) * g->h[2];
        if (++i == n) {
            i = 0;
            if (++j == n) j = 0, k++;
        }
    }
}

static int finite_answer(int order, const dfl_surfpoint *sp)
{
    int ok = isfinite(sp->p[0]) && isfinite(sp->p[1]) && isfinite(sp->p[2]) &&
             isfinite(sp->n[0]) && isfinite(sp->n[1]) && isfinite(sp->n[2]) && isfinite(sp->d);
    if (order == 2) {
        const dfl_curvature *c = &sp->curv;
        ok = ok && isfinite(c->k1) && isfinite(c->k2) && isfinite(c->e1[0]) &&
             isfinite(c->e1[1]) && isfinite(c->e1[2]) && isfinite(c->e2[0]) &&
             isfinite(c->e2[1]) && isfinite(c->e2[2]);
    }
    return ok;
}

/* Caps the logical scalars s (footpoint already as stored: displacement
 * or absolute) to what the storage keeps finite (store.h); returns 1 when
 * a value changed.  A displacement is shortened along itself (the normal it
 * carries survives); absolute coordinates are clamped one by one. */
static int clamp_scalars(const dfl_proxy_grid *g, double *s)
{
    const double fmax = storage_max(g->storage);
    int clamped = 0;
    if (g->position == DFL_PROXY_DISPLACEMENT) {
        double m = 0;
        for (int j = 0; j < 3; j++)
            if (fabs(s[j]) > m) m = fabs(s[j]);
        if (m > fmax) {
            /* 1 - 2^-12 keeps the largest component below fmax after the
             * multiplication's rounding in every storage */
            const double f = fmax / m * (1.0 - 0x1p-12);
            for (int j = 0; j < 3; j++) s[j] *= f;
            clamped = 1;
        }
    } else {
        for (int j = 0; j < 3; j++)
            if (fabs(s[j]) > fmax) s[j] = copysign(fmax, s[j]), clamped = 1;
    }
    if (g->order == 2) {
        double kmax = 0x1p64 / dfl_proxy_cell_size(g);
        if (kmax > fmax) kmax = fmax;
        for (int q = 3; q < 5; q++)
            if (fabs(s[q]) > kmax) s[q] = copysign(kmax, s[q]), clamped = 1;
    }
    return clamped;
}

/* Tries of the move length: delta_0, 2 delta_0, ..., 2^8 delta_0 (for a
 * half grid's delta_0 = h 2^-10 a quarter cell; in practice the first try
 * survives, see moved_delta). */
#define MOVE_TRIES 9

static void store_failed(const dfl_proxy_grid *g, void *base, dfl_proxy_stats *cnt)
{
    cnt->failed++;
    for (int q = 0; q < g->nscalar; q++) dfl_proxy_store_put(g->storage, base, (size_t)q, NAN);
}

/* Encodes and stores cell c from its answer; updates the chunk's counts. */
static void store_cell(dfl_proxy_grid *g, const dfl_proxy_build_opts *o, size_t c,
                       const double xc[3], const dfl_surfpoint *sp, dfl_proxy_stats *cnt)
{
    double s[DFL_PROXY_NSCALAR_MAX];
    const int ns = g->nscalar;
    void *base = (char *)g->data + c * (size_t)ns * dfl_proxy_storage_size(g->storage);
    if (!sp->certified) cnt->uncertified++;
    if (!finite_answer(g->order, sp)) {
        store_failed(g, base, cnt);
        return;
    }
    double w[3];
    const int noisy = o->noise > 0 && (o->noise_cell < 0 || (size_t)o->noise_cell == c);
    if (noisy) {
        noise_dir(o->seed, c, w);
        for (int j = 0; j < 3; j++) w[j] *= o->noise;
    }
    /* The normal is decoded from the stored footpoint, so the stored
     * (rounded) displacement from the centre must keep at least half the
     * move length delta: when it does not, delta doubles, at most
     * MOVE_TRIES times; a cell that still fails is counted as failed. */
    double delta = moved_delta(g, xc);
    int side = 1, moved = 0, clamped = 0, ok = 0;
    for (int it = 0; it < MOVE_TRIES && !ok; it++, delta *= 2) {
        moved = dfl_proxy_encode(g->order, xc, sp, noisy ? w : NULL, delta, s, &side);
        /* a moved displacement is -delta n itself: through x_c - delta n
         * and back it would keep only delta / ulp(x_c) of n's direction */
        if (g->position == DFL_PROXY_DISPLACEMENT)
            for (int j = 0; j < 3; j++) s[j] = moved ? -delta * sp->n[j] : s[j] - xc[j];
        clamped = clamp_scalars(g, s);
        double dd[3];
        for (int j = 0; j < 3; j++) {
            const double r = dfl_proxy_store_round(g->storage, s[j]);
            dd[j] = g->position == DFL_PROXY_DISPLACEMENT ? r : r - xc[j];
        }
        const double l2 = dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2];
        ok = isfinite(l2) && l2 >= 0.25 * delta * delta;
    }
    for (int q = 0; q < ns && ok; q++) ok = isfinite(dfl_proxy_store_round(g->storage, s[q]));
    if (!ok) {
        store_failed(g, base, cnt);
        return;
    }
    cnt->moved += (size_t)moved;
    cnt->clamped += (size_t)clamped;
    for (int q = 0; q < ns; q++) dfl_proxy_store_put(g->storage, base, (size_t)q, s[q]);
    if (g->side) g->side[c] = (signed char)side;
}

dfl_status dfl_proxy_grid_build(const dfl_proxy_input *in, const dfl_proxy_build_opts *o,
                                dfl_proxy_grid *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    if (!in || !in->query) return dfl_err_set(err, DFL_E_INPUT, "proxy grid: no input");
    dfl_proxy_grid g;
    const int with_side = o && o->order == 1 && in->has_inside;
    dfl_status st = dfl_proxy_grid_alloc(o, in->has_inside, with_side, &g, err);
    if (st) return st;
    const size_t nchunk = (g.ncells + CHUNK - 1) / CHUNK;
    const int need_curv = g.order == 2;
    dfl_status first_st = DFL_OK;
    size_t first_bad = nchunk;
    dfl_err first_err;
    dfl_err_clear(&first_err);
    dfl_proxy_stats tot = {0, 0, 0, 0};
    dfl_proxy_stats *per = calloc(nchunk, sizeof *per);
    if (!per) {
        dfl_proxy_grid_free(&g);
        return dfl_err_set(err, DFL_E_NOMEM, "proxy grid: out of memory");
    }
    int nomem = 0;
#pragma omp parallel
    {
        double *x = malloc(3 * CHUNK * sizeof *x);
        dfl_surfpoint *sp = malloc(CHUNK * sizeof *sp);
        if (!x || !sp) {
#pragma omp atomic write
            nomem = 1;
        }
#pragma omp for schedule(static)
        for (size_t k = 0; k < nchunk; k++) {
            if (!x || !sp) continue;
            const size_t c0 = k * CHUNK;
            const size_t m = c0 + CHUNK <= g.ncells ? CHUNK : g.ncells - c0;
            centres(&g, c0, m, x);
            dfl_err e;
            dfl_status s2 = dfl_proxy_input_query(in, m, x, need_curv, sp, &e);
            if (s2 != DFL_OK) {
#pragma omp critical(dfl_proxy_build_err)
                if (k < first_bad) {
                    first_bad = k;
                    first_st = s2;
                    first_err = e;
                }
                continue;
            }
            for (size_t i = 0; i < m; i++)
                store_cell(&g, o, c0 + i, x + 3 * i, &sp[i], &per[k]);
        }
        free(x);
        free(sp);
    }
    if (nomem) first_st = dfl_err_set(&first_err, DFL_E_NOMEM, "proxy grid: out of memory");
    for (size_t k = 0; k < nchunk; k++) {
        tot.uncertified += per[k].uncertified;
        tot.failed += per[k].failed;
        tot.moved += per[k].moved;
        tot.clamped += per[k].clamped;
    }
    free(per);
    if (first_st != DFL_OK) {
        dfl_proxy_grid_free(&g);
        if (err) *err = first_err;
        return first_st;
    }
    g.stats = tot;
    *out = g;
    return DFL_OK;
}

void dfl_proxy_cell_decode(const dfl_proxy_grid *g, size_t c, dfl_proxy_geom *out)
{
    const size_t n = (size_t)g->res;
    dfl_proxy_cell_decode_ijk(g, c % n, (c / n) % n, c / (n * n), out);
}
