/* The study registry: every folder's list reaches `dflab list`, names are
 * unique, lookup by name finds each study, and the folders are exactly the
 * study folders of experiments/ (so a new folder needs its one row and
 * nothing here). */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "harness/experiment.h"

Test(registry, names_unique_and_found)
{
    size_t n = dfl_study_count();
    cr_assert_gt(n, 0);
    for (size_t i = 0; i < n; i++) {
        const dfl_study *s = dfl_study_at(i);
        cr_assert_not_null(s);
        cr_assert_not_null(s->run, "%s has no run()", s->name);
        cr_assert(s->summary && s->summary[0], "%s has no summary", s->name);
        cr_assert_eq(dfl_study_find(s->name), s, "lookup of %s", s->name);
        for (size_t j = 0; j < i; j++)
            cr_assert_str_neq(dfl_study_at(j)->name, s->name, "study name %s twice", s->name);
    }
    cr_assert_null(dfl_study_at(n));
    cr_assert_null(dfl_study_find("no_such_study"));
}

/* Each folder's list is concatenated whole, in group order, and every
 * study's name begins with its folder's name. */
Test(registry, concatenates_group_lists)
{
    size_t ng;
    const dfl_study_group *g = dfl_study_groups(&ng);
    size_t total = 0;
    for (size_t k = 0; k < ng; k++)
        for (const dfl_study *const *s = g[k].studies; *s; s++) {
            cr_assert_eq(dfl_study_at(total), *s, "%s at %zu", (*s)->name, total);
            cr_assert_eq(dfl_study_find((*s)->name), *s);
            cr_assert(strncmp((*s)->name, g[k].folder, strlen(g[k].folder)) == 0,
                      "%s in the %s list", (*s)->name, g[k].folder);
            total++;
        }
    cr_assert_eq(total, dfl_study_count());
}

/* The groups are the folders of experiments/ that hold a <folder>.h list
 * (cfg/ and harness/ are glue, not study folders), one row each. */
Test(registry, one_row_per_study_folder)
{
    size_t ng;
    const dfl_study_group *g = dfl_study_groups(&ng);
    DIR *d = opendir("experiments");
    cr_assert_not_null(d, "run from the repository root");
    size_t found = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char list[600];
        snprintf(list, sizeof list, "experiments/%s/%s.h", e->d_name, e->d_name);
        struct stat st;
        if (stat(list, &st) != 0) continue;
        found++;
        size_t k = 0;
        while (k < ng && strcmp(g[k].folder, e->d_name) != 0) k++;
        cr_expect_lt(k, ng, "experiments/%s/ has no row in the registry", e->d_name);
    }
    closedir(d);
    cr_assert_eq(found, ng, "%zu study folders, %zu registry rows", found, ng);
}
