#include "e2e_util.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

void e2e_tmpdir(char *buf, size_t size)
{
    snprintf(buf, size, "/tmp/dflab-test-XXXXXX");
    if (!mkdtemp(buf)) buf[0] = '\0';
}

const char *e2e_write(const char *dir, const char *name, const char *text, char *buf, size_t size)
{
    snprintf(buf, size, "%s/%s", dir, name);
    FILE *fp = fopen(buf, "w");
    if (fp) {
        fputs(text, fp);
        fclose(fp);
    }
    return buf;
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

int e2e_count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *de;
    while ((de = readdir(d)))
        if (strcmp(de->d_name, ".") && strcmp(de->d_name, "..")) n++;
    closedir(d);
    return n;
}

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
