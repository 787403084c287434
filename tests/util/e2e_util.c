#include "util/e2e_util.h"

#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

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

/* Minimal CSV reading for tests: no quoted cells in numeric tables. */
static int split_csv(char *line, char **f, int maxf)
{
    int n = 0;
    char *s = line;
    for (;;) {
        char *c = strchr(s, ',');
        if (c) *c = '\0';
        if (n < maxf) f[n++] = s;
        if (!c) break;
        s = c + 1;
    }
    return n;
}

double e2e_csv_get(const char *path, size_t row, const char *col)
{
    FILE *fp = fopen(path, "r");
    if (!fp) return NAN;
    static char line[65536];
    char *f[512];
    int idx = -1;
    double v = NAN;
    if (fgets(line, sizeof line, fp)) {
        line[strcspn(line, "\r\n")] = '\0';
        int n = split_csv(line, f, 512);
        for (int i = 0; i < n; i++)
            if (strcmp(f[i], col) == 0) idx = i;
    }
    size_t r = 0;
    while (idx >= 0 && fgets(line, sizeof line, fp)) {
        if (r++ != row) continue;
        line[strcspn(line, "\r\n")] = '\0';
        int n = split_csv(line, f, 512);
        if (idx < n && *f[idx]) v = strtod(f[idx], NULL);
        break;
    }
    fclose(fp);
    return v;
}

long e2e_csv_rows(const char *path)
{
    FILE *fp = fopen(path, "r");
    if (!fp) return -1;
    static char line[65536];
    long n = -1;
    while (fgets(line, sizeof line, fp)) n++;
    fclose(fp);
    return n;
}

char *e2e_csv_cell(const char *path, long row, const char *col)
{
    char *all = e2e_slurp(path);
    if (!all) return NULL;
    char *save = NULL, *line = strtok_r(all, "\n", &save);
    int ci = -1, k = 0;
    for (char *p = line, *q; p; p = q ? q + 1 : NULL, k++) {
        q = strchr(p, ',');
        size_t len = q ? (size_t)(q - p) : strlen(p);
        if (strlen(col) == len && strncmp(p, col, len) == 0) ci = k;
    }
    char *out = NULL;
    for (long r = 0; ci >= 0 && (line = strtok_r(NULL, "\n", &save)); r++) {
        if (r != row) continue;
        char *p = line;
        for (int j = 0; j < ci && p; j++) {
            p = strchr(p, ',');
            if (p) p++;
        }
        if (p) {
            size_t len = strcspn(p, ",");
            out = malloc(len + 1);
            memcpy(out, p, len);
            out[len] = '\0';
        }
        break;
    }
    free(all);
    return out;
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

void e2e_run_expect_fail(const char *cfg, const char *extra, const char *want)
{
    char dir[256], out[512];
    e2e_tmpdir(dir, sizeof dir);
    const int rc = e2e_run_cfg(dir, cfg, extra, out, sizeof out);
    char *msg = e2e_err_text(dir);
    cr_expect_eq(rc, 2, "%s: exit %d, %s", extra, rc, msg);
    cr_expect(msg && strstr(msg, want), "%s: message '%s'", extra, msg);
    cr_expect_eq(e2e_count_entries(out), -1, "%s left %s behind", extra, out);
    free(msg);
}
