/* `dflab plan`: the points of a sweep, and the jobs that run them on the
 * engines users already have (GNU parallel, a Slurm job array).  dflab
 * schedules nothing itself; every job is `dflab run --point K` and a final
 * `dflab merge`. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/sweep.h"
#include "io/path.h"

/* s quoted for a POSIX shell (as is when it needs no quotes). */
static void put_sh(FILE *out, const char *s)
{
    if (*s && strspn(s, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./=,:+-@%") ==
                  strlen(s)) {
        fputs(s, out);
        return;
    }
    fputc('\'', out);
    for (; *s; s++) {
        if (*s == '\'') fputs("'\\''", out);
        else fputc(*s, out);
    }
    fputc('\'', out);
}

/* Absolute form of a path (jobs may start elsewhere). */
static void absolute(const char *p, char *buf, size_t size)
{
    char cwd[PATH_MAX];
    if (p[0] == '/' || !getcwd(cwd, sizeof cwd)) snprintf(buf, size, "%s", p);
    else snprintf(buf, size, "%s/%s", cwd, p);
}

/* `dflab run CONFIG --set ... --out OUT [--threads N] --quiet` without --point. */
static void put_run(FILE *out, const dfl_plan_opts *o, const char *config, const char *outdir)
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
    if (o->run.threads > 0) fprintf(out, " --threads %d", o->run.threads);
    fputs(" --quiet", out);
}

static void emit_slurm(FILE *out, const dfl_plan_opts *o, const dfl_sweep *s, const char *config,
                       const char *outdir, long m)
{
    char stem[512], logs[4200];
    dfl_path_stem(config, stem, sizeof stem);
    snprintf(logs, sizeof logs, "%s.logs", outdir);
    fprintf(out, "#!/bin/bash\n");
    fprintf(out, "# dflab sweep of %s: %zu points as a Slurm job array, then a merge job.\n",
            config, s->np);
    fprintf(out, "#   bash THIS_FILE     creates the log folder, submits the array and the merge\n"
                 "#                      (which starts when every task succeeded)\n"
                 "#   sbatch THIS_FILE   submits the array only; then `dflab merge OUT`\n");
    fprintf(out, "#SBATCH --job-name=dflab-%s\n", stem);
    fprintf(out, "#SBATCH --array=0-%zu%%%ld\n", s->np - 1, m);
    fprintf(out, "#SBATCH --output=%s/point_%%a.log\n", logs);
    fprintf(out, "#SBATCH --ntasks=1\n");
    if (o->run.threads > 0) fprintf(out, "#SBATCH --cpus-per-task=%d\n", o->run.threads);
    char cwd[PATH_MAX];
    if (getcwd(cwd, sizeof cwd)) {
        fputs("#SBATCH --chdir=", out);
        put_sh(out, cwd);
        fputc('\n', out);
    }
    fputs("set -euo pipefail\n", out);
    fputs("if [ -z \"${SLURM_ARRAY_TASK_ID:-}\" ]; then\n  mkdir -p ", out);
    put_sh(out, logs);
    fputs("\n  array=$(sbatch --parsable \"$0\")\n", out);
    fprintf(out, "  sbatch --parsable --dependency=afterok:\"${array%%%%;*}\" --job-name=dflab-%s-merge "
                 "--output=", stem);
    put_sh(out, logs);
    fputs("/merge.log --wrap=", out);
    /* the wrapped command is one shell word */
    char *cmd = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&cmd, &len);
    if (mem) {
        put_sh(mem, o->exe);
        fputs(" merge ", mem);
        put_sh(mem, outdir);
        fclose(mem);
        put_sh(out, cmd);
        free(cmd);
    }
    fputs("\n  exit 0\nfi\nexec ", out);
    put_run(out, o, config, outdir);
    fputs(" --point \"$SLURM_ARRAY_TASK_ID\"\n", out);
}

static void emit_parallel(FILE *out, const dfl_plan_opts *o, const dfl_sweep *s,
                          const char *config, const char *outdir, long m)
{
    char log[8400], pdir[8300];
    snprintf(pdir, sizeof pdir, "%s.points", outdir);
    snprintf(log, sizeof log, "%s/parallel.joblog", pdir);
    fputs("mkdir -p ", out);
    put_sh(out, pdir);
    fputs(" && parallel --joblog ", out);
    put_sh(out, log);
    fprintf(out, " --resume-failed -j %ld ", m);
    put_run(out, o, config, outdir);
    fprintf(out, " --point {} ::: $(seq 0 %zu) && ", s->np - 1);
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
    if (o->emit && strcmp(o->emit, "slurm") == 0) {
        emit_slurm(out, o, &s, config, outdir, m);
    } else if (o->emit) {
        emit_parallel(out, o, &s, config, outdir, m);
    } else {
        if (!o->commands)
            fprintf(out, "# %s: study %s, %zu point%s, output %s\n", o->run.config,
                    s.study->name, s.np, s.np == 1 ? "" : "s", s.outdir);
        for (size_t k = 0; k < s.np && st == DFL_OK; k++) {
            if (o->commands) {
                put_run(out, o, config, outdir);
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
