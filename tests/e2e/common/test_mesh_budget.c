/* The mesh shape's bytes in the budget (experiments/cfg/field_cost.h,
 * dfl_shape_cost) through the binary: a tight [study] memory_budget
 * refuses the repository's Wuson config before the mesh is read (one
 * line naming [shape] file, exit 2, no output), the default budget runs
 * it, and the peak RSS that loading Wuson and its signed queries add over
 * the same run on a sphere stays below the bound. */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cfg/field_cost.h"
#include "util/e2e_util.h"

static const char *const WUSON = "/usr/share/assimp/models/AC/Wuson.ac";

/* a smoke run of the exact field of [shape] on a 2^3 grid (8 signed
 * queries), no volume or image files */
static void write_cfg(const char *dir, const char *name, const char *shape)
{
    char ini[PATH_MAX + 512], path[600];
    snprintf(ini, sizeof ini,
             "[study]\nname = smoke\n%s[field]\nkind = exact\n[grid]\nn = 2\n"
             "lo = -0.1 -0.1 -0.1\nhi = 0.1 0.1 0.1\n[output]\nvti = false\nexr = false\n",
             shape);
    e2e_write(dir, name, ini, path, sizeof path);
}

static void wuson_cfg(const char *dir)
{
    char cwd[PATH_MAX], shape[PATH_MAX + 64];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    snprintf(shape, sizeof shape, "[shape]\ninclude = %s/configs/shapes/wuson.ini\n", cwd);
    write_cfg(dir, "w.ini", shape);
}

Test(e2e_mesh_budget, tight_budget_refuses_wuson_before_reading_it, .timeout = 120)
{
    char dir[256], args[1024], out[600];
    e2e_tmpdir(dir, sizeof dir);
    wuson_cfg(dir);
    snprintf(out, sizeof out, "%s/o", dir);
    snprintf(args, sizeof args, "run %s/w.ini --out %s --set study.memory_budget=0.1", dir, out);
    const int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_expect_eq(rc, 2, "%s", msg);
    cr_expect(strstr(msg, "wuson.ini:10: [shape] file") != NULL, "%s", msg);
    cr_expect(strstr(msg, "3.73e+03 triangles") != NULL, "the file's 3,732 triangles: %s", msg);
    cr_expect(strstr(msg, "memory budget of 0.1 GB") != NULL, "%s", msg);
    const char *nl = strchr(msg, '\n');
    cr_expect(nl && nl[1] == '\0', "one line: %s", msg);
    free(msg);
    cr_expect_eq(e2e_count_entries(out), -1, "no output directory");
    /* the budget that holds the bound runs it */
    double tris, size;
    dfl_err err;
    cr_assert_eq(dfl_mesh_file_tris_bound(WUSON, &tris, &size, &err), DFL_OK, "%s", err.msg);
    snprintf(args, sizeof args, "run %s/w.ini --out %s --set study.memory_budget=%.6f", dir, out,
             (size + dfl_mesh_bytes_bound(tris, 1)) / 1e9 + 0.01);
    cr_expect_eq(e2e_dflab(dir, args), 0);
    e2e_rmtree(dir);
}

/* The largest resident set of one dflab run (its process tree), in bytes. */
static double run_rss(const char *dir, const char *args)
{
    char path[600];
    snprintf(path, sizeof path, "%s/rss.txt", dir);
    const pid_t pid = fork();
    cr_assert_neq(pid, -1);
    if (pid == 0) {
        const int rc = e2e_dflab(dir, args);
        struct rusage ru;
        getrusage(RUSAGE_CHILDREN, &ru);
        FILE *f = fopen(path, "w");
        if (f) fprintf(f, "%ld\n", ru.ru_maxrss), fclose(f);
        _exit(rc == 0 && f ? 0 : 1);
    }
    int status;
    cr_assert_eq(waitpid(pid, &status, 0), pid);
    cr_assert(WIFEXITED(status) && WEXITSTATUS(status) == 0, "%s", args);
    char *s = e2e_slurp(path);
    cr_assert_not_null(s);
    const double kb = atof(s);
    free(s);
    return kb * 1024;
}

Test(e2e_mesh_budget, wuson_rss_growth_below_the_bound, .timeout = 300)
{
    char dir[256], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    wuson_cfg(dir);
    write_cfg(dir, "s.ini", "[shape]\nkind = sphere\ncenter = 0 0 0\nradius = 0.5\n");
    snprintf(args, sizeof args, "run %s/s.ini --out %s/os", dir, dir);
    const double base = run_rss(dir, args);
    snprintf(args, sizeof args, "run %s/w.ini --out %s/ow", dir, dir);
    const double wuson = run_rss(dir, args);
    double tris, size;
    dfl_err err;
    cr_assert_eq(dfl_mesh_file_tris_bound(WUSON, &tris, &size, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(tris, 3732.0, "Wuson's refs, each a triangle");
    const double bound = size + dfl_mesh_bytes_bound(tris, 1);
    cr_expect_leq(wuson - base, bound, "RSS growth %.4g bytes, bound %.4g", wuson - base, bound);
    cr_expect_gt(wuson - base, 0.0, "the mesh is read: %.4g", wuson - base);
    e2e_rmtree(dir);
}

/* `dflab plan` of quick.ini with only `methods` on Wuson at a 0.1 GB
 * budget, in dir: exit 2 and one stderr text holding each of want[0..n)
 * (the key, what it charged, the budget). */
static void expect_quick_plan_refused(const char *dir, const char *methods, int n,
                                      const char *const *want)
{
    char args[1024];
    snprintf(args, sizeof args,
             "plan configs/compare/quick.ini --set study.methods=%s --set "
             "study.shapes=s_wuson --set study.memory_budget=0.1 --out %s/o",
             methods, dir);
    const int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_expect_eq(rc, 2, "%s", msg);
    for (int k = 0; k < n; k++)
        cr_expect(strstr(msg, want[k]), "%s: '%s' not in %s", methods, want[k], msg);
    free(msg);
}

/* compare_methods charges the mesh with each field built on it: the exact
 * method on Wuson alone needs the mesh's bound (170 MB with the file), so
 * 0.1 GB refuses it at plan time; the default budget plans quick.ini. */
Test(e2e_mesh_budget, compare_charges_the_mesh_and_quick_fits_the_default, .timeout = 120)
{
    char dir[256], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    static const char *const want[] = {"study.methods", "[m_exact]", "memory budget of 0.1 GB"};
    expect_quick_plan_refused(dir, "m_exact", 3, want);
    snprintf(args, sizeof args, "plan configs/compare/quick.ini --out %s/o", dir);
    cr_expect_eq(e2e_dflab(dir, args), 0, "quick.ini within the default budget");
    cr_expect_eq(e2e_count_entries(dir), 2, "out.txt and err.txt only: plan writes nothing");
    e2e_rmtree(dir);
}

/* A shape no method applies to is still built for its points and
 * reference: R-functions of 2D curves on Wuson build no field, yet the
 * mesh's bound is charged (key [study] shapes). */
Test(e2e_mesh_budget, compare_charges_a_shape_without_fields, .timeout = 120)
{
    char dir[256];
    e2e_tmpdir(dir, sizeof dir);
    static const char *const want[] = {"study.shapes", "the shape [s_wuson]"};
    expect_quick_plan_refused(dir, "m_rfunc", 2, want);
    e2e_rmtree(dir);
}
