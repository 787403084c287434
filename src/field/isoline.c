/* Marching squares / marching cubes (tetrahedral split) on sampled grids.
 *
 * Vertices are created once per grid (or tetrahedron) edge and found again
 * through that edge's key, which is what makes the output watertight and
 * the polyline assembly a walk over a graph of degree <= 2. */
#include "field/isoline.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NONE SIZE_MAX

typedef struct builder {
    dfl_iso *iso;
    size_t cap_pts, cap_tris;
} builder;

static dfl_status nomem(dfl_err *err)
{
    return dfl_err_set(err, DFL_E_NOMEM, "isoline: out of memory");
}

void dfl_iso_free(dfl_iso *iso)
{
    if (!iso) return;
    free(iso->points);
    free(iso->edge);
    free(iso->line_offsets);
    free(iso->line_conn);
    free(iso->tris);
    memset(iso, 0, sizeof *iso);
}

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 0;
    size_t c = *cap ? *cap : 256;
    while (c < need) c *= 2;
    void *q = realloc(*p, c * elem);
    if (!q) return -1;
    *p = q;
    *cap = c;
    return 0;
}

/* A new vertex on the edge from node a (below) to node b (above). */
static size_t add_vertex(builder *b, const dfl_grid *g, size_t na, size_t nb, double va,
                         double vb, double level)
{
    dfl_iso *iso = b->iso;
    size_t cap = b->cap_pts, cap2 = b->cap_pts;
    if (grow((void **)&iso->points, &cap, iso->npoints + 1, 3 * sizeof(double))) return NONE;
    if (grow((void **)&iso->edge, &cap2, iso->npoints + 1, 6 * sizeof(double))) return NONE;
    b->cap_pts = cap;
    double *e = iso->edge + 6 * iso->npoints, *p = iso->points + 3 * iso->npoints;
    memset(e, 0, 6 * sizeof *e);
    dfl_grid_node(g, na, e);
    dfl_grid_node(g, nb, e + 3);
    const double t = vb > va ? (level - va) / (vb - va) : 0.5;
    for (int j = 0; j < 3; j++) p[j] = e[j] + t * (e[3 + j] - e[j]);
    return iso->npoints++;
}

static void strides(const dfl_grid *g, size_t s[3])
{
    s[0] = 1;
    s[1] = (size_t)g->n[0];
    s[2] = (size_t)g->n[0] * (size_t)g->n[1];
}

static dfl_status check_values(const dfl_grid *g, const double *val, double level, dfl_err *err)
{
    if (!isfinite(level)) return dfl_err_set(err, DFL_E_INPUT, "isoline: level is not finite");
    const size_t m = dfl_grid_size(g);
    for (size_t i = 0; i < m; i++)
        if (!isfinite(val[i]))
            return dfl_err_set(err, DFL_E_INPUT, "isoline: value %zu is not finite", i);
    return DFL_OK;
}

/* Orders the edge (a, b) from below to above the level. */
static void orient_edge(size_t *na, size_t *nb, double *va, double *vb, double level)
{
    if (*va >= level) {
        const size_t tn = *na;
        const double tv = *va;
        *na = *nb, *nb = tn;
        *va = *vb, *vb = tv;
    }
}

/* Zeroes *out and checks the grid and the values. */
static dfl_status iso_begin(const dfl_grid *g, const double *val, double level, dfl_iso *out,
                            dfl_err *err)
{
    memset(out, 0, sizeof *out);
    dfl_status st = dfl_grid_check(g, err);
    return st ? st : check_values(g, val, level, err);
}

/* ---- marching squares ---- */

/* Segment table: for each corner case (bit c set when corner c is above;
 * corners c0 (i,j), c1 (i+1,j), c2 (i+1,j+1), c3 (i,j+1); edges e0 bottom,
 * e1 right, e2 top, e3 left), up to two segments as edge pairs.  Saddles
 * (5, 10) list the "centre below" split; the other one is chosen below. */
static const signed char MS_SEG[16][4] = {
    {-1, -1, -1, -1}, {3, 0, -1, -1}, {0, 1, -1, -1}, {3, 1, -1, -1},
    {1, 2, -1, -1},   {3, 0, 1, 2},   {0, 2, -1, -1}, {3, 2, -1, -1},
    {2, 3, -1, -1},   {0, 2, -1, -1}, {0, 1, 2, 3},   {1, 2, -1, -1},
    {3, 1, -1, -1},   {0, 1, -1, -1}, {3, 0, -1, -1}, {-1, -1, -1, -1},
};
/* centre above: the above corners connect, the below ones are cut off */
static const signed char MS_SADDLE_ABOVE[16][4] = {
    [5] = {0, 1, 2, 3},
    [10] = {3, 0, 1, 2},
};

typedef struct ms_grid {
    const dfl_grid *g;
    const double *val;
    double level;
    size_t st[3];
    int p, q;       /* active axes */
    size_t np, nq;
    size_t nh;      /* horizontal edges (along p) */
    size_t *vmap;   /* edge id -> vertex */
} ms_grid;

static size_t ms_node(const ms_grid *m, size_t i, size_t j)
{
    return i * m->st[m->p] + j * m->st[m->q];
}

/* Vertex of cell (i, j)'s edge e (0..3), created on first use. */
static size_t ms_edge_vertex(builder *b, ms_grid *m, size_t i, size_t j, int e)
{
    size_t id, na, nb;
    switch (e) {
    case 0: id = i + (m->np - 1) * j; na = ms_node(m, i, j); nb = ms_node(m, i + 1, j); break;
    case 1: id = m->nh + (i + 1) + m->np * j; na = ms_node(m, i + 1, j); nb = ms_node(m, i + 1, j + 1); break;
    case 2: id = i + (m->np - 1) * (j + 1); na = ms_node(m, i, j + 1); nb = ms_node(m, i + 1, j + 1); break;
    default: id = m->nh + i + m->np * j; na = ms_node(m, i, j); nb = ms_node(m, i, j + 1); break;
    }
    if (m->vmap[id] != NONE) return m->vmap[id];
    double va = m->val[na], vb = m->val[nb];
    orient_edge(&na, &nb, &va, &vb, m->level);
    return m->vmap[id] = add_vertex(b, m->g, na, nb, va, vb, m->level);
}

/* Joins the segments (pairs in seg) into polylines: open chains from their
 * degree-1 ends first, then cycles, each from its lowest vertex. */
static dfl_status assemble(dfl_iso *iso, const size_t *seg, size_t nseg, dfl_err *err)
{
    const size_t n = iso->npoints;
    size_t *nb = malloc((2 * n + 1) * sizeof *nb);
    unsigned char *seen = calloc(n + 1, 1);
    iso->line_offsets = malloc((nseg + 2) * sizeof *iso->line_offsets);
    iso->line_conn = malloc((3 * nseg + 2) * sizeof *iso->line_conn);
    if (!nb || !seen || !iso->line_offsets || !iso->line_conn) {
        free(nb);
        free(seen);
        return nomem(err);
    }
    for (size_t i = 0; i < 2 * n; i++) nb[i] = NONE;
    for (size_t s = 0; s < nseg; s++) {
        const size_t a = seg[2 * s], c = seg[2 * s + 1];
        if (a == c) continue;  /* both ends on one vertex cannot happen; kept safe */
        nb[2 * a + (nb[2 * a] != NONE)] = c;
        nb[2 * c + (nb[2 * c] != NONE)] = a;
    }
    size_t nconn = 0;
    iso->nlines = 0;
    iso->line_offsets[0] = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (size_t v0 = 0; v0 < n; v0++) {
            const int deg = (nb[2 * v0] != NONE) + (nb[2 * v0 + 1] != NONE);
            if (seen[v0] || deg == 0 || (pass == 0 && deg != 1)) continue;
            size_t prev = NONE, v = v0;
            while (v != NONE && !seen[v]) {
                seen[v] = 1;
                iso->line_conn[nconn++] = v;
                size_t nx = nb[2 * v] != prev ? nb[2 * v] : nb[2 * v + 1];
                if (nx == prev && nb[2 * v] == nb[2 * v + 1]) nx = NONE;
                prev = v;
                v = nx;
            }
            if (pass == 1) {  /* a cycle: close it */
                iso->line_conn[nconn++] = v0;
                iso->nclosed++;
            }
            iso->line_offsets[++iso->nlines] = nconn;
        }
    }
    free(nb);
    free(seen);
    return DFL_OK;
}

dfl_status dfl_iso_lines(const dfl_grid *g, const double *val, double level, dfl_iso *out,
                         dfl_err *err)
{
    dfl_status st = iso_begin(g, val, level, out, err);
    if (st) return st;
    const int flat = dfl_grid_flat_axis(g);
    if (g->dim == 3 && flat < 0)
        return dfl_err_set(err, DFL_E_INPUT, "isoline: marching squares needs a 2D or a plane grid");
    ms_grid m = {.g = g, .val = val, .level = level};
    strides(g, m.st);
    m.p = flat == 0 ? 1 : 0;
    m.q = flat == 2 || g->dim == 2 ? 1 : 2;
    if (flat == 1) m.q = 2;
    m.np = (size_t)g->n[m.p];
    m.nq = (size_t)g->n[m.q];
    m.nh = (m.np - 1) * m.nq;
    const size_t nedges = m.nh + m.np * (m.nq - 1);
    m.vmap = malloc(nedges * sizeof *m.vmap);
    size_t *seg = NULL, nseg = 0, capseg = 0;
    builder b = {.iso = out};
    if (!m.vmap) return nomem(err);
    for (size_t i = 0; i < nedges; i++) m.vmap[i] = NONE;
    for (size_t j = 0; j + 1 < m.nq && st == DFL_OK; j++)
        for (size_t i = 0; i + 1 < m.np; i++) {
            const double c[4] = {val[ms_node(&m, i, j)], val[ms_node(&m, i + 1, j)],
                                 val[ms_node(&m, i + 1, j + 1)], val[ms_node(&m, i, j + 1)]};
            int cs = 0;
            for (int k = 0; k < 4; k++) cs |= (c[k] >= level) << k;
            const signed char *tab = MS_SEG[cs];
            if ((cs == 5 || cs == 10) && (c[0] + c[1] + c[2] + c[3]) / 4.0 >= level)
                tab = MS_SADDLE_ABOVE[cs];
            for (int s = 0; s < 4 && tab[s] >= 0; s += 2) {
                if (grow((void **)&seg, &capseg, 2 * nseg + 2, sizeof *seg)) { st = nomem(err); break; }
                const size_t va = ms_edge_vertex(&b, &m, i, j, tab[s]);
                const size_t vb = ms_edge_vertex(&b, &m, i, j, tab[s + 1]);
                if (va == NONE || vb == NONE) { st = nomem(err); break; }
                seg[2 * nseg] = va;
                seg[2 * nseg + 1] = vb;
                nseg++;
            }
            if (st) break;
        }
    if (st == DFL_OK) st = assemble(out, seg, nseg, err);
    free(seg);
    free(m.vmap);
    if (st) dfl_iso_free(out);
    return st;
}

/* ---- marching cubes by tetrahedra ---- */

/* The 6 tetrahedra of a cube around its diagonal 0-7 (corner c = dx + 2 dy + 4 dz). */
static const int TETS[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7},
                               {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

typedef struct tri_key {
    uint64_t k[3];
} tri_key;

static uint64_t edge_key(size_t a, size_t b, size_t nodes)
{
    return a < b ? (uint64_t)a * nodes + b : (uint64_t)b * nodes + a;
}

static int cmp_u64(const void *x, const void *y)
{
    const uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return a < b ? -1 : a > b;
}

typedef struct mc_state {
    const dfl_grid *g;
    const double *val;
    double level;
    size_t nodes;
    tri_key *tk;
    size_t ntk, captk;
} mc_state;

static void node_xyz(const dfl_grid *g, size_t idx, double x[3])
{
    dfl_grid_node(g, idx, x);
}

/* Adds triangle (e1, e2, e3) of tetrahedron edges (pairs of nodes),
 * oriented from below node lo to above node hi. */
static int mc_tri(mc_state *s, const size_t e[3][2], size_t lo, size_t hi)
{
    if (grow((void **)&s->tk, &s->captk, s->ntk + 1, sizeof *s->tk)) return -1;
    double p[3][3], a[3], c[3];
    for (int v = 0; v < 3; v++) {
        size_t na = e[v][0], nb = e[v][1];
        double va = s->val[na], vb = s->val[nb], xa[3], xb[3];
        orient_edge(&na, &nb, &va, &vb, s->level);
        node_xyz(s->g, na, xa);
        node_xyz(s->g, nb, xb);
        const double t = vb > va ? (s->level - va) / (vb - va) : 0.5;
        for (int j = 0; j < 3; j++) p[v][j] = xa[j] + t * (xb[j] - xa[j]);
    }
    node_xyz(s->g, lo, a);
    node_xyz(s->g, hi, c);
    double u[3], w[3];
    for (int j = 0; j < 3; j++) { u[j] = p[1][j] - p[0][j]; w[j] = p[2][j] - p[0][j]; }
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2],
                         u[0] * w[1] - u[1] * w[0]};
    const double o = n[0] * (c[0] - a[0]) + n[1] * (c[1] - a[1]) + n[2] * (c[2] - a[2]);
    int order[3] = {0, 1, 2};
    if (o < 0) { order[1] = 2; order[2] = 1; }
    for (int v = 0; v < 3; v++)
        s->tk[s->ntk].k[v] = edge_key(e[order[v]][0], e[order[v]][1], s->nodes);
    s->ntk++;
    return 0;
}

static int mc_tet(mc_state *s, const size_t nd[4])
{
    size_t up[4], dn[4];
    int nu = 0, nd_ = 0;
    for (int v = 0; v < 4; v++) {
        if (s->val[nd[v]] >= s->level) up[nu++] = nd[v];
        else dn[nd_++] = nd[v];
    }
    if (nu == 0 || nu == 4) return 0;
    if (nu == 1 || nu == 3) {
        const size_t lone = nu == 1 ? up[0] : dn[0];
        const size_t *other = nu == 1 ? dn : up;
        const size_t e[3][2] = {{lone, other[0]}, {lone, other[1]}, {lone, other[2]}};
        return mc_tri(s, e, dn[0], up[0]);
    }
    /* quad a0b0, a0b1, a1b1, a1b0 (a above, b below), cyclic */
    const size_t e1[3][2] = {{up[0], dn[0]}, {up[0], dn[1]}, {up[1], dn[1]}};
    const size_t e2[3][2] = {{up[0], dn[0]}, {up[1], dn[1]}, {up[1], dn[0]}};
    if (mc_tri(s, e1, dn[0], up[0])) return -1;
    return mc_tri(s, e2, dn[0], up[0]);
}

static size_t key_index(const uint64_t *keys, size_t n, uint64_t k)
{
    size_t lo = 0, hi = n;
    while (lo < hi) {
        const size_t mid = lo + (hi - lo) / 2;
        if (keys[mid] < k) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

/* Vertices from the unique edge keys (sorted: deterministic order). */
static dfl_status mc_vertices(mc_state *s, dfl_iso *out, dfl_err *err)
{
    const size_t nk = 3 * s->ntk;
    uint64_t *keys = malloc((nk + 1) * sizeof *keys);
    if (!keys) return nomem(err);
    for (size_t t = 0; t < s->ntk; t++)
        for (int v = 0; v < 3; v++) keys[3 * t + v] = s->tk[t].k[v];
    qsort(keys, nk, sizeof *keys, cmp_u64);
    size_t nu = 0;
    for (size_t i = 0; i < nk; i++)
        if (nu == 0 || keys[i] != keys[nu - 1]) keys[nu++] = keys[i];
    builder b = {.iso = out};
    for (size_t i = 0; i < nu; i++) {
        size_t na = (size_t)(keys[i] / s->nodes), nb = (size_t)(keys[i] % s->nodes);
        double va = s->val[na], vb = s->val[nb];
        orient_edge(&na, &nb, &va, &vb, s->level);
        if (add_vertex(&b, s->g, na, nb, va, vb, s->level) == NONE) {
            free(keys);
            return nomem(err);
        }
    }
    out->tris = malloc((3 * s->ntk + 1) * sizeof *out->tris);
    if (!out->tris) {
        free(keys);
        return nomem(err);
    }
    for (size_t t = 0; t < s->ntk; t++)
        for (int v = 0; v < 3; v++) out->tris[3 * t + v] = key_index(keys, nu, s->tk[t].k[v]);
    out->ntris = s->ntk;
    free(keys);
    return DFL_OK;
}

dfl_status dfl_iso_surface(const dfl_grid *g, const double *val, double level, dfl_iso *out,
                           dfl_err *err)
{
    dfl_status st = iso_begin(g, val, level, out, err);
    if (st) return st;
    if (g->dim != 3 || dfl_grid_flat_axis(g) >= 0)
        return dfl_err_set(err, DFL_E_INPUT, "isosurface: marching cubes needs a 3D volume grid");
    mc_state s = {.g = g, .val = val, .level = level, .nodes = dfl_grid_size(g)};
    size_t sd[3];
    strides(g, sd);
    for (int k = 0; k + 1 < g->n[2]; k++)
        for (int j = 0; j + 1 < g->n[1]; j++)
            for (int i = 0; i + 1 < g->n[0]; i++) {
                const size_t base = (size_t)i + sd[1] * (size_t)j + sd[2] * (size_t)k;
                size_t corner[8];
                for (int c = 0; c < 8; c++)
                    corner[c] = base + (c & 1) * sd[0] + ((c >> 1) & 1) * sd[1] + (c >> 2) * sd[2];
                for (int t = 0; t < 6; t++) {
                    const size_t nd[4] = {corner[TETS[t][0]], corner[TETS[t][1]],
                                          corner[TETS[t][2]], corner[TETS[t][3]]};
                    if (mc_tet(&s, nd)) {
                        free(s.tk);
                        return nomem(err);
                    }
                }
            }
    st = mc_vertices(&s, out, err);
    free(s.tk);
    if (st) dfl_iso_free(out);
    return st;
}

/* ---- refinement ---- */

dfl_status dfl_iso_refine(dfl_iso *iso, const dfl_field *f, double level, int iters,
                          dfl_err *err)
{
    const size_t n = iso->npoints;
    const int dim = f->dim;
    if (dim != 2 && dim != 3) return dfl_err_set(err, DFL_E_INPUT, "isoline refine: field dim %d", dim);
    for (size_t i = 0; i < n && dim == 2; i++)
        if (iso->edge[6 * i + 2] != 0.0 || iso->edge[6 * i + 5] != 0.0)
            return dfl_err_set(err, DFL_E_INPUT, "isoline refine: a 2D field needs a 2D grid");
    if (n == 0) return DFL_OK;
    double *x = malloc(n * (size_t)dim * sizeof *x), *v = malloc(n * sizeof *v);
    double *t = malloc(5 * n * sizeof *t);
    signed char *last = calloc(n, 1);
    if (!x || !v || !t || !last) {
        free(x); free(v); free(t); free(last);
        return nomem(err);
    }
    double *tlo = t, *thi = t + n, *flo = t + 2 * n, *fhi = t + 3 * n, *side = t + 4 * n;
    /* bracket end values */
    for (int e = 0; e < 2; e++) {
        for (size_t i = 0; i < n; i++)
            for (int j = 0; j < dim; j++) x[i * dim + j] = iso->edge[6 * i + 3 * e + j];
        f->ops->eval(f->ctx, n, x, v, NULL);
        for (size_t i = 0; i < n; i++) (e ? fhi : flo)[i] = v[i] - level;
    }
    for (size_t i = 0; i < n; i++) {
        tlo[i] = 0.0;
        thi[i] = 1.0;
        side[i] = 0.0;
    }
    for (int it = 0; it < iters; it++) {
        for (size_t i = 0; i < n; i++) {
            const double *e = iso->edge + 6 * i;
            double tt = 0.5;
            if (flo[i] < 0.0 && fhi[i] >= 0.0) tt = tlo[i] + (thi[i] - tlo[i]) * (-flo[i]) / (fhi[i] - flo[i]);
            if (!(tt >= tlo[i] && tt <= thi[i])) tt = 0.5 * (tlo[i] + thi[i]);
            side[i] = tt;
            for (int j = 0; j < dim; j++) x[i * dim + j] = e[j] + tt * (e[3 + j] - e[j]);
        }
        f->ops->eval(f->ctx, n, x, v, NULL);
        for (size_t i = 0; i < n; i++) {
            if (!(flo[i] < 0.0 && fhi[i] >= 0.0)) continue;  /* no bracket: keep the estimate */
            const double fv = v[i] - level, tt = side[i];
            double *p = iso->points + 3 * i;
            for (int j = 0; j < dim; j++) p[j] = x[i * dim + j];
            /* Illinois: when the same end moves twice in a row, halve the
             * other end's value so the secant leaves it */
            if (fv < 0.0) {
                tlo[i] = tt;
                flo[i] = fv;
                if (last[i] < 0) fhi[i] *= 0.5;
                last[i] = -1;
            } else {
                thi[i] = tt;
                fhi[i] = fv;
                if (last[i] > 0) flo[i] *= 0.5;
                last[i] = 1;
            }
            if (fv == 0.0) { flo[i] = -0.0; fhi[i] = 0.0; tlo[i] = thi[i] = tt; }
        }
    }
    free(x); free(v); free(t); free(last);
    return DFL_OK;
}

void dfl_iso_vtp(const dfl_iso *iso, dfl_vtp_data *out)
{
    memset(out, 0, sizeof *out);
    out->npoints = iso->npoints;
    out->points = iso->points;
    out->nlines = iso->nlines;
    out->line_offsets = iso->nlines ? iso->line_offsets : NULL;
    out->line_conn = iso->line_conn;
    out->ntris = iso->ntris;
    out->tris = iso->tris;
}
