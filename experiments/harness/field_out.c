#include "harness/field_out.h"

#include <math.h>
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

double dfl_field_out_bytes(const dfl_field_write_opts *opts, double nodes)
{
    if (!opts->vti && !opts->exr) return 0;
    return 8.0 * (5 + 7) * nodes;
}

double dfl_field_out_units(const dfl_field_write_opts *opts, double nodes)
{
    return opts->vti || opts->exr ? 100 * nodes : 0;
}

dfl_status dfl_volume_opts_from_cfg(const dfl_cfg *cfg, long def_n, dfl_volume_opts *o,
                                    dfl_err *err)
{
    dfl_status st = dfl_cfg_bool_opt(cfg, "output", "vti", true, &o->vti, err);
    if (!st) st = dfl_cfg_int_opt(cfg, "output", "vti_n", def_n, 2, 1024, &o->n, err);
    if (!st) st = dfl_cfg_bool_opt(cfg, "output", "compress", true, &o->compress, err);
    return st;
}

/* value, gradient (3), reference; the writer's grad_norm and error; the
 * zlib copies of the largest array set (at most the raw size): 2 x 7
 * doubles per node, plus the cell arrays once and compressed once. */
double dfl_volume_bytes(long n, int ncell_arrays)
{
    const double nodes = (double)n * n * n, cells = (double)(n - 1) * (n - 1) * (n - 1);
    return 8.0 * (14 * nodes + 2 * ncell_arrays * cells);
}

void dfl_volume_grid(const double lo[3], const double hi[3], long n, dfl_grid *g)
{
    g->dim = 3;
    for (int a = 0; a < 3; a++) g->n[a] = (int)n, g->lo[a] = lo[a], g->hi[a] = hi[a];
}

dfl_status dfl_volume_write(const dfl_study_ctx *ctx, const char *stem, const dfl_field *f,
                            const dfl_field *ref, bool unsigned_ref, const dfl_grid *g,
                            const dfl_vtk_array *cells, int ncells, bool compress, dfl_err *err)
{
    const size_t m = dfl_grid_size(g);
    dfl_field_bufs b = {0};
    char path[4400];
    dfl_study_path(ctx, stem, "vti", path, sizeof path);
    if (!dfl_field_bufs_alloc(&b, m, 3, true)) {
        dfl_field_bufs_free(&b);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory sampling %s", path);
    }
    const int threads = ctx->threads > 0 ? ctx->threads : 1;
    dfl_status st = dfl_field_sample(f, g, threads, b.u, b.gu, err);
    if (!st) st = dfl_field_sample(ref, g, threads, b.ref, NULL, err);
    if (!st && unsigned_ref)
        for (size_t i = 0; i < m; i++) b.ref[i] = fabs(b.ref[i]);
    dfl_field_samples s = {.gdim = 3, .u = b.u, .gu = b.gu, .ref = b.ref, .cells = cells,
                           .ncells = ncells};
    dfl_grid_frame(g, s.dims, s.origin, s.spacing);
    if (!st) st = dfl_field_write_vti(path, &s, compress, err);
    dfl_field_bufs_free(&b);
    return st;
}
