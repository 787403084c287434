#include "bs04/bs04_space_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/slice_cfg.h"
#include "io/vtk.h"

dfl_status dfl_bs04_space_out_from_cfg(const dfl_cfg *cfg, bool with_compress,
                                       dfl_bs04_space_out *o, dfl_err *err)
{
    dfl_status st = dfl_slices_from_cfg(cfg, "study", o->slices, DFL_BS04_MAX_SLICES,
                                        &o->nslices, err);
    if (st == DFL_OK && with_compress)
        st = dfl_cfg_bool_opt(cfg, "study", "compress", true, &o->compress, err);
    if (st == DFL_OK) st = dfl_field_out_from_cfg(cfg, &o->out, err);
    return st;
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
                                 const dfl_bs04_space_out *o, const char *prefix, dfl_err *err)
{
    char stem[64];
    dfl_status st = DFL_OK;
    for (int s = 0; s < o->nslices && st == DFL_OK; s++) {
        const dfl_grid *g = &o->slices[s];
        dfl_field_bufs b;
        if (!dfl_field_bufs_alloc(&b, dfl_grid_size(g), 3, false))
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        if (!st) st = dfl_field_sample(f, g, ctx->threads, b.u, b.gu, err);
        snprintf(stem, sizeof stem, "%s%d", prefix, s);
        if (!st) st = dfl_field_out_write(ctx, stem, g, b.u, b.gu, NULL, &o->out, err);
        dfl_field_bufs_free(&b);
    }
    return st;
}

void dfl_bs04_slices_cost(const dfl_bs04_space_out *o, dfl_cost_class cls, double units,
                          dfl_cost_class xcls, double extra, double extra_bytes, dfl_cost *c)
{
    double big = 0, all = 0;
    for (int s = 0; s < o->nslices; s++) {
        const double m = (double)dfl_grid_size(&o->slices[s]);
        big = fmax(big, m);
        all += m;
    }
    if (!o->nslices) return;
    dfl_cost_add_bytes(c, "study", "slice_n",
                       big * (32 + extra_bytes) + dfl_field_out_bytes(&o->out, big),
                       "section planes of %.3g nodes", big);
    dfl_cost_add_work(c, "study", "slice_n", cls, all * units, "%.3g slice nodes", all);
    dfl_cost_add_work(c, "study", "slice_n", DFL_COST_CHEAP, dfl_field_out_units(&o->out, all),
                      "the files of %.3g slice nodes", all);
    if (extra > 0)
        dfl_cost_add_work(c, "study", "slice_n", xcls, all * extra, "%.3g slice nodes", all);
}
