#include "util/e2e_util.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cfg/curve_cfg.h"
#include "io/config.h"
#include "util/tmpdir.h"

void e2e_tmpdir(char *buf, size_t size) { tmpdir_new(buf, size); }

const char *e2e_write(const char *dir, const char *name, const char *text, char *buf, size_t size)
{
    return tmpdir_write(dir, name, text, buf, size);
}

int e2e_dflab(const char *dir, const char *args)
{
    const char *bin = getenv("DFL_DFLAB");
    if (!bin || !*bin) bin = "build/dflab";
    size_t n = strlen(bin) + strlen(args) + 2 * strlen(dir) + 64;
    char *cmd = malloc(n);
    snprintf(cmd, n, "%s %s >%s/out.txt 2>%s/err.txt", bin, args, dir, dir);
    int rc = system(cmd);
    free(cmd);
    if (rc == -1 || !WIFEXITED(rc)) return -1;
    return WEXITSTATUS(rc);
}

char *e2e_slurp(const char *path)
{
    FILE *fp = fopen(path, "rb");
    if (!fp) return NULL;
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    size_t r = fread(s, 1, (size_t)n, fp);
    s[r] = '\0';
    fclose(fp);
    return s;
}

int e2e_count_entries(const char *dir) { return tmpdir_count(dir); }

const char *e2e_python(void)
{
    const char *p = getenv("DFL_PYTHON");
    return p && *p ? p : "/usr/bin/python3";
}

/* Minimal CSV reading for tests: a header line, comma-separated cells, no
 * quoting; one function finds a cell, the others build on it. */

/* Index of col among the cells of the header line (the last match), -1 if absent. */
static int csv_column(const char *header, const char *col)
{
    const size_t want = strlen(col);
    int ci = -1;
    for (int k = 0;; k++) {
        const size_t len = strcspn(header, ",\r\n");
        if (len == want && strncmp(header, col, len) == 0) ci = k;
        if (header[len] != ',') return ci;
        header += len + 1;
    }
}

char *e2e_csv_cell(const char *path, long row, const char *col)
{
    char *all = e2e_slurp(path);
    if (!all) return NULL;
    const int ci = csv_column(all, col);
    /* p: the newline before data row `row` */
    const char *p = row >= 0 ? strchr(all, '\n') : NULL;
    for (long r = 0; p && r < row; r++) p = strchr(p + 1, '\n');
    char *out = NULL;
    if (ci >= 0 && p && p[1] != '\0') {
        p++;
        for (int j = 0; j < ci && p; j++) {
            p += strcspn(p, ",\n");
            p = *p == ',' ? p + 1 : NULL;
        }
        if (p) {
            const size_t len = strcspn(p, ",\r\n");
            out = malloc(len + 1);
            memcpy(out, p, len);
            out[len] = '\0';
        }
    }
    free(all);
    return out;
}

double e2e_csv_get(const char *path, size_t row, const char *col)
{
    char *c = e2e_csv_cell(path, (long)row, col);
    const double v = c && *c ? strtod(c, NULL) : NAN;
    free(c);
    return v;
}

long e2e_csv_rows(const char *path)
{
    char *all = e2e_slurp(path);
    if (!all) return -1;
    long lines = 0;
    const char *s = all;
    for (; *s; s++) lines += *s == '\n';
    if (s > all && s[-1] != '\n') lines++; /* a last line without newline */
    free(all);
    return lines - 1;
}

int e2e_rmtree(const char *dir)
{
    static const char prefix[] = "/tmp/dflab-test-";
    if (strncmp(dir, prefix, sizeof prefix - 1) != 0 || strchr(dir, '\'')) return -1;
    const size_t n = strlen(dir) + 16;
    char *cmd = malloc(n);
    snprintf(cmd, n, "rm -rf '%s'", dir);
    const int rc = system(cmd);
    free(cmd);
    return rc == 0 ? 0 : -1;
}

int e2e_python_run(const char *dir, char **out, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    const int na = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char path[1024];
    snprintf(path, sizeof path, "%s/py.txt", dir);
    const size_t n = strlen(e2e_python()) + (size_t)na + strlen(path) + 16;
    char *cmd = malloc(n);
    int k = snprintf(cmd, n, "%s ", e2e_python());
    va_start(ap, fmt);
    k += vsnprintf(cmd + k, n - (size_t)k, fmt, ap);
    va_end(ap);
    snprintf(cmd + k, n - (size_t)k, " >%s 2>&1", path);
    const int rc = system(cmd);
    free(cmd);
    if (out) {
        *out = e2e_slurp(path);
        if (!*out) *out = calloc(1, 1);
    }
    if (rc == -1 || !WIFEXITED(rc)) return -1;
    return WEXITSTATUS(rc);
}

void e2e_vti_read(const char *dir, const char *path, const char *const *names, int nnames,
                  e2e_vti *v)
{
    char args[2048];
    size_t k = (size_t)snprintf(args, sizeof args, "tests/e2e/common/vtk_dump.py %s", path);
    for (int i = 0; i < nnames && k < sizeof args; i++)
        k += (size_t)snprintf(args + k, sizeof args - k, " %s", names[i]);
    cr_assert(k < sizeof args, "e2e_vti_read: too many array names");
    char *txt;
    const int rc = e2e_python_run(dir, &txt, "%s", args);
    cr_assert_eq(rc, 0, "VTK read of %s failed: %s", path, txt);
    memset(v, 0, sizeof *v);
    v->narrays = nnames;
    char *s = txt, *end;
    for (int j = 0; j < 3; j++) v->dims[j] = (int)strtol(s, &s, 10);
    for (int j = 0; j < 3; j++) v->origin[j] = strtod(s, &s);
    for (int j = 0; j < 3; j++) v->spacing[j] = strtod(s, &s);
    const long np = strtol(s, &end, 10);
    cr_assert(end != s && np == (long)v->dims[0] * v->dims[1] * v->dims[2],
              "%s: bad dump header: %.200s", path, txt);
    v->npoints = (size_t)np;
    v->pts = malloc(3 * v->npoints * sizeof *v->pts);
    v->val = malloc((v->npoints * (size_t)nnames + 1) * sizeof *v->val);
    for (size_t i = 0; i < v->npoints; i++)
        for (int j = 0; j < 3 + nnames; j++) {
            s = end;
            const double x = strtod(s, &end);
            cr_assert(end != s, "%s: dump ends at point %zu", path, i);
            if (j < 3) v->pts[3 * i + (size_t)j] = x;
            else v->val[i * (size_t)nnames + (size_t)(j - 3)] = x;
        }
    free(txt);
}

void e2e_vti_free(e2e_vti *v)
{
    free(v->pts);
    free(v->val);
    v->pts = v->val = NULL;
}

char *e2e_err_text(const char *dir)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/err.txt", dir);
    return e2e_slurp(path);
}

int e2e_run_cfg(const char *dir, const char *cfg, const char *extra, char *out, size_t size)
{
    char args[4096];
    snprintf(out, size, "%s/res", dir);
    snprintf(args, sizeof args, "run %s --out %s --quiet %s", cfg, out, extra ? extra : "");
    return e2e_dflab(dir, args);
}

long e2e_run_table(const char *cfg, const char *extra, const char *study, long nrows, char *out,
                   size_t nout, char *csv, size_t ncsv)
{
    e2e_run_ok(cfg, extra, out, nout);
    snprintf(csv, ncsv, "%s/%s.csv", out, study);
    const long n = e2e_csv_rows(csv);
    if (nrows >= 0) cr_assert_eq(n, nrows, "%s: %ld rows, expected %ld", csv, n, nrows);
    return n;
}

long e2e_ini_table(e2e_table *t, const char *name, const char *ini, const char *study,
                   long nrows)
{
    if (!t->dir[0]) e2e_tmpdir(t->dir, sizeof t->dir);
    e2e_write(t->dir, name, ini, t->cfg, sizeof t->cfg);
    return e2e_run_table(t->cfg, NULL, study, nrows, t->out, sizeof t->out, t->csv, sizeof t->csv);
}

int e2e_sjp10_counts(const char *csv, long r, int dim)
{
    char *m = e2e_csv_cell(csv, r, "method");
    cr_assert(m, "%s: no method in row %ld", csv, r);
    const int uniform = strcmp(m, "uniform") == 0;
    free(m);
    const double cells = e2e_csv_get(csv, (size_t)r, "cells");
    const double base = e2e_csv_get(csv, (size_t)r, "base_vertices");
    cr_expect_eq(e2e_csv_get(csv, (size_t)r, "dofs"), ldexp(base, dim), "row %ld", r);
    if (!uniform) return -1;
    const int k = (int)e2e_csv_get(csv, (size_t)r, "uniform_level");
    const double s = ldexp(1.0, k);
    cr_expect_eq(cells, pow(s, dim), "row %ld level %d", r, k);
    cr_expect_eq(base, pow(s + 1, dim), "row %ld level %d", r, k);
    return k;
}

void e2e_run_ok(const char *cfg, const char *extra, char *out, size_t size)
{
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    const int rc = e2e_run_cfg(dir, cfg, extra, out, size);
    char *msg = e2e_err_text(dir);
    cr_assert_eq(rc, 0, "dflab run %s %s failed (%d): %s", cfg, extra ? extra : "", rc,
                 msg ? msg : "");
    free(msg);
}

/* The rejected run's checks, shared by the two entry points below. */
static void expect_rejected(const char *dir, int rc, const char *what, const char *out,
                            const char *want1, const char *want2)
{
    char *msg = e2e_err_text(dir);
    cr_expect_eq(rc, 2, "%s: exit %d, %s", what, rc, msg);
    cr_expect(msg && strstr(msg, want1) && (!want2 || strstr(msg, want2)), "%s: message '%s'",
              what, msg);
    cr_expect_eq(e2e_count_entries(out), -1, "%s left %s behind", what, out);
    free(msg);
}

void e2e_expect_bad_runs(const char *cfg, const char *fixed, const char *const rows[][2], size_t n)
{
    for (size_t i = 0; i < n; i++) {
        char extra[1024];
        snprintf(extra, sizeof extra, "%s%s%s", fixed ? fixed : "", fixed ? " " : "", rows[i][0]);
        e2e_run_expect_fail(cfg, extra, rows[i][1]);
    }
}

void e2e_expect_bad_config(const char *ini_text, const char *want1, const char *want2)
{
    char dir[256], cfg[600], out[600];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "bad.ini", ini_text, cfg, sizeof cfg);
    const int rc = e2e_run_cfg(dir, cfg, NULL, out, sizeof out);
    expect_rejected(dir, rc, cfg, out, want1, want2);
}

void e2e_run_expect_fail(const char *cfg, const char *extra, const char *want)
{
    char dir[256], out[512];
    e2e_tmpdir(dir, sizeof dir);
    const int rc = e2e_run_cfg(dir, cfg, extra, out, sizeof out);
    expect_rejected(dir, rc, extra, out, want, NULL);
}

void e2e_load_curve(const char *path, const char *sec, dfl_bspline *c)
{
    dfl_cfg *cfg;
    dfl_err err;
    cr_assert_eq(dfl_cfg_load(path, &cfg, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_curve_from_cfg(cfg, sec, c, &err), DFL_OK, "%s: %s", path, err.msg);
    dfl_cfg_free(cfg);
}

void e2e_expect_binary_script(const char *script, const char *extra, const char *what)
{
    const char *bin = getenv("DFL_DFLAB");
    if (!bin || !*bin) bin = "build/dflab";
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    char *out = NULL;
    const int rc = e2e_python_run(dir, &out, "%s %s %s", script, bin, extra ? extra : "");
    cr_expect_eq(rc, 0, "%s:\n%s", what, out ? out : "");
    free(out);
    e2e_rmtree(dir);
}
