/* Slices go through the same chunked OpenMP pattern as field/sample.c (a
 * stack buffer of coordinates per chunk, one eval call per chunk), since
 * the grid sampler only knows grids of the field's own dimension. */
#include "harness/slice.h"

#include <ctype.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "io/exr.h"
#include "io/vtk.h"

#define CHUNK 256
#define MAX_N 2048

void dfl_slice_axes(int axis, int *a0, int *a1)
{
    *a0 = axis == 0 ? 1 : 0;
    *a1 = axis == 2 ? 1 : 2;
}

dfl_status dfl_slice_parse(const char *text, const char *where, dfl_slice *out, dfl_err *err)
{
    const char *s = text;
    while (isspace((unsigned char)*s)) s++;
    const int axis = *s == 'x' ? 0 : *s == 'y' ? 1 : *s == 'z' ? 2 : -1;
    double v[5];
    int nv = 0;
    const char *q = s + 1;
    if (axis >= 0 && isspace((unsigned char)*q)) {
        for (;;) {
            while (isspace((unsigned char)*q)) q++;
            if (!*q || nv == 5) break;
            char *end;
            v[nv] = strtod(q, &end);
            if (end == q || !isfinite(v[nv])) break;
            nv++;
            q = end;
        }
    }
    while (isspace((unsigned char)*q)) q++;
    if (axis < 0 || *q || (nv != 1 && nv != 5))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: expected '<x|y|z> <coordinate> [lo0 lo1 hi0 hi1]', got '%s'",
                           where, text);
    if (nv == 5 && !(v[1] < v[3] && v[2] < v[4]))
        return dfl_err_set(err, DFL_E_INPUT, "%s: slice '%s' needs hi > lo per axis", where,
                           text);
    out->axis = axis;
    out->at = v[0];
    if (nv == 5) {
        out->lo[0] = v[1];
        out->lo[1] = v[2];
        out->hi[0] = v[3];
        out->hi[1] = v[4];
    }
    return DFL_OK;
}

dfl_status dfl_slices_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_slice *out, int max,
                               int *count, dfl_err *err)
{
    char w[600], item[256];
    const char *raw;
    long n;
    double lo[2], hi[2];
    const double dlo[2] = {0, 0}, dhi[2] = {1, 1};
    dfl_status st;
    if ((st = dfl_cfg_string(cfg, sec, "slices", &raw, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "slice_n", 200, 2, MAX_N, &n, err))) return st;
    if ((st = dfl_cfg_vec_opt(cfg, sec, "slice_lo", 2, dlo, lo, err))) return st;
    if ((st = dfl_cfg_vec_opt(cfg, sec, "slice_hi", 2, dhi, hi, err))) return st;
    if (!(lo[0] < hi[0] && lo[1] < hi[1]))
        return dfl_err_set(err, DFL_E_INPUT, "%s: expected slice_hi > slice_lo per axis",
                           dfl_cfg_where(cfg, sec, "slice_hi", w, sizeof w));
    dfl_cfg_where(cfg, sec, "slices", w, sizeof w);
    int c = 0;
    for (const char *s = raw; *s;) {
        size_t len = strcspn(s, ";");
        if (len >= sizeof item)
            return dfl_err_set(err, DFL_E_INPUT, "%s: slice entry too long", w);
        memcpy(item, s, len);
        item[len] = '\0';
        s += len + (s[len] == ';');
        if (strspn(item, " \t") == len) continue;
        if (c == max)
            return dfl_err_set(err, DFL_E_INPUT, "%s: at most %d slices", w, max);
        out[c].n[0] = out[c].n[1] = (int)n;
        memcpy(out[c].lo, lo, sizeof lo);
        memcpy(out[c].hi, hi, sizeof hi);
        if ((st = dfl_slice_parse(item, w, &out[c], err))) return st;
        c++;
    }
    if (c == 0) return dfl_err_set(err, DFL_E_INPUT, "%s: expected at least one slice", w);
    *count = c;
    return DFL_OK;
}

size_t dfl_slice_size(const dfl_slice *s) { return (size_t)s->n[0] * (size_t)s->n[1]; }

void dfl_slice_point(const dfl_slice *s, size_t idx, double *x)
{
    int a0, a1;
    dfl_slice_axes(s->axis, &a0, &a1);
    const size_t i = idx % (size_t)s->n[0], j = idx / (size_t)s->n[0];
    /* interpolated so that the last sample is exactly hi (as the grid does) */
    const double t0 = (double)i / (double)(s->n[0] - 1), t1 = (double)j / (double)(s->n[1] - 1);
    x[s->axis] = s->at;
    x[a0] = (1.0 - t0) * s->lo[0] + t0 * s->hi[0];
    x[a1] = (1.0 - t1) * s->lo[1] + t1 * s->hi[1];
}

dfl_status dfl_slice_sample(const dfl_field *f, const dfl_slice *s, int threads, double *val,
                            double *grad, dfl_err *err)
{
    if (f->dim != 3) return dfl_err_set(err, DFL_E_INPUT, "slice: the field is %dD, not 3D", f->dim);
    const size_t total = dfl_slice_size(s);
    const size_t nchunks = (total + CHUNK - 1) / CHUNK;
    if (threads <= 0) threads = omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
    for (size_t c = 0; c < nchunks; c++) {
        double pts[CHUNK * 3];
        const size_t start = c * CHUNK;
        const size_t m = total - start < CHUNK ? total - start : CHUNK;
        for (size_t q = 0; q < m; q++) dfl_slice_point(s, start + q, pts + 3 * q);
        f->ops->eval(f->ctx, m, pts, val + start, grad ? grad + 3 * start : NULL);
    }
    return DFL_OK;
}

dfl_status dfl_slice_write(const dfl_study_ctx *ctx, const char *stem, const dfl_slice *s,
                           const double *val, const double *grad, const double *ref,
                           const dfl_field_out_opts *o, dfl_err *err)
{
    const size_t m = dfl_slice_size(s);
    double *gn = grad ? malloc(m * sizeof *gn) : NULL;
    double *er = ref ? malloc(m * sizeof *er) : NULL;
    float *fv = NULL, *fg = NULL, *fe = NULL;
    char path[4400];
    dfl_status st = DFL_OK;
    if ((grad && !gn) || (ref && !er)) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory writing %s", stem);
        goto done;
    }
    for (size_t i = 0; i < m; i++) {
        if (gn) gn[i] = sqrt(grad[3 * i] * grad[3 * i] + grad[3 * i + 1] * grad[3 * i + 1] +
                             grad[3 * i + 2] * grad[3 * i + 2]);
        if (er) er[i] = val[i] - ref[i];
    }
    int a0, a1;
    dfl_slice_axes(s->axis, &a0, &a1);
    if (o->vti) {
        /* VTK orders x fastest; the in-plane axes are increasing, so sample
         * (i, j) maps to node (i, j) of the two non-degenerate axes. */
        int dims[3];
        double origin[3], sp[3];
        dims[s->axis] = 1;
        dims[a0] = s->n[0];
        dims[a1] = s->n[1];
        origin[s->axis] = s->at;
        origin[a0] = s->lo[0];
        origin[a1] = s->lo[1];
        sp[s->axis] = 1.0;
        sp[a0] = (s->hi[0] - s->lo[0]) / (s->n[0] - 1);
        sp[a1] = (s->hi[1] - s->lo[1]) / (s->n[1] - 1);
        dfl_vtk_array arr[5];
        int na = 0;
        arr[na++] = (dfl_vtk_array){"value", 1, val};
        if (grad) arr[na++] = (dfl_vtk_array){"gradient", 3, grad};
        if (grad) arr[na++] = (dfl_vtk_array){"grad_norm", 1, gn};
        if (ref) arr[na++] = (dfl_vtk_array){"error", 1, er};
        if (ref) arr[na++] = (dfl_vtk_array){"reference", 1, ref};
        st = dfl_vti_write(dfl_study_path(ctx, stem, "vti", path, sizeof path), dims, origin, sp,
                           arr, na, o->compress, err);
        if (st != DFL_OK) goto done;
    }
    if (o->exr) {
        const int wd = s->n[0], ht = s->n[1];
        fv = malloc(m * sizeof *fv);
        fg = malloc(m * sizeof *fg);
        fe = malloc(m * sizeof *fe);
        if (!fv || !fg || !fe) {
            st = dfl_err_set(err, DFL_E_NOMEM, "out of memory writing %s", stem);
            goto done;
        }
        for (int r = 0; r < ht; r++)
            for (int i = 0; i < wd; i++) {
                const size_t idx = (size_t)i + (size_t)wd * (size_t)(ht - 1 - r);
                const size_t p = (size_t)r * (size_t)wd + (size_t)i;
                fv[p] = (float)val[idx];
                fg[p] = gn ? (float)gn[idx] : 0.0f;
                fe[p] = er ? (float)er[idx] : 0.0f;
            }
        dfl_exr_channel ch[3];
        int nch = 0;
        ch[nch++] = (dfl_exr_channel){"value", fv};
        if (gn) ch[nch++] = (dfl_exr_channel){"grad_norm", fg};
        if (er) ch[nch++] = (dfl_exr_channel){"error", fe};
        st = dfl_exr_write(dfl_study_path(ctx, stem, "exr", path, sizeof path), wd, ht, ch, nch,
                           o->half, err);
    }
done:
    free(gn), free(er), free(fv), free(fg), free(fe);
    return st;
}
