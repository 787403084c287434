/* The gradient norm is summed in axis order from 0 (the same value as
 * g0^2 + g1^2 + g2^2 written out) so that both files and every lattice
 * report the same bits for the same gradient. */
#include "io/field_write.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "io/exr.h"
#include "io/meta_attrs.h"
#include "io/vtk.h"

static double grad_norm(const double *g, int gdim)
{
    double s = 0;
    for (int d = 0; d < gdim; d++) s += g[d] * g[d];
    return sqrt(s);
}

static size_t node_count(const dfl_field_samples *s)
{
    return (size_t)s->dims[0] * (size_t)s->dims[1] * (size_t)s->dims[2];
}

dfl_status dfl_field_write_vti(const char *path, const dfl_field_samples *s, int compress,
                               dfl_err *err)
{
    const size_t m = node_count(s);
    const int gd = s->gdim;
    /* VTK wants 3-component vectors: 2D gradients are padded with z = 0 */
    double *g3 = s->gu && gd != 3 ? calloc(3 * m, sizeof *g3) : NULL;
    double *gn = s->gu ? malloc(m * sizeof *gn) : NULL;
    double *er = s->ref ? malloc(m * sizeof *er) : NULL;
    dfl_status st = DFL_OK;
    if ((s->gu && gd != 3 && !g3) || (s->gu && !gn) || (s->ref && !er)) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory writing %s", path);
        goto done;
    }
    for (size_t i = 0; i < m; i++) {
        if (s->gu) {
            const double *g = s->gu + i * (size_t)gd;
            if (g3)
                for (int d = 0; d < gd; d++) g3[3 * i + (size_t)d] = g[d];
            gn[i] = grad_norm(g, gd);
        }
        if (er) er[i] = s->u[i] - s->ref[i];
    }
    dfl_vtk_array arr[5];
    int na = 0;
    arr[na++] = (dfl_vtk_array){"value", 1, s->u};
    if (s->gu) arr[na++] = (dfl_vtk_array){"gradient", 3, g3 ? g3 : s->gu};
    if (s->gu) arr[na++] = (dfl_vtk_array){"grad_norm", 1, gn};
    if (s->ref) arr[na++] = (dfl_vtk_array){"error", 1, er};
    if (s->ref) arr[na++] = (dfl_vtk_array){"reference", 1, s->ref};
    st = dfl_vti_write_cells(path, s->dims, s->origin, s->spacing, arr, na, s->cells, s->ncells,
                             compress, err);
done:
    free(g3), free(gn), free(er);
    return st;
}

/* Where the image lies: its domain, spacing and, for a volume, which
 * section it is (a viewer shows only pixels). */
static dfl_status section_attrs(const char *path, const dfl_field_samples *s, int c, int a0, int a1,
                                size_t k0, dfl_err *err)
{
    static const char axis[] = "xyz";
    char lo[128], hi[128], sp[128], sec[256];
    snprintf(lo, sizeof lo, "%.17g %.17g", s->origin[a0], s->origin[a1]);
    snprintf(hi, sizeof hi, "%.17g %.17g", s->origin[a0] + (s->dims[a0] - 1) * s->spacing[a0],
             s->origin[a1] + (s->dims[a1] - 1) * s->spacing[a1]);
    snprintf(sp, sizeof sp, "%.17g %.17g", s->spacing[a0], s->spacing[a1]);
    if (s->dims[c] > 1)
        snprintf(sec, sizeof sec, "middle slice of a volume: %c = %.17g (node %zu of %d); "
                                  "image x = %c, image y = %c (row 0 at the largest)",
                 axis[c], s->origin[c] + (double)k0 * s->spacing[c], k0, s->dims[c], axis[a0],
                 axis[a1]);
    else
        snprintf(sec, sizeof sec, "whole lattice at %c = %.17g; image x = %c, image y = %c (row 0 "
                                  "at the largest)", axis[c], s->origin[c], axis[a0], axis[a1]);
    const char *names[] = {"dflab_domain_lo", "dflab_domain_hi", "dflab_spacing", "dflab_section"};
    const char *values[] = {lo, hi, sp, sec};
    return dfl_exr_add_attrs(path, 4, names, values, err);
}

dfl_status dfl_field_write_exr(const char *path, const dfl_field_samples *s, int half,
                               dfl_err *err)
{
    /* the section's normal c, its node k0 and the image axes a0 (x), a1 (y) */
    int c = 2;
    for (int d = 0; d < 3; d++)
        if (s->dims[d] == 1) c = d;
    const int a0 = c == 0 ? 1 : 0, a1 = c == 2 ? 1 : 2;
    const size_t stride[3] = {1, (size_t)s->dims[0], (size_t)s->dims[0] * (size_t)s->dims[1]};
    const size_t k0 = (size_t)(s->dims[c] / 2);
    const int w = s->dims[a0], h = s->dims[a1];
    const size_t pix = (size_t)w * (size_t)h;
    float *fv = malloc(pix * sizeof *fv);
    float *fg = s->gu ? malloc(pix * sizeof *fg) : NULL;
    float *fe = s->ref ? malloc(pix * sizeof *fe) : NULL;
    dfl_status st = DFL_OK;
    if (!fv || (s->gu && !fg) || (s->ref && !fe)) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory writing %s", path);
        goto done;
    }
    for (int r = 0; r < h; r++) {
        const size_t j = (size_t)(h - 1 - r);
        for (int i = 0; i < w; i++) {
            const size_t idx = (size_t)i * stride[a0] + j * stride[a1] + k0 * stride[c];
            const size_t p = (size_t)r * (size_t)w + (size_t)i;
            fv[p] = (float)s->u[idx];
            if (fg) fg[p] = (float)grad_norm(s->gu + idx * (size_t)s->gdim, s->gdim);
            if (fe) fe[p] = (float)(s->u[idx] - s->ref[idx]);
        }
    }
    dfl_exr_channel ch[3];
    int nch = 0;
    ch[nch++] = (dfl_exr_channel){"value", fv};
    if (fg) ch[nch++] = (dfl_exr_channel){"grad_norm", fg};
    if (fe) ch[nch++] = (dfl_exr_channel){"error", fe};
    st = dfl_exr_write(path, w, h, ch, nch, half, err);
    if (st == DFL_OK) st = section_attrs(path, s, c, a0, a1, k0, err);
done:
    free(fv), free(fg), free(fe);
    return st;
}

dfl_status dfl_field_write(const char *vti_path, const char *exr_path, const dfl_field_samples *s,
                           const dfl_field_write_opts *o, dfl_err *err)
{
    dfl_status st = DFL_OK;
    if (o->vti) st = dfl_field_write_vti(vti_path, s, o->compress, err);
    if (st == DFL_OK && o->exr) st = dfl_field_write_exr(exr_path, s, o->half, err);
    return st;
}
