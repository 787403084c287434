#include "harness/field_out.h"

#include <math.h>
#include <stdlib.h>

#include "io/exr.h"
#include "io/vtk.h"

dfl_status dfl_field_out_from_cfg(const dfl_cfg *cfg, dfl_field_out_opts *o, dfl_err *err)
{
    bool vti, exr, comp, half;
    dfl_status st = dfl_cfg_bool_opt(cfg, "output", "vti", true, &vti, err);
    if (st == DFL_OK) st = dfl_cfg_bool_opt(cfg, "output", "exr", true, &exr, err);
    if (st == DFL_OK) st = dfl_cfg_bool_opt(cfg, "output", "compress", true, &comp, err);
    if (st == DFL_OK) st = dfl_cfg_bool_opt(cfg, "output", "half", false, &half, err);
    if (st != DFL_OK) return st;
    o->vti = vti, o->exr = exr, o->compress = comp, o->half = half;
    return DFL_OK;
}

dfl_status dfl_field_out_write(const dfl_study_ctx *ctx, const char *stem, const dfl_grid *g,
                               const double *u, const double *gu, const double *ref,
                               const dfl_field_out_opts *o, dfl_err *err)
{
    const size_t m = dfl_grid_size(g);
    const int dim = g->dim;
    dfl_status st = DFL_OK;
    double *g3 = NULL, *gn = NULL, *er = NULL;
    float *fv = NULL, *fg = NULL, *fe = NULL;
    char path[4400];
    g3 = calloc(3 * m, sizeof *g3);
    gn = malloc(m * sizeof *gn);
    er = ref ? malloc(m * sizeof *er) : NULL;
    if (!g3 || !gn || (ref && !er)) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory writing %s", stem);
        goto done;
    }
    for (size_t i = 0; i < m; i++) {
        double s = 0;
        for (int d = 0; d < dim; d++) {
            double v = gu ? gu[i * (size_t)dim + d] : NAN;
            g3[3 * i + d] = v;
            s += v * v;
        }
        gn[i] = sqrt(s);
        if (er) er[i] = u[i] - ref[i];
    }
    if (o->vti) {
        dfl_vtk_array arr[5];
        int na = 0;
        arr[na++] = (dfl_vtk_array){"value", 1, u};
        if (gu) arr[na++] = (dfl_vtk_array){"gradient", 3, g3};
        if (gu) arr[na++] = (dfl_vtk_array){"grad_norm", 1, gn};
        if (ref) arr[na++] = (dfl_vtk_array){"error", 1, er};
        if (ref) arr[na++] = (dfl_vtk_array){"reference", 1, ref};
        int dims[3] = {g->n[0], g->n[1], dim == 3 ? g->n[2] : 1};
        double origin[3] = {g->lo[0], g->lo[1], dim == 3 ? g->lo[2] : 0};
        double sp[3] = {dfl_grid_spacing(g, 0), dfl_grid_spacing(g, 1),
                        dim == 3 ? dfl_grid_spacing(g, 2) : 1};
        st = dfl_vti_write(dfl_study_path(ctx, stem, "vti", path, sizeof path), dims, origin, sp,
                           arr, na, o->compress, err);
        if (st != DFL_OK) goto done;
    }
    if (o->exr) {
        const int w = g->n[0], h = g->n[1];
        const size_t k0 = dim == 3 ? (size_t)(g->n[2] / 2) : 0;
        const size_t pix = (size_t)w * (size_t)h;
        fv = malloc(pix * sizeof *fv);
        fg = malloc(pix * sizeof *fg);
        fe = malloc(pix * sizeof *fe);
        if (!fv || !fg || !fe) {
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory writing %s", stem);
            goto done;
        }
        for (int r = 0; r < h; r++) {
            size_t j = (size_t)(h - 1 - r);
            for (int i = 0; i < w; i++) {
                size_t idx = (size_t)i + (size_t)w * (j + (size_t)h * k0);
                size_t p = (size_t)r * (size_t)w + (size_t)i;
                fv[p] = (float)u[idx];
                fg[p] = (float)gn[idx];
                fe[p] = er ? (float)er[idx] : 0.0f;
            }
        }
        dfl_exr_channel ch[3] = {{"value", fv}, {"grad_norm", fg}, {"error", fe}};
        int nch = 1 + (gu ? 1 : 0);
        if (!gu) ch[1] = ch[2];
        if (er) nch++;
        if (!gu && !er) nch = 1;
        st = dfl_exr_write(dfl_study_path(ctx, stem, "exr", path, sizeof path), w, h, ch, nch,
                           o->half, err);
    }
done:
    free(g3), free(gn), free(er), free(fv), free(fg), free(fe);
    return st;
}
