#include "cfg/slice_cfg.h"

#include <assert.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


#define MAX_N 2048

typedef struct slice_entry {
    int axis;
    double at, lo[2], hi[2];
} slice_entry;

/* One entry "<axis> <at> [lo0 lo1 hi0 hi1]"; without the extent, e->lo/hi
 * stay as the caller set them. */
static dfl_status parse_entry(const char *text, const char *where, slice_entry *e, dfl_err *err)
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
    e->axis = axis;
    e->at = v[0];
    if (nv == 5) {
        e->lo[0] = v[1];
        e->lo[1] = v[2];
        e->hi[0] = v[3];
        e->hi[1] = v[4];
    }
    return DFL_OK;
}

dfl_status dfl_slices_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_grid *out, int max,
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
        return dfl_cfg_reject(cfg, sec, "slice_hi", err, "expected slice_hi > slice_lo per axis");
    dfl_cfg_where(cfg, sec, "slices", w, sizeof w);
    const int nn[2] = {(int)n, (int)n};
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
        slice_entry e;
        memcpy(e.lo, lo, sizeof lo);
        memcpy(e.hi, hi, sizeof hi);
        if ((st = parse_entry(item, w, &e, err))) return st;
        dfl_grid_plane(e.axis, e.at, nn, e.lo, e.hi, &out[c]);
        c++;
    }
    if (c == 0) return dfl_err_set(err, DFL_E_INPUT, "%s: expected at least one slice", w);
    *count = c;
    return DFL_OK;
}

const char *dfl_slice_label(const dfl_grid *plane, char *buf, size_t size)
{
    const int axis = dfl_grid_flat_axis(plane);
    assert(axis >= 0);
    snprintf(buf, size, "%c = %g", "xyz"[axis], plane->lo[axis]);
    return buf;
}
