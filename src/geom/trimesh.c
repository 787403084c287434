#include "geom/trimesh.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/domain.h"
#include "core/vec.h"
#include "io/meshfile.h"

dfl_status dfl_trimesh_check(const dfl_trimesh *m, dfl_err *err)
{
    if (m->ntris == 0) return dfl_err_set(err, DFL_E_INPUT, "no triangles");
    for (size_t i = 0; i < 3 * m->nverts; i++)
        if (!(fabs(m->verts[i]) <= DFL_COORD_MAX))
            return dfl_err_set(err, DFL_E_INPUT,
                               "vertex %zu has a coordinate %g (expected finite, |x| <= %g)",
                               i / 3, m->verts[i], DFL_COORD_MAX);
    for (size_t t = 0; t < m->ntris; t++) {
        const size_t *T = m->tris + 3 * t;
        if (T[0] >= m->nverts || T[1] >= m->nverts || T[2] >= m->nverts)
            return dfl_err_set(err, DFL_E_INPUT, "triangle %zu has a vertex index >= %zu", t,
                               m->nverts);
        const double *a = m->verts + 3 * T[0], *b = m->verts + 3 * T[1], *c = m->verts + 3 * T[2];
        double e1[3], e2[3], n[3];
        for (int j = 0; j < 3; j++) {
            e1[j] = b[j] - a[j];
            e2[j] = c[j] - a[j];
        }
        dfl_vec3_cross(e1, e2, n);
        if (!(dfl_vec3_norm(n) > 0.0))
            return dfl_err_set(err, DFL_E_INPUT, "triangle %zu is degenerate (zero area)", t);
    }
    return DFL_OK;
}

dfl_status dfl_trimesh_read(const char *path, dfl_trimesh *out, dfl_err *err)
{
    memset(out, 0, sizeof *out);
    dfl_meshfile f;
    dfl_status st = dfl_meshfile_read(path, &f, err);
    if (st != DFL_OK) return st;
    dfl_trimesh m = {0};
    m.nverts = f.nverts;
    m.verts = f.verts;
    m.ntris = f.ntris;
    m.tris = f.tris;
    if ((st = dfl_trimesh_check(&m, err)) != DFL_OK) {
        dfl_err_prefix(err, "%s", path);
        dfl_trimesh_free(&m);
        return st;
    }
    *out = m;
    return DFL_OK;
}

static int edge_cmp(const void *pa, const void *pb)
{
    const size_t *a = pa, *b = pb;
    if (a[0] != b[0]) return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}

dfl_status dfl_trimesh_edges(const dfl_trimesh *m, size_t *boundary, size_t *nonmanifold,
                             dfl_err *err)
{
    const size_t ne = 3 * m->ntris;
    size_t *e = malloc((ne ? ne : 1) * 2 * sizeof *e);
    if (!e) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    for (size_t t = 0; t < m->ntris; t++)
        for (int k = 0; k < 3; k++) {
            size_t u = m->tris[3 * t + k], v = m->tris[3 * t + (k + 1) % 3];
            e[2 * (3 * t + k)] = u < v ? u : v;
            e[2 * (3 * t + k) + 1] = u < v ? v : u;
        }
    qsort(e, ne, 2 * sizeof *e, edge_cmp);
    size_t nb = 0, nn = 0;
    for (size_t i = 0; i < ne;) {
        size_t j = i + 1;
        while (j < ne && e[2 * j] == e[2 * i] && e[2 * j + 1] == e[2 * i + 1]) j++;
        if (j - i == 1) nb++;
        if (j - i >= 3) nn++;
        i = j;
    }
    free(e);
    if (boundary) *boundary = nb;
    if (nonmanifold) *nonmanifold = nn;
    return DFL_OK;
}

void dfl_trimesh_bbox(const dfl_trimesh *m, double *lo, double *hi)
{
    for (int j = 0; j < 3; j++) {
        lo[j] = INFINITY;
        hi[j] = -INFINITY;
    }
    for (size_t i = 0; i < m->nverts; i++)
        for (int j = 0; j < 3; j++) {
            lo[j] = fmin(lo[j], m->verts[3 * i + j]);
            hi[j] = fmax(hi[j], m->verts[3 * i + j]);
        }
}

void dfl_trimesh_fit(dfl_trimesh *m, const double *center, double size)
{
    assert(isfinite(size) && size > 0.0);
    double lo[3], hi[3], mid[3], ext = 0.0;
    dfl_trimesh_bbox(m, lo, hi);
    for (int j = 0; j < 3; j++) {
        mid[j] = 0.5 * (lo[j] + hi[j]);
        ext = fmax(ext, hi[j] - lo[j]);
    }
    assert(ext > 0.0);
    const double s = size / ext;
    for (size_t i = 0; i < m->nverts; i++)
        for (int j = 0; j < 3; j++)
            m->verts[3 * i + j] = center[j] + s * (m->verts[3 * i + j] - mid[j]);
}
