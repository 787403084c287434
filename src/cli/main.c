/* dflab command line.  Exit status: 0 success, 2 bad input (config, points
 * file, geometry, usage, an unusable --out), 1 any other failure (I/O such
 * as a full disk or a closed stdout, out of memory, numerical). */
#include <limits.h>
#include <omp.h>
#include <stdarg.h>
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/isa.h"
#include "core/jet.h"
#include "dfl_version.h"
#include "harness/experiment.h"
#include "io/manifest.h"
#include "io/path.h"
#include "harness/help.h"
#include "harness/meaning.h"
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
    "        [--point K] [--force]\n"
    "        run the study the config names; a comma list in a value is a sweep axis\n"
    "  plan CONFIG.ini [--set ...]... [--out DIR] [--commands | --emit slurm|parallel] [-j M]\n"
    "        the sweep points, one command per point, or a Slurm array / GNU parallel job\n"
    "  merge DIR   assemble the points run with --point into what one run writes\n"
    "  probe CONFIG.ini --points FILE.csv [--field SECTION] [--jet K] [--set ...]...\n"
    "        evaluate the config's [field] at points; CSV on stdout\n"
    "  list  studies and the configs that use them\n"
    "  help [COMMAND | STUDY [CONFIG.ini] [--columns]]   this text, a command's help, the\n"
    "        keys a study reads (meaning, value, range; through CONFIG), or its columns\n"
    "  --version\n"
    "\n"
    "environment: DFL_ISA=sse2|avx2|avx512 runs the hot kernels compiled for that\n"
    "instruction set (default: the widest this CPU runs); results are the same\n"
    "bytes on every one.  An unknown value, or one this CPU does not run, is exit 2.\n"
    "\n"
    "exit status: 0 success; 2 bad input (config, points file, geometry, usage,\n"
    "an unusable --out such as a file, / or a place where no directory can be\n"
    "made); 1 a failure of the machine (disk full, stdout closed or full, out of\n"
    "memory) or of a numerical method.  Every failure prints one line\n"
    "`dflab: error: ...` on stderr (non-printable bytes as \\xNN) and leaves no\n"
    "output behind -- but for one: a table that holds a point whose value was\n"
    "not finite (NaN or inf: an error of +inf, counted in its `nonfinite`\n"
    "columns) is written, then the run exits 1 naming table, row, column and\n"
    "count, unless the config says `[study] allow_nonfinite = true`.\n";

static const char *const usage_run =
    "usage: dflab run CONFIG.ini [--set section.key=value]... [--out DIR] [--threads N] [--quiet]\n"
    "                [--point K] [--force]\n"
    "\n"
    "Runs the study named by [study] name.  A value holding a comma list (e.g.\n"
    "`n = 16, 32, 64`) is a sweep axis; several axes form a cartesian product\n"
    "(last axis fastest; `dflab plan` lists the points).  Every CSV gets a `point`\n"
    "column and one column per swept key.  --set overrides or adds a key (and may\n"
    "itself be a list); --set S.kind=K to a new kind drops the file's other keys\n"
    "of [S] (the old kind's); --set S=@FILE replaces [S] by FILE's [S] (a group,\n"
    "e.g. --set field=@configs/fields/proxy_o2.ini).  Outputs go to DIR: default\n"
    "results/<config stem>/, or\n"
    "results/runs/<config stem>/<overrides>/ when --set is given.  DIR holds\n"
    "<study>.csv, config.ini (resolved), manifest.json and the study's .vti/.vtp/.exr\n"
    "files; DIR.points/ptNNN/ holds each committed sweep point.  Every point is\n"
    "validated before any computes; each is committed when it completes, and a\n"
    "rerun skips points whose config and dflab binary match (--force recomputes)\n"
    "and whose files all have the size and sha256 their point.json records: a point\n"
    "with a changed or missing file is recomputed (a note names the file), one with\n"
    "a malformed point.json, a file it does not list or a non-regular entry (FIFO,\n"
    "folder, link) is exit 2.  `dflab merge DIR` recomputes nothing: it refuses any\n"
    "such point with exit 2 naming the file.  Merged files are copies, never links.\n"
    "DIR is replaced as a whole when the run succeeds (in one atomic swap), and only\n"
    "when it is new, empty or a folder dflab wrote: its manifest.json is dflab's and\n"
    "lists every other entry; anything else is refused (exit 2) and left alone.\n"
    "DIR cannot end in . or ..  --point K runs only point K\n"
    "into DIR.points/ (for job arrays); `dflab merge DIR` then assembles DIR.\n"
    "--point A-B runs points A..B one after another (a batch: one process,\n"
    "one validation).  Progress goes to stderr at most every 2 s (--quiet: none).  --threads N: OpenMP\n"
    "threads (default: OMP_NUM_THREADS, else every core); results are the same bytes\n"
    "at any N.  Exit 2 on bad input (incl. an unusable --out), 1 on machine failures\n"
    "(see `dflab help`).\n";

static const char *const usage_plan =
    "usage: dflab plan CONFIG.ini [--set section.key=value]... [--out DIR] [--threads T]\n"
    "                 [--commands | --emit slurm | --emit parallel] [-j M]\n"
    "                 [--points-per-task K] [--mem MEM] [--time TIME]\n"
    "\n"
    "Validates every sweep point and prints them (index, then every swept\n"
    "section.key=value).  --commands prints one `dflab run ... --point K` line per\n"
    "point and the `dflab merge` line.  --emit slurm prints an sbatch script for a\n"
    "job array (#SBATCH --array=0-(J-1)%M, a log per task in DIR.logs/); `bash` it\n"
    "to submit the array and a merge job that runs when the array has ended\n"
    "(afterany: also after a failed or cancelled task; the merge then refuses,\n"
    "naming the missing points).  --emit parallel prints the GNU parallel line\n"
    "(--joblog, --resume-failed: rerun it after a failure or kill).  -j M: at most M\n"
    "jobs at once (default 4).  Each job runs K points (--points-per-task, default\n"
    "1) in one process (`--point A-B`) with --threads T (default: this machine's\n"
    "cores / M, at least 1; Slurm: --cpus-per-task=T).  Slurm --mem (default: the\n"
    "largest point's estimated memory x 1.5 + 512 MB) and --time (default: the\n"
    "slowest job's estimated time on T cores x 2 + 10 minutes; dflab's estimates\n"
    "are conservative, see [study] memory_budget / work_budget).  Every name and\n"
    "path in an emitted script is quoted.  Exit 2 on bad input.\n";

static const char *const usage_merge =
    "usage: dflab merge DIR [--quiet]\n"
    "\n"
    "Assembles DIR.points/ptNNN/ (written by `dflab run CONFIG --point K --out DIR`)\n"
    "into DIR exactly as a one-process run writes it.  Refuses (exit 2) when a point\n"
    "is missing, claimed twice, or comes from another config or dflab binary.\n";

static const char *const usage_probe =
    "usage: dflab probe CONFIG.ini --points FILE.csv [--field SECTION] [--jet K]\n"
    "                  [--set section.key=value]...\n"
    "\n"
    "Evaluates the field defined by the config's [field] section (--field SECTION:\n"
    "that section instead, e.g. field_alpha90; exit 2 when the config has none;\n"
    "[shape] for kind = exact) at the points of FILE.csv (header x,y[,z]; with\n"
    "--jet also dx,dy[,dz]).  Prints CSV x,y,z,value,gx,gy,gz[,d1..dK] on stdout,\n"
    "where dk is the exact k-th derivative of s -> u(x + s*dir) at s = 0+.  Exit 2\n"
    "on bad input.  Sections [field] (when the study does not read it) and\n"
    "[field_NAME] are the probe's: the runner checks their keys, studies ignore them.\n";

static const char *const usage_list =
    "usage: dflab list\n\nLists the studies and the configs that name them: those under ./configs/,\n"
    "or, from any other folder, under the configs/ beside the dflab binary's folder.\n";

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
    const char *cmd = usage == usage_run     ? "run"
                      : usage == usage_probe ? "probe"
                      : usage == usage_plan  ? "plan"
                      : usage == usage_merge ? "merge"
                                             : "";
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
    if (rc == 0 && !*config)
        rc = usage_error(spec->usage, spec->usage == usage_merge ? "missing DIR" : "missing CONFIG.ini");
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
    } else if (strcmp(opt, "--point") == 0) {
        char *end;
        const long k = strtol(v, &end, 10);
        long last = k;
        if (*end == '-' && end != v) { /* a batch A-B */
            char *e2;
            last = strtol(end + 1, &e2, 10);
            if (*e2 || e2 == end + 1 || last < k) end = (char *)"x";
            else end = e2;
        }
        if (*end || end == v || k < 0)
            return usage_error(usage_run, "--point %s: expected a point index >= 0 or a range "
                                          "A-B with A <= B (see `dflab plan`)", v);
        o->point = k;
        o->point_last = last;
        o->has_point = 1;
    } else if (strcmp(opt, "--force") == 0) {
        o->force = 1;
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
        if (strcmp(stem, ".") == 0 || strcmp(stem, "..") == 0) { /* results/.. is the cwd */
            dfl_err_set(&err, DFL_E_INPUT, "%s: the config's name '%s' cannot name its results "
                        "folder; rename the config or give --out", o->config, stem);
            return fail(&err);
        }
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
    } else if (strcmp(opt, "--field") == 0) {
        o->field = v;
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

static int cmd_run(int argc, char **argv, const char *cmdline)
{
    static const char *const valued[] = {"--out", "--threads", "--point", NULL};
    static const char *const flags[] = {"--quiet", "-q", "--force", NULL};
    static const cmd_spec spec = {usage_run, valued, flags, take_run, exec_run};
    dfl_run_opts o = {.cmdline = cmdline};
    return command(argc, argv, &spec, &o, &o.config, &o.sets, &o.nsets);
}

static int take_plan(void *opts, const char *opt, const char *v)
{
    dfl_plan_opts *o = opts;
    if (strcmp(opt, "--emit") == 0) {
        if (strcmp(v, "slurm") != 0 && strcmp(v, "parallel") != 0)
            return usage_error(usage_plan, "--emit %s: expected slurm or parallel", v);
        o->emit = v;
    } else if (strcmp(opt, "-j") == 0) {
        char *end;
        const long m = strtol(v, &end, 10);
        if (*end || end == v || m < 1 || m > 100000)
            return usage_error(usage_plan, "-j %s: expected an integer in [1, 100000]", v);
        o->max_parallel = m;
    } else if (strcmp(opt, "--points-per-task") == 0) {
        char *end;
        const long k = strtol(v, &end, 10);
        if (*end || end == v || k < 1 || k > 100000000)
            return usage_error(usage_plan, "--points-per-task %s: expected an integer >= 1", v);
        o->per_task = k;
    } else if (strcmp(opt, "--mem") == 0) {
        /* sbatch's form: an integer with an optional unit K, M, G or T */
        size_t n = strspn(v, "0123456789");
        if (n == 0 || n > 12 || (v[n] && (strchr("KMGT", v[n]) == NULL || v[n + 1])))
            return usage_error(usage_plan, "--mem %s: expected an integer with an optional unit "
                                           "K, M, G or T (sbatch --mem)", v);
        o->mem = v;
    } else if (strcmp(opt, "--time") == 0) {
        /* sbatch's forms: minutes, M:S, H:M:S, D-H, D-H:M, D-H:M:S */
        if (!v[0] || strspn(v, "0123456789:-") != strlen(v) || strlen(v) > 20 || !isdigit((unsigned char)v[0]))
            return usage_error(usage_plan, "--time %s: expected sbatch's time: minutes, "
                                           "H:M:S or D-H:M:S", v);
        o->time = v;
    } else if (strcmp(opt, "--commands") == 0) {
        o->commands = 1;
    } else if (strcmp(opt, "--quiet") != 0 && strcmp(opt, "-q") != 0) {
        return take_run(&o->run, opt, v); /* --out, --threads */
    }
    return 0;
}

static int exec_plan(void *opts)
{
    dfl_plan_opts *o = opts;
    if (o->commands && o->emit)
        return usage_error(usage_plan, "--commands and --emit exclude each other");
    if ((o->mem || o->time || o->per_task) && !o->emit)
        return usage_error(usage_plan, "--mem, --time and --points-per-task shape emitted jobs: "
                                       "give --emit slurm|parallel");
    if ((o->mem || o->time) && strcmp(o->emit, "slurm") != 0)
        return usage_error(usage_plan, "--mem and --time are Slurm's: give --emit slurm");
    const long cores = sysconf(_SC_NPROCESSORS_ONLN);
    o->cores = cores > 0 ? (int)cores : 1;
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    exe[n > 0 ? n : 0] = '\0';
    o->exe = n > 0 ? exe : "dflab";
    dfl_err err;
    dfl_err_clear(&err);
    return dfl_plan(o, stdout, &err) == DFL_OK ? 0 : fail(&err);
}

static int cmd_plan(int argc, char **argv)
{
    static const char *const valued[] = {"--out", "--threads", "--emit", "-j", "--points-per-task",
                                         "--mem", "--time", NULL};
    static const char *const flags[] = {"--commands", "--quiet", "-q", NULL};
    static const cmd_spec spec = {usage_plan, valued, flags, take_plan, exec_plan};
    dfl_plan_opts o = {0};
    return command(argc, argv, &spec, &o, &o.run.config, &o.run.sets, &o.run.nsets);
}

typedef struct merge_opts {
    const char *dir, *cmdline;
    int quiet;
    const char *const *sets;
    int nsets;
} merge_opts;

static int take_merge(void *opts, const char *opt, const char *v)
{
    (void)opt, (void)v;
    ((merge_opts *)opts)->quiet = 1; /* --quiet, -q */
    return 0;
}

static int exec_merge(void *opts)
{
    const merge_opts *o = opts;
    if (o->nsets) return usage_error(usage_merge, "--set does not apply to merge");
    dfl_err err;
    dfl_err_clear(&err);
    return dfl_merge(o->dir, o->quiet, o->cmdline, &err) == DFL_OK ? 0 : fail(&err);
}

static int cmd_merge(int argc, char **argv, const char *cmdline)
{
    static const char *const none[] = {NULL};
    static const char *const flags[] = {"--quiet", "-q", NULL};
    static const cmd_spec spec = {usage_merge, none, flags, take_merge, exec_merge};
    merge_opts o = {.cmdline = cmdline};
    int rc = command(argc, argv, &spec, &o, &o.dir, &o.sets, &o.nsets);
    return rc;
}

static int cmd_probe(int argc, char **argv)
{
    static const char *const valued[] = {"--points", "--jet", "--field", NULL};
    static const char *const none[] = {NULL};
    static const cmd_spec spec = {usage_probe, valued, none, take_probe, exec_probe};
    dfl_probe_opts o = {0};
    return command(argc, argv, &spec, &o, &o.config, &o.sets, &o.nsets);
}

/* The configs folder: ./configs when there is one, else the one beside the
 * dflab binary's folder (build/dflab -> configs/), so `dflab list` works
 * from any folder. */
static void configs_root(char *buf, size_t size)
{
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (access("configs", R_OK | X_OK) == 0 || n <= 0) {
        snprintf(buf, size, "configs");
        return;
    }
    exe[n] = '\0';
    if (!dfl_path_beside(exe, "../configs", buf, size)) snprintf(buf, size, "configs");
}

/* Scans the configs folder for `name = <study>` lines under [study]; prints
 * each (indented) when out is not NULL, and keeps the first (configs/paper
 * sorts first among the folders that name studies) in first. */
static void list_configs_for(const char *study, FILE *out, char *first, size_t size)
{
    char root[4096], cmd[4300];
    configs_root(root, sizeof root);
    if (first && size) first[0] = '\0';
    snprintf(cmd, sizeof cmd, "find '%s' -name '*.ini' 2>/dev/null | LC_ALL=C sort", root);
    FILE *p = popen(cmd, "r");
    if (!p) return;
    char path[4096];
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
        if (hit && out) fprintf(out, "    %s\n", path);
        if (hit && first && !first[0]) snprintf(first, size, "%s", path);
    }
    pclose(p);
}

static int cmd_list(void)
{
    for (size_t i = 0; i < dfl_study_count(); i++) {
        const dfl_study *s = dfl_study_at(i);
        printf("%-28s %s\n", s->name, s->summary);
        list_configs_for(s->name, stdout, NULL, 0);
    }
    return 0;
}

/* `dflab help STUDY [CONFIG] [--columns]`: the study's keys through CONFIG
 * (default: the first config under configs/ that uses it), or its column
 * glossary. */
static int cmd_help_study(const dfl_study *s, int argc, char **argv)
{
    char config[4096] = "";
    int columns = 0;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--columns") == 0) columns = 1;
        else if (!config[0] && argv[i][0] != '-') snprintf(config, sizeof config, "%s", argv[i]);
        else {
            char esc[1024];
            fprintf(stderr, "dflab: error: help %s: unexpected argument '%s' (expected CONFIG.ini "
                            "or --columns)\n", s->name, dfl_text_escape(argv[i], esc, sizeof esc));
            return 2;
        }
    }
    if (columns) return dfl_study_columns(s, stdout) ? 0 : 2;
    if (!config[0]) list_configs_for(s->name, NULL, config, sizeof config);
    if (!config[0]) {
        fprintf(stderr, "dflab: error: help %s: no config under configs/ names this study\n",
                s->name);
        return 2;
    }
    dfl_err err;
    dfl_err_clear(&err);
    return dfl_study_help(s, config, stdout, &err) == DFL_OK ? 0 : fail(&err);
}

/* The command line for manifests, arguments with blanks or quotes quoted. */
static void join_args(int argc, char **argv, char *buf, size_t size)
{
    size_t n = 0;
    buf[0] = '\0';
    for (int i = 0; i < argc && n < size; i++) {
        const int q = !argv[i][0] || strpbrk(argv[i], " \t'\"\\$*?;&|<>()") != NULL;
        n += (size_t)snprintf(buf + n, size - n, q ? "%s'%s'" : "%s%s", i ? " " : "", argv[i]);
    }
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
    /* DFL_ISA (core/isa.h) is input: a bad value stops every command
     * before it computes anything. */
    dfl_isa isa;
    dfl_err err;
    if (dfl_isa_from_env(&isa, &err) != DFL_OK) {
        fprintf(stderr, "dflab: error: %s\n", err.msg);
        return 2;
    }
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
        const dfl_study *study = dfl_study_find(t);
        if (study) return cmd_help_study(study, argc - 3, argv + 3);
        static const char *const topics[] = {"", "run", "probe", "list", "plan", "merge",
                                             "help", "--help", "-h"};
        int known = 0;
        for (size_t i = 0; i < sizeof topics / sizeof topics[0]; i++)
            known |= strcmp(t, topics[i]) == 0;
        if (!known) {
            char esc[1024];
            fprintf(stderr, "dflab: error: help: no command or study '%s' (see `dflab list`)\n",
                    dfl_text_escape(t, esc, sizeof esc));
            return 2;
        }
        fputs(strcmp(t, "run") == 0     ? usage_run
              : strcmp(t, "probe") == 0 ? usage_probe
              : strcmp(t, "list") == 0  ? usage_list
              : strcmp(t, "plan") == 0  ? usage_plan
              : strcmp(t, "merge") == 0 ? usage_merge
                                        : usage_main,
              stdout);
        return 0;
    }
    if (strcmp(cmd, "--version") == 0) {
        printf("dflab %s (%s)\n", DFL_VERSION, DFL_GIT_REV);
        return 0;
    }
    char cmdline[8192];
    join_args(argc, argv, cmdline, sizeof cmdline);
    if (strcmp(cmd, "run") == 0) return cmd_run(argc - 2, argv + 2, cmdline);
    if (strcmp(cmd, "plan") == 0) return cmd_plan(argc - 2, argv + 2);
    if (strcmp(cmd, "merge") == 0) return cmd_merge(argc - 2, argv + 2, cmdline);
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
