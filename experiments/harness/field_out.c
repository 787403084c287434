#include "harness/field_out.h"

#include <stdlib.h>

dfl_status dfl_field_out_from_cfg(const dfl_cfg *cfg, dfl_field_write_opts *o, dfl_err *err)
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

bool dfl_field_bufs_alloc(dfl_field_bufs *b, size_t m, int dim, bool with_ref)
{
    b->u = malloc(m * sizeof *b->u);
    b->gu = malloc((size_t)dim * m * sizeof *b->gu);
    b->ref = with_ref ? malloc(m * sizeof *b->ref) : NULL;
    return (b->u && b->gu && (!with_ref || b->ref)) || m == 0;
}

void dfl_field_bufs_free(dfl_field_bufs *b)
{
    free(b->u);
    free(b->gu);
    free(b->ref);
    b->u = b->gu = b->ref = NULL;
}

dfl_status dfl_field_out_write(const dfl_study_ctx *ctx, const char *stem, const dfl_grid *g,
                               const double *u, const double *gu, const double *ref,
                               const dfl_field_write_opts *o, dfl_err *err)
{
    char vti[4400], exr[4400];
    dfl_field_samples s = {.gdim = g->dim, .u = u, .gu = gu, .ref = ref};
    dfl_grid_frame(g, s.dims, s.origin, s.spacing);
    return dfl_field_write(dfl_study_path(ctx, stem, "vti", vti, sizeof vti),
                           dfl_study_path(ctx, stem, "exr", exr, sizeof exr), &s, o, err);
}
