#include "bs04/bs04_space_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/vtk.h"

void dfl_bs04_gradstat(size_t m, int dim, const double *grad, const unsigned char *mask,
                       dfl_gradstat *out)
{
    size_t c = 0;
    double mn = INFINITY, mx = -INFINITY, s = 0;
    for (size_t i = 0; i < m; i++) {
        if (mask && !mask[i]) continue;
        double q = 0;
        const double *g = grad + i * (size_t)dim;
        for (int j = 0; j < dim; j++) q += g[j] * g[j];
        q = sqrt(q);
        mn = fmin(mn, q);
        mx = fmax(mx, q);
        s += q;
        c++;
    }
    out->count = c;
    out->min = c ? mn : NAN;
    out->max = c ? mx : NAN;
    out->mean = c ? s / (double)c : NAN;
}

dfl_status dfl_bs04_put_gradstat(dfl_table *t, const char *sfx, const dfl_gradstat *g,
                                 dfl_err *err)
{
    char col[96];
    dfl_status st;
    snprintf(col, sizeof col, "grad_min%s", sfx);
    st = dfl_table_set_double(t, col, g->min, err);
    snprintf(col, sizeof col, "grad_mean%s", sfx);
    if (st == DFL_OK) st = dfl_table_set_double(t, col, g->mean, err);
    snprintf(col, sizeof col, "grad_max%s", sfx);
    if (st == DFL_OK) st = dfl_table_set_double(t, col, g->max, err);
    return st;
}

double dfl_bs04_loglog_slope(size_t n, const double *x, const double *y)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < n; i++) {
        const double lx = log(x[i]), ly = log(y[i]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    const double dn = (double)n;
    return (dn * sxy - sx * sy) / (dn * sxx - sx * sx);
}

static double *to3d(int dim, size_t n, const double *pts)
{
    double *p3 = malloc((n ? n : 1) * 3 * sizeof *p3);
    if (!p3) return NULL;
    for (size_t i = 0; i < n; i++)
        for (int j = 0; j < 3; j++)
            p3[3 * i + (size_t)j] = j < dim ? pts[i * (size_t)dim + (size_t)j] : 0.0;
    return p3;
}

dfl_status dfl_bs04_vtp_polyline(const char *path, int dim, size_t n, const double *pts,
                                 const dfl_vtk_array *arr, int compress, dfl_err *err)
{
    double *p3 = to3d(dim, n, pts);
    size_t *conn = malloc((n ? n : 1) * sizeof *conn);
    if (!p3 || !conn) {
        free(p3);
        free(conn);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory writing %s", path);
    }
    for (size_t i = 0; i < n; i++) conn[i] = i;
    size_t off[2] = {0, n};
    dfl_vtp_data d = {n, p3, 1, off, conn, 0, NULL, arr, arr ? 1 : 0};
    dfl_status st = dfl_vtp_write(path, &d, compress, err);
    free(p3);
    free(conn);
    return st;
}

dfl_status dfl_bs04_vtp_trimesh(const char *path, size_t nv, const double *verts, size_t nt,
                                const size_t *tris, int compress, dfl_err *err)
{
    dfl_vtp_data d = {nv, verts, 0, NULL, NULL, nt, tris, NULL, 0};
    return dfl_vtp_write(path, &d, compress, err);
}

dfl_status dfl_bs04_vtp_points(const char *path, size_t n, const double *pts, const char *name,
                               const double *values, int compress, dfl_err *err)
{
    /* each point as a one-point polyline would clutter; VTK shows points
     * of PolyData without cells only with a glyph filter, so give them
     * vertex-like one-point lines */
    size_t *conn = malloc((n ? n : 1) * sizeof *conn), *off = malloc((n + 1) * sizeof *off);
    if (!conn || !off) {
        free(conn);
        free(off);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory writing %s", path);
    }
    off[0] = 0;
    for (size_t i = 0; i < n; i++) {
        conn[i] = i;
        off[i + 1] = i + 1;
    }
    dfl_vtk_array arr = {name, 1, values};
    dfl_vtp_data d = {n, pts, n, off, conn, 0, NULL, &arr, 1};
    dfl_status st = dfl_vtp_write(path, &d, compress, err);
    free(conn);
    free(off);
    return st;
}

dfl_status dfl_bs04_write_slices(const dfl_study_ctx *ctx, const dfl_field *f,
                                 const dfl_grid *slices, int n, const char *prefix,
                                 const dfl_field_write_opts *o, dfl_err *err)
{
    char stem[64];
    dfl_status st = DFL_OK;
    for (int s = 0; s < n && st == DFL_OK; s++) {
        const size_t m = dfl_grid_size(&slices[s]);
        double *u = malloc(m * sizeof *u), *gu = malloc(3 * m * sizeof *gu);
        if (!u || !gu) st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        if (!st) st = dfl_field_sample(f, &slices[s], ctx->threads, u, gu, err);
        snprintf(stem, sizeof stem, "%s%d", prefix, s);
        if (!st) st = dfl_field_out_write(ctx, stem, &slices[s], u, gu, NULL, o, err);
        free(u);
        free(gu);
    }
    return st;
}
