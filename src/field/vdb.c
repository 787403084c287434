/* The C side of field/vdb.h: the name tables (X-macro designated
 * initializers are C, not C++) and the dfl_field adapter over
 * dfl_vdb_sample.  The grid itself is in vdb_grid.cc. */
#include "field/vdb.h"

#include <stdlib.h>

DFL_NAMES_DEFINE(dfl_vdb_sampler, DFL_VDB_SAMPLER_LIST, DFL_VDB_SAMPLER_COUNT,
                 dfl_vdb_sampler_names, dfl_vdb_sampler_name, dfl_vdb_sampler_parse, "sampler")
DFL_NAMES_DEFINE(dfl_vdb_build, DFL_VDB_BUILD_LIST, DFL_VDB_BUILD_COUNT, dfl_vdb_build_names,
                 dfl_vdb_build_name, dfl_vdb_build_parse, "build")

typedef struct vdb_field {
    dfl_vdb *grid;
    dfl_vdb_sampler sampler;
} vdb_field;

static void vdb_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    const vdb_field *f = ctx;
    dfl_vdb_sample(f->grid, f->sampler, m, pts, val, grad);
}

static void vdb_destroy(void *ctx)
{
    vdb_field *f = ctx;
    dfl_vdb_free(f->grid);
    free(f);
}

/* Stored: OpenVDB's memUsage of the grid's tree (dfl_vdb_bytes). */
static size_t vdb_bytes(const void *ctx)
{
    const vdb_field *f = ctx;
    return dfl_vdb_bytes(f->grid);
}

static const dfl_field_ops vdb_ops = {"openvdb", vdb_eval, NULL, vdb_destroy, vdb_bytes};

dfl_status dfl_vdb_field_new(dfl_vdb **g, dfl_vdb_sampler s, dfl_field *out, dfl_err *err)
{
    vdb_field *f = malloc(sizeof *f);
    if (!f) return dfl_err_set(err, DFL_E_NOMEM, "openvdb: out of memory");
    f->grid = *g;
    f->sampler = s;
    *g = NULL;
    out->dim = 3;
    out->ops = &vdb_ops;
    out->ctx = f;
    return DFL_OK;
}

const dfl_vdb *dfl_vdb_field_grid(const dfl_field *f, dfl_vdb_sampler *s)
{
    if (!f || f->ops != &vdb_ops) return NULL;
    const vdb_field *v = f->ctx;
    if (s) *s = v->sampler;
    return v->grid;
}
