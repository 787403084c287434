/* dflab command line.  Exit status: 0 success, 2 bad input (config, points
 * file, geometry, usage), 1 any other failure (I/O, numerical). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/jet.h"
#include "dfl_version.h"
#include "harness/experiment.h"
#include "io/manifest.h"
#include "harness/probe.h"
#include "harness/runner.h"

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
    "  --version\n";

static const char *const usage_run =
    "usage: dflab run CONFIG.ini [--set section.key=value]... [--out DIR] [--threads N] [--quiet]\n"
    "\n"
    "Runs the study named by [study] name.  A value holding a comma list (e.g.\n"
    "`n = 16, 32, 64`) is a sweep axis; several axes form a cartesian product, one\n"
    "CSV row (or group of rows) per sweep point with a column per swept key.\n"
    "--set overrides or adds a key (and may itself be a list).  Outputs go to DIR\n"
    "(default results/<config stem>/): <study>.csv, config.ini (resolved),\n"
    "manifest.json and the study's .vti/.vtp/.exr files; nothing is written unless\n"
    "the whole run succeeds.  Exit 2 on bad input.\n";

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
    fprintf(stderr, "dflab: error: %s\n", err->msg);
    return err->code == DFL_E_INPUT ? 2 : 1;
}

/* One line, like every other error; the usage text is one command away. */
static int usage_error(const char *msg, const char *usage)
{
    const char *cmd = usage == usage_run ? "run" : usage == usage_probe ? "probe" : "";
    fprintf(stderr, "dflab: error: %s (see `dflab help %s`)\n", msg, cmd);
    return 2;
}

static int cmd_run(int argc, char **argv)
{
    const char **sets = calloc((size_t)argc + 1, sizeof *sets);
    if (!sets) return 1;
    dfl_run_opts o = {0};
    o.sets = sets;
    char msg[512];
    int rc = 0;
    for (int i = 0; i < argc && rc == 0; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage_run, stdout);
            free(sets);
            return 0;
        } else if (strcmp(a, "--set") == 0 || strcmp(a, "--out") == 0 || strcmp(a, "--threads") == 0) {
            if (i + 1 >= argc) {
                snprintf(msg, sizeof msg, "%s needs a value", a);
                rc = usage_error(msg, usage_run);
                break;
            }
            const char *v = argv[++i];
            if (a[2] == 's') sets[o.nsets++] = v;
            else if (a[2] == 'o') o.outdir = v;
            else {
                char *end;
                long t = strtol(v, &end, 10);
                if (*end || t < 1 || t > 1024) {
                    snprintf(msg, sizeof msg, "--threads %s: expected an integer in [1, 1024]", v);
                    rc = usage_error(msg, usage_run);
                }
                o.threads = (int)t;
            }
        } else if (strncmp(a, "--set=", 6) == 0) {
            sets[o.nsets++] = a + 6;
        } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            o.quiet = 1;
        } else if (a[0] == '-') {
            snprintf(msg, sizeof msg, "unknown option '%s'", a);
            rc = usage_error(msg, usage_run);
        } else if (!o.config) {
            o.config = a;
        } else {
            snprintf(msg, sizeof msg, "unexpected argument '%s'", a);
            rc = usage_error(msg, usage_run);
        }
    }
    if (rc == 0 && !o.config) rc = usage_error("missing CONFIG.ini", usage_run);
    if (rc == 0) {
        dfl_err err;
        dfl_err_clear(&err);
        if (dfl_run(&o, &err) != DFL_OK) rc = fail(&err);
    }
    free(sets);
    return rc;
}

static int cmd_probe(int argc, char **argv)
{
    const char **sets = calloc((size_t)argc + 1, sizeof *sets);
    if (!sets) return 1;
    dfl_probe_opts o = {0};
    o.sets = sets;
    char msg[512];
    int rc = 0;
    for (int i = 0; i < argc && rc == 0; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage_probe, stdout);
            free(sets);
            return 0;
        } else if (strcmp(a, "--set") == 0 || strcmp(a, "--points") == 0 || strcmp(a, "--jet") == 0) {
            if (i + 1 >= argc) {
                snprintf(msg, sizeof msg, "%s needs a value", a);
                rc = usage_error(msg, usage_probe);
                break;
            }
            const char *v = argv[++i];
            if (a[2] == 's') sets[o.nsets++] = v;
            else if (a[2] == 'p') o.points = v;
            else {
                char *end;
                long k = strtol(v, &end, 10);
                if (*end || end == v || k < 0 || k > DFL_JET_MAX) {
                    snprintf(msg, sizeof msg, "--jet %s: expected an integer in [0, %d]", v, DFL_JET_MAX);
                    rc = usage_error(msg, usage_probe);
                }
                o.jet = (int)k;
            }
        } else if (a[0] == '-') {
            snprintf(msg, sizeof msg, "unknown option '%s'", a);
            rc = usage_error(msg, usage_probe);
        } else if (!o.config) {
            o.config = a;
        } else {
            snprintf(msg, sizeof msg, "unexpected argument '%s'", a);
            rc = usage_error(msg, usage_probe);
        }
    }
    if (rc == 0 && !o.config) rc = usage_error("missing CONFIG.ini", usage_probe);
    if (rc == 0 && !o.points) rc = usage_error("missing --points FILE.csv", usage_probe);
    if (rc == 0) {
        dfl_err err;
        dfl_err_clear(&err);
        if (dfl_probe(&o, stdout, &err) != DFL_OK) rc = fail(&err);
    }
    free(sets);
    return rc;
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

int main(int argc, char **argv)
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
    fprintf(stderr, "dflab: error: unknown command '%s'\n%s", cmd, usage_main);
    return 2;
}
