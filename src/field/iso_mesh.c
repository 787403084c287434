/* Zero set of a field as a dfl_trimesh (iso_mesh.h): the marching-cubes
 * pipeline of field/isoline.h, repackaged for mesh consumers. */
#include "field/iso_mesh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "field/isoline.h"

dfl_status dfl_iso_trimesh(const dfl_field *f, const dfl_grid *g, int refine, int threads,
                           dfl_trimesh *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    dfl_status st = dfl_grid_check(g, err);
    if (st) return st;
    if (g->dim != 3 || f->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "iso mesh: expected a 3D field and grid");
    const size_t n = dfl_grid_size(g);
    double *v = malloc(n * sizeof *v);
    if (!v) return dfl_err_set(err, DFL_E_NOMEM, "iso mesh: out of memory");
    dfl_iso iso = {0};
    st = dfl_field_sample(f, g, threads, v, NULL, err);
    if (!st) st = dfl_iso_surface(g, v, 0.0, &iso, err);
    free(v);
    if (!st) st = dfl_iso_refine(&iso, f, 0.0, refine, err);
    if (st) {
        dfl_iso_free(&iso);
        return st;
    }
    out->verts = iso.points;   /* 3 * npoints, taken over */
    out->nverts = iso.npoints;
    out->tris = iso.tris;
    out->ntris = iso.ntris;
    out->bound = NAN;
    iso.points = NULL;
    iso.tris = NULL;
    dfl_iso_free(&iso);
    return DFL_OK;
}
