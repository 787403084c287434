/* `dflab plan`: the points of a sweep, and the jobs that run them on the
 * engines users already have (GNU parallel, a Slurm job array).  dflab
 * schedules nothing itself; every job is `dflab run --point K` and a final
 * `dflab merge`. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/sweep.h"
#include "io/path.h"
#include "io/shell.h"

#define put_sh dfl_shell_put

/* Why sbatch cannot read p whole as the value of an #SBATCH option, or
 * NULL when it can.  sbatch splits those lines at blanks, takes quotes
 * and '#' as its own syntax, and expands '%' (%j, %a, %x ...) and '\'
 * escapes in file names; a newline ends the line and starts a shell line.
 * Quoting is no way out (not every sbatch removes quotes), so such paths
 * are refused. */
static const char *sbatch_problem(const char *p)
{
    for (const unsigned char *c = (const unsigned char *)p; *c; c++) {
        if (*c == '\n') return "a newline";
        if (*c < 0x20 || *c == 0x7f) return "a control character";
        if (*c == ' ') return "a space";
        if (*c == '%') return "a '%' (sbatch expands %j, %a ... in file names)";
        if (*c == '\\') return "a backslash (sbatch's escape in file names)";
        if (*c == '"' || *c == '\'') return "a quote";
        if (*c == '#') return "a '#'";
    }
    return NULL;
}

/* A job name for Slurm: the stem with every byte outside [A-Za-z0-9._-]
 * replaced by '_' (a name is a label, not a path: nothing is lost). */
static void job_name(const char *stem, char *buf, size_t size)
{
    snprintf(buf, size, "%s", stem);
    for (char *c = buf; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
              *c == '.' || *c == '_' || *c == '-'))
            *c = '_';
}

/* s for a '#' comment line: control bytes (a newline would end the
 * comment) as '?'. */
static void put_comment(FILE *out, const char *s)
{
    for (const unsigned char *c = (const unsigned char *)s; *c; c++)
        fputc(*c < 0x20 || *c == 0x7f ? '?' : *c, out);
}

/* Absolute form of a path (jobs may start elsewhere). */
static void absolute(const char *p, char *buf, size_t size)
{
    char cwd[PATH_MAX];
    if (p[0] == '/' || !getcwd(cwd, sizeof cwd)) snprintf(buf, size, "%s", p);
    else snprintf(buf, size, "%s/%s", cwd, p);
}

/* `dflab run CONFIG --set ... --out OUT [--threads N] --quiet` without --point
 * (threads: T of the jobs, <= 0: none given). */
static void put_run(FILE *out, const dfl_plan_opts *o, const char *config, const char *outdir,
                    int threads)
{
    put_sh(out, o->exe);
    fputs(" run ", out);
    put_sh(out, config);
    for (int i = 0; i < o->run.nsets; i++) {
        fputs(" --set ", out);
        put_sh(out, o->run.sets[i]);
    }
    fputs(" --out ", out);
    put_sh(out, outdir);
    if (threads > 0) fprintf(out, " --threads %d", threads);
    fputs(" --quiet", out);
}

/* What the emitted jobs get: T threads each, K points per job, nb jobs,
 * and the Slurm resources. */
typedef struct job_shape {
    int threads;
    size_t per_task, njobs;
    char mem[64], time[64];
} job_shape;

/* T = --threads or max(1, cores / jobs at once); K, nb; --mem and --time
 * from the points' estimates unless given: the largest point's bytes
 * x 1.5 + 512 MB (the binary, libraries, slack), in MB; the slowest batch
 * (its points run one after another) on T cores x 2 + 10 minutes. */
static dfl_status shape_jobs(const dfl_plan_opts *o, const dfl_sweep *s, long m, job_shape *j,
                             dfl_err *err)
{
    const int cores = o->cores > 0 ? o->cores : 1;
    j->threads = o->run.threads > 0 ? o->run.threads : (int)(cores / m > 1 ? cores / m : 1);
    j->per_task = o->per_task > 0 ? (size_t)o->per_task : 1;
    j->njobs = (s->np + j->per_task - 1) / j->per_task;
    double big = 0, slow = 0;
    for (size_t b = 0; b < j->njobs; b++) {
        double batch = 0;
        for (size_t k = b * j->per_task; k < s->np && k < (b + 1) * j->per_task; k++) {
            double bytes, sec;
            dfl_status st = dfl_sweep_estimate(s, k, j->threads, &bytes, &sec, err);
            if (st) return st;
            if (bytes > big) big = bytes;
            batch += sec;
        }
        if (batch > slow) slow = batch;
    }
    if (o->mem) snprintf(j->mem, sizeof j->mem, "%s", o->mem);
    else snprintf(j->mem, sizeof j->mem, "%.0fM", ceil((1.5 * big + 512e6) / 1e6));
    if (o->time) snprintf(j->time, sizeof j->time, "%s", o->time);
    else snprintf(j->time, sizeof j->time, "%.0f", ceil(2 * slow / 60 + 10));
    return DFL_OK;
}

static dfl_status emit_slurm(FILE *out, const dfl_plan_opts *o, const dfl_sweep *s,
                             const char *config, const char *outdir, long m, const job_shape *j,
                             dfl_err *err)
{
    char stem[512], job[512], logs[4200], cwd[PATH_MAX];
    dfl_path_stem(config, stem, sizeof stem);
    job_name(stem, job, sizeof job);
    snprintf(logs, sizeof logs, "%s.logs", outdir);
    const char *why = sbatch_problem(logs);
    if (why)
        return dfl_err_set(err, DFL_E_INPUT,
                           "--out %s: the Slurm log folder %s holds %s, which an #SBATCH "
                           "--output line cannot carry; choose an output folder without it",
                           s->outdir, logs, why);
    if (!getcwd(cwd, sizeof cwd))
        return dfl_err_set(err, DFL_E_IO, "cannot read the working directory");
    if ((why = sbatch_problem(cwd)))
        return dfl_err_set(err, DFL_E_INPUT,
                           "--emit slurm: the working directory %s holds %s, which an #SBATCH "
                           "--chdir line cannot carry; run dflab plan from another folder",
                           cwd, why);
    fprintf(out, "#!/bin/bash\n");
    fputs("# dflab sweep of ", out);
    put_comment(out, config);
    fprintf(out, ": %zu points as a Slurm job array of %zu task%s (%zu point%s each), then a "
                 "merge job.\n", s->np, j->njobs, j->njobs == 1 ? "" : "s", j->per_task,
            j->per_task == 1 ? "" : "s");
    fprintf(out, "#   bash THIS_FILE     creates the log folder, submits the array and the merge\n"
                 "#                      (which starts when the array ends; it refuses, naming\n"
                 "#                      them, when points are missing: rerun, then merge)\n"
                 "#   sbatch THIS_FILE   submits the array only; then `dflab merge OUT`\n"
                 "# --mem and --time come from dflab's conservative estimate unless given to\n"
                 "# `dflab plan` (--mem, --time).\n");
    fprintf(out, "#SBATCH --job-name=dflab-%s\n", job);
    fprintf(out, "#SBATCH --array=0-%zu%%%ld\n", j->njobs - 1, m);
    fprintf(out, "#SBATCH --output=%s/task_%%a.log\n", logs);
    fprintf(out, "#SBATCH --ntasks=1\n");
    fprintf(out, "#SBATCH --cpus-per-task=%d\n", j->threads);
    fprintf(out, "#SBATCH --mem=%s\n", j->mem);
    fprintf(out, "#SBATCH --time=%s\n", j->time);
    fprintf(out, "#SBATCH --chdir=%s\n", cwd);
    fputs("set -euo pipefail\n", out);
    fputs("if [ -z \"${SLURM_ARRAY_TASK_ID:-}\" ]; then\n  mkdir -p ", out);
    put_sh(out, logs);
    fputs("\n  array=$(sbatch --parsable \"$0\")\n", out);
    fprintf(out, "  sbatch --parsable --dependency=afterany:\"${array%%%%;*}\" --job-name=dflab-%s-merge "
                 "--output=", job);
    put_sh(out, logs);
    fputs("/merge.log --wrap=", out);
    /* the wrapped command is one shell word, read again by sbatch's sh */
    char *cmd = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&cmd, &len);
    if (!mem) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    put_sh(mem, o->exe);
    fputs(" merge ", mem);
    put_sh(mem, outdir);
    fclose(mem);
    put_sh(out, cmd);
    free(cmd);
    fprintf(out, "\n  exit 0\nfi\n"
                 "a=$((SLURM_ARRAY_TASK_ID * %zu))\nb=$((a + %zu))\n"
                 "if [ \"$b\" -gt %zu ]; then b=%zu; fi\nexec ",
            j->per_task, j->per_task - 1, s->np - 1, s->np - 1);
    put_run(out, o, config, outdir, j->threads);
    fputs(" --point \"$a-$b\"\n", out);
    return DFL_OK;
}

/* GNU parallel joins its command words with blanks, replaces {}, {.},
 * {/} ... in them and hands the result to a shell: a name in those words
 * would be read twice and could be replaced.  So the names travel in
 * environment variables (quoted once, for the shell that runs this line)
 * and the command names only the variables. */
static void emit_parallel(FILE *out, const dfl_plan_opts *o, const dfl_sweep *s,
                          const char *config, const char *outdir, long m, const job_shape *j)
{
    char log[8400], pdir[8300];
    snprintf(pdir, sizeof pdir, "%s.points", outdir);
    snprintf(log, sizeof log, "%s/parallel.joblog", pdir);
    fputs("mkdir -p ", out);
    put_sh(out, pdir);
    fputs(" && DFLAB_EXE=", out);
    put_sh(out, o->exe);
    fputs(" DFLAB_CONFIG=", out);
    put_sh(out, config);
    fputs(" DFLAB_OUT=", out);
    put_sh(out, outdir);
    for (int i = 0; i < o->run.nsets; i++) {
        fprintf(out, " DFLAB_SET_%d=", i);
        put_sh(out, o->run.sets[i]);
    }
    fputs(" parallel --joblog ", out);
    put_sh(out, log);
    fprintf(out, " --resume-failed -j %ld '\"$DFLAB_EXE\"' run '\"$DFLAB_CONFIG\"'", m);
    for (int i = 0; i < o->run.nsets; i++) fprintf(out, " --set '\"$DFLAB_SET_%d\"'", i);
    fputs(" --out '\"$DFLAB_OUT\"'", out);
    fprintf(out, " --threads %d", j->threads);
    if (j->per_task == 1) {
        fprintf(out, " --quiet --point {} ::: $(seq 0 %zu) && ", s->np - 1);
    } else { /* the batches A-B, one word each */
        fputs(" --quiet --point {} :::", out);
        for (size_t b = 0; b < j->njobs; b++) {
            const size_t a = b * j->per_task, e = a + j->per_task - 1;
            fprintf(out, " %zu-%zu", a, e < s->np ? e : s->np - 1);
        }
        fputs(" && ", out);
    }
    put_sh(out, o->exe);
    fputs(" merge ", out);
    put_sh(out, outdir);
    fputc('\n', out);
}

dfl_status dfl_plan(const dfl_plan_opts *o, FILE *out, dfl_err *err)
{
    dfl_sweep s;
    dfl_status st = dfl_sweep_open(&o->run, &s, err);
    if (st != DFL_OK) {
        dfl_sweep_close(&s);
        return st;
    }
    char config[PATH_MAX + 8], outdir[PATH_MAX + 8];
    absolute(o->run.config, config, sizeof config);
    absolute(s.outdir, outdir, sizeof outdir);
    const long m = o->max_parallel > 0 ? o->max_parallel : 4;
    job_shape j = {0};
    if (o->emit) st = shape_jobs(o, &s, m, &j, err);
    if (st == DFL_OK && o->emit && strcmp(o->emit, "slurm") == 0) {
        st = emit_slurm(out, o, &s, config, outdir, m, &j, err);
    } else if (st == DFL_OK && o->emit) {
        emit_parallel(out, o, &s, config, outdir, m, &j);
    } else if (st == DFL_OK) {
        if (!o->commands)
        {
            fputs("# ", out);
            put_comment(out, o->run.config);
            fprintf(out, ": study %s, %zu point%s, output ", s.study->name, s.np,
                    s.np == 1 ? "" : "s");
            put_comment(out, s.outdir);
            fputc('\n', out);
        }
        for (size_t k = 0; k < s.np && st == DFL_OK; k++) {
            if (o->commands) {
                put_run(out, o, config, outdir, o->run.threads);
                fprintf(out, " --point %zu\n", k);
                continue;
            }
            dfl_cfg *pt = NULL;
            st = dfl_cfg_sweep_point(s.cfg, k, &pt, err);
            char label[2048];
            if (st == DFL_OK)
                fprintf(out, "%zu\t%s\n", k, dfl_sweep_label(&s, pt, label, sizeof label));
            dfl_cfg_free(pt);
        }
        if (o->commands && st == DFL_OK) {
            put_sh(out, o->exe);
            fputs(" merge ", out);
            put_sh(out, outdir);
            fputc('\n', out);
        }
    }
    dfl_sweep_close(&s);
    return st;
}
