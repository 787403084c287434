#include "harness/probe.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/field_cfg.h"
#include "rfunc/rfield.h"
#include "io/config.h"

enum { C_X, C_Y, C_Z, C_DX, C_DY, C_DZ, C_N };
static const char *const colnames[C_N] = {"x", "y", "z", "dx", "dy", "dz"};

static char *trim(char *s)
{
    while (isspace((unsigned char)*s)) s++;
    size_t n = strlen(s);
    while (n && isspace((unsigned char)s[n - 1])) s[--n] = '\0';
    return s;
}

/* Splits line at commas in place; returns the field count (max maxf). */
static int split(char *line, char **f, int maxf)
{
    int n = 0;
    char *s = line;
    for (;;) {
        char *c = strchr(s, ',');
        if (c) *c = '\0';
        if (n < maxf) f[n] = trim(s);
        n++;
        if (!c) break;
        s = c + 1;
    }
    return n;
}

typedef struct pts {
    double *v;   /* rows of 6: x y z dx dy dz */
    size_t n, cap;
} pts;

static dfl_status read_points(const char *path, int dim, int want_dir, pts *p, dfl_err *err)
{
    FILE *fp = fopen(path, "r");
    if (!fp) return dfl_err_set(err, DFL_E_INPUT, "%s: cannot open points file: %s", path, strerror(errno));
    char line[4096];
    int lineno = 0, map[16], ncols = 0, have[C_N] = {0};
    dfl_status st = DFL_OK;
    char *f[16];
    while (fgets(line, sizeof line, fp)) {
        lineno++;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n') {
            st = dfl_err_set(err, DFL_E_INPUT, "%s:%d: line too long", path, lineno);
            break;
        }
        char *t = trim(line);
        if (*t == '\0') continue;
        int nf = split(t, f, 16);
        if (ncols == 0) { /* header */
            if (nf > 16) {
                st = dfl_err_set(err, DFL_E_INPUT, "%s:%d: too many columns", path, lineno);
                break;
            }
            for (int i = 0; i < nf && st == DFL_OK; i++) {
                int k = -1;
                for (int c = 0; c < C_N; c++)
                    if (strcmp(f[i], colnames[c]) == 0) k = c;
                if (k < 0)
                    st = dfl_err_set(err, DFL_E_INPUT,
                                     "%s:%d: unknown column '%s' (expected header x,y[,z][,dx,dy[,dz]])",
                                     path, lineno, f[i]);
                else if (have[k])
                    st = dfl_err_set(err, DFL_E_INPUT, "%s:%d: duplicate column '%s'", path, lineno, f[i]);
                else
                    have[k] = 1, map[i] = k;
            }
            if (st != DFL_OK) break;
            ncols = nf;
            int need[C_N] = {1, 1, dim == 3, want_dir, want_dir, want_dir && dim == 3};
            for (int c = 0; c < C_N && st == DFL_OK; c++) {
                if (need[c] && !have[c])
                    st = dfl_err_set(err, DFL_E_INPUT, "%s:%d: missing column '%s'%s", path, lineno,
                                     colnames[c], c >= C_DX ? " (the --jet direction)" : "");
                if (!need[c] && have[c])
                    st = dfl_err_set(err, DFL_E_INPUT, "%s:%d: column '%s' not expected for a %dD field%s",
                                     path, lineno, colnames[c], dim, want_dir ? "" : " without --jet");
            }
            if (st != DFL_OK) break;
            continue;
        }
        if (nf != ncols) {
            st = dfl_err_set(err, DFL_E_INPUT, "%s:%d: expected %d fields, got %d", path, lineno,
                             ncols, nf);
            break;
        }
        if (p->n == p->cap) {
            size_t cap = p->cap ? 2 * p->cap : 256;
            double *v = realloc(p->v, cap * 6 * sizeof *v);
            if (!v) {
                st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
                break;
            }
            p->v = v;
            p->cap = cap;
        }
        double *row = p->v + 6 * p->n;
        for (int c = 0; c < 6; c++) row[c] = 0.0;
        for (int i = 0; i < nf && st == DFL_OK; i++) {
            char *end;
            errno = 0;
            double x = strtod(f[i], &end);
            if (end == f[i] || *end != '\0' || errno == ERANGE || !isfinite(x))
                st = dfl_err_set(err, DFL_E_INPUT, "%s:%d: column '%s': expected a finite number, got '%.60s'",
                                 path, lineno, colnames[map[i]], f[i]);
            row[map[i]] = x;
        }
        if (st != DFL_OK) break;
        p->n++;
    }
    if (st == DFL_OK && ferror(fp)) st = dfl_err_set(err, DFL_E_INPUT, "%s: read error", path);
    if (st == DFL_OK && ncols == 0) st = dfl_err_set(err, DFL_E_INPUT, "%s: empty file (expected a header x,y[,z])", path);
    if (st == DFL_OK && p->n == 0) st = dfl_err_set(err, DFL_E_INPUT, "%s: no points after the header", path);
    fclose(fp);
    return st;
}

dfl_status dfl_probe(const dfl_probe_opts *o, FILE *out, dfl_err *err)
{
    dfl_cfg *cfg = NULL;
    dfl_field f = {0};
    pts p = {0};
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
    st = dfl_field_from_cfg(cfg, "field", &f, err);
    if (st == DFL_OK) st = dfl_cfg_check_used_in(cfg, "field", err);
    if (st == DFL_OK) st = dfl_cfg_check_used_in(cfg, "shape", err);
    if (st != DFL_OK) goto done;
    if (o->jet > 0 && !f.ops->jet) {
        st = dfl_err_set(err, DFL_E_INPUT, "--jet: field '%s' has no exact derivatives", f.ops->name);
        goto done;
    }
    st = read_points(o->points, f.dim, o->jet > 0, &p, err);
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
    }
    fprintf(out, "x,y,z,value,gx,gy,gz");
    for (int k = 1; k <= K; k++) fprintf(out, ",d%d", k);
    fputc('\n', out);
    for (size_t i = 0; i < p.n; i++) {
        for (int c = 0; c < w; c++) fprintf(out, "%s%.17g", c ? "," : "", res[i * (size_t)w + c]);
        fputc('\n', out);
    }
    if (fflush(out) != 0) st = dfl_err_set(err, DFL_E_IO, "cannot write probe output");
done:
    free(res);
    free(p.v);
    dfl_field_destroy(&f);
    dfl_cfg_free(cfg);
    return st;
}
