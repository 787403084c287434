/* bs04 Sec. 3.2.2 / Fig. 12: the approximate distance field of a
 * triangulated B-spline surface on a section plane.  The surface is
 * triangulated with certified maximum deviation eps (geom/polygonize.h),
 * every triangle gets the field of Sec. 3.2.1 (tri3d.h) and the fields are
 * joined by R-equivalence of order 2, as in the paper.
 *
 * On the plane the study separates the two error sources:
 *   d_S   exact distance to the surface (footpoints, geom/footpoint.h);
 *   d_M   exact distance to the triangulation (brute force over triangles);
 *   u     the R-function field.
 * |d_M - d_S| <= Hausdorff(surface, mesh) <= the certified bound (the
 * distance functions of two sets differ by at most their Hausdorff
 * distance), and u - d_M is the R-function construction's own error.
 *
 * Keys.  [field] kind = rfunc (cfg/rfunc_cfg.h; the field of Fig. 12, so
 * `dflab probe` evaluates it) with one part key:
 *   surface  = surface       section with kind = bspline_surface | bezier_surface
 *   eps      = 0.05          triangulation bound (> 0)
 *   max_tris = 200000        refuse larger triangulations
 *   join, p                  (default requiv, 2)
 *   tri_trim = conditional   prism | conditional; a = 0.2, k = 2; smooth = false
 * [study]:
 *   band     = 0.05          metrics also over d_S <= band
 *   slices, slice_n, slice_lo, slice_hi   section planes (cfg/slice_cfg.h)
 *   compress = true          [output] see field_out.h
 * Rows (one per eps): eps, triangles, vertices, bound, join, p, tri_trim, and
 * per slice k: metrics of u against d_S (suffix _s<k>, _s<k>_band), of u
 * against d_M (_s<k>_mesh), mesh_dev_max_s<k> = max |d_M - d_S|, |grad u| in
 * the band (grad_*_s<k>_band), u_le_dmesh_s<k> (fraction of samples with
 * u <= d_M (1 + 1e-12)).
 * Files: mesh<tag>.vtp, surface_slice<k><tag>.vti/.exr (error = u - d_S).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bs04/bs04_space_util.h"
#include "cfg/rfunc_cfg.h"
#include "cfg/curve_cfg.h"
#include "harness/experiment.h"
#include "field/exact.h"
#include "field/meshdist.h"
#include "field/metrics.h"
#include "geom/polygonize.h"
#include "rfunc/rfield.h"
#include "rfunc/tri3d.h"
#include "cfg/slice_cfg.h"
#include "harness/field_out.h"
#include "cfg/field_cost.h"

typedef struct keys {
    dfl_rfunc_field_spec spec; /* [field] (owned): the triangulation */
    const char *sec, *kind;
    double eps, band;
    dfl_rfunc_join join;
    int p;
    dfl_rfunc_tri_opts o;
    dfl_bs04_space_out so;
} keys;

static dfl_status read_keys(const dfl_cfg *cfg, keys *k, dfl_err *err)
{
    dfl_status st;
    memset(k, 0, sizeof *k);
    if ((st = dfl_rfunc_spec_from_kind_cfg(cfg, "field", "bs04_surface", &k->spec, err)))
        return st;
    const dfl_rfunc_field_spec *sp = &k->spec;
    if (!sp->surface || sp->n || sp->nregion || sp->npoints || dfl_cfg_has(cfg, "field", "triangles"))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: [field] of bs04_surface: expected one surface (surface = a"
                           " section), nothing else",
                           dfl_cfg_path(cfg));
    if ((st = dfl_rfunc_join_check(sp->join, sp->p, err)))
        return dfl_cfg_err_at(cfg, "field", "p", st, err);
    k->sec = sp->surface;
    if ((st = dfl_cfg_string(cfg, k->sec, "kind", &k->kind, err))) return st;
    k->eps = sp->eps;
    k->join = sp->join;
    k->p = sp->p;
    k->o = sp->tri;
    if ((st = dfl_cfg_double_opt(cfg, "study", "band", 0.05, 0.0, 1e300, &k->band, err))) return st;
    return dfl_bs04_space_out_from_cfg(cfg, true, &k->so, err);
}

static dfl_status do_slice(const keys *k, int s, const dfl_field *f, const dfl_field *exact,
                           const dfl_trimesh *M, const dfl_study_ctx *ctx, dfl_table *table,
                           dfl_err *err)
{
    const dfl_grid *sl = &k->so.slices[s];
    const size_t m = dfl_grid_size(sl);
    dfl_field_bufs b;
    double *dm = malloc(m * sizeof *dm);
    unsigned char *mask = malloc(m);
    char sfx[48], col[64], stem[64];
    dfl_status st = DFL_OK;
    if (!dfl_field_bufs_alloc(&b, m, 3, true) || !dm || !mask)
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    const double *u = b.u, *gu = b.gu, *ds = b.ref;
    if (!st) st = dfl_field_sample(f, sl, ctx->threads, b.u, b.gu, err);
    if (!st) st = dfl_field_sample(exact, sl, ctx->threads, b.ref, NULL, err);
    if (st) goto done;
    dfl_meshdist_sample(M, sl, ctx->threads, dm);
    dfl_metrics all, inb, mesh;
    st = dfl_metrics_compute(m, 3, u, gu, ds, 0.0, &all, err);
    if (!st) st = dfl_metrics_compute(m, 3, u, gu, ds, k->band, &inb, err);
    if (!st) st = dfl_metrics_compute(m, 3, u, gu, dm, 0.0, &mesh, err);
    if (st) goto done;
    double dev = 0;
    size_t le = 0;
    for (size_t i = 0; i < m; i++) {
        dev = fmax(dev, fabs(dm[i] - ds[i]));
        le += u[i] <= dm[i] * (1 + 1e-12);
        mask[i] = ds[i] <= k->band;
    }
    dfl_gradstat gs;
    dfl_metrics_gradstat(m, 3, gu, mask, &gs);
    snprintf(sfx, sizeof sfx, "_s%d", s);
    st = dfl_metrics_put(table, sfx, &all, err);
    snprintf(sfx, sizeof sfx, "_s%d_band", s);
    if (!st) st = dfl_metrics_put(table, sfx, &inb, err);
    if (!st) st = dfl_metrics_put_gradstat(table, sfx, &gs, err);
    snprintf(sfx, sizeof sfx, "_s%d_mesh", s);
    if (!st) st = dfl_metrics_put(table, sfx, &mesh, err);
    snprintf(col, sizeof col, "mesh_dev_max_s%d", s);
    if (!st) st = dfl_table_set_double(table, col, dev, err);
    snprintf(col, sizeof col, "u_le_dmesh_s%d", s);
    if (!st) st = dfl_table_set_double(table, col, (double)le / (double)m, err);
    snprintf(col, sizeof col, "slice%d", s);
    char desc[64];
    dfl_slice_label(sl, desc, sizeof desc);
    if (!st) st = dfl_table_set_string(table, col, desc, err);
    snprintf(stem, sizeof stem, "surface_slice%d", s);
    if (!st) st = dfl_field_out_write(ctx, stem, sl, u, gu, ds, &k->so.out, err);
done:
    dfl_field_bufs_free(&b);
    free(dm), free(mask);
    return st;
}

static dfl_status surf_run(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_table *table,
                           dfl_err *err)
{
    keys k;
    dfl_surface_set S = {0};
    dfl_shape sh = {0};
    dfl_field exact = {0}, f = {0};
    int haveS = 0;
    char path[4400];
    dfl_status st = read_keys(cfg, &k, err);
    const dfl_trimesh M = k.spec.mesh;
    if (!st) st = dfl_surface_from_cfg(cfg, k.sec, k.kind, &S, err);
    if (!st) haveS = 1;
    if (!st) st = dfl_param_shape_from_cfg(cfg, k.sec, k.kind, &sh, err);
    if (!st && (st = dfl_field_exact_new(&sh, &exact, err))) dfl_shape_free(&sh);
    if (!st) st = dfl_cfg_check_used(cfg, err);
    if (st) goto done;

    /* the field of [field]: its triangles in the triangulation's order */
    if ((st = dfl_rfunc_field_from_spec(cfg, "field", &k.spec, &f, err))) goto done;

    st = dfl_table_row(table, err);
    if (!st) st = dfl_table_set_double(table, "eps", k.eps, err);
    if (!st) st = dfl_table_set_int(table, "triangles", (long)M.ntris, err);
    if (!st) st = dfl_table_set_int(table, "vertices", (long)M.nverts, err);
    if (!st) st = dfl_table_set_double(table, "bound", M.bound, err);
    if (!st) st = dfl_table_set_string(table, "join", dfl_rfunc_join_name(k.join), err);
    if (!st) st = dfl_table_set_int(table, "p", k.p, err);
    if (!st)
        st = dfl_table_set_string(table, "tri_trim",
                                  dfl_rfunc_tri_trim_name(k.o.trim), err);
    if (!st) st = dfl_bs04_vtp_trimesh(dfl_study_path(ctx, "mesh", "vtp", path, sizeof path),
                                       M.nverts, M.verts, M.ntris, M.tris, k.so.compress, err);
    if (!st) st = dfl_study_put_file(table, "mesh_vtp", ctx, "mesh", "vtp", true, err);
    for (int s = 0; s < k.so.nslices && !st; s++)
        st = do_slice(&k, s, &f, &exact, &M, ctx, table, err);
done:
    dfl_field_destroy(&f);
    dfl_field_destroy(&exact);
    if (haveS) dfl_surface_set_free(&S);
    dfl_rfunc_spec_free(&k.spec);
    return st;
}

/* Peak memory: the field ([field]'s cost: at most max_tris triangles,
 * DFL_RFUNC_PART_BYTES each, the triangulation included) and one slice at
 * a time: u, grad u, d_S, d_M and the band mask (49 bytes a node) and the
 * writer's buffers.  Work per slice node: u (one CHEAP per triangle), d_M
 * (brute force, one CHEAP per triangle) and d_S (a footpoint on the
 * surface).  The keys are read without triangulating (read_keys does). */
static dfl_status surf_estimate(const dfl_cfg *cfg, const dfl_study_ctx *ctx, dfl_cost *c,
                                dfl_err *err)
{
    dfl_bs04_space_out so;
    double band, parts = 0;
    const char *key;
    memset(&so, 0, sizeof so);
    dfl_status st = dfl_study_estimate_default(cfg, ctx, c, err);
    if (!st && dfl_cfg_has(cfg, "field", "surface"))
        st = dfl_rfunc_parts_bound(cfg, "field", &parts, &key, err);
    if (!st) st = dfl_cfg_double_opt(cfg, "study", "band", 0.05, 0.0, 1e300, &band, err);
    if (!st) st = dfl_bs04_space_out_from_cfg(cfg, true, &so, err);
    if (st) return st;
    dfl_bs04_slices_cost(&so, DFL_COST_CHEAP, 2 * parts + DFL_RFUNC_EVAL_UNITS, DFL_COST_FOOTPOINT,
                         1, 17, c);
    return DFL_OK;
}

DFL_STUDY_DEFINE_ESTIMATED(bs04_surface, surf_run, surf_estimate,
                 "bs04 Fig. 12: field of a triangulated B-spline surface on a section plane");
