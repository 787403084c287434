/* Memory limits from /proc and /sys/fs/cgroup, and the cost accumulator
 * (budget.h).  Every reader takes its paths as parameters so that tests can
 * point it at fake files; a file that cannot be read is "no limit", never
 * an error, because a budget must not stop a run on a machine whose /sys
 * looks different. */
#include "core/budget.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void dfl_budget_paths_default(dfl_budget_paths *p)
{
    p->proc_cgroup = "/proc/self/cgroup";
    p->cgroup_root = "/sys/fs/cgroup";
    p->meminfo = "/proc/meminfo";
}

/* The first line of path as a limit in bytes: "max" or a value >= 2^60 is
 * no limit (v1 writes 2^63 rounded to pages for "unlimited"). */
static double read_limit(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return INFINITY;
    char line[128];
    double v = INFINITY;
    if (fgets(line, sizeof line, f)) {
        char *end;
        const double x = strtod(line, &end);
        if (end != line && x >= 0 && x < 0x1p60) v = x;
    }
    fclose(f);
    return v;
}

/* min over dir/rel/file and every ancestor of rel up to dir itself. */
static double min_up(const char *dir, const char *rel, const char *file)
{
    char path[4096], r[2048];
    snprintf(r, sizeof r, "%s", rel);
    double best = INFINITY;
    for (int guard = 0; guard < 256; guard++) {
        size_t n = strlen(r);
        while (n > 0 && r[n - 1] == '/') r[--n] = '\0';
        snprintf(path, sizeof path, "%s%s%s/%s", dir, r[0] == '/' || !r[0] ? "" : "/", r, file);
        const double v = read_limit(path);
        if (v < best) best = v;
        char *slash = strrchr(r, '/');
        if (!r[0]) break;
        if (slash) *slash = '\0';
        else r[0] = '\0';
    }
    return best;
}

static int has_memory_controller(const char *list)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save))
        if (strcmp(t, "memory") == 0) return 1;
    return 0;
}

double dfl_budget_cgroup_limit(const dfl_budget_paths *p)
{
    FILE *f = fopen(p->proc_cgroup, "r");
    if (!f) return INFINITY;
    double best = INFINITY;
    char line[4096], dir[4096];
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        char *c1 = strchr(line, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
        if (!c2) continue;
        *c1 = *c2 = '\0';
        const char *ctrl = c1 + 1, *rel = c2 + 1;
        double v = INFINITY;
        if (strcmp(line, "0") == 0 && !ctrl[0]) {
            v = min_up(p->cgroup_root, rel, "memory.max");
        } else if (has_memory_controller(ctrl)) {
            snprintf(dir, sizeof dir, "%s/memory", p->cgroup_root);
            v = min_up(dir, rel, "memory.limit_in_bytes");
        }
        if (v < best) best = v;
    }
    fclose(f);
    return best;
}

double dfl_budget_meminfo(const dfl_budget_paths *p, const char *field)
{
    FILE *f = fopen(p->meminfo, "r");
    if (!f) return NAN;
    char line[256];
    const size_t fl = strlen(field);
    double v = NAN;
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, field, fl) != 0 || line[fl] != ':') continue;
        char *end;
        const double x = strtod(line + fl + 1, &end);
        if (end == line + fl + 1 || !(x >= 0)) break;
        while (*end == ' ') end++;
        v = strncmp(end, "kB", 2) == 0 ? x * 1024.0 : x;
        break;
    }
    fclose(f);
    return v;
}

double dfl_budget_memory_default_at(const dfl_budget_paths *p)
{
    const double total = dfl_budget_meminfo(p, "MemTotal");
    const double avail = dfl_budget_meminfo(p, "MemAvailable");
    const double cg = dfl_budget_cgroup_limit(p);
    double m = total > 0 ? total : INFINITY;
    if (cg < m) m = cg;
    if (!isfinite(m)) return 4e9;
    m *= 0.5;
    if (avail > 0 && avail < m) m = avail;
    return m > 0 ? m : 4e9;
}

double dfl_budget_memory_default(void)
{
    dfl_budget_paths p;
    dfl_budget_paths_default(&p);
    return dfl_budget_memory_default_at(&p);
}

static const double class_seconds[] = {
#define X(code, name, sec) sec,
    DFL_COST_CLASSES(X)
#undef X
};

double dfl_cost_class_seconds(dfl_cost_class cls) { return class_seconds[cls]; }

/* The largest single contribution names the key a refusal points at. */
static void keep_largest(double v, double *big, const char **bsec, const char **bkey,
                         char *what, size_t size, const char *sec, const char *key,
                         const char *fmt, va_list ap)
{
    if (v > *big || !*bkey) {
        *big = v;
        *bsec = sec, *bkey = key;
        vsnprintf(what, size, fmt, ap);
    }
}

void dfl_cost_add_bytes(dfl_cost *c, const char *sec, const char *key, double bytes,
                        const char *what, ...)
{
    c->bytes += bytes;
    va_list ap;
    va_start(ap, what);
    keep_largest(bytes, &c->big_bytes, &c->mem_sec, &c->mem_key, c->mem_what,
                 sizeof c->mem_what, sec, key, what, ap);
    va_end(ap);
}

void dfl_cost_add_work(dfl_cost *c, const char *sec, const char *key, dfl_cost_class cls,
                       double n, const char *what, ...)
{
    c->evals[cls] += n;
    va_list ap;
    va_start(ap, what);
    keep_largest(n * class_seconds[cls], &c->big_seconds, &c->work_sec, &c->work_key,
                 c->work_what, sizeof c->work_what, sec, key, what, ap);
    va_end(ap);
}

static void take_mem(dfl_cost *c, const dfl_cost *b)
{
    if (b->mem_key && (b->big_bytes > c->big_bytes || !c->mem_key)) {
        c->big_bytes = b->big_bytes;
        c->mem_sec = b->mem_sec, c->mem_key = b->mem_key;
        memcpy(c->mem_what, b->mem_what, sizeof c->mem_what);
    }
}

static void add_work_of(dfl_cost *c, const dfl_cost *b)
{
    for (int k = 0; k < DFL_COST_NCLASSES; k++) c->evals[k] += b->evals[k];
    if (b->work_key && (b->big_seconds > c->big_seconds || !c->work_key)) {
        c->big_seconds = b->big_seconds;
        c->work_sec = b->work_sec, c->work_key = b->work_key;
        memcpy(c->work_what, b->work_what, sizeof c->work_what);
    }
}

void dfl_cost_add_cost(dfl_cost *c, const dfl_cost *b)
{
    c->bytes += b->bytes;
    take_mem(c, b);
    add_work_of(c, b);
}

void dfl_cost_add_step(dfl_cost *c, const dfl_cost *step)
{
    if (step->bytes > c->bytes || (!c->mem_key && step->mem_key)) {
        c->bytes = step->bytes;
        c->big_bytes = 0;
        c->mem_key = NULL;
        take_mem(c, step);
    }
    add_work_of(c, step);
}

double dfl_cost_seconds(const dfl_cost *c, int threads)
{
    double s = 0;
    for (int k = 0; k < DFL_COST_NCLASSES; k++) s += c->evals[k] * class_seconds[k];
    return s / (threads >= 1 ? threads : 1);
}
