/* The mixed kind: R-equivalence of parts of several kinds, or of one kind
 * the built-in kernels refuse only for its layout (segments that are not a
 * chain: several polylines, separate segments; triangles with different
 * eq. 4 trims).
 *
 * Why it is a sum of kernels: R-equivalence's sums S = sum h_i^-p and
 * V = sum h_i^-(p+2) h_i grad h_i (batch.h) are sums over parts, so they
 * are the sums of the built-in kernels over groups of parts of one kernel
 * kind (2D/3D segments with the disk trim, with the strip trim, points,
 * convex regions, triangles of one eq. 4 trim).  Each group is a sub-batch
 * whose arrays hold its parts in field order (the segment kernels read a
 * and b per segment, so a group need not be a chain); the mixed batch's
 * sums run every group's kernel into scratch and add the groups in the
 * order of their first part in the field.  That order is fixed, so a
 * point's sums depend neither on how points are chunked nor on threads.
 * It is not the per-point path's order (part by part), which changes the
 * sums by rounding only (tests/rfunc/test_batch_mixed.c: 1e-12).  Points
 * the kernels do not trust (on a part, overflowing sums) fall back to the
 * field's per-point path as for every sums kind (batch.c's test), except
 * points inside a region, where u = 0 exactly (mixed_kernel).
 *
 * Not taken (NULL): other joins (R-conjunction, the corrected join),
 * eq. 5 trims of segments or triangles (their own kind), conditional
 * triangle trims with k != 2. */
#include <stdlib.h>
#include <string.h>

#include "rfunc/batch_impl.h"

/* A group: part kind and, for segments, the trim; for triangles the
 * conditional flag and weight (prism triangles share one group). */
typedef struct group_key {
    dfl_rfunc_part_kind kind;
    int trim; /* segments: dfl_rfunc_trim; triangles: 1 conditional, 0 prism */
    double a; /* conditional triangles: the weight */
} group_key;

typedef struct mixed_kd {
    size_t ng;
    dfl_rfunc_batch **g; /* ng sub-batches, in the order of their first part */
    size_t nreg;
    const dfl_rfunc_region **reg; /* the region parts (borrowed from the field) */
} mixed_kd;

static void mixed_free(void *p)
{
    mixed_kd *kd = p;
    if (!kd) return;
    for (size_t i = 0; i < kd->ng; i++) dfl_rfunc_batch_free(kd->g[i]);
    free(kd->g);
    free(kd->reg);
    free(kd);
}

/* The part's group key, or 0 when no kernel computes the part. */
static int part_key(const dfl_rfunc_part *pt, group_key *k)
{
    memset(k, 0, sizeof *k);
    k->kind = pt->kind;
    switch (pt->kind) {
    case DFL_RFUNC_PART_SEGMENT:
        k->trim = (int)pt->u.seg.trim;
        return pt->u.seg.trim == DFL_RFUNC_TRIM_DISK || pt->u.seg.trim == DFL_RFUNC_TRIM_STRIP;
    case DFL_RFUNC_PART_TRIANGLE: {
        const dfl_rfunc_tri_opts *o = &pt->u.tri.o;
        if (o->smooth) return 0;
        if (o->trim == DFL_RFUNC_TRI_CONDITIONAL) {
            k->trim = 1;
            k->a = o->a;
            return o->k == 2;
        }
        return o->trim == DFL_RFUNC_TRI_PRISM;
    }
    case DFL_RFUNC_PART_POINT:
    case DFL_RFUNC_PART_REGION: return 1;
    }
    return 0;
}

static int key_eq(const group_key *x, const group_key *y)
{
    return x->kind == y->kind && x->trim == y->trim && x->a == y->a;
}

/* Sub-batch of the parts of d with key k (cnt of them), arrays filled as
 * the built-in constructors fill them (segments: dfl_rfunc_batch_new_opts's
 * frames from the parts' own rfunc/segment.c data, so f, p1, p2 are
 * bitwise the per-point path's). */
static dfl_status build_group(const dfl_rfunc_batch_desc *d, const group_key *k, size_t cnt,
                              dfl_rfunc_batch **out, dfl_err *err)
{
    dfl_field zero = {0};
    dfl_rfunc_batch *b;
    dfl_status st = dfl_rfunc_batch_alloc(d->dim, d->p, cnt, &zero, &b, err);
    if (st != DFL_OK) return st;
    b->fb = d->slow;
    if (k->kind == DFL_RFUNC_PART_TRIANGLE || k->kind == DFL_RFUNC_PART_REGION) {
        /* the kernels' own layouts (batch_tri.c, batch_region.c) */
        const int tri = k->kind == DFL_RFUNC_PART_TRIANGLE;
        void *arr = malloc(cnt * (tri ? sizeof(dfl_rfunc_tri) : sizeof(dfl_rfunc_region)));
        if (!arr) {
            dfl_rfunc_batch_free(b);
            return dfl_err_set(err, DFL_E_NOMEM, "out of memory for %zu parts", cnt);
        }
        size_t j = 0;
        for (size_t i = 0; i < d->n; i++) {
            group_key ki;
            if (!part_key(&d->parts[i], &ki) || !key_eq(&ki, k)) continue;
            if (tri) ((dfl_rfunc_tri *)arr)[j++] = d->parts[i].u.tri;
            else ((dfl_rfunc_region *)arr)[j++] = d->parts[i].u.reg; /* shallow: read only */
        }
        st = tri ? dfl_rfunc_batch_tri_attach(b, arr, cnt, err)
                 : dfl_rfunc_batch_reg_attach(b, arr, cnt, err);
        free(arr);
        if (st != DFL_OK) {
            dfl_rfunc_batch_free(b);
            return st;
        }
        *out = b;
        return DFL_OK;
    }
    b->strip = k->kind == DFL_RFUNC_PART_SEGMENT && k->trim == DFL_RFUNC_TRIM_STRIP;
    b->points = k->kind == DFL_RFUNC_PART_POINT;
    size_t j = 0;
    for (size_t i = 0; i < d->n; i++) {
        const dfl_rfunc_part *pt = &d->parts[i];
        group_key ki;
        if (!part_key(pt, &ki) || !key_eq(&ki, k)) continue;
        if (k->kind == DFL_RFUNC_PART_SEGMENT) {
            dfl_rfunc_batch_put_seg(b, j, &pt->u.seg);
        } else {
            b->ax[j] = pt->u.pt.c[0];
            b->ay[j] = pt->u.pt.c[1];
            b->az[j] = d->dim == 3 ? pt->u.pt.c[2] : 0.0;
        }
        j++;
    }
    *out = b;
    return DFL_OK;
}

/* 1 + dim sums of one group (the built-in kernels' dispatch of batch.c). */
static void group_sums(const dfl_rfunc_batch *g, size_t m, const double *pts, double *out)
{
    if (g->regions) dfl_rfunc_batch_sums_reg(g, m, pts, out);
    else if (g->tris) dfl_rfunc_batch_sums_tri(g, m, pts, out);
    else if (g->points) dfl_rfunc_batch_sums_pts(g, m, pts, out);
    else dfl_rfunc_batch_sums_seg(g, m, pts, out);
}

/* The groups' sums added in group order, SCRATCH points at a time. */
static void mixed_sums(const dfl_rfunc_batch *b, size_t m, const double *pts, double *out)
{
    const mixed_kd *kd = b->kd;
    const size_t dim = (size_t)b->dim, w = dim + 1;
    double tmp[4 * SCRATCH];
    for (size_t i = 0; i < m; i += SCRATCH) {
        const size_t c = m - i < SCRATCH ? m - i : SCRATCH;
        double *o = out + w * i;
        group_sums(kd->g[0], c, pts + dim * i, o);
        for (size_t gi = 1; gi < kd->ng; gi++) {
            group_sums(kd->g[gi], c, pts + dim * i, tmp);
            for (size_t j = 0; j < w * c; j++) o[j] += tmp[j];
        }
    }
}

/* 1 when x is inside (or on) a region part: there the per-point path's
 * accumulator sees h = 0 and returns u = 0 with a zero gradient whatever
 * the other parts are (rfunc/join.h), so the point needs no fallback.
 * Regions are the parts whose zero sets have area: a grid puts many
 * points there (bs04 Fig. 13a: a tenth of the nodes). */
static int in_region(const mixed_kd *kd, const double *x)
{
    for (size_t i = 0; i < kd->nreg; i++)
        if (!(dfl_rfunc_region_eval(kd->reg[i], x, NULL) > 0.0)) return 1;
    return 0;
}

/* u and grad u: the sums, batch.c's test, then zero inside a region or
 * the per-point path. */
static void mixed_kernel(const dfl_rfunc_batch *b, size_t m, const double *pts, double *val,
                         double *grad)
{
    const mixed_kd *kd = b->kd;
    const size_t dim = (size_t)b->dim;
    double s[4 * SCRATCH];
    for (size_t i0 = 0; i0 < m; i0 += SCRATCH) {
        const size_t c = m - i0 < SCRATCH ? m - i0 : SCRATCH;
        mixed_sums(b, c, pts + dim * i0, s);
        for (size_t i = 0; i < c; i++) {
            const double *x = pts + dim * (i0 + i);
            double u, g[3] = {0, 0, 0};
            if (!dfl_rfunc_batch_accept(b->p, b->dim, s + (dim + 1) * i, &u, g))
                u = in_region(kd, x) ? 0.0 : dfl_field_eval1(b->fb, x, g);
            val[i0 + i] = u;
            if (grad) memcpy(grad + dim * (i0 + i), g, dim * sizeof *g);
        }
    }
}

/* Points of m that mixed_kernel hands to the per-point path. */
static size_t mixed_count_fb(const dfl_rfunc_batch *b, size_t m, const double *pts)
{
    const mixed_kd *kd = b->kd;
    const size_t dim = (size_t)b->dim;
    double s[4 * SCRATCH];
    size_t cnt = 0;
    for (size_t i0 = 0; i0 < m; i0 += SCRATCH) {
        const size_t c = m - i0 < SCRATCH ? m - i0 : SCRATCH;
        mixed_sums(b, c, pts + dim * i0, s);
        for (size_t i = 0; i < c; i++) {
            double u, g[3];
            cnt += !dfl_rfunc_batch_accept(b->p, b->dim, s + (dim + 1) * i, &u, g) &&
                   !in_region(kd, pts + dim * (i0 + i));
        }
    }
    return cnt;
}

dfl_status dfl_rfunc_batch_try_mixed(const dfl_rfunc_batch_desc *d, dfl_rfunc_batch **out,
                                     dfl_err *err)
{
    *out = NULL;
    if (d->join != DFL_RFUNC_REQUIV || d->n < 2) return DFL_OK;
    group_key *keys = malloc(d->n * sizeof *keys);
    size_t *cnt = calloc(d->n, sizeof *cnt);
    mixed_kd *kd = calloc(1, sizeof *kd);
    dfl_status st = DFL_OK;
    if (!keys || !cnt || !kd) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        goto done;
    }
    size_t ng = 0;
    for (size_t i = 0; i < d->n; i++) {
        group_key k;
        if (!part_key(&d->parts[i], &k)) goto done; /* not ours: NULL */
        size_t g = 0;
        while (g < ng && !key_eq(&keys[g], &k)) g++;
        if (g == ng) keys[ng++] = k;
        cnt[g]++;
    }
    kd->g = calloc(ng, sizeof *kd->g);
    kd->reg = malloc(d->n * sizeof *kd->reg);
    if (!kd->g || !kd->reg) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        goto done;
    }
    for (size_t g = 0; g < ng && st == DFL_OK; g++) {
        st = build_group(d, &keys[g], cnt[g], &kd->g[g], err);
        if (st == DFL_OK) kd->ng++;
    }
    if (st != DFL_OK) goto done;
    for (size_t i = 0; i < d->n; i++)
        if (d->parts[i].kind == DFL_RFUNC_PART_REGION) kd->reg[kd->nreg++] = &d->parts[i].u.reg;
    dfl_field zero = {0};
    dfl_rfunc_batch *b;
    if ((st = dfl_rfunc_batch_alloc(d->dim, d->p, 0, &zero, &b, err)) != DFL_OK) goto done;
    b->n = d->n;
    b->fb = d->slow;
    b->kernel = mixed_kernel;
    b->count_fb = mixed_count_fb;
    b->kd = kd;
    b->kd_free = mixed_free;
    kd = NULL;
    *out = b;
done:
    mixed_free(kd);
    free(keys);
    free(cnt);
    return st;
}
