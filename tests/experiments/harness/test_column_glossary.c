/* The column glossary (`dflab help STUDY --columns`, harness/meaning.h)
 * against the real tables: every study of the registry is run through the
 * binary on one of its configs under configs/ (made small with --set; the
 * columns do not depend on the sizes), and the header of its <study>.csv
 * must be covered exactly:
 *   - every column has an entry (its own, or one every table shares: point,
 *     the swept <section>.<key>, vti), and
 *   - every entry of the study's own names at least one column,
 * where an entry's * and <...> (slice<k>, <section>.<key>) stand for any
 * text.  A study without a row in runs[] fails too, so a new study brings
 * its glossary and its run.  The runs together take ~15 s on 2 cores. */
#include <criterion/criterion.h>
#include <fnmatch.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness/experiment.h"
#include "harness/meaning.h"
#include "util/e2e_util.h"

typedef struct run_spec {
    const char *study, *cfg, *extra;
} run_spec;

/* One run per study: a config that makes the study write every column it
 * has (sweeps that reach the columns some rows lack: rconj p = 1's n/a row
 * and the smooth trims' trim_limit, the uniform and pht rows of sjp10, the
 * measured and skipped rows of compare_methods), shrunk by --set. */
static const run_spec runs[] = {
    {"smoke", "configs/smoke/smoke.ini", "--set grid.n=11"},
    {"bs04_gradbounds", "configs/paper/bs04/bs04_gradbounds.ini",
     "--set study.alpha=60 --set study.p=2 --set study.parts=disk --set study.samples=720"
     " --set study.fig5_nphi=11"},
    {"bs04_corrected", "configs/paper/bs04/bs04_corrected.ini",
     "--set study.alpha=60 --set study.p=2 --set study.parts=disk --set grid.n=21"
     " --set study.sector_nr=4 --set study.sector_nt=3"},
    {"bs04_normalization", "configs/paper/bs04/bs04_normalization.ini",
     "--set 'field.p=1, 2' --set study.fan=3"},
    {"bs04_fields", "configs/paper/bs04/bs04_fields.ini",
     "--set grid.n=21 --set 'field.trim=disk, disk_smooth'"},
    {"bs04_recursive", "configs/paper/bs04/bs04_recursive.ini",
     "--set grid.n=21 --set field.m=2 --set implicit.b=0.5 --set study.points=8"},
    {"bs04_polygonization", "configs/paper/bs04/bs04_polygonization.ini", NULL},
    {"bs04_bulging", "configs/paper/bs04/bs04_bulging.ini",
     "--set study.p=2 --set study.steps=32 --set study.rounds=3"
     " --set collinear_disk.rays=21 --set collinear_strip.rays=21 --set W_fig2.rays=21"
     " --set collinear_disk.cap_rays=4 --set collinear_strip.cap_rays=4"
     " --set W_fig2.cap_rays=4 --set grid_collinear.n=21 --set grid_W.n=21"},
    {"bs04_scurve", "configs/paper/bs04/bs04_scurve.ini",
     "--set field.eps=1e-2 --set field.join=requiv --set study.rays=21 --set study.cap_rays=4"
     " --set grid.n=21 --set study.steps=16 --set study.rounds=3"},
    {"bs04_spacecurves", "configs/paper/bs04/bs04_spacecurves.ini",
     "--set study.trim=disk --set grid.n=8 --set study.slice_n=8"},
    {"bs04_triangle", "configs/paper/bs04/bs04_triangle.ini",
     "--set study.vertices=0 --set study.radii=1e-3 --set study.samples=100"
     " --set study.slice_n=8 --set study.theory_samples=1000"},
    {"bs04_triedge", "configs/paper/bs04/bs04_triedge.ini",
     "--set study.dihedral=90 --set study.p=2 --set study.samples=360 --set study.slice_n=8"},
    {"bs04_surface", "configs/paper/bs04/bs04_surface.ini",
     "--set field.eps=0.5 --set field.p=2 --set study.slice_n=8"},
    {"bs04_hetero", "configs/paper/bs04/bs04_hetero.ini", "--set grid.n=21 --set field.p=2"},
    {"sjp10_fig1", "configs/paper/sjp10/sjp10_fig1.ini",
     "--set study.cases=circle --set fit.eps=1e-2 --set fit.max_level=4 --set study.val_n=21"
     " --set study.image_n=11 --set study.graph_n=11"},
    {"sjp10_cells", "configs/paper/sjp10/sjp10_cells.ini",
     "--set study.cases=circle --set study.eps=1e-2 --set study.uniform_levels=2"
     " --set study.val_n=21 --set fit.max_level=4"},
    {"sjp10_offsets", "configs/paper/sjp10/sjp10_offsets.ini",
     "--set fit.eps=1e-2 --set fit.max_level=4 --set fit3.eps=0.3 --set fit3.max_level=2"
     " --set fit3.samples=2 --set convex_off.grid_n=41 --set nonconvex_off.grid_n=41"
     " --set tip_off.grid_n=41 --set torus_off.grid_n=9 --set convex_off.offset_samples=400"
     " --set nonconvex_off.offset_samples=400 --set tip_off.offset_samples=400"},
    {"sjp10_3d", "configs/paper/sjp10/sjp10_3d.ini",
     "--set study.eps=0.3 --set study.uniform_levels=2 --set fit.max_level=2 --set fit.samples=2"
     " --set sphere_case.val_n=9 --set torus_case.val_n=9 --set torus_implicit_case.val_n=9"
     " --set genus2_case.val_n=5 --set goursat_case.val_n=5 --set torus_case.eps=0.3"
     " --set torus_implicit_case.eps=0.3 --set genus2_case.eps=0.3 --set goursat_case.eps=1"},
    {"hvb25_accuracy", "configs/paper/hvb25/hvb25_table1_sphere.ini",
     "--set field.res=8 --set field.order=1 --set field.input=sdf --set eval.n=21"},
    {"hvb25_render", "configs/paper/hvb25/hvb25_fig10.ini",
     "--set camera.width=16 --set camera.height=16 --set field.res=8"},
    {"compare_methods", "configs/compare/quick.ini",
     "--set 'study.shapes=s_convex s_torus' --set compare.grid2d=21 --set compare.grid3d=9"
     " --set compare.surface=200 --set compare.medial_draws=2000 --set compare.pairs=200"
     " --set compare.repeats=1"},
};

static const run_spec *run_of(const char *study)
{
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++)
        if (strcmp(runs[i].study, study) == 0) return &runs[i];
    return NULL;
}

/* An entry's name as a pattern: <...> becomes *. */
static bool entry_matches(const char *entry, const char *col)
{
    char pat[256];
    size_t j = 0;
    for (const char *e = entry; *e && j + 1 < sizeof pat; e++) {
        if (*e == '<') {
            pat[j++] = '*';
            while (*e && *e != '>') e++;
            if (!*e) break;
        } else {
            pat[j++] = *e;
        }
    }
    pat[j] = '\0';
    return fnmatch(pat, col, 0) == 0;
}

/* The header of path split at the commas into cols (malloc'ed copies of
 * the names); returns the count (0 when unreadable). */
static size_t csv_header(const char *path, char **cols, size_t max)
{
    FILE *fp = fopen(path, "r");
    if (!fp) return 0;
    static char line[1 << 16];
    size_t n = 0;
    if (fgets(line, sizeof line, fp)) {
        line[strcspn(line, "\r\n")] = '\0';
        for (char *s = line; n < max;) {
            const size_t k = strcspn(s, ",");
            const char q = s[k];
            s[k] = '\0';
            cols[n++] = strdup(s);
            if (!q) break;
            s += k + 1;
        }
    }
    fclose(fp);
    return n;
}

/* Runs study's row of runs[] and checks its table against the glossary;
 * returns the number of columns checked. */
static size_t check_study(const char *study)
{
    const run_spec *r = run_of(study);
    cr_expect(r, "%s: no run in runs[] of %s", study, __FILE__);
    if (!r) return 0;
    char dir[256], out[512], csv[800];
    e2e_tmpdir(dir, sizeof dir);
    const int rc = e2e_run_cfg(dir, r->cfg, r->extra, out, sizeof out);
    char *err = e2e_err_text(dir);
    cr_expect_eq(rc, 0, "%s: dflab run %s %s: exit %d: %s", study, r->cfg,
                 r->extra ? r->extra : "", rc, err ? err : "");
    free(err);
    snprintf(csv, sizeof csv, "%s/%s.csv", out, study);
    char *cols[1024];
    const size_t ncols = csv_header(csv, cols, sizeof cols / sizeof cols[0]);
    cr_expect_gt(ncols, 1, "%s: no header in %s", study, csv);

    /* the glossary as `dflab help STUDY --columns` prints it */
    const char *col, *meaning;
    bool own;
    size_t nown = 0;
    for (size_t i = 0; dfl_study_column(study, i, &col, &meaning, &own); i++) {
        cr_expect(meaning && meaning[0], "%s: entry %s has no meaning", study, col);
        if (!own) continue;
        nown++;
        bool used = false;
        for (size_t c = 0; c < ncols && !used; c++) used = entry_matches(col, cols[c]);
        cr_expect(used, "%s: glossary entry '%s' names no column of %s (%s %s)", study, col,
                  csv, r->cfg, r->extra ? r->extra : "");
    }
    cr_expect_gt(nown, 0, "%s: no column glossary", study);
    for (size_t c = 0; c < ncols; c++) {
        bool found = false;
        for (size_t i = 0; !found && dfl_study_column(study, i, &col, &meaning, &own); i++)
            found = entry_matches(col, cols[c]);
        cr_expect(found, "%s: column '%s' of %s has no glossary entry "
                  "(experiments/harness/meaning.c columns[])", study, cols[c], csv);
        free(cols[c]);
    }
    /* and the command a researcher types prints it */
    char args[256];
    snprintf(args, sizeof args, "help %s --columns", study);
    cr_expect_eq(e2e_dflab(dir, args), 0, "%s: dflab %s", study, args);
    e2e_rmtree(dir);
    return ncols;
}

Test(column_glossary, every_study_csv_matches_its_glossary, .timeout = 400)
{
    const size_t n = dfl_study_count();
    size_t total = 0;
    for (size_t i = 0; i < n; i++) total += check_study(dfl_study_at(i)->name);
    cr_expect_gt(total, 600, "%zu columns checked", total);
    /* no row of runs[] for a study that is gone */
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++)
        cr_expect(dfl_study_find(runs[i].study), "runs[] names no study '%s'", runs[i].study);
}

/* The matching the check relies on, and that it can fail. */
Test(column_glossary, entry_patterns)
{
    cr_expect(entry_matches("*_band", "l1_band"));
    cr_expect(entry_matches("<section>.<key>", "field.res"));
    cr_expect_not(entry_matches("<section>.<key>", "field_res"));
    cr_expect(entry_matches("slice<k>", "slice0"));
    cr_expect(entry_matches("*_s<k>_band", "count_s1_band"));
    cr_expect_not(entry_matches("l1", "l1_band"));
    cr_expect_not(entry_matches("band_nodes_<i>", "band_1"));
    const char *col, *meaning;
    bool own;
    cr_expect_not(dfl_study_column("no_such_study", 0, &col, &meaning, &own) && own);
}
