#include <criterion/criterion.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/budget.h"
#include "util/tmpdir.h"

/* A fake machine under dir: /proc/self/cgroup text, meminfo text. */
static void fake(char *dir, size_t n, const char *cgroup, const char *meminfo,
                 dfl_budget_paths *p, char *pc, char *root, char *mi)
{
    tmpdir_new(dir, n);
    tmpdir_write(dir, "proc_cgroup", cgroup, pc, 4096);
    tmpdir_write(dir, "meminfo", meminfo, mi, 4096);
    snprintf(root, 4096, "%s/cg", dir);
    p->proc_cgroup = pc, p->cgroup_root = root, p->meminfo = mi;
}

static const char *MEM = "MemTotal:       16000000 kB\nMemFree:  100 kB\n"
                         "MemAvailable:   12000000 kB\n";

Test(budget, cgroup_v2_own_group_and_ancestors)
{
    char dir[64], pc[4096], root[4096], mi[4096];
    dfl_budget_paths p;
    fake(dir, sizeof dir, "0::/a/b\n", MEM, &p, pc, root, mi);
    tmpdir_write(dir, "cg/a/b/memory.max", "max\n", NULL, 0);
    cr_expect(isinf(dfl_budget_cgroup_limit(&p)), "max is no limit");
    tmpdir_write(dir, "cg/a/memory.max", "1610612736\n", NULL, 0); /* 1.5 GiB on the parent */
    cr_expect_eq(dfl_budget_cgroup_limit(&p), 1610612736.0);
    tmpdir_write(dir, "cg/a/b/memory.max", "1073741824\n", NULL, 0); /* tighter child */
    cr_expect_eq(dfl_budget_cgroup_limit(&p), 1073741824.0);
    /* half the cgroup limit, below half of MemTotal (8.2 GB) and MemAvailable */
    cr_expect_eq(dfl_budget_memory_default_at(&p), 0.5 * 1073741824.0);
    tmpdir_remove(dir);
}

Test(budget, cgroup_v2_root_file_counts_inside_a_namespace)
{
    char dir[64], pc[4096], root[4096], mi[4096];
    dfl_budget_paths p;
    fake(dir, sizeof dir, "0::/\n", MEM, &p, pc, root, mi);
    tmpdir_write(dir, "cg/memory.max", "2000000000\n", NULL, 0);
    cr_expect_eq(dfl_budget_cgroup_limit(&p), 2e9);
    tmpdir_remove(dir);
}

Test(budget, cgroup_v1_memory_line)
{
    char dir[64], pc[4096], root[4096], mi[4096];
    dfl_budget_paths p;
    fake(dir, sizeof dir, "5:cpu,cpuacct:/x\n4:memory:/job/7\n0::/\n", MEM, &p, pc, root, mi);
    /* v1 "unlimited" is 2^63 rounded down to a page */
    tmpdir_write(dir, "cg/memory/job/7/memory.limit_in_bytes", "9223372036854771712\n", NULL, 0);
    cr_expect(isinf(dfl_budget_cgroup_limit(&p)));
    tmpdir_write(dir, "cg/memory/job/memory.limit_in_bytes", "3000000000\n", NULL, 0);
    cr_expect_eq(dfl_budget_cgroup_limit(&p), 3e9);
    /* the cpu line's group is not read as a memory limit */
    tmpdir_write(dir, "cg/memory/x/memory.limit_in_bytes", "1000\n", NULL, 0);
    cr_expect_eq(dfl_budget_cgroup_limit(&p), 3e9);
    tmpdir_remove(dir);
}

Test(budget, missing_files_are_no_limit)
{
    dfl_budget_paths p = {.proc_cgroup = "/nonexistent/cg", .cgroup_root = "/nonexistent",
                          .meminfo = "/nonexistent/mi"};
    cr_expect(isinf(dfl_budget_cgroup_limit(&p)));
    cr_expect(isnan(dfl_budget_meminfo(&p, "MemTotal")));
    cr_expect_eq(dfl_budget_memory_default_at(&p), 4e9, "nothing readable: 4 GB");
}

Test(budget, meminfo_fields_and_default_without_cgroup)
{
    char dir[64], pc[4096], root[4096], mi[4096];
    dfl_budget_paths p;
    fake(dir, sizeof dir, "0::/\n", MEM, &p, pc, root, mi);
    cr_expect_eq(dfl_budget_meminfo(&p, "MemTotal"), 16000000.0 * 1024);
    cr_expect_eq(dfl_budget_meminfo(&p, "MemAvailable"), 12000000.0 * 1024);
    cr_expect(isnan(dfl_budget_meminfo(&p, "Mem")), "a prefix is not a field");
    cr_expect_eq(dfl_budget_memory_default_at(&p), 0.5 * 16000000.0 * 1024);
    tmpdir_remove(dir);
    /* a longer field that starts with the name is not the field: the name
     * must be followed by ':' */
    fake(dir, sizeof dir, "0::/\n", "MemTotalX: 77 kB\nMemTotal: 1000 kB\n", &p, pc, root, mi);
    cr_expect_eq(dfl_budget_meminfo(&p, "MemTotal"), 1000.0 * 1024);
    tmpdir_remove(dir);
    /* MemAvailable below half the total caps the default */
    fake(dir, sizeof dir, "0::/\n", "MemTotal: 1000 kB\nMemAvailable: 100 kB\n", &p, pc, root,
         mi);
    cr_expect_eq(dfl_budget_memory_default_at(&p), 100.0 * 1024);
    tmpdir_remove(dir);
}

Test(budget, cost_sums_and_names_the_largest)
{
    dfl_cost c = {0};
    dfl_cost_add_bytes(&c, "grid", "n", 100, "a grid");
    dfl_cost_add_bytes(&c, "field", "res", 1000, "%d proxies", 7);
    dfl_cost_add_bytes(&c, "eval", "n", 10, "points");
    cr_expect_eq(c.bytes, 1110);
    cr_expect_str_eq(c.mem_sec, "field");
    cr_expect_str_eq(c.mem_key, "res");
    cr_expect_str_eq(c.mem_what, "7 proxies");
    dfl_cost_add_work(&c, "eval", "n", DFL_COST_CHEAP, 1e6, "decodes");
    dfl_cost_add_work(&c, "field", "res", DFL_COST_FOOTPOINT, 10, "footpoints");
    const double s = 1e6 * dfl_cost_class_seconds(DFL_COST_CHEAP) +
                     10 * dfl_cost_class_seconds(DFL_COST_FOOTPOINT);
    cr_expect_eq(dfl_cost_seconds(&c, 1), s);
    cr_expect_eq(dfl_cost_seconds(&c, 4), s / 4);
    cr_expect_eq(dfl_cost_seconds(&c, 0), s, "threads < 1 counts as one");
    /* 1e6 cheap = 0.02 s > 10 footpoints = 1e-3 s */
    cr_expect_str_eq(c.work_key, "n");
}

/* A real cgroup v2 with memory.max = 1.5 GiB: a child moved into it reads
 * that limit through the default paths.  Needs root and a writable cgroup2
 * root with the memory controller; skips otherwise. */
Test(budget, real_cgroup_v2)
{
    char ctl[256] = "";
    FILE *f = fopen("/sys/fs/cgroup/cgroup.subtree_control", "r");
    if (f) {
        if (!fgets(ctl, sizeof ctl, f)) ctl[0] = '\0';
        fclose(f);
    }
    FILE *pcg = fopen("/proc/self/cgroup", "r");
    char own[512] = "";
    if (pcg) {
        if (!fgets(own, sizeof own, pcg)) own[0] = '\0';
        fclose(pcg);
    }
    if (geteuid() != 0 || !strstr(ctl, "memory") || strncmp(own, "0::/", 4) != 0 ||
        access("/sys/fs/cgroup/cgroup.procs", W_OK) != 0)
        cr_skip_test("needs root and a writable cgroup v2 root with the memory controller");
    char g[128];
    snprintf(g, sizeof g, "/sys/fs/cgroup/dflab-test-%ld", (long)getpid());
    if (mkdir(g, 0755) != 0) cr_skip_test("cannot create %s: %s", g, strerror(errno));
    char path[256];
    snprintf(path, sizeof path, "%s/memory.max", g);
    f = fopen(path, "w");
    int ok = f && fprintf(f, "1610612736\n") > 0;
    if (f) ok = (fclose(f) == 0) && ok;
    int fd[2];
    cr_assert_eq(pipe(fd), 0);
    const pid_t pid = ok ? fork() : -1;
    if (pid == 0) {
        close(fd[0]);
        char procs[256];
        snprintf(procs, sizeof procs, "%s/cgroup.procs", g);
        FILE *pf = fopen(procs, "w");
        if (pf) {
            fprintf(pf, "%ld\n", (long)getpid());
            fclose(pf);
        }
        double v = dfl_budget_memory_default();
        if (write(fd[1], &v, sizeof v) != (ssize_t)sizeof v) _exit(1);
        _exit(0);
    }
    close(fd[1]);
    double v = 0;
    const ssize_t got = pid > 0 ? read(fd[0], &v, sizeof v) : -1;
    close(fd[0]);
    if (pid > 0) waitpid(pid, NULL, 0);
    rmdir(g);
    cr_assert(ok, "could not set %s", path);
    cr_assert_eq(got, (ssize_t)sizeof v);
    cr_expect_leq(v, 0.5 * 1610612736.0, "default budget %g above half the cgroup's 1.5 GiB", v);
}

/* read_limit: "values >= 2^60 = no limit" (budget.h), so 2^60 itself is no
 * limit while the double just below it (2^60 - 128, written out exactly)
 * still is one. */
Test(budget, limit_of_2_pow_60_is_no_limit)
{
    char dir[64], pc[4096], root[4096], mi[4096];
    dfl_budget_paths p;
    fake(dir, sizeof dir, "0::/g\n", MEM, &p, pc, root, mi);
    tmpdir_write(dir, "cg/g/memory.max", "1152921504606846976\n", NULL, 0); /* 2^60 */
    cr_expect(isinf(dfl_budget_cgroup_limit(&p)), "2^60 is no limit");
    tmpdir_write(dir, "cg/g/memory.max", "1152921504606846848\n", NULL, 0); /* 2^60 - 128 */
    cr_expect_eq(dfl_budget_cgroup_limit(&p), 0x1p60 - 128);
    tmpdir_remove(dir);
}

/* The work key names the largest contribution in seconds (evaluations times
 * the class's time per evaluation), not in evaluations: with the table's
 * times, 1e3 footpoints outweigh 1e6 cheap evaluations. */
Test(budget, work_key_is_the_largest_in_seconds)
{
    const double cheap = 1e6 * dfl_cost_class_seconds(DFL_COST_CHEAP);
    const double foot = 1e3 * dfl_cost_class_seconds(DFL_COST_FOOTPOINT);
    cr_assert_gt(foot, cheap, "the premise: fewer footpoints take longer");
    dfl_cost c = {0};
    dfl_cost_add_work(&c, "eval", "n", DFL_COST_CHEAP, 1e6, "lookups");
    dfl_cost_add_work(&c, "case", "feet", DFL_COST_FOOTPOINT, 1e3, "footpoints");
    cr_expect_str_eq(c.work_key, "feet");
    cr_expect_str_eq(c.work_what, "footpoints");
    cr_expect_eq(c.big_seconds, foot);
}

/* add_step: steps run one after another, so the bytes are the larger of the
 * two (with that step's key) and the work adds up; add_cost: held at the
 * same time, bytes and work add up (budget.h). */
Test(budget, steps_keep_the_largest_held_costs_add_up)
{
    dfl_cost a = {0}, b = {0}, small = {0};
    dfl_cost_add_bytes(&a, "case", "a", 500, "case a");
    dfl_cost_add_work(&a, "case", "a", DFL_COST_EXACT, 100, "a");
    dfl_cost_add_bytes(&b, "case", "b", 2000, "case b");
    dfl_cost_add_work(&b, "case", "b", DFL_COST_EXACT, 300, "b");
    dfl_cost_add_bytes(&small, "case", "c", 10, "case c");
    dfl_cost_add_work(&small, "case", "c", DFL_COST_CHEAP, 7, "c");
    /* both orders: the larger step's bytes and key win */
    for (int order = 0; order < 2; order++) {
        dfl_cost seq = {0};
        dfl_cost_add_step(&seq, order ? &b : &a);
        dfl_cost_add_step(&seq, order ? &a : &b);
        dfl_cost_add_step(&seq, &small);
        cr_expect_eq(seq.bytes, 2000, "order %d", order);
        cr_expect_str_eq(seq.mem_key, "b", "order %d", order);
        cr_expect_eq(seq.evals[DFL_COST_EXACT], 400, "order %d", order);
        cr_expect_eq(seq.evals[DFL_COST_CHEAP], 7, "order %d", order);
        /* the sequence held alongside a grid: bytes add, the step still names */
        dfl_cost held = {0};
        dfl_cost_add_bytes(&held, "grid", "n", 1000, "a grid");
        dfl_cost_add_work(&held, "grid", "n", DFL_COST_EXACT, 1, "grid");
        dfl_cost_add_cost(&held, &seq);
        cr_expect_eq(held.bytes, 3000, "order %d", order);
        cr_expect_str_eq(held.mem_key, "b", "order %d", order);
        cr_expect_eq(held.evals[DFL_COST_EXACT], 401, "order %d", order);
        cr_expect_eq(held.evals[DFL_COST_CHEAP], 7, "order %d", order);
    }
}
