/* The command line's stated rules, each checked through the real binary in
 * a fresh folder (the binary runs with that folder as its working
 * directory, so relative --out names land there):
 *   usage text of `dflab run` / `dflab plan` (src/cli/main.c): --threads N
 *     in [1, 1024]; --point K >= 0 or A-B with A <= B; -j M >= 1; --commands
 *     and --emit exclude each other; a missing value or CONFIG is a usage
 *     error;
 *   exit status (main.c's header): 2 bad input, 1 a failure of the machine
 *     (out of memory, a write that fails);
 *   the results folder (src/cli/outdir.h, src/io/dirs.h): '.'/'..' and
 *     '..' after a missing folder refused, no folder under a file, a
 *     failed run removes only the folders it created, DIR is replaced only
 *     when it is new, empty or a folder whose manifest.json is dflab's
 *     (format "dflab-results" version 1, or the old {"tool": "dflab"}
 *     shape) listing every other entry, a symbolic link is refused.
 * Expected statuses and message parts are the rule's wording; the sweep
 * of every test config has two points (0 and 1). */
#define _GNU_SOURCE /* realpath, syscall */
#include <criterion/criterion.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <errno.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef RENAME_EXCHANGE
#define RENAME_EXCHANGE (1 << 1)
#endif

#include "util/e2e_util.h"

#define TWO_POINTS "[study]\nname = smoke\n[shape]\nkind = circle\ncenter = 0.5 0.5\n" \
                   "radius = 0.3\n[field]\nkind = exact\n[grid]\nn = 8, 12\n"
/* 4096^2 samples: more than a 600 MB address space holds */
#define TOO_BIG "[study]\nname = smoke\n[shape]\nkind = circle\ncenter = 0.5 0.5\n" \
                "radius = 0.3\n[field]\nkind = exact\n[grid]\nn = 4096\n"

typedef struct cli_case {
    char dir[256];
    char err[8192];
} cli_case;

static void case_new(cli_case *c)
{
    e2e_tmpdir(c->dir, sizeof c->dir);
    char p[512];
    e2e_write(c->dir, "g.ini", TWO_POINTS, p, sizeof p);
}

/* Runs `[prefix] dflab ARGS` in c->dir (stdout to `out`, or to out.txt when
 * NULL); returns the exit status, -1 when dflab did not exit (a signal);
 * stderr into c->err. */
static int run_in(cli_case *c, const char *prefix, const char *out, const char *fmt, ...)
{
    const char *bin = getenv("DFL_DFLAB") ? getenv("DFL_DFLAB") : "build/dflab";
    char abs[PATH_MAX];
    cr_assert_not_null(realpath(bin, abs), "no dflab binary at %s", bin);
    char args[2048], cmd[8192];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    snprintf(cmd, sizeof cmd, "cd '%s' && { %s '%s' %s > %s 2> '%s/err.txt'; }", c->dir,
             prefix ? prefix : "", abs, args, out ? out : "out.txt", c->dir);
    const int rc = system(cmd);
    char path[512];
    snprintf(path, sizeof path, "%s/err.txt", c->dir);
    char *e = e2e_slurp(path);
    snprintf(c->err, sizeof c->err, "%s", e ? e : "");
    free(e);
    return rc == -1 || !WIFEXITED(rc) ? -1 : WEXITSTATUS(rc);
}

static int exists(const cli_case *c, const char *rel)
{
    char p[512];
    struct stat sb;
    snprintf(p, sizeof p, "%s/%s", c->dir, rel);
    return lstat(p, &sb) == 0;
}

static void sh(const cli_case *c, const char *script)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "cd '%s' && %s", c->dir, script);
    cr_assert_eq(system(cmd), 0, "%s", script);
}

/* exit status 2, one `dflab: error:` line holding want1 and want2 */
#define EXPECT_REFUSED(c, rc, want1, want2)                                                  \
    do {                                                                                     \
        cr_expect_eq(rc, 2, "exit %d, stderr: %s", rc, (c)->err);                            \
        cr_expect(strstr((c)->err, "dflab: error: ") == (c)->err &&                          \
                      strchr((c)->err, '\n') == (c)->err + strlen((c)->err) - 1,             \
                  "not one error line: %s", (c)->err);                                       \
        cr_expect(strstr((c)->err, want1) != NULL, "lacks '%s': %s", want1, (c)->err);       \
        cr_expect(strstr((c)->err, want2) != NULL, "lacks '%s': %s", want2, (c)->err);       \
    } while (0)

Test(cli_rules, threads_is_an_integer_in_1_to_1024)
{
    cli_case c;
    case_new(&c);
    /* both ends of the range are accepted (plan validates and computes nothing) */
    cr_expect_eq(run_in(&c, NULL, NULL, "plan g.ini --threads 1 --commands"), 0, "%s", c.err);
    cr_expect_eq(run_in(&c, NULL, NULL, "plan g.ini --threads 1024 --commands"), 0, "%s", c.err);
    const char *bad[] = {"0", "1025", "-1", "4x", "", " "};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        const int rc = run_in(&c, NULL, NULL, "run g.ini --out o --quiet --threads '%s'", bad[i]);
        char want[64];
        snprintf(want, sizeof want, "--threads %s", bad[i]);
        EXPECT_REFUSED(&c, rc, want, "expected an integer in [1, 1024]");
        cr_expect(!exists(&c, "o") && !exists(&c, "o.points"), "--threads '%s' wrote", bad[i]);
    }
    e2e_rmtree(c.dir);
}

Test(cli_rules, point_is_an_index_or_a_range_a_to_b_with_a_le_b)
{
    cli_case c;
    case_new(&c);
    /* A-A is a range with A <= B: point 1 alone */
    cr_assert_eq(run_in(&c, NULL, NULL, "run g.ini --out o --quiet --point 1-1"), 0, "%s", c.err);
    cr_expect(exists(&c, "o.points/pt001") && !exists(&c, "o.points/pt000"));
    cr_expect(!exists(&c, "o"), "--point writes only DIR.points/");
    /* index 0 is a point */
    cr_assert_eq(run_in(&c, NULL, NULL, "run g.ini --out o --quiet --point 0"), 0, "%s", c.err);
    cr_expect(exists(&c, "o.points/pt000"));
    const char *bad[] = {"-1", "2-1", "1-0", "0-", "-", "1-x", "x", "", "1-1x"};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        const int rc = run_in(&c, NULL, NULL, "run g.ini --out p --quiet --point '%s'", bad[i]);
        char want[64];
        snprintf(want, sizeof want, "--point %s", bad[i]);
        EXPECT_REFUSED(&c, rc, want, "expected a point index >= 0 or a range A-B with A <= B");
        cr_expect(!exists(&c, "p") && !exists(&c, "p.points"), "--point '%s' wrote", bad[i]);
    }
    /* beyond the sweep: bad input too */
    const int rc = run_in(&c, NULL, NULL, "run g.ini --out p --quiet --point 1-2");
    EXPECT_REFUSED(&c, rc, "--point 2", "2 sweep points");
    e2e_rmtree(c.dir);
}

Test(cli_rules, plan_jobs_at_least_one_and_commands_exclude_emit)
{
    cli_case c;
    case_new(&c);
    cr_expect_eq(run_in(&c, NULL, NULL, "plan g.ini --emit parallel -j 1"), 0, "%s", c.err);
    int rc = run_in(&c, NULL, NULL, "plan g.ini --emit parallel -j 0");
    EXPECT_REFUSED(&c, rc, "-j 0", "[1, 100000]");
    rc = run_in(&c, NULL, NULL, "plan g.ini --commands --emit slurm");
    EXPECT_REFUSED(&c, rc, "--commands and --emit", "exclude each other");
    e2e_rmtree(c.dir);
}

Test(cli_rules, usage_errors_are_exit_2)
{
    cli_case c;
    case_new(&c);
    int rc = run_in(&c, NULL, NULL, "");
    cr_expect_eq(rc, 2, "no command: exit %d", rc);
    rc = run_in(&c, NULL, NULL, "frobnicate");
    EXPECT_REFUSED(&c, rc, "unknown command 'frobnicate'", "dflab help");
    rc = run_in(&c, NULL, NULL, "run");
    EXPECT_REFUSED(&c, rc, "missing CONFIG.ini", "dflab help run");
    rc = run_in(&c, NULL, NULL, "merge");
    EXPECT_REFUSED(&c, rc, "missing DIR", "dflab help merge");
    const char *last[] = {"--out", "--threads", "--point"};
    for (size_t i = 0; i < 3; i++) {
        rc = run_in(&c, NULL, NULL, "run g.ini --quiet %s", last[i]);
        char want[64];
        snprintf(want, sizeof want, "%s needs a value", last[i]);
        EXPECT_REFUSED(&c, rc, want, "dflab help run");
    }
    rc = run_in(&c, NULL, NULL, "run g.ini --out o --frobnicate");
    EXPECT_REFUSED(&c, rc, "unknown option '--frobnicate'", "dflab help run");
    rc = run_in(&c, NULL, NULL, "run g.ini other.ini --out o");
    EXPECT_REFUSED(&c, rc, "unexpected argument 'other.ini'", "dflab help run");
    cr_expect(!exists(&c, "o") && !exists(&c, "results"), "a usage error wrote results");
    e2e_rmtree(c.dir);
}

Test(cli_rules, machine_failures_are_exit_1, .timeout = 120)
{
    cli_case c;
    case_new(&c);
    /* a write to a full stdout that dflab itself sees (probe's rows: more
     * than a stdio buffer) and one only the final flush sees */
    FILE *fp;
    char p[512];
    snprintf(p, sizeof p, "%s/pts.csv", c.dir);
    cr_assert_not_null(fp = fopen(p, "w"));
    fputs("x,y\n", fp);
    for (int i = 0; i < 20000; i++) fprintf(fp, "0.%d,0.25\n", i % 10);
    fclose(fp);
    int rc = run_in(&c, NULL, "/dev/full", "probe g.ini --set grid.n=8 --points pts.csv");
    cr_expect_eq(rc, 1, "probe into a full stdout: exit %d: %s", rc, c.err);
    cr_expect(strstr(c.err, "dflab: error: ") == c.err, "%s", c.err);
    rc = run_in(&c, NULL, "/dev/full", "--version");
    cr_expect_eq(rc, 1, "--version into a full stdout: exit %d: %s", rc, c.err);
    cr_expect(strstr(c.err, "cannot write to standard output") != NULL, "%s", c.err);
    /* out of memory: exit 1, and the folders the run made (n/deep, the
     * points' parent) are gone again: "n" is a one-letter relative name,
     * so the existing ancestor is the working directory itself.  Not under
     * the sanitizer build: ASan cannot reserve its shadow memory under
     * ulimit -v */
    if (getenv("DFL_SANITIZE")) {
        e2e_rmtree(c.dir);
        return;
    }
    e2e_write(c.dir, "big.ini", TOO_BIG, p, sizeof p);
    rc = run_in(&c, "ulimit -v 600000;", NULL, "run big.ini --out n/deep/o --quiet");
    cr_expect_eq(rc, 1, "out of memory: exit %d: %s", rc, c.err);
    cr_expect(strstr(c.err, "out of memory") != NULL, "%s", c.err);
    cr_expect(!exists(&c, "n"), "a failed run left the folder n it created");
    /* an existing parent stays */
    sh(&c, "mkdir keep");
    rc = run_in(&c, "ulimit -v 600000;", NULL, "run big.ini --out keep/a/b --quiet");
    cr_expect_eq(rc, 1, "out of memory: exit %d: %s", rc, c.err);
    cr_expect(exists(&c, "keep") && !exists(&c, "keep/a"), "undo removed too much or too little");
    e2e_rmtree(c.dir);
}

/* A failed run removes only the folders it made (src/cli/outdir.h: undo
 * "removes the (empty) directories the run created above dir"): an
 * existing empty --out folder stays, whether the run fails validating
 * (before anything is made) or computing. */
Test(cli_rules, a_failed_run_keeps_an_existing_empty_out_folder)
{
    cli_case c;
    case_new(&c);
    char p[512];
    e2e_write(c.dir, "bad.ini", TWO_POINTS "nn = 3\n", p, sizeof p);
    sh(&c, "mkdir empty");
    const int rc = run_in(&c, NULL, NULL, "run bad.ini --out empty --quiet");
    EXPECT_REFUSED(&c, rc, "bad.ini:11", "[grid] nn");
    cr_expect(exists(&c, "empty"), "a failed run removed the existing folder --out named");
    e2e_rmtree(c.dir);
}

/* The same rule when the run fails computing (out of memory under a
 * ulimit): dfl_run removes only the empty folders it made itself
 * (experiments/harness/runner.c); it used to rmdir() DIR and DIR.points
 * after any failed point, also when they existed before the run. */
Test(cli_rules, a_run_failing_to_compute_keeps_an_existing_empty_out_folder, .timeout = 60)
{
    /* ASan cannot reserve its shadow memory under ulimit -v */
    if (getenv("DFL_SANITIZE")) cr_skip_test("ulimit -v under the sanitizer build");
    cli_case c;
    case_new(&c);
    char p[512];
    e2e_write(c.dir, "big.ini", TOO_BIG, p, sizeof p);
    sh(&c, "mkdir empty empty.points");
    const int rc = run_in(&c, "ulimit -v 600000;", NULL, "run big.ini --out empty --quiet");
    cr_expect_eq(rc, 1, "out of memory: exit %d: %s", rc, c.err);
    cr_expect(exists(&c, "empty"), "a failed run removed the existing folder --out named");
    cr_expect(exists(&c, "empty.points"), "a failed run removed the existing DIR.points");
    e2e_rmtree(c.dir);
}

Test(cli_rules, out_names_that_cannot_be_results_folders)
{
    cli_case c;
    case_new(&c);
    sh(&c, "cp g.ini ..ini && cp g.ini ...ini && echo x > file");
    int rc = run_in(&c, NULL, NULL, "run g.ini --out . --quiet");
    EXPECT_REFUSED(&c, rc, "--out .:", "cannot be named '.' or '..'");
    rc = run_in(&c, NULL, NULL, "run g.ini --out sub/. --quiet");
    EXPECT_REFUSED(&c, rc, "--out sub/.:", "cannot be named '.' or '..'");
    rc = run_in(&c, NULL, NULL, "run g.ini --out nonexist/../y --quiet");
    EXPECT_REFUSED(&c, rc, "--out nonexist/../y", "'..' follows nonexist");
    rc = run_in(&c, NULL, NULL, "run ...ini --quiet");
    EXPECT_REFUSED(&c, rc, "...ini", "the config's name '..' cannot name its results folder");
    rc = run_in(&c, NULL, NULL, "run ..ini --quiet");
    EXPECT_REFUSED(&c, rc, "..ini", "the config's name '.' cannot name its results folder");
    rc = run_in(&c, NULL, NULL, "run g.ini --out /// --quiet");
    EXPECT_REFUSED(&c, rc, "--out /:", "the root directory");
    rc = run_in(&c, NULL, NULL, "run g.ini --out file/sub/o --quiet");
    EXPECT_REFUSED(&c, rc, "--out file/sub/o", "file is not a directory");
    rc = run_in(&c, NULL, NULL, "run g.ini --out /proc/x --quiet");
    EXPECT_REFUSED(&c, rc, "--out /proc/x", "cannot create directories in /proc");
    cr_expect(!exists(&c, "nonexist") && !exists(&c, "y") && !exists(&c, "results") &&
              !exists(&c, "sub"), "a refused name left a folder behind");
    e2e_rmtree(c.dir);
}

/* refused (exit 2, naming `want`) and the folder's listing unchanged */
static void expect_left_alone(cli_case *c, const char *folder, const char *want)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "(find %s -printf '%%P %%y %%s\\n' | sort; cat $(find %s -type f | sort)) > before.txt",
             folder, folder);
    sh(c, cmd);
    const int rc = run_in(c, NULL, NULL, "run g.ini --out %s --quiet --force", folder);
    char want1[256];
    snprintf(want1, sizeof want1, "--out %s", folder);
    EXPECT_REFUSED(c, rc, want1, want);
    snprintf(cmd, sizeof cmd,
             "(find %s -printf '%%P %%y %%s\\n' | sort; cat $(find %s -type f | sort)) > after.txt"
             " && cmp -s before.txt after.txt",
             folder, folder);
    char full[1400];
    snprintf(full, sizeof full, "cd '%s' && %s", c->dir, cmd);
    cr_expect_eq(system(full), 0, "%s changed although refused", folder);
}

Test(cli_rules, a_folder_is_replaced_only_when_dflab_wrote_it)
{
    cli_case c;
    case_new(&c);
    /* new, then dflab's own (a stale file of the old run goes with it) */
    cr_assert_eq(run_in(&c, NULL, NULL, "run g.ini --out o --quiet"), 0, "%s", c.err);
    cr_assert(exists(&c, "o/manifest.json"));
    sh(&c, "cp -r o proto && cp -r o.points proto.points");
    sh(&c, "sed -i 's/\"name\": \"smoke.csv\"/\"name\": \"old.csv\"/' o/manifest.json"
           " && mv o/smoke.csv o/old.csv");
    cr_assert_eq(run_in(&c, NULL, NULL, "run g.ini --out o --quiet"), 0, "%s", c.err);
    cr_expect(exists(&c, "o/smoke.csv") && !exists(&c, "o/old.csv"),
              "a dflab folder was not replaced as a whole");
    /* empty: accepted */
    sh(&c, "mkdir e");
    cr_expect_eq(run_in(&c, NULL, NULL, "run g.ini --out e --quiet"), 0, "%s", c.err);
    cr_expect(exists(&c, "e/manifest.json"));
    /* the old shape (no format magic, "tool": "dflab"): accepted */
    sh(&c, "cp -r proto old && cp -r proto.points old.points && sed -i '/\"format/d' old/manifest.json"
           " && ! grep -q format old/manifest.json && grep -q '\"tool\": \"dflab\"' old/manifest.json");
    cr_expect_eq(run_in(&c, NULL, NULL, "run g.ini --out old --quiet --force"), 0, "%s", c.err);
    sh(&c, "grep -q '\"format\": \"dflab-results\"' old/manifest.json");

    /* foreign: no manifest; an entry it does not list */
    sh(&c, "mkdir web && echo '<html>' > web/index.html");
    expect_left_alone(&c, "web", "not a dflab results folder");
    sh(&c, "cp -r proto extra && echo n > extra/notes.txt");
    expect_left_alone(&c, "extra", "holds notes.txt");
    /* the magic: another format string, another version */
    sh(&c, "cp -r proto fmt && sed -i 's/\"format\": \"dflab-results\"/\"format\": \"dflab-resultz\"/'"
           " fmt/manifest.json && grep -q dflab-resultz fmt/manifest.json");
    expect_left_alone(&c, "fmt", "is not a dflab results manifest");
    sh(&c, "cp -r proto ver && sed -i 's/\"format_version\": 1,/\"format_version\": 2,/'"
           " ver/manifest.json && grep -q '\"format_version\": 2' ver/manifest.json");
    expect_left_alone(&c, "ver", "is not a dflab results manifest");
    /* the old shape written by another tool, listing every entry */
    sh(&c, "mkdir tool && echo '<html>' > tool/index.html && printf '{\"tool\": \"webpack\", "
           "\"files\": [{\"name\": \"index.html\"}]}\\n' > tool/manifest.json");
    expect_left_alone(&c, "tool", "is not a dflab results manifest");
    /* a symbolic link to a folder dflab wrote: the swap would replace the link */
    sh(&c, "ln -s proto lnk");
    const int rc = run_in(&c, NULL, NULL, "run g.ini --out lnk --quiet --force");
    EXPECT_REFUSED(&c, rc, "--out lnk", "symbolic link");
    struct stat sb;
    char p[512];
    snprintf(p, sizeof p, "%s/lnk", c.dir);
    cr_expect(lstat(p, &sb) == 0 && S_ISLNK(sb.st_mode), "the link was replaced");
    e2e_rmtree(c.dir);
}

/* "Output to stdout that did not reach it ... exit status 1, never 0"
 * (main.c): also when a write failed and a later one succeeded (a
 * transient EIO, injected by strace into dflab's first write to the
 * file), so that the final flush alone does not see it. */
Test(cli_rules, a_lost_write_to_stdout_is_exit_1, .timeout = 60)
{
    if (system("command -v strace > /dev/null 2>&1") != 0) cr_skip_test("no strace");
    cli_case c;
    case_new(&c);
    /* more than one stdio buffer (st_blksize of the file), so that a write
     * happens before exit */
    cr_assert_eq(run_in(&c, NULL, "whole.txt", "list"), 0, "%s", c.err);
    char p[512];
    snprintf(p, sizeof p, "%s/whole.txt", c.dir);
    struct stat sb;
    cr_assert(stat(p, &sb) == 0 && sb.st_size > sb.st_blksize, "list prints %ld bytes",
              (long)sb.st_size);
    char prefix[700];
    snprintf(prefix, sizeof prefix,
             "strace -qq -o /dev/null -P '%s/lost.txt' -e trace=write "
             "-e inject=write:error=EIO:when=1",
             c.dir);
    const int rc = run_in(&c, prefix, "lost.txt", "list");
    cr_expect_eq(rc, 1, "a lost write: exit %d: %s", rc, c.err);
    cr_expect(strstr(c.err, "dflab: error: cannot write to standard output") != NULL, "%s", c.err);
    e2e_rmtree(c.dir);
}

/* "an existing dst is swapped with fresh in one renameat2(RENAME_EXCHANGE)"
 * (io/dirs.h; `dflab help run`: "in one atomic swap"): where the file system
 * has the exchange, the old folder is never moved aside by rename(2) (a
 * kill then would leave no DIR).  A preloaded rename() kills dflab right
 * after it moves DIR away; a run that swaps never calls it on DIR. */
static const char kill_shim[] =
    "#define _GNU_SOURCE\n#include <dlfcn.h>\n#include <signal.h>\n#include <stdlib.h>\n"
    "#include <string.h>\n"
    "int rename(const char *from, const char *to)\n{\n"
    "    int (*real)(const char *, const char *) =\n"
    "        (int (*)(const char *, const char *))dlsym(RTLD_NEXT, \"rename\");\n"
    "    const int r = real(from, to);\n"
    "    const char *k = getenv(\"KILL_AFTER_MOVING\");\n"
    "    if (r == 0 && k && strcmp(from, k) == 0) raise(SIGKILL);\n"
    "    return r;\n}\n";

Test(cli_rules, an_existing_folder_is_swapped_in_one_exchange, .timeout = 60)
{
    /* a library preloaded ahead of the sanitizer runtime stops the process */
    if (getenv("DFL_SANITIZE")) cr_skip_test("preloading under the sanitizer build");
    if (system("command -v cc > /dev/null 2>&1") != 0) cr_skip_test("no C compiler");
    cli_case c;
    case_new(&c);
    char a[512], b[512];
    snprintf(a, sizeof a, "%s/xa", c.dir);
    snprintf(b, sizeof b, "%s/xb", c.dir);
    cr_assert(mkdir(a, 0755) == 0 && mkdir(b, 0755) == 0);
    if (syscall(SYS_renameat2, AT_FDCWD, a, AT_FDCWD, b, RENAME_EXCHANGE) != 0) {
        e2e_rmtree(c.dir);
        cr_skip_test("this file system has no RENAME_EXCHANGE (errno %d)", errno);
    }
    char p[512];
    e2e_write(c.dir, "shim.c", kill_shim, p, sizeof p);
    sh(&c, "cc -shared -fPIC -o shim.so shim.c -ldl");
    cr_assert_eq(run_in(&c, NULL, NULL, "run g.ini --out o --quiet"), 0, "%s", c.err);
    char prefix[1200];
    snprintf(prefix, sizeof prefix, "KILL_AFTER_MOVING='%s/o' LD_PRELOAD='%s/shim.so'", c.dir,
             c.dir);
    const int rc = run_in(&c, prefix, NULL, "run g.ini --out '%s/o' --quiet --force", c.dir);
    cr_expect_eq(rc, 0, "the replacement moved o aside with rename(2) (exit %d): %s", rc, c.err);
    cr_expect(exists(&c, "o/manifest.json"), "no o after the replacement");
    e2e_rmtree(c.dir);
}
