#include "rfunc/exact_polyline.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/hypot.h"
#include "geom/segdist.h"

typedef struct spoly {
    int dim, p;
    dfl_rfunc_join join;
    dfl_rfunc_correction corr;
    size_t n;       /* vertices */
    double *v;      /* n * dim */
} spoly;

static void spoly_eval(const void *ctx, size_t m, const double *pts, double *val, double *grad)
{
    const spoly *s = ctx;
    const int dim = s->dim, want = grad != NULL;
    const int corrected = s->join == DFL_RFUNC_REQUIV_CORRECTED;
    for (size_t i = 0; i < m; i++) {
        const double *x = pts + i * (size_t)dim;
        dfl_rfunc_acc acc;
        double hprev = 0.0, gprev[3] = {0, 0, 0};
        dfl_rfunc_acc_begin(&acc, s->join, s->p, dim, want);
        if (corrected) dfl_rfunc_acc_set_correction(&acc, s->corr);
        for (size_t k = 0; k + 1 < s->n && !dfl_rfunc_acc_is_zero(&acc); k++) {
            const double *a = s->v + k * (size_t)dim;
            double g[3] = {0, 0, 0};
            const double h = dfl_segdist_eval(dim, a, a + dim, x, g);
            dfl_rfunc_acc_add(&acc, h, g);
            if (corrected && k > 0) {
                /* vertex k joins segments k - 1 and k */
                double w[3] = {0, 0, 0}, gq[3] = {0, 0, 0}, gt[3];
                for (int j = 0; j < dim; j++) w[j] = x[j] - a[j];
                const double q = dfl_hypot_vec(dim, w);
                for (int j = 0; j < dim; j++) gq[j] = q > 0.0 ? w[j] / q : 0.0;
                if (s->corr == DFL_RFUNC_CORR_EQ20) {
                    dfl_rfunc_acc_add_q(&acc, q, gq);
                } else {
                    const double qt = dfl_rfunc_guard(dim, q, gq, hprev, gprev, h, g, gt);
                    dfl_rfunc_acc_add_q(&acc, qt, gt);
                }
            }
            hprev = h;
            memcpy(gprev, g, sizeof g);
        }
        val[i] = dfl_rfunc_acc_end(&acc, want ? grad + i * (size_t)dim : NULL);
    }
}

static void spoly_destroy(void *ctx)
{
    spoly *s = ctx;
    if (!s) return;
    free(s->v);
    free(s);
}

static const dfl_field_ops spoly_ops = {"exact_polyline", spoly_eval, NULL, spoly_destroy, NULL};

dfl_status dfl_rfunc_exact_polyline_field(int dim, const double *v, size_t n,
                                          dfl_rfunc_join join, int p, dfl_field *out,
                                          dfl_err *err)
{
    return dfl_rfunc_exact_polyline_field_corr(dim, v, n, join, DFL_RFUNC_CORR_GUARDED, p, out,
                                               err);
}

dfl_status dfl_rfunc_exact_polyline_field_corr(int dim, const double *v, size_t n,
                                               dfl_rfunc_join join, dfl_rfunc_correction corr,
                                               int p, dfl_field *out, dfl_err *err)
{
    if (dim != 2 && dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "segment polyline: dimension %d (expected 2 or 3)",
                           dim);
    dfl_status st = dfl_rfunc_join_check(join, p, err);
    if (st != DFL_OK) return st;
    if (n < 2)
        return dfl_err_set(err, DFL_E_INPUT, "segment polyline: %zu vertices (need at least 2)",
                           n);
    for (size_t i = 0; i < n * (size_t)dim; i++)
        if (!isfinite(v[i]))
            return dfl_err_set(err, DFL_E_INPUT, "segment polyline: vertex %zu is not finite",
                               i / (size_t)dim + 1);
    for (size_t i = 0; i + 1 < n; i++)
        if (memcmp(v + i * (size_t)dim, v + (i + 1) * (size_t)dim, (size_t)dim * sizeof *v) == 0)
            return dfl_err_set(err, DFL_E_INPUT,
                               "segment polyline: vertices %zu and %zu coincide", i + 1, i + 2);
    spoly *s = calloc(1, sizeof *s);
    double *cv = malloc(n * (size_t)dim * sizeof *cv);
    if (!s || !cv) {
        free(s);
        free(cv);
        return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    }
    memcpy(cv, v, n * (size_t)dim * sizeof *cv);
    s->dim = dim;
    s->p = p;
    s->join = join;
    s->corr = corr;
    s->n = n;
    s->v = cv;
    out->dim = dim;
    out->ops = &spoly_ops;
    out->ctx = s;
    return DFL_OK;
}
