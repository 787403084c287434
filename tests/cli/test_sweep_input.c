/* Bad input to the sweep commands (run --point, plan, merge, --out): exit
 * status 2, one error line naming what and where, nothing left behind in
 * the case directory. */
#include <criterion/criterion.h>
#include <criterion/parameterized.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "util/e2e_util.h"

#define SWEEP "[study]\nname = smoke\n[shape]\nkind = circle\ncenter = 0.5 0.5\nradius = 0.3\n" \
              "[field]\nkind = exact\n[grid]\nn = 8, 12, 16\n"

/* args: after "dflab", a printf format whose %1$s is the case directory */
typedef struct sweep_case {
    const char *name, *args, *want1, *want2;
} sweep_case;

static const sweep_case cases[] = {
    {"point out of range", "run %1$s/s.ini --point 3 --out %1$s/o", "--point 3", "3 sweep points (0..2)"},
    {"point not a number", "run %1$s/s.ini --point x --out %1$s/o", "--point x", "index"},
    {"negative point", "run %1$s/s.ini --point -1 --out %1$s/o", "--point -1", "index"},
    {"bad point value", "run %1$s/s.ini --set grid.n=8,1 --point 0 --out %1$s/o", "sweep point 1", "grid.n"},
    {"plan empty sweep item", "plan %1$s/s.ini --set grid.n=8,", "grid.n", "empty item"},
    {"plan bad value", "plan %1$s/s.ini --set grid.n=8,16,0", "sweep point 2", "[2, 4096]"},
    {"plan bad emit", "plan %1$s/s.ini --emit cron", "--emit cron", "slurm or parallel"},
    {"plan bad -j", "plan %1$s/s.ini --emit slurm -j 0", "-j 0", "[1, 100000]"},
    {"plan commands and emit", "plan %1$s/s.ini --commands --emit slurm", "--commands", "exclude"},
    {"plan bad mem", "plan %1$s/s.ini --emit slurm --mem 2GB", "--mem 2GB", "K, M, G or T"},
    {"plan mem with a blank", "plan %1$s/s.ini --emit slurm --mem '2 G'", "--mem 2 G", "K, M, G or T"},
    {"plan bad time", "plan %1$s/s.ini --emit slurm --time 'now;x'", "--time now;x", "H:M:S"},
    {"plan time without slurm", "plan %1$s/s.ini --emit parallel --time 10", "--time", "Slurm"},
    {"plan per task without emit", "plan %1$s/s.ini --points-per-task 2", "--points-per-task", "--emit"},
    {"plan per task 0", "plan %1$s/s.ini --emit slurm --points-per-task 0", "--points-per-task 0", ">= 1"},
    {"run bad range", "run %1$s/s.ini --point 2-1", "--point 2-1", "A <= B"},
    {"run range past the sweep", "run %1$s/s.ini --point 1-9", "--point 9", "out of range"},
    {"out under a file", "run %1$s/s.ini --out %1$s/s.ini/o", "--out", "not a directory"},
    {"out unwritable", "run %1$s/s.ini --out /proc/dflab-nope/o", "--out /proc/dflab-nope/o", "cannot create directories"},
    {"merge nothing", "merge %1$s/o", "o.points", "no sweep points"},
    {"out is not a results folder", "run %1$s/s.ini --out %1$s", "not a dflab results folder", "--out"},
    {"merge no dir", "merge", "missing DIR", "merge"},
};

#define NCASES (sizeof cases / sizeof cases[0])
static int case_index[NCASES];

ParameterizedTestParameters(sweep_input, table)
{
    for (size_t i = 0; i < NCASES; i++) case_index[i] = (int)i;
    return cr_make_param_array(int, case_index, NCASES);
}

ParameterizedTest(const int *ci, sweep_input, table)
{
    const sweep_case *c = &cases[*ci];
    char dir[256], path[512], args[2048];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "s.ini", SWEEP, path, sizeof path);
    snprintf(args, sizeof args, c->args, dir); /* every %1$s is the case directory */
    const int rc = e2e_dflab(dir, args);
    char *msg = e2e_err_text(dir);
    cr_assert_not_null(msg);
    cr_expect_eq(rc, 2, "[%s] exit status %d: %s", c->name, rc, msg);
    cr_expect(strstr(msg, c->want1) != NULL, "[%s] lacks '%s': %s", c->name, c->want1, msg);
    cr_expect(strstr(msg, c->want2) != NULL, "[%s] lacks '%s': %s", c->name, c->want2, msg);
    const char *e = strstr(msg, "dflab: error: ");
    cr_expect(e == msg && strchr(e, '\n') && strchr(e, '\n')[1] == '\0', "[%s] not one line: %s",
              c->name, msg);
    /* s.ini, out.txt, err.txt and nothing else (no o/, o.points/, stages) */
    cr_expect_eq(e2e_count_entries(dir), 3, "[%s] files left behind in %s", c->name, dir);
    free(msg);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* plan: the points in order (last axis fastest), the commands, the engines' jobs. */
Test(sweep_plan, points_commands_and_jobs)
{
    char dir[256], path[512], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "s.ini", SWEEP, path, sizeof path);
    snprintf(args, sizeof args, "plan %s/s.ini --set shape.radius=0.2,0.3", dir);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = e2e_slurp(path);
    cr_assert_not_null(out);
    const char *nl = strchr(out, '\n');
    cr_assert_not_null(nl);
    cr_expect_str_eq(nl + 1, "0\tshape.radius=0.2 grid.n=8\n1\tshape.radius=0.2 grid.n=12\n"
                             "2\tshape.radius=0.2 grid.n=16\n3\tshape.radius=0.3 grid.n=8\n"
                             "4\tshape.radius=0.3 grid.n=12\n5\tshape.radius=0.3 grid.n=16\n");
    free(out);
    snprintf(args, sizeof args, "plan %s/s.ini --commands --out %s/o", dir, dir);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    out = e2e_slurp(path);
    size_t lines = 0;
    for (const char *s = out; *s; s++) lines += *s == '\n';
    cr_expect_eq(lines, 4, "%s", out);
    cr_expect(strstr(out, " --point 2\n") && strstr(out, " merge "), "%s", out);
    free(out);
    snprintf(args, sizeof args, "plan %s/s.ini --emit slurm -j 2 --out %s/o", dir, dir);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    out = e2e_slurp(path);
    cr_expect(strstr(out, "\n#SBATCH --array=0-2%2\n") != NULL, "%s", out);
    /* the merge runs after the array whatever its tasks did (a failed or
     * cancelled task leaves points missing: the merge names them) */
    cr_expect(strstr(out, "task_%a.log") && strstr(out, "--dependency=afterany:"), "%s", out);
    cr_expect(strstr(out, "--point \"$a-$b\"") != NULL, "%s", out);
    /* resources: threads = cpus-per-task, memory and time from the estimate */
    cr_expect(strstr(out, "\n#SBATCH --cpus-per-task=") && strstr(out, "\n#SBATCH --mem=") &&
                  strstr(out, "\n#SBATCH --time="), "%s", out);
    free(out);
    /* given: threads, memory, time; 3 points in batches of 2: tasks 0-1 */
    snprintf(args, sizeof args, "plan %s/s.ini --emit slurm -j 2 --out %s/o --threads 3 --mem 2G "
                                "--time 1:30:00 --points-per-task 2", dir, dir);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    out = e2e_slurp(path);
    cr_expect(strstr(out, "\n#SBATCH --array=0-1%2\n") && strstr(out, "\n#SBATCH --cpus-per-task=3\n") &&
                  strstr(out, "\n#SBATCH --mem=2G\n") && strstr(out, "\n#SBATCH --time=1:30:00\n"),
              "%s", out);
    cr_expect(strstr(out, "a=$((SLURM_ARRAY_TASK_ID * 2))\nb=$((a + 1))\nif [ \"$b\" -gt 2 ]; then "
                          "b=2; fi\n"), "%s", out);
    cr_expect(strstr(out, " --threads 3 --quiet --point \"$a-$b\"\n"), "%s", out);
    free(out);
    snprintf(args, sizeof args, "plan %s/s.ini --emit parallel -j 2 --out %s/o --points-per-task 2",
             dir, dir);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    out = e2e_slurp(path);
    cr_expect(strstr(out, " --point {} ::: 0-1 2-2 && "), "%s", out);
    free(out);
    snprintf(args, sizeof args, "plan %s/s.ini --emit parallel --out %s/o", dir, dir);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    out = e2e_slurp(path);
    cr_expect(strstr(out, "--joblog") && strstr(out, "--resume-failed") &&
                  strstr(out, "::: $(seq 0 2) && "),
              "%s", out);
    free(out);
    cr_expect_eq(e2e_count_entries(dir), 3, "plan wrote files");
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* --set runs get their own folder, named from the overrides (Hydra-style). */
Test(sweep_plan, set_runs_go_to_their_own_folder)
{
    char dir[256], path[512], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "s.ini", SWEEP, path, sizeof path);
    snprintf(args, sizeof args, "plan %s/s.ini --set grid.n=8 --set 'shape.radius=0.2'", dir);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = e2e_slurp(path);
    cr_expect(strstr(out, "output results/runs/s/grid.n=8,shape.radius=0.2\n") != NULL, "%s", out);
    free(out);
    snprintf(args, sizeof args, "plan %s/s.ini", dir);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    out = e2e_slurp(path);
    cr_expect(strstr(out, "output results/s\n") != NULL, "%s", out);
    free(out);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* A subset of a list of case sections: the cases --set leaves out are the
 * config's, not unknown keys (every point validates); a typo'd section is
 * still refused. */
Test(sweep_plan, a_subset_of_cases_validates)
{
    char dir[256], path[512], args[1024];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(args, sizeof args, "plan %s/configs/paper/sjp10/sjp10_fig1.ini --set study.cases=circle",
             getcwd(path, sizeof path) ? path : ".");
    cr_expect_eq(e2e_dflab(dir, args), 0);
    snprintf(args, sizeof args, "plan %s/configs/paper/sjp10/sjp10_fig1.ini "
                                "--set 'study.cases=circle, convex'",
             getcwd(path, sizeof path) ? path : ".");
    cr_expect_eq(e2e_dflab(dir, args), 0);
    snprintf(args, sizeof args, "plan %s/configs/paper/sjp10/sjp10_fig1.ini --set study.cases=circle "
                                "--set circel.x=1", getcwd(path, sizeof path) ? path : ".");
    cr_expect_eq(e2e_dflab(dir, args), 2);
    snprintf(path, sizeof path, "%s/err.txt", dir);
    char *e = e2e_slurp(path);
    cr_expect(e && strstr(e, "circel.x: unknown key"), "%s", e ? e : "");
    free(e);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* --set S=@FILE is the same run as a config with FILE's [S] written in
 * (same CSV bytes); a switch of kind by --set drops the old kind's keys, so
 * a proxy config runs as an exact one. */
Test(sweep_plan, a_field_group_equals_the_section_written_in)
{
    char dir[256], path[512], cwd[512], args[2048];
    cr_assert_not_null(getcwd(cwd, sizeof cwd));
    e2e_tmpdir(dir, sizeof dir);
    const char *base = "[study]\nname = smoke\n[shape]\nkind = sphere\ncenter = 0.5 0.5 0.5\n"
                       "radius = 0.3\n%s[grid]\nn = 12\nlo = 0 0 0\nhi = 1 1 1\n";
    char text[1024];
    snprintf(text, sizeof text, base, "[field]\nkind = exact\n");
    e2e_write(dir, "g.ini", text, path, sizeof path);
    snprintf(text, sizeof text, base,
             "[field]\nkind = proxy\norder = 2\nres = 32\ninput = sdf\nstorage = half\n");
    e2e_write(dir, "inline.ini", text, path, sizeof path);
    snprintf(args, sizeof args, "run %s/g.ini --set field=@%s/configs/fields/proxy_o2.ini "
                                "--out %s/a --quiet", dir, cwd, dir);
    cr_assert_eq(e2e_dflab(dir, args), 0, "%s", e2e_err_text(dir));
    snprintf(args, sizeof args, "run %s/inline.ini --out %s/b --quiet", dir, dir);
    cr_assert_eq(e2e_dflab(dir, args), 0, "%s", e2e_err_text(dir));
    snprintf(path, sizeof path, "%s/a/smoke.csv", dir);
    char *a = e2e_slurp(path);
    snprintf(path, sizeof path, "%s/b/smoke.csv", dir);
    char *b = e2e_slurp(path);
    cr_assert(a && b);
    cr_expect_str_eq(a, b);
    free(a), free(b);
    /* the proxy config switched to kind = exact: its order, res, ... dropped */
    snprintf(args, sizeof args, "run %s/inline.ini --set field.kind=exact --out %s/c --quiet", dir,
             dir);
    cr_expect_eq(e2e_dflab(dir, args), 0, "%s", e2e_err_text(dir));
    snprintf(path, sizeof path, "%s/c/config.ini", dir);
    char *c = e2e_slurp(path);
    cr_expect(c && strstr(c, "[field]\nkind = exact\n\n[grid]"), "%s", c ? c : "");
    free(c);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
