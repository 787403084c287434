#include "harness/metrics_cols.h"

#include <stdio.h>

dfl_status dfl_metrics_put(dfl_table *t, const char *sfx, const dfl_metrics *m)
{
    char col[96];
    dfl_status st;
    snprintf(col, sizeof col, "count%s", sfx);
    st = dfl_table_set_int(t, col, (long)m->count);
#define PUT(name, v)                                              \
    do {                                                          \
        snprintf(col, sizeof col, "%s%s", name, sfx);             \
        if (st == DFL_OK) st = dfl_table_set_double(t, col, v);   \
    } while (0)
    PUT("l1", m->l1);
    PUT("mse", m->mse);
    PUT("rms", m->rms);
    PUT("linf", m->linf);
    PUT("graddefect_mean", m->gdef_mean);
    PUT("graddefect_max", m->gdef_max);
#undef PUT
    return st;
}
