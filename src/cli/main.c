/* dflab command line.  Exit status: 0 success, 2 bad input (config, points
 * file, geometry, usage, an unusable --out), 1 any other failure (I/O such
 * as a full disk or a closed stdout, out of memory, numerical). */
#include <limits.h>
#include <omp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/jet.h"
#include "dfl_version.h"
#include "harness/experiment.h"
#include "io/manifest.h"
#include "harness/probe.h"
#include "harness/runner.h"
#include "io/lines.h"
#include "io/path.h"
#include "outdir.h"

static const char *const usage_main =
    "usage: dflab <command> [options]\n"
    "\n"
    "commands:\n"
    "  run CONFIG.ini [--set section.key=value]... [--out DIR] [--threads N] [--quiet]\n"
    "        run the study the config names; a comma list in a value is a sweep axis\n"
    "  probe CONFIG.ini --points FILE.csv [--jet K] [--set section.key=value]...\n"
    "        evaluate the config's [field] at points; CSV on stdout\n"
    "  list  studies and the configs that use them\n"
    "  help [COMMAND]   this text, or a command's help\n"
    "  --version\n"
    "\n"
    "exit status: 0 success; 2 bad input (config, points file, geometry, usage,\n"
    "an unusable --out such as a file, / or a place where no directory can be\n"
    "made); 1 a failure of the machine (disk full, stdout closed or full, out of\n"
    "memory) or of a numerical method.  Every failure prints one line\n"
    "`dflab: error: ...` on stderr (non-printable bytes as \\xNN) and leaves no\n"
    "output behind.\n";

static const char *const usage_run =
    "usage: dflab run CONFIG.ini [--set section.key=value]... [--out DIR] [--threads N] [--quiet]\n"
    "\n"
    "Runs the study named by [study] name.  A value holding a comma list (e.g.\n"
    "`n = 16, 32, 64`) is a sweep axis; several axes form a cartesian product, one\n"
    "CSV row (or group of rows) per sweep point with a column per swept key.\n"
    "--set overrides or adds a key (and may itself be a list).  Outputs go to DIR\n"
    "(default results/<config stem>/): <study>.csv, config.ini (resolved),\n"
    "manifest.json and the study's .vti/.vtp/.exr files; nothing is written unless\n"
    "the whole run succeeds.  --threads N: OpenMP threads (default: OMP_NUM_THREADS,\n"
    "else every core); results are the same bytes at any N.  Exit 2 on bad input\n"
    "(incl. an unusable --out), 1 on machine failures (see `dflab help`).\n";

static const char *const usage_probe =
    "usage: dflab probe CONFIG.ini --points FILE.csv [--jet K] [--set section.key=value]...\n"
    "\n"
    "Evaluates the field defined by the config's [field] section (and [shape]) at\n"
    "the points of FILE.csv (header x,y[,z]; with --jet also dx,dy[,dz]).  Prints\n"
    "CSV x,y,z,value,gx,gy,gz[,d1..dK] on stdout, where dk is the exact k-th\n"
    "derivative of s -> u(x + s*dir) at s = 0+.  Exit 2 on bad input.\n";

static const char *const usage_list = "usage: dflab list\n\nLists the studies and the configs under configs/ that name them.\n";

static int fail(const dfl_err *err)
{
    /* the message may quote input bytes: escaped, so it stays one line */
    char esc[4 * DFL_ERR_MSG_MAX];
    fprintf(stderr, "dflab: error: %s\n", dfl_text_escape(err->msg, esc, sizeof esc));
    return err->code == DFL_E_INPUT ? 2 : 1;
}

/* One line, like every other error; the usage text is one command away. */
static int usage_error(const char *usage, const char *fmt, ...)
{
    const char *cmd = usage == usage_run ? "run" : usage == usage_probe ? "probe" : "";
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    char esc[4 * sizeof msg];
    fprintf(stderr, "dflab: error: %s (see `dflab help %s`)\n",
            dfl_text_escape(msg, esc, sizeof esc), cmd);
    return 2;
}

/* One command: its usage text, its options besides what every command takes
 * (--help, -h, --set V, --set=V and the config path), and what it does. */
typedef struct cmd_spec {
    const char *usage;
    const char *const *valued;  /* options followed by a value, NULL-terminated */
    const char *const *flags;   /* options without a value, NULL-terminated */
    /* Stores option opt (its value v, NULL for a flag) into the command's
     * options; returns 0, or 2 after reporting a usage error. */
    int (*take)(void *opts, const char *opt, const char *v);
    /* Runs the command on its parsed options; returns the exit status. */
    int (*exec)(void *opts);
} cmd_spec;

static int listed(const char *const *names, const char *a)
{
    for (; *names; names++)
        if (strcmp(*names, a) == 0) return 1;
    return 0;
}

/* Parses a command's arguments up to the first error: the config path into
 * *config, each --set value into sets (room for argc entries) and *nsets,
 * the spec's options through spec->take(opts, ...).  Returns 0, 2 after
 * reporting a usage error, or -1 when --help printed the usage. */
static int parse_args(int argc, char **argv, const cmd_spec *spec, void *opts,
                      const char **config, const char **sets, int *nsets)
{
    int rc = 0;
    for (int i = 0; i < argc && rc == 0; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(spec->usage, stdout);
            return -1;
        } else if (strcmp(a, "--set") == 0 || listed(spec->valued, a)) {
            if (i + 1 >= argc) return usage_error(spec->usage, "%s needs a value", a);
            const char *v = argv[++i];
            if (a[2] == 's') sets[(*nsets)++] = v;
            else rc = spec->take(opts, a, v);
        } else if (strncmp(a, "--set=", 6) == 0) {
            sets[(*nsets)++] = a + 6;
        } else if (listed(spec->flags, a)) {
            rc = spec->take(opts, a, NULL);
        } else if (a[0] == '-') {
            rc = usage_error(spec->usage, "unknown option '%s'", a);
        } else if (!*config) {
            *config = a;
        } else {
            rc = usage_error(spec->usage, "unexpected argument '%s'", a);
        }
    }
    if (rc == 0 && !*config) rc = usage_error(spec->usage, "missing CONFIG.ini");
    return rc;
}

/* Parses argv into opts (whose config, sets and nsets fields are passed
 * apart) and runs the command; returns the exit status. */
static int command(int argc, char **argv, const cmd_spec *spec, void *opts, const char **config,
                   const char *const **sets, int *nsets)
{
    const char **list = calloc((size_t)argc + 1, sizeof *list);
    if (!list) return 1;
    *sets = list;
    int rc = parse_args(argc, argv, spec, opts, config, list, nsets);
    if (rc == 0) rc = spec->exec(opts);
    free(list);
    return rc < 0 ? 0 : rc;
}

static int take_run(void *opts, const char *opt, const char *v)
{
    dfl_run_opts *o = opts;
    if (strcmp(opt, "--out") == 0) {
        o->outdir = v;
    } else if (strcmp(opt, "--threads") == 0) {
        char *end;
        const long t = strtol(v, &end, 10);
        if (*end || t < 1 || t > 1024)
            return usage_error(usage_run, "--threads %s: expected an integer in [1, 1024]", v);
        o->threads = (int)t;
    } else {
        o->quiet = 1; /* --quiet, -q */
    }
    return 0;
}

static int exec_run(void *opts)
{
    dfl_run_opts *o = opts;
    dfl_err err;
    dfl_err_clear(&err);
    /* --threads is the one control: every parallel region of the run
     * (also those that take no thread count) uses it */
    if (o->threads > 0) omp_set_num_threads(o->threads);
    else o->threads = omp_get_max_threads();
    char def[600], stem[512];
    if (!o->outdir) {
        dfl_path_stem(o->config, stem, sizeof stem);
        snprintf(def, sizeof def, "results/%s", stem);
    }
    dfl_outdir_guard g;
    if (dfl_outdir_check(o->outdir ? o->outdir : def, &g, &err) != DFL_OK) return fail(&err);
    if (dfl_run(opts, &err) == DFL_OK) return 0;
    dfl_outdir_undo(&g);
    return fail(&err);
}

static int take_probe(void *opts, const char *opt, const char *v)
{
    dfl_probe_opts *o = opts;
    if (strcmp(opt, "--points") == 0) {
        o->points = v;
    } else { /* --jet */
        /* The range is core/jet.h's; the message is the CLI's, since it
         * also answers text that is not an integer. */
        char *end;
        const long k = strtol(v, &end, 10);
        if (*end || end == v || k < INT_MIN || k > INT_MAX ||
            dfl_jet_check_order((int)k, NULL) != DFL_OK)
            return usage_error(usage_probe, "--jet %s: expected an integer in [0, %d]", v,
                               DFL_JET_MAX);
        o->jet = (int)k;
    }
    return 0;
}

static int exec_probe(void *opts)
{
    const dfl_probe_opts *o = opts;
    if (!o->points) return usage_error(usage_probe, "missing --points FILE.csv");
    dfl_err err;
    dfl_err_clear(&err);
    return dfl_probe(o, stdout, &err) == DFL_OK ? 0 : fail(&err);
}

static int cmd_run(int argc, char **argv)
{
    static const char *const valued[] = {"--out", "--threads", NULL};
    static const char *const flags[] = {"--quiet", "-q", NULL};
    static const cmd_spec spec = {usage_run, valued, flags, take_run, exec_run};
    dfl_run_opts o = {0};
    return command(argc, argv, &spec, &o, &o.config, &o.sets, &o.nsets);
}

static int cmd_probe(int argc, char **argv)
{
    static const char *const valued[] = {"--points", "--jet", NULL};
    static const char *const none[] = {NULL};
    static const cmd_spec spec = {usage_probe, valued, none, take_probe, exec_probe};
    dfl_probe_opts o = {0};
    return command(argc, argv, &spec, &o, &o.config, &o.sets, &o.nsets);
}

/* Scans configs/ (two levels) for `name = <study>` lines under [study]. */
static void list_configs_for(const char *study)
{
    FILE *p = popen("find configs -name '*.ini' 2>/dev/null | sort", "r");
    if (!p) return;
    char path[1024];
    while (fgets(path, sizeof path, p)) {
        path[strcspn(path, "\n")] = '\0';
        FILE *fp = fopen(path, "r");
        if (!fp) continue;
        char line[1024];
        int in_study = 0, hit = 0;
        while (fgets(line, sizeof line, fp)) {
            char *s = line;
            while (*s == ' ' || *s == '\t') s++;
            if (*s == '[') in_study = strncmp(s, "[study]", 7) == 0;
            else if (in_study && strncmp(s, "name", 4) == 0) {
                char *eq = strchr(s, '=');
                if (!eq) continue;
                eq++;
                while (*eq == ' ') eq++;
                size_t n = strcspn(eq, " \t\r\n#");
                if (n == strlen(study) && strncmp(eq, study, n) == 0) hit = 1;
            }
        }
        fclose(fp);
        if (hit) printf("    %s\n", path);
    }
    pclose(p);
}

static int cmd_list(void)
{
    for (size_t i = 0; i < dfl_study_count(); i++) {
        const dfl_study *s = dfl_study_at(i);
        printf("%-28s %s\n", s->name, s->summary);
        list_configs_for(s->name);
    }
    return 0;
}

/* Output to stdout that did not reach it (a closed or full stdout) is a
 * failure of the machine: exit status 1, never 0. */
static int flushed(int rc)
{
    if ((fflush(stdout) != 0 || ferror(stdout)) && rc == 0) {
        fprintf(stderr, "dflab: error: cannot write to standard output\n");
        return 1;
    }
    return rc;
}

/* libgomp reads OMP_WAIT_POLICY once, when it loads, before main: so the
 * passive default (idle threads sleep instead of spinning, which on a busy
 * machine made small runs crawl) is set by running dflab again with it in
 * the environment.  A user's own OMP_WAIT_POLICY is left alone. */
static void passive_omp(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT")) return;
    /* under valgrind /proc/self/exe is the tool, not dflab: no re-exec */
    const char *pre = getenv("LD_PRELOAD");
    if (pre && strstr(pre, "vgpreload")) return;
    if (setenv("OMP_WAIT_POLICY", "PASSIVE", 1) != 0) return;
    execv("/proc/self/exe", argv);
    /* exec failed: carry on with the active default */
}

static int dispatch(int argc, char **argv);

int main(int argc, char **argv)
{
    passive_omp(argv);
    return flushed(dispatch(argc, argv));
}

static int dispatch(int argc, char **argv)
{
    if (argc < 2) {
        fputs(usage_main, stderr);
        return 2;
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0) {
        fputs(usage_main, stdout);
        return 0;
    }
    if (strcmp(cmd, "help") == 0) {
        const char *t = argc > 2 ? argv[2] : "";
        fputs(strcmp(t, "run") == 0     ? usage_run
              : strcmp(t, "probe") == 0 ? usage_probe
              : strcmp(t, "list") == 0  ? usage_list
                                        : usage_main,
              stdout);
        return 0;
    }
    if (strcmp(cmd, "--version") == 0) {
        printf("dflab %s (%s)\n", DFL_VERSION, DFL_GIT_REV);
        return 0;
    }
    if (strcmp(cmd, "run") == 0) return cmd_run(argc - 2, argv + 2);
    if (strcmp(cmd, "probe") == 0) return cmd_probe(argc - 2, argv + 2);
    if (strcmp(cmd, "list") == 0) {
        if (argc > 2 && (strcmp(argv[2], "--help") == 0 || strcmp(argv[2], "-h") == 0)) {
            fputs(usage_list, stdout);
            return 0;
        }
        return cmd_list();
    }
    char esc[1024];
    fprintf(stderr, "dflab: error: unknown command '%s' (see `dflab help`)\n",
            dfl_text_escape(cmd, esc, sizeof esc));
    return 2;
}
