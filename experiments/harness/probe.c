#include "harness/probe.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cfg/field_cfg.h"
#include "core/domain.h"
#include "rfunc/rfield.h"
#include "io/config.h"
#include "io/points.h"
#include "io/table.h"

/* A point of the points file inside dflab's domain (core/domain.h), and
 * with --jet a direction that is finite, inside it and not zero. */
static dfl_status check_point(const char *path, size_t i, const double *row, int dim, int K,
                              dfl_err *err)
{
    for (int j = 0; j < dim; j++)
        if (!dfl_coord_ok(row[j]))
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s: point %zu: coordinate %c = %g is outside dflab's range "
                               "|x| <= %g",
                               path, i + 1, "xyz"[j], row[j], DFL_COORD_MAX);
    if (K == 0) return DFL_OK;
    double n2 = 0.0;
    for (int j = 0; j < dim; j++) {
        if (!dfl_coord_ok(row[3 + j]))
            return dfl_err_set(err, DFL_E_INPUT,
                               "%s: point %zu: direction d%c = %g is outside |d| <= %g", path,
                               i + 1, "xyz"[j], row[3 + j], DFL_COORD_MAX);
        n2 = fmax(n2, fabs(row[3 + j]));
    }
    if (!(n2 > 0.0))
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: point %zu: the --jet direction is zero (expected a non-zero "
                           "dx,dy%s)",
                           path, i + 1, dim == 3 ? ",dz" : "");
    return DFL_OK;
}

/* Reads the points file: io/points.h's format, each point checked. */
static dfl_status read_points(const char *path, int dim, int K, dfl_points *p, dfl_err *err)
{
    FILE *fp = fopen(path, "r");
    if (!fp)
        return dfl_err_set(err, DFL_E_INPUT, "%s: cannot open points file: %s", path,
                           strerror(errno));
    struct stat sb;
    dfl_status st;
    if (fstat(fileno(fp), &sb) == 0 && S_ISDIR(sb.st_mode))
        st = dfl_err_set(err, DFL_E_INPUT, "%s: cannot read points file: a directory", path);
    else
        st = dfl_points_read(fp, path, dim, K > 0, p, err);
    fclose(fp);
    for (size_t i = 0; st == DFL_OK && i < p->n; i++)
        st = check_point(path, i, p->v + 6 * i, dim, K, err);
    if (st != DFL_OK) dfl_points_free(p);
    return st;
}

/* A value that is not finite at a point inside the domain is a failure of
 * the method, never a number to print -- except NaN from a field that
 * defines NaN as "undefined here" (bs04's eq. 20 literally, nan_ok). */
static dfl_status check_row(const char *path, size_t i, const double *r, int w, bool nan_ok,
                            dfl_err *err)
{
    static const char *const names[7] = {"x", "y", "z", "value", "gx", "gy", "gz"};
    for (int c = 3; c < w; c++)
        if (!isfinite(r[c]) && !(nan_ok && isnan(r[c]))) {
            char nm[16];
            if (c < 7) snprintf(nm, sizeof nm, "%s", names[c]);
            else snprintf(nm, sizeof nm, "d%d", c - 6);
            return dfl_err_set(err, DFL_E_NUMERIC,
                               "%s: point %zu: %s is not finite (%g); nothing printed", path,
                               i + 1, nm, r[c]);
        }
    return DFL_OK;
}

dfl_status dfl_probe(const dfl_probe_opts *o, FILE *out, dfl_err *err)
{
    dfl_cfg *cfg = NULL;
    dfl_field f = {0};
    dfl_points p = {0};
    double *res = NULL;
    dfl_status st = dfl_cfg_load(o->config, &cfg, err);
    for (int i = 0; st == DFL_OK && i < o->nsets; i++) st = dfl_cfg_set(cfg, o->sets[i], err);
    if (st != DFL_OK) goto done;
    if (dfl_cfg_sweep_points(cfg) > 1) {
        const char *ax = dfl_cfg_sweep_axis_name(cfg, 0);
        st = dfl_err_set(err, DFL_E_INPUT,
                         "%s: %s is a sweep list; probe needs a single value (use --set %s=...)",
                         o->config, ax, ax);
        goto done;
    }
    if (o->jet < 0 || o->jet > DFL_JET_MAX) {
        st = dfl_err_set(err, DFL_E_INPUT, "--jet %d: expected an order in [0, %d]", o->jet, DFL_JET_MAX);
        goto done;
    }
    const char *sec = o->field ? o->field : "field";
    if (!dfl_cfg_has_section(cfg, sec)) {
        st = dfl_err_set(err, DFL_E_INPUT, "%s: --field %s: the config has no section [%s]",
                         o->config, sec, sec);
        goto done;
    }
    st = dfl_field_from_cfg(cfg, sec, &f, err);
    if (st == DFL_OK) st = dfl_cfg_check_used_in(cfg, sec, err);
    if (st == DFL_OK) st = dfl_cfg_check_used_in(cfg, "shape", err);
    if (st != DFL_OK) goto done;
    if (o->jet > 0 && !f.ops->jet) {
        st = dfl_err_set(err, DFL_E_INPUT, "--jet: field '%s' has no exact derivatives", f.ops->name);
        goto done;
    }
    st = read_points(o->points, f.dim, o->jet, &p, err);
    if (st != DFL_OK) goto done;
    const int dim = f.dim, K = o->jet, w = 7 + K;
    res = malloc(p.n * (size_t)w * sizeof *res);
    if (!res) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        goto done;
    }
    for (size_t i = 0; i < p.n; i++) {
        const double *row = p.v + 6 * i;
        double x[3] = {row[0], row[1], row[2]}, g[3] = {0, 0, 0};
        double *r = res + i * (size_t)w;
        /* rfunc fields state a domain of validity (rfunc/domain.h) */
        st = dfl_rfield_check_point(&f, x, K > 0, err);
        if (st != DFL_OK) {
            dfl_err_prefix(err, "%s: point %zu", o->points, i + 1);
            goto done;
        }
        double val = dfl_field_eval1(&f, x, g);
        r[0] = x[0], r[1] = x[1], r[2] = dim == 3 ? x[2] : 0.0;
        r[3] = val, r[4] = g[0], r[5] = g[1], r[6] = dim == 3 ? g[2] : 0.0;
        if (K > 0) {
            dfl_jet j;
            double dir[3] = {row[3], row[4], row[5]};
            st = dfl_field_jet(&f, x, dir, K, &j, err);
            if (st != DFL_OK) {
                dfl_err_prefix(err, "%s: point %zu", o->points, i + 1);
                goto done;
            }
            for (int k = 1; k <= K; k++) r[6 + k] = dfl_jet_deriv(&j, k);
        }
        if ((st = check_row(o->points, i, r, w, dfl_rfield_nan_is_undefined(&f), err)) != DFL_OK)
            goto done;
    }
    fprintf(out, "x,y,z,value,gx,gy,gz");
    for (int k = 1; k <= K; k++) fprintf(out, ",d%d", k);
    fputc('\n', out);
    for (size_t i = 0; i < p.n; i++) {
        /* the CSVs' form: the shortest text that reads back exactly */
        for (int c = 0; c < w; c++) {
            char b[32];
            fprintf(out, "%s%s", c ? "," : "",
                    dfl_table_format_double(res[i * (size_t)w + c], b, sizeof b));
        }
        fputc('\n', out);
    }
    if (fflush(out) != 0) st = dfl_err_set(err, DFL_E_IO, "cannot write probe output");
done:
    free(res);
    dfl_points_free(&p);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
    return st;
}

void dfl_probe_sections_defer(dfl_cfg *c)
{
    dfl_cfg_defer_sections(c, "field");
}

dfl_status dfl_probe_sections_check(const dfl_cfg *c, dfl_err *err)
{
    /* each pass reads every key of one section or fails, so this ends */
    for (const char *sec; (sec = dfl_cfg_unused_deferred(c)) != NULL;) {
        dfl_field f = {0};
        dfl_status st = dfl_field_from_cfg(c, sec, &f, err);
        if (st == DFL_OK) dfl_field_destroy(&f);
        if (st == DFL_OK) st = dfl_cfg_check_used_in(c, sec, err);
        if (st != DFL_OK) return st;
    }
    return DFL_OK;
}
