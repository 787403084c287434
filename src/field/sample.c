/* Chunks of CHUNK nodes: large enough that the per-chunk call through the
 * field's function pointer is noise, small enough that the coordinates fit
 * in a stack buffer (no allocation inside the parallel loop).  Section
 * planes are grids with a flat axis rather than a second sampler, so that a
 * plane's nodes, chunks and evaluation order are those of any grid. */
#include "field/sample.h"

#include <assert.h>
#include <math.h>
#include <omp.h>

#define CHUNK 256

dfl_status dfl_grid_check(const dfl_grid *g, dfl_err *err)
{
    if (g->dim != 2 && g->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "grid dimension %d (expected 2 or 3)", g->dim);
    int flat = -1;
    for (int d = 0; d < g->dim; d++) {
        if (g->dim == 3 && g->n[d] == 1) {
            if (flat >= 0)
                return dfl_err_set(err, DFL_E_INPUT,
                                   "grid: one node on axes %d and %d (a plane has one flat axis)",
                                   flat, d);
            if (!(g->lo[d] == g->hi[d]) || !isfinite(g->lo[d]))
                return dfl_err_set(err, DFL_E_INPUT,
                                   "grid: one node on axis %d needs finite lo == hi, not [%g, %g]",
                                   d, g->lo[d], g->hi[d]);
            flat = d;
            continue;
        }
        if (g->n[d] < 2)
            return dfl_err_set(err, DFL_E_INPUT, "grid: %d nodes on axis %d (expected >= 2)",
                               g->n[d], d);
        if (!(g->lo[d] < g->hi[d]) || !isfinite(g->lo[d]) || !isfinite(g->hi[d]))
            return dfl_err_set(err, DFL_E_INPUT, "grid: empty range [%g, %g] on axis %d",
                               g->lo[d], g->hi[d], d);
    }
    if (g->dim == 2 && g->n[2] != 1)
        return dfl_err_set(err, DFL_E_INPUT, "grid: 2D grid with n[2] = %d", g->n[2]);
    return DFL_OK;
}

void dfl_grid_plane(int axis, double at, const int n[2], const double lo[2], const double hi[2],
                    dfl_grid *out)
{
    assert(axis >= 0 && axis <= 2);
    const int a0 = axis == 0 ? 1 : 0, a1 = axis == 2 ? 1 : 2;
    out->dim = 3;
    out->n[axis] = 1;
    out->lo[axis] = out->hi[axis] = at;
    out->n[a0] = n[0];
    out->lo[a0] = lo[0];
    out->hi[a0] = hi[0];
    out->n[a1] = n[1];
    out->lo[a1] = lo[1];
    out->hi[a1] = hi[1];
}

int dfl_grid_flat_axis(const dfl_grid *g)
{
    if (g->dim != 3) return -1;
    for (int d = 0; d < 3; d++)
        if (g->n[d] == 1) return d;
    return -1;
}

size_t dfl_grid_size(const dfl_grid *g)
{
    return (size_t)g->n[0] * (size_t)g->n[1] * (size_t)(g->dim == 3 ? g->n[2] : 1);
}

double dfl_grid_spacing(const dfl_grid *g, int axis)
{
    if (g->n[axis] == 1) return 0.0;
    return (g->hi[axis] - g->lo[axis]) / (double)(g->n[axis] - 1);
}

void dfl_grid_node(const dfl_grid *g, size_t idx, double *x)
{
    size_t i = idx % (size_t)g->n[0];
    size_t rest = idx / (size_t)g->n[0];
    size_t j = rest % (size_t)g->n[1];
    size_t k = rest / (size_t)g->n[1];
    /* lo + i*h is not exact at i = n-1; interpolate so that the last node is hi */
    size_t ijk[3] = {i, j, k};
    for (int d = 0; d < g->dim; d++) {
        if (g->n[d] == 1) { /* a plane's flat axis */
            x[d] = g->lo[d];
            continue;
        }
        double t = (double)ijk[d] / (double)(g->n[d] - 1);
        x[d] = (1.0 - t) * g->lo[d] + t * g->hi[d];
    }
}

void dfl_grid_frame(const dfl_grid *g, int dims[3], double origin[3], double spacing[3])
{
    for (int d = 0; d < 3; d++) {
        const int in = d < g->dim;
        dims[d] = in ? g->n[d] : 1;
        origin[d] = in ? g->lo[d] : 0.0;
        spacing[d] = in && g->n[d] > 1 ? dfl_grid_spacing(g, d) : 1.0;
    }
}

dfl_status dfl_field_sample(const dfl_field *f, const dfl_grid *g, int threads, double *val,
                            double *grad, dfl_err *err)
{
    dfl_status st = dfl_grid_check(g, err);
    if (st != DFL_OK) return st;
    if (f->dim != g->dim)
        return dfl_err_set(err, DFL_E_INPUT, "field is %dD but the grid is %dD", f->dim, g->dim);
    const size_t total = dfl_grid_size(g);
    const size_t nchunks = (total + CHUNK - 1) / CHUNK;
    const int dim = g->dim;
    if (threads <= 0) threads = omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
    for (size_t c = 0; c < nchunks; c++) {
        double pts[CHUNK * 3];
        size_t start = c * CHUNK;
        size_t m = total - start < CHUNK ? total - start : CHUNK;
        for (size_t q = 0; q < m; q++) dfl_grid_node(g, start + q, pts + q * (size_t)dim);
        f->ops->eval(f->ctx, m, pts, val + start, grad ? grad + start * (size_t)dim : NULL);
    }
    return DFL_OK;
}
