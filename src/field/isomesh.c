#include "field/isomesh.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/vec.h"
#include "field/isoline.h"
#include "geom/implicit.h"

static int zero_area(const double *a, const double *b, const double *c)
{
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3];
    dfl_vec3_cross(e1, e2, n);
    return !(dfl_vec3_norm(n) > 0.0);
}

dfl_status dfl_field_isomesh(const dfl_field *f, const dfl_grid *g, int refine, int threads,
                             dfl_trimesh *out, size_t *dropped, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    if (f->dim != 3) return dfl_err_set(err, DFL_E_INPUT, "isomesh: the field is not 3D");
    dfl_status st = dfl_grid_check(g, err);
    if (st != DFL_OK) return st;
    const size_t nn = dfl_grid_size(g);
    double *val = malloc(nn * sizeof *val);
    if (!val) return dfl_err_set(err, DFL_E_NOMEM, "isomesh: out of memory");
    st = dfl_field_sample(f, g, threads, val, NULL, err);
    dfl_iso iso = {0};
    if (st == DFL_OK) st = dfl_iso_surface(g, val, 0.0, &iso, err);
    free(val);
    if (st == DFL_OK && refine > 0) st = dfl_iso_refine(&iso, f, 0.0, refine, err);
    if (st != DFL_OK) {
        dfl_iso_free(&iso);
        return st;
    }
    size_t *map = malloc((iso.npoints ? iso.npoints : 1) * sizeof *map);
    size_t *tris = malloc((iso.ntris ? iso.ntris : 1) * 3 * sizeof *tris);
    double *verts = malloc((iso.npoints ? iso.npoints : 1) * 3 * sizeof *verts);
    if (!map || !tris || !verts) {
        free(map), free(tris), free(verts);
        dfl_iso_free(&iso);
        return dfl_err_set(err, DFL_E_NOMEM, "isomesh: out of memory");
    }
    for (size_t i = 0; i < iso.npoints; i++) map[i] = SIZE_MAX;
    size_t nt = 0, nv = 0, drop = 0;
    for (size_t t = 0; t < iso.ntris; t++) {
        const size_t *T = iso.tris + 3 * t;
        if (zero_area(iso.points + 3 * T[0], iso.points + 3 * T[1], iso.points + 3 * T[2])) {
            drop++;
            continue;
        }
        for (int k = 0; k < 3; k++) {
            if (map[T[k]] == SIZE_MAX) {
                memcpy(verts + 3 * nv, iso.points + 3 * T[k], 3 * sizeof *verts);
                map[T[k]] = nv++;
            }
            tris[3 * nt + k] = map[T[k]];
        }
        nt++;
    }
    free(map);
    dfl_iso_free(&iso);
    if (nt == 0) {
        free(tris), free(verts);
        return dfl_err_set(err, DFL_E_INPUT, "isomesh: the level set f = 0 does not cross the grid");
    }
    out->nverts = nv;
    out->verts = verts;
    out->ntris = nt;
    out->tris = tris;
    if (dropped) *dropped = drop;
    return DFL_OK;
}

/* Borrowed views of a shape as a field (no ownership, nothing to free). */
static void implicit_g_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    for (size_t i = 0; i < m; i++)
        val[i] = dfl_implicit_g(ctx, pts + 3 * i, grad ? grad + 3 * i : NULL, NULL);
}

static void shape_view_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    dfl_shape_eval(ctx, m, pts, val, grad);
}

static const dfl_field_ops implicit_g_ops = {"implicit_g", implicit_g_eval, NULL, NULL, NULL};
static const dfl_field_ops shape_view_ops = {"shape", shape_view_eval, NULL, NULL, NULL};

dfl_status dfl_shape_isomesh(const dfl_shape *s, const dfl_grid *g, int refine, int threads,
                             dfl_trimesh *out, size_t *dropped, dfl_err *err)
{
    const dfl_implicit *imp = dfl_implicit_of_shape(s);
    dfl_field f = {s->dim, imp ? &implicit_g_ops : &shape_view_ops,
                   imp ? (void *)imp : (void *)s};
    return dfl_field_isomesh(&f, g, refine, threads, out, dropped, err);
}
