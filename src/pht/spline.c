/* PHT spline: resolution of hanging data, cell polynomials, evaluation
 * (spline.h).
 *
 * Hermite basis on [0, 1] in power form, index 2 c + b for corner c (0, 1)
 * and derivative order b (0, 1):
 *   H0 = 1 - 3u^2 + 2u^3 (value at 0)   H1 = u - 2u^2 + u^3 (slope at 0)
 *   H2 = 3u^2 - 2u^3     (value at 1)   H3 = -u^2 + u^3     (slope at 1)
 * A tensor product of these interpolates the mask-ordered corner data;
 * derivatives scale by the side lengths h_j (d/du_j = h_j d/dx_j).  Along an
 * edge (on a face) only the basis functions of that edge's (face's) corners
 * are non-zero in value and normal derivative, which is why a cell's
 * polynomial on its boundary depends on the boundary's corners only. */
#include "pht/spline.h"

#include <assert.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/isa.h"
#include "pht/hermite.h"

static const double HB[4][4] = {{1, 0, -3, 2}, {0, 1, -2, 1}, {0, 0, 3, -2}, {0, 0, -1, 1}};

typedef struct snode {
    double mid[3];
    int64_t child;   /* first child node, or -(leaf index) - 1 */
    int axis;        /* -1 cross, else the binary split axis */
} snode;

struct dfl_pht_spline {
    int dim, nc;
    size_t ncell, nnode, nbase;
    double lo[3], hi[3];
    snode *node;
    double *cell;    /* per cell: lo[dim], 1/h[dim], coef[nc] */
    double *chi;     /* per cell: hi[dim] (exact, for dfl_pht_spline_cell) */
    int *level;
    size_t stride;
    /* location index: a uniform grid of gn^dim cells over the box (gn =
     * 2^gbits), each holding the deepest tree node that contains it; the
     * grid lines gline[j*(gn+1) + k] are the tree's split positions */
    int gn;
    double ginv[3];
    double *gline;
    int64_t *gnode;
};

/* Derivative order r (0..2) of basis idx at t. */
static double hb(int idx, int r, double t)
{
    const double *c = HB[idx];
    if (r == 0) return ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
    if (r == 1) return (3 * c[3] * t + 2 * c[2]) * t + c[1];
    return 6 * c[3] * t + 2 * c[2];
}

static void resolve_edge(int nd, const dfl_tmesh_vertex *v, const dfl_tmesh_vertex *A,
                         const dfl_tmesh_vertex *B, const double *da, const double *db,
                         double *out)
{
    int a = v->axis, bit = 1 << a;
    double t = (double)(v->key[a] - A->key[a]) / (double)(B->key[a] - A->key[a]);
    double L = B->x[a] - A->x[a];
    for (int b = 0; b < nd; b++) {
        if (b & bit) continue;
        double g0 = da[b], s0 = da[b | bit] * L, g1 = db[b], s1 = db[b | bit] * L;
        out[b] = hb(0, 0, t) * g0 + hb(1, 0, t) * s0 + hb(2, 0, t) * g1 + hb(3, 0, t) * s1;
        out[b | bit] =
            (hb(0, 1, t) * g0 + hb(1, 1, t) * s0 + hb(2, 1, t) * g1 + hb(3, 1, t) * s1) / L;
    }
}

static void resolve_face(const dfl_tmesh_vertex *v, const dfl_tmesh_vertex *C[4],
                         const double *D[4], double *out)
{
    int n = v->axis, a = n == 0 ? 1 : 0, b = n == 2 ? 1 : 2;
    int ba = 1 << a, bb = 1 << b;
    double ta = (double)(v->key[a] - C[0]->key[a]) / (double)(C[1]->key[a] - C[0]->key[a]);
    double tb = (double)(v->key[b] - C[0]->key[b]) / (double)(C[2]->key[b] - C[0]->key[b]);
    double La = C[1]->x[a] - C[0]->x[a], Lb = C[2]->x[b] - C[0]->x[b];
    for (int c = 0; c < 2; c++) {
        int base = c ? 1 << n : 0;
        for (int r = 0; r < 4; r++) {  /* output derivative bits: 1 along a, 2 along b */
            double acc = 0.0;
            for (int e = 0; e < 4; e++)
                for (int q = 0; q < 4; q++) {
                    int ia = 2 * (e & 1) + (q & 1), ib = 2 * ((e >> 1) & 1) + ((q >> 1) & 1);
                    int mask = base | ((q & 1) ? ba : 0) | ((q & 2) ? bb : 0);
                    double val = D[e][mask] * ((q & 1) ? La : 1.0) * ((q & 2) ? Lb : 1.0);
                    acc += val * hb(ia, r & 1, ta) * hb(ib, (r >> 1) & 1, tb);
                }
            int mask = base | ((r & 1) ? ba : 0) | ((r & 2) ? bb : 0);
            out[mask] = acc / (((r & 1) ? La : 1.0) * ((r & 2) ? Lb : 1.0));
        }
    }
}

void dfl_pht_resolve(const dfl_tmesh *m, double *data)
{
    int nd = DFL_PHT_NDATA(dfl_tmesh_dim(m));
    size_t n;
    const size_t *order = dfl_tmesh_order(m, &n);
    for (size_t i = 0; i < n; i++) {
        dfl_tmesh_vertex v, C[4];
        dfl_tmesh_vertex_get(m, order[i], &v);
        double *out = data + order[i] * (size_t)nd;
        if (v.kind == DFL_TMESH_EDGE) {
            for (int e = 0; e < 2; e++) dfl_tmesh_vertex_get(m, v.dep[e], &C[e]);
            resolve_edge(nd, &v, &C[0], &C[1], data + v.dep[0] * (size_t)nd,
                         data + v.dep[1] * (size_t)nd, out);
        } else {
            assert(v.kind == DFL_TMESH_FACE);
            const dfl_tmesh_vertex *pc[4];
            const double *D[4];
            for (int e = 0; e < 4; e++) {
                dfl_tmesh_vertex_get(m, v.dep[e], &C[e]);
                pc[e] = &C[e];
                D[e] = data + v.dep[e] * (size_t)nd;
            }
            resolve_face(&v, pc, D, out);
        }
    }
}

/* Separable: the local data, indexed per axis by q = 2 corner + derivative,
 * form a 4^dim tensor; the coefficients are that tensor with the 4x4 basis
 * matrix applied along every axis (3 * 64 * 4 products in 3D instead of
 * 64 * 64 * 3). */
void dfl_pht_cell_poly(int dim, const double *lo, const double *hi, const double *corner,
                       double *coef)
{
    int nd = DFL_PHT_NDATA(dim), nc = DFL_PHT_NCOEF(dim), ncor = 1 << dim;
    double h[3] = {1, 1, 1}, T[64];
    for (int j = 0; j < dim; j++) h[j] = hi[j] - lo[j];
    for (int c = 0; c < ncor; c++)
        for (int b = 0; b < nd; b++) {
            double D = corner[c * nd + b];
            int q = 0;
            for (int j = 0; j < dim; j++) {
                if (b >> j & 1) D *= h[j];
                q += (2 * ((c >> j) & 1) + ((b >> j) & 1)) << (2 * j);
            }
            coef[q] = D;
        }
    for (int j = 0; j < dim; j++) {
        int st = 1 << (2 * j);
        for (int k = 0; k < nc; k++) {
            if ((k >> (2 * j)) & 3) continue;
            for (int i = 0; i < 4; i++) {
                double acc = 0.0;
                for (int q = 0; q < 4; q++) acc += HB[q][i] * coef[k + q * st];
                T[k + i * st] = acc;
            }
        }
        memcpy(coef, T, (size_t)nc * sizeof *coef);
    }
}

static size_t grid_size(const dfl_pht_spline *s)
{
    size_t n = 1;
    for (int j = 0; j < s->dim; j++) n *= (size_t)s->gn;
    return n;
}

/* The node a grid cell starts from: descend with the cell's centre while
 * no split plane of the node cuts the cell's interior. */
static int64_t grid_cell_node(const dfl_pht_spline *s, const double *glo, const double *ghi)
{
    int64_t id = 0;
    double c[3];
    for (int j = 0; j < s->dim; j++) c[j] = 0.5 * (glo[j] + ghi[j]);
    while (s->node[id].child >= 0) {
        const snode *q = &s->node[id];
        int idx = 0;
        for (int j = 0; j < s->dim; j++) {
            if (q->axis >= 0 && q->axis != j) continue;
            if (q->mid[j] > glo[j] && q->mid[j] < ghi[j]) return id;
            if (c[j] >= q->mid[j]) idx |= q->axis >= 0 ? 1 : 1 << j;
        }
        id = q->child + idx;
    }
    return id;
}

/* gbits: 7 in 2D (16 k entries), 5 in 3D (32 k), fewer for shallow trees. */
static int build_grid(dfl_pht_spline *s, int depth)
{
    int gbits = depth < (s->dim == 2 ? 7 : 5) ? depth : (s->dim == 2 ? 7 : 5);
    s->gn = 1 << gbits;
    int gn = s->gn;
    s->gline = malloc((size_t)s->dim * (size_t)(gn + 1) * sizeof *s->gline);
    s->gnode = malloc(grid_size(s) * sizeof *s->gnode);
    if (!s->gline || !s->gnode) return -1;
    for (int j = 0; j < s->dim; j++) {
        s->ginv[j] = gn / (s->hi[j] - s->lo[j]);
        for (int k = 0; k <= gn; k++) {
            s->gline[j * (gn + 1) + k] =
                k == gn ? s->hi[j] : s->lo[j] + (s->hi[j] - s->lo[j]) * ((double)k / gn);
            /* grid_index_block recomputes the lines with this product */
            assert((double)k / gn == (double)k * (1.0 / gn));
        }
    }
    for (size_t g = 0; g < grid_size(s); g++) {
        double glo[3], ghi[3];
        size_t r = g;
        for (int j = 0; j < s->dim; j++) {
            size_t i = r % (size_t)gn;
            r /= (size_t)gn;
            glo[j] = s->gline[j * (gn + 1) + (int)i];
            ghi[j] = s->gline[j * (gn + 1) + (int)i + 1];
        }
        s->gnode[g] = grid_cell_node(s, glo, ghi);
    }
    return 0;
}

dfl_status dfl_pht_spline_new(const dfl_tmesh *m, const double *data, dfl_pht_spline **out,
                              dfl_err *err)
{
    int dim = dfl_tmesh_dim(m), nd = DFL_PHT_NDATA(dim), nc = DFL_PHT_NCOEF(dim);
    dfl_pht_spline *s = calloc(1, sizeof *s);
    size_t nnode = dfl_tmesh_ncells(m), ncell = dfl_tmesh_nleaves(m);
    const size_t *leaves = dfl_tmesh_leaves(m);
    int64_t *leaf_of = s ? malloc(nnode * sizeof *leaf_of) : NULL;
    if (s) {
        s->dim = dim;
        s->nc = nc;
        s->ncell = ncell;
        s->nnode = nnode;
        s->nbase = dfl_tmesh_nbase(m);
        s->stride = (size_t)(2 * dim + nc);
        s->node = malloc(nnode * sizeof *s->node);
        s->cell = malloc(ncell * s->stride * sizeof *s->cell);
        s->level = malloc(ncell * sizeof *s->level);
        s->chi = malloc(ncell * (size_t)dim * sizeof *s->chi);
    }
    if (!s || !leaf_of || !s->node || !s->cell || !s->level || !s->chi) {
        free(leaf_of);
        dfl_pht_spline_free(s);
        return dfl_err_set(err, DFL_E_NOMEM, "PHT spline: out of memory");
    }
    for (int j = 0; j < dim; j++) {
        s->lo[j] = dfl_tmesh_lo(m)[j];
        s->hi[j] = dfl_tmesh_hi(m)[j];
    }
    for (size_t i = 0; i < nnode; i++) leaf_of[i] = -1;
    for (size_t i = 0; i < ncell; i++) leaf_of[leaves[i]] = (int64_t)i;
    for (size_t id = 0; id < nnode; id++) {
        dfl_tmesh_cell c;
        dfl_tmesh_cell_get(m, id, &c);
        snode *q = &s->node[id];
        memset(q, 0, sizeof *q);
        q->axis = c.split_axis;
        if (c.nchild == 0) {
            q->child = -leaf_of[id] - 1;
            continue;
        }
        q->child = (int64_t)c.child;
        /* the children's shared corner is the split position */
        dfl_tmesh_cell k;
        dfl_tmesh_cell_get(m, c.child, &k);
        for (int j = 0; j < dim; j++) q->mid[j] = k.hi[j];
    }
#pragma omp parallel for schedule(static) if (ncell > 4096)
    for (size_t i = 0; i < ncell; i++) {
        dfl_tmesh_cell c;
        dfl_tmesh_cell_get(m, leaves[i], &c);
        double *cell = s->cell + i * s->stride, corner[8 * DFL_PHT_NDATA_MAX];
        for (int j = 0; j < dim; j++) {
            cell[j] = c.lo[j];
            cell[dim + j] = 1.0 / (c.hi[j] - c.lo[j]);
            s->chi[i * (size_t)dim + (size_t)j] = c.hi[j];
        }
        for (int k = 0; k < (1 << dim); k++)
            memcpy(corner + k * nd, data + c.corner[k] * (size_t)nd, (size_t)nd * sizeof(double));
        dfl_pht_cell_poly(dim, c.lo, c.hi, corner, cell + 2 * dim);
        s->level[i] = c.level;
    }
    free(leaf_of);
    if (build_grid(s, dfl_tmesh_max_level(m)) != 0) {
        dfl_pht_spline_free(s);
        return dfl_err_set(err, DFL_E_NOMEM, "PHT spline: out of memory");
    }
    *out = s;
    return DFL_OK;
}

void dfl_pht_spline_free(dfl_pht_spline *s)
{
    if (!s) return;
    free(s->node);
    free(s->cell);
    free(s->level);
    free(s->chi);
    free(s->gline);
    free(s->gnode);
    free(s);
}

int dfl_pht_spline_dim(const dfl_pht_spline *s) { return s->dim; }
size_t dfl_pht_spline_ncells(const dfl_pht_spline *s) { return s->ncell; }
size_t dfl_pht_spline_nbase(const dfl_pht_spline *s) { return s->nbase; }
size_t dfl_pht_spline_dofs(const dfl_pht_spline *s)
{
    return s->nbase * (size_t)DFL_PHT_NDATA(s->dim);
}

size_t dfl_pht_spline_bytes(const dfl_pht_spline *s)
{
    return sizeof *s + s->nnode * sizeof *s->node +
           s->ncell * (s->stride * sizeof *s->cell + sizeof *s->level +
                       (size_t)s->dim * sizeof *s->chi) +
           (size_t)s->dim * (size_t)(s->gn + 1) * sizeof *s->gline +
           grid_size(s) * sizeof *s->gnode;
}

void dfl_pht_spline_box(const dfl_pht_spline *s, double *lo, double *hi)
{
    for (int j = 0; j < s->dim; j++) {
        lo[j] = s->lo[j];
        hi[j] = s->hi[j];
    }
}

static inline size_t locate(const dfl_pht_spline *s, const double *x, const double *dir)
{
    const snode *nd = s->node;
    int64_t id = 0;
    while (nd[id].child >= 0) {
        const snode *q = &nd[id];
        int idx = 0;
        if (q->axis >= 0) {
            int a = q->axis;
            idx = x[a] > q->mid[a] || (x[a] == q->mid[a] && !(dir && dir[a] < 0));
        } else {
            for (int j = 0; j < s->dim; j++)
                if (x[j] > q->mid[j] || (x[j] == q->mid[j] && !(dir && dir[j] < 0)))
                    idx |= 1 << j;
        }
        id = q->child + idx;
    }
    return (size_t)(-nd[id].child - 1);
}

size_t dfl_pht_spline_locate(const dfl_pht_spline *s, const double *x, const double *dir)
{
    return locate(s, x, dir);
}

const double *dfl_pht_spline_cell(const dfl_pht_spline *s, size_t i, double *lo, double *hi,
                                  int *level)
{
    assert(i < s->ncell);
    const double *c = s->cell + i * s->stride;
    for (int j = 0; j < s->dim; j++) {
        if (lo) lo[j] = c[j];
        if (hi) hi[j] = s->chi[i * (size_t)s->dim + (size_t)j];
    }
    if (level) *level = s->level[i];
    return c + 2 * s->dim;
}

#define H3(c, t) (((c)[3] * (t) + (c)[2]) * (t) + (c)[1]) * (t) + (c)[0]
#define D3(c, t) (3 * (c)[3] * (t) + 2 * (c)[2]) * (t) + (c)[1]
#define DD3(c, t) 6 * (c)[3] * (t) + 2 * (c)[2]

DFL_ISA_BODY void eval2(const double *cell, const double *x, double *val, double *g, double *H)
{
    const double *c = cell + 4, *ih = cell + 2;
    double u = (x[0] - cell[0]) * ih[0], v = (x[1] - cell[1]) * ih[1];
    double r[4], rp[4], rpp[4];
    for (int j = 0; j < 4; j++) {
        r[j] = H3(c + 4 * j, u);
        rp[j] = D3(c + 4 * j, u);
        rpp[j] = DD3(c + 4 * j, u);
    }
    if (val) *val = H3(r, v);
    if (g) {
        g[0] = (H3(rp, v)) * ih[0];
        g[1] = (D3(r, v)) * ih[1];
    }
    if (H) {
        H[0] = (H3(rpp, v)) * ih[0] * ih[0];
        H[1] = H[2] = (D3(rp, v)) * ih[0] * ih[1];
        H[3] = (DD3(r, v)) * ih[1] * ih[1];
    }
}

DFL_ISA_BODY void eval3(const double *cell, const double *x, double *val, double *g, double *H)
{
    const double *c = cell + 6, *ih = cell + 3;
    double u = (x[0] - cell[0]) * ih[0], v = (x[1] - cell[1]) * ih[1],
           w = (x[2] - cell[2]) * ih[2];
    double r0[16], r1[16], r2[16];
    for (int jk = 0; jk < 16; jk++) {
        r0[jk] = H3(c + 4 * jk, u);
        r1[jk] = D3(c + 4 * jk, u);
        r2[jk] = DD3(c + 4 * jk, u);
    }
    double s00[4], s01[4], s02[4], s10[4], s11[4], s20[4];
    for (int k = 0; k < 4; k++) {
        s00[k] = H3(r0 + 4 * k, v);
        s01[k] = D3(r0 + 4 * k, v);
        s02[k] = DD3(r0 + 4 * k, v);
        s10[k] = H3(r1 + 4 * k, v);
        s11[k] = D3(r1 + 4 * k, v);
        s20[k] = H3(r2 + 4 * k, v);
    }
    if (val) *val = H3(s00, w);
    if (g) {
        g[0] = (H3(s10, w)) * ih[0];
        g[1] = (H3(s01, w)) * ih[1];
        g[2] = (D3(s00, w)) * ih[2];
    }
    if (H) {
        H[0] = (H3(s20, w)) * ih[0] * ih[0];
        H[4] = (H3(s02, w)) * ih[1] * ih[1];
        H[8] = (DD3(s00, w)) * ih[2] * ih[2];
        H[1] = H[3] = (H3(s11, w)) * ih[0] * ih[1];
        H[2] = H[6] = (D3(s10, w)) * ih[0] * ih[2];
        H[5] = H[7] = (D3(s01, w)) * ih[1] * ih[2];
    }
}

/* Value and gradient without the Hessian's terms: the operations of eval2
 * and eval3 for val and g, in the same order (the same bytes), with the
 * second-derivative rows (rpp; r2, s02, s11, s20) left out. */
DFL_ISA_BODY void eval2_vg(const double *cell, const double *x, double *val, double *g)
{
    const double *c = cell + 4, *ih = cell + 2;
    double u = (x[0] - cell[0]) * ih[0], v = (x[1] - cell[1]) * ih[1];
    double r[4], rp[4];
    for (int j = 0; j < 4; j++) {
        r[j] = H3(c + 4 * j, u);
        rp[j] = D3(c + 4 * j, u);
    }
    *val = H3(r, v);
    g[0] = (H3(rp, v)) * ih[0];
    g[1] = (D3(r, v)) * ih[1];
}

DFL_ISA_BODY void eval3_vg(const double *cell, const double *x, double *val, double *g)
{
    const double *c = cell + 6, *ih = cell + 3;
    double u = (x[0] - cell[0]) * ih[0], v = (x[1] - cell[1]) * ih[1],
           w = (x[2] - cell[2]) * ih[2];
    double r0[16], r1[16];
    for (int jk = 0; jk < 16; jk++) {
        r0[jk] = H3(c + 4 * jk, u);
        r1[jk] = D3(c + 4 * jk, u);
    }
    double s00[4], s01[4], s10[4];
    for (int k = 0; k < 4; k++) {
        s00[k] = H3(r0 + 4 * k, v);
        s01[k] = D3(r0 + 4 * k, v);
        s10[k] = H3(r1 + 4 * k, v);
    }
    *val = H3(s00, w);
    g[0] = (H3(s10, w)) * ih[0];
    g[1] = (H3(s01, w)) * ih[1];
    g[2] = (D3(s00, w)) * ih[2];
}

/* Points per block of the value + gradient loop: located together, so that
 * the cache misses of their tree descents and coefficient rows overlap
 * (the 3D splines of the studies are tens of MB: a random point's cell is
 * a miss). */
#define EVAL_BLOCK 32

/* Rows of at most this many bytes in all stay in a core's L2 cache once
 * read: their prefetches (3 to 10 per point) would only cost issue slots. */
#define ROWS_CACHED (256u << 10)

/* The location grid's cells of the EVAL_BLOCK points X[j][k] (coordinate
 * j of point k; dim is the spline's, a constant where inlined) into
 * gidx[k]: index arithmetic, corrected against the grid lines so that it
 * agrees with the tree's comparisons.  Written for the vectorizer (a loop
 * over the points with no branch: comparisons as 0/1, selects as masks),
 * the same integers as the per-point rule
 *     i = t >= 0 ? (t < gn ? (int)t : gn - 1) : 0   (t = (x - lo) / cell width; NaN: 0)
 *     i - 1 if x < line i (i > 0), else i + 1 if x >= line i + 1 (i < gn - 1).
 * Line k is recomputed as build_grid computes it, lo + (hi - lo) * (k / gn),
 * with k / gn = k * (1 / gn) exactly (gn is a power of two). */
DFL_ISA_BODY void grid_index_block(const dfl_pht_spline *s, const int dim,
                                   const double (*X)[EVAL_BLOCK], int *gidx)
{
    const int gn = s->gn;
    const double gnd = gn, ign = 1.0 / gnd;
    for (int k = 0; k < EVAL_BLOCK; k++) gidx[k] = 0;
    for (int j = 0, mul = 1; j < dim; j++, mul *= gn) {
        const double lo = s->lo[j], span = s->hi[j] - s->lo[j], ginv = s->ginv[j];
        for (int k = 0; k < EVAL_BLOCK; k++) {
            const double x = X[j][k], t = (x - lo) * ginv;
            const int ge0 = t >= 0.0, ltn = t < gnd;
            int i = (int)(ge0 & ltn ? t : 0.0);
            i = (i & -ltn) | ((gn - 1) & (ltn - 1)); /* t >= gn: gn - 1 */
            i &= -ge0;                               /* t < 0, NaN: 0 */
            const double Li = lo + span * ((double)i * ign),
                         Li1 = lo + span * ((double)(i + 1) * ign);
            const int dn = (i > 0) & (x < Li);
            const int up = !dn & (i < gn - 1) & (x >= Li1);
            gidx[k] += (i + up - dn) * mul;
        }
    }
}

/* Location for evaluation of n <= EVAL_BLOCK points (ties to the high
 * side, like locate without a direction): each point starts at its grid
 * cell's node and descends with branch-free child selection; the points
 * descend level by level together, so that the misses on the nodes they
 * read next (prefetched) overlap.  cells[k] gets point k's row (cell lo,
 * 1/h, coefficients), whose cache lines are prefetched too unless all rows
 * fit in ROWS_CACHED. */
DFL_ISA_BODY void locate_block(const dfl_pht_spline *s, const int dim, size_t n,
                               const double *pts, const double **cells)
{
    const snode *nd = s->node;
    int64_t id[EVAL_BLOCK];
    double X[3][EVAL_BLOCK];
    int gidx[EVAL_BLOCK];
    for (size_t k = 0; k < EVAL_BLOCK; k++) {
        const double *x = pts + (k < n ? k : n - 1) * (size_t)dim; /* past n: a copy */
        for (int j = 0; j < dim; j++) X[j][k] = x[j];
    }
    grid_index_block(s, dim, (const double(*)[EVAL_BLOCK])X, gidx);
    for (size_t k = 0; k < n; k++) {
        id[k] = s->gnode[gidx[k]];
        __builtin_prefetch(&nd[id[k]]);
    }
    for (int more = 1; more;) {
        more = 0;
        for (size_t k = 0; k < n; k++) {
            const snode *q = &nd[id[k]];
            if (q->child < 0) continue;
            const double *x = pts + k * (size_t)dim;
            int idx;
            if (q->axis >= 0) {
                idx = x[q->axis] >= q->mid[q->axis];
            } else {
                idx = (x[0] >= q->mid[0]) | ((x[1] >= q->mid[1]) << 1);
                if (dim == 3) idx |= (x[2] >= q->mid[2]) << 2;
            }
            id[k] = q->child + idx;
            __builtin_prefetch(&nd[id[k]]);
            more = 1;
        }
    }
    const size_t bytes = (size_t)(2 * dim + DFL_PHT_NCOEF(dim)) * sizeof(double);
    assert(bytes == s->stride * sizeof(double));
    for (size_t k = 0; k < n; k++)
        cells[k] = s->cell + (size_t)(-nd[id[k]].child - 1) * s->stride;
    if (s->ncell * bytes <= ROWS_CACHED) return;
    for (size_t k = 0; k < n; k++) {
        const char *b = (const char *)cells[k];
        for (size_t off = 0; off < bytes; off += 64) __builtin_prefetch(b + off);
        __builtin_prefetch(b + bytes - 1);
    }
}

/* The evaluation loop, compiled per ISA (core/isa.h): same bytes on each.
 * Points go in located blocks, software-pipelined: block b + 1 is located
 * (and its rows prefetched) before block b is evaluated.  Value + gradient
 * (the field adapter's call) skips the Hessian's terms.  d is the
 * spline's dimension, a constant in each of the two copies
 * eval_points_body makes (the loops over axes unroll). */
DFL_ISA_BODY void eval_points_dim(const dfl_pht_spline *s, const int d, size_t m,
                                  const double *pts, double *val, double *grad, double *hess)
{
    const int vg = val && grad && !hess;
    const double *cells[2][EVAL_BLOCK];
    if (m) locate_block(s, d, m < EVAL_BLOCK ? m : EVAL_BLOCK, pts, cells[0]);
    for (size_t i0 = 0, b = 0; i0 < m; i0 += EVAL_BLOCK, b ^= 1) {
        const size_t n = m - i0 < EVAL_BLOCK ? m - i0 : EVAL_BLOCK, i1 = i0 + n;
        if (i1 < m)
            locate_block(s, d, m - i1 < EVAL_BLOCK ? m - i1 : EVAL_BLOCK, pts + i1 * (size_t)d,
                         cells[b ^ 1]);
        const double *const *cl = cells[b];
        if (vg && d == 2) {
            for (size_t k = 0, i = i0; k < n; k++, i++)
                eval2_vg(cl[k], pts + 2 * i, val + i, grad + 2 * i);
        } else if (vg) {
            for (size_t k = 0, i = i0; k < n; k++, i++)
                eval3_vg(cl[k], pts + 3 * i, val + i, grad + 3 * i);
        } else {
            for (size_t k = 0, i = i0; k < n; k++, i++) {
                const double *x = pts + i * (size_t)d;
                double *v = val ? val + i : NULL, *g = grad ? grad + i * (size_t)d : NULL,
                       *H = hess ? hess + i * (size_t)(d * d) : NULL;
                if (d == 2) eval2(cl[k], x, v, g, H);
                else eval3(cl[k], x, v, g, H);
            }
        }
    }
}
DFL_ISA_BODY void eval_points_body(const dfl_pht_spline *s, size_t m, const double *pts,
                                   double *val, double *grad, double *hess)
{
    if (s->dim == 2) eval_points_dim(s, 2, m, pts, val, grad, hess);
    else eval_points_dim(s, 3, m, pts, val, grad, hess);
}
DFL_ISA_KERNEL(eval_points,
               (const dfl_pht_spline *s, size_t m, const double *pts, double *val,
                double *grad, double *hess),
               (s, m, pts, val, grad, hess))

void dfl_pht_eval(const dfl_pht_spline *s, size_t m, const double *pts, double *val,
                  double *grad, double *hess)
{
    eval_points(s, m, pts, val, grad, hess);
}

void dfl_pht_eval_cell(const dfl_pht_spline *s, size_t ci, size_t m, const double *pts,
                       double *val, double *grad, double *hess)
{
    assert(ci < s->ncell);
    const int d = s->dim;
    const double *cell = s->cell + ci * s->stride;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + i * (size_t)d;
        double *v = val ? val + i : NULL, *g = grad ? grad + i * (size_t)d : NULL,
               *H = hess ? hess + i * (size_t)(d * d) : NULL;
        if (d == 2) eval2(cell, x, v, g, H);
        else eval3(cell, x, v, g, H);
    }
}

/* out = a * b for polynomials in t (coefficient arrays, lowest degree
 * first, na and nb coefficients): writes and returns na + nb - 1 of them. */
static int poly_mul(const double *a, int na, const double *b, int nb, double *out)
{
    for (int k = 0; k < na + nb - 1; k++) out[k] = 0.0;
    for (int i = 0; i < na; i++)
        for (int j = 0; j < nb; j++) out[i + j] += a[i] * b[j];
    return na + nb - 1;
}

dfl_status dfl_pht_jet(const void *spline, const double *x, const double *dir, int K,
                       dfl_jet *out, dfl_err *err)
{
    const dfl_pht_spline *s = spline;
    dfl_status st = dfl_jet_check_order(K, err);
    if (st != DFL_OK) return st;
    const int d = s->dim;
    const double *cell = s->cell + locate(s, x, dir) * s->stride;
    const double *coef = cell + 2 * d;
    /* pw[j][e] = coefficients of (u0_j + a_j t)^e, e = 0..3 (e + 1 terms) */
    double pw[3][4][4];
    for (int j = 0; j < d; j++) {
        double u0 = (x[j] - cell[j]) * cell[d + j], a = dir[j] * cell[d + j];
        double lin[2] = {u0, a};
        pw[j][0][0] = 1.0;
        for (int e = 1; e < 4; e++) poly_mul(pw[j][e - 1], e, lin, 2, pw[j][e]);
    }
    double acc[10] = {0};
    int nc = DFL_PHT_NCOEF(d);
    for (int k = 0; k < nc; k++) {
        if (coef[k] == 0.0) continue;
        double t1[8], t2[10];
        int e0 = k & 3, e1 = (k >> 2) & 3, n = poly_mul(pw[0][e0], e0 + 1, pw[1][e1], e1 + 1, t1);
        const double *t = t1;
        if (d == 3) {
            int e2 = (k >> 4) & 3;
            n = poly_mul(t1, n, pw[2][e2], e2 + 1, t2);
            t = t2;
        }
        for (int q = 0; q < n; q++) acc[q] += coef[k] * t[q];
    }
    dfl_jet_poly(acc, 3 * d + 1, K, out);
    return DFL_OK;
}
