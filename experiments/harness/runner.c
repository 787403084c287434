#include "harness/runner.h"

#include <dirent.h>
#include <errno.h>
#include <libgen.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "harness/experiment.h"
#include "io/path.h"
#include "io/atomic.h"
#include "io/config.h"
#include "io/manifest.h"
#include "io/table.h"

static void remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (d) {
        struct dirent *de;
        char p[8192];
        while ((de = readdir(d))) {
            if (strcmp(de->d_name, ".") == 0 || strcmp(de->d_name, "..") == 0) continue;
            snprintf(p, sizeof p, "%s/%s", dir, de->d_name);
            remove(p);
        }
        closedir(d);
    }
    rmdir(dir);
}

static dfl_status move_all(const char *from, const char *to, dfl_err *err)
{
    DIR *d = opendir(from);
    if (!d) return dfl_err_set(err, DFL_E_IO, "%s: cannot list: %s", from, strerror(errno));
    struct dirent *de;
    char a[8192], b[8192];
    dfl_status st = DFL_OK;
    /* manifest last, so a complete manifest means complete outputs */
    while ((de = readdir(d))) {
        if (de->d_name[0] == '.' || strcmp(de->d_name, "manifest.json") == 0) continue;
        snprintf(a, sizeof a, "%s/%s", from, de->d_name);
        snprintf(b, sizeof b, "%s/%s", to, de->d_name);
        if (rename(a, b) != 0) {
            st = dfl_err_set(err, DFL_E_IO, "%s: cannot move into place: %s", b, strerror(errno));
            break;
        }
    }
    closedir(d);
    if (st != DFL_OK) return st;
    snprintf(a, sizeof a, "%s/manifest.json", from);
    snprintf(b, sizeof b, "%s/manifest.json", to);
    if (rename(a, b) != 0)
        return dfl_err_set(err, DFL_E_IO, "%s: cannot move into place: %s", b, strerror(errno));
    return DFL_OK;
}

/* "configs/paper/x.ini" -> "x" */
dfl_status dfl_run(const dfl_run_opts *o, dfl_err *err)
{
    dfl_cfg *cfg = NULL;
    dfl_status st = dfl_cfg_load(o->config, &cfg, err);
    if (st != DFL_OK) return st;
    for (int i = 0; i < o->nsets && st == DFL_OK; i++) st = dfl_cfg_set(cfg, o->sets[i], err);
    if (st != DFL_OK) {
        dfl_cfg_free(cfg);
        return st;
    }

    const char *study_name;
    st = dfl_cfg_string(cfg, "study", "name", &study_name, err);
    if (st != DFL_OK) {
        dfl_cfg_free(cfg);
        return st;
    }
    const dfl_study *study = dfl_study_find(study_name);
    if (!study) {
        dfl_cfg_reject(cfg, "study", "name", err, "unknown study '%s' (see `dflab list`)",
                       study_name);
        dfl_cfg_free(cfg); /* study_name points into cfg */
        return DFL_E_INPUT;
    }

    char stem[512], outdir[4096], stage[4200];
    dfl_path_stem(o->config, stem, sizeof stem);
    if (o->outdir)
        snprintf(outdir, sizeof outdir, "%s", o->outdir);
    else
        snprintf(outdir, sizeof outdir, "results/%s", stem);
    size_t ol = strlen(outdir);
    while (ol > 1 && outdir[ol - 1] == '/') outdir[--ol] = '\0';
    snprintf(stage, sizeof stage, "%s.stage.%ld", outdir, (long)getpid());

    /* parent of the results directory must exist for the stage rename trick */
    char parent[4096];
    snprintf(parent, sizeof parent, "%s", outdir);
    char *pd = dirname(parent);
    st = dfl_mkdir_p(pd, err);
    if (st == DFL_OK) st = dfl_mkdir_p(stage, err);
    if (st != DFL_OK) {
        dfl_cfg_free(cfg);
        return st;
    }

    dfl_table *table = dfl_table_new();
    dfl_manifest *man = dfl_manifest_new(o->config, study->name);
    if (!table || !man) {
        st = dfl_err_set(err, DFL_E_NOMEM, "out of memory");
        goto fail;
    }
    for (int i = 0; i < o->nsets; i++) dfl_manifest_note(man, "set", o->sets[i]);

    size_t np = dfl_cfg_sweep_points(cfg), na = dfl_cfg_sweep_axes(cfg);
    for (size_t a = 0; a < na; a++)
        if (strcmp(dfl_cfg_sweep_axis_name(cfg, a), "study.name") == 0) {
            st = dfl_err_set(err, DFL_E_INPUT, "%s: [study] name cannot be a sweep", o->config);
            goto fail;
        }
    /* a large sweep says what it is about to do, even with --quiet */
    if (np >= 1000) fprintf(stderr, "dflab: %s: running %zu sweep points\n", study->name, np);
    for (size_t i = 0; i < np; i++) {
        dfl_cfg *pt = NULL;
        st = dfl_cfg_sweep_point(cfg, i, &pt, err);
        if (st != DFL_OK) goto fail;
        const char *dummy;
        dfl_cfg_string(pt, "study", "name", &dummy, NULL); /* mark used */
        dfl_table_prefix_clear(table);
        char label[2048] = "";
        size_t ll = 0;
        for (size_t a = 0; a < na; a++) {
            st = dfl_table_prefix_string(table, dfl_cfg_sweep_axis_name(cfg, a),
                                         dfl_cfg_axis_value(pt, a), err);
            if (st != DFL_OK) {
                dfl_cfg_free(pt);
                goto fail;
            }
            if (ll < sizeof label)
                ll += (size_t)snprintf(label + ll, sizeof label - ll, "%s%s=%s", a ? " " : "",
                                       dfl_cfg_sweep_axis_name(cfg, a), dfl_cfg_axis_value(pt, a));
        }
        char tag[32];
        dfl_study_tag(i, np, tag, sizeof tag);
        dfl_study_ctx ctx = {.stage_dir = stage, .tag = tag, .point = i, .npoints = np,
                             .threads = o->threads};
        if (!o->quiet)
            fprintf(stderr, "dflab: %s point %zu/%zu %s\n", study->name, i + 1, np, label);
        double t0 = dfl_wall_seconds();
        st = study->run(pt, &ctx, table, err);
        if (st == DFL_OK) st = dfl_cfg_check_used(pt, err);
        double t1 = dfl_wall_seconds();
        dfl_cfg_free(pt);
        if (st != DFL_OK) {
            if (np > 1) dfl_err_prefix(err, "sweep point %zu (%s)", i, label);
            goto fail;
        }
        char step[2100];
        snprintf(step, sizeof step, "point %zu%s%s", i, ll ? ": " : "", label);
        dfl_manifest_step(man, step, t1 - t0);
    }

    {
        double t0 = dfl_wall_seconds();
        char path[8192];
        snprintf(path, sizeof path, "%s/%s.csv", stage, study->name);
        st = dfl_table_write_csv(table, path, err);
        if (st != DFL_OK) goto fail;
        snprintf(path, sizeof path, "%s/config.ini", stage);
        st = dfl_cfg_write(cfg, path, err);
        if (st != DFL_OK) goto fail;
        dfl_manifest_step(man, "write tables", dfl_wall_seconds() - t0);
        st = dfl_manifest_write(man, stage, err);
        if (st != DFL_OK) goto fail;
        st = dfl_mkdir_p(outdir, err);
        if (st != DFL_OK) goto fail;
        st = move_all(stage, outdir, err);
        if (st != DFL_OK) goto fail;
    }
    remove_dir(stage);
    if (!o->quiet) fprintf(stderr, "dflab: wrote %s/\n", outdir);
    dfl_table_free(table);
    dfl_manifest_free(man);
    dfl_cfg_free(cfg);
    return DFL_OK;

fail:
    remove_dir(stage);
    dfl_table_free(table);
    dfl_manifest_free(man);
    dfl_cfg_free(cfg);
    return st;
}
