#include "pht/tmesh.h"

const char * dfl_pht_split_name(dfl_pht_split s)
{
    (void)s;
    return NULL;
}

int dfl_pht_split_from_name(const char *name)
{
    (void)name;
    return 0;
}

dfl_status dfl_tmesh_new(int dim, const double *lo, const double *hi, dfl_tmesh **out, dfl_err *err)
{
    (void)dim;
    (void)lo;
    (void)hi;
    (void)out;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

void dfl_tmesh_free(dfl_tmesh *m)
{
    (void)m;
}

int dfl_tmesh_dim(const dfl_tmesh *m)
{
    (void)m;
    return 0;
}

const double * dfl_tmesh_lo(const dfl_tmesh *m)
{
    (void)m;
    return NULL;
}

const double * dfl_tmesh_hi(const dfl_tmesh *m)
{
    (void)m;
    return NULL;
}

dfl_status dfl_tmesh_refine(dfl_tmesh *m, size_t n, const size_t *ids, dfl_pht_split rule, dfl_err *err)
{
    (void)m;
    (void)n;
    (void)ids;
    (void)rule;
    (void)err;
    return dfl_err_set(err, DFL_E_INTERNAL, "%s: not implemented yet", __func__);
}

size_t dfl_tmesh_ncells(const dfl_tmesh *m)
{
    (void)m;
    return 0;
}

void dfl_tmesh_cell_get(const dfl_tmesh *m, size_t id, dfl_tmesh_cell *out)
{
    (void)m;
    (void)id;
    (void)out;
}

size_t dfl_tmesh_nleaves(const dfl_tmesh *m)
{
    (void)m;
    return 0;
}

const size_t * dfl_tmesh_leaves(const dfl_tmesh *m)
{
    (void)m;
    return NULL;
}

int dfl_tmesh_max_level(const dfl_tmesh *m)
{
    (void)m;
    return 0;
}

size_t dfl_tmesh_nverts(const dfl_tmesh *m)
{
    (void)m;
    return 0;
}

void dfl_tmesh_vertex_get(const dfl_tmesh *m, size_t v, dfl_tmesh_vertex *out)
{
    (void)m;
    (void)v;
    (void)out;
}

size_t dfl_tmesh_nbase(const dfl_tmesh *m)
{
    (void)m;
    return 0;
}

const size_t * dfl_tmesh_order(const dfl_tmesh *m, size_t *n)
{
    (void)m;
    (void)n;
    return NULL;
}

size_t dfl_tmesh_locate(const dfl_tmesh *m, const double *x, const double *dir)
{
    (void)m;
    (void)x;
    (void)dir;
    return 0;
}

size_t dfl_tmesh_bytes(const dfl_tmesh *m)
{
    (void)m;
    return 0;
}

