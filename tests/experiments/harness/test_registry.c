/* The study registry: every paper's list reaches `dflab list`, names are
 * unique, and lookup by name finds each study. */
#include <criterion/criterion.h>
#include <string.h>

#include "bs04/bs04.h"
#include "harness/experiment.h"
#include "hvb25/hvb25.h"
#include "sjp10/sjp10.h"
#include "smoke/smoke.h"

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

/* Each paper's list is concatenated whole: the registry holds exactly the
 * studies of the per-paper lists. */
Test(registry, concatenates_paper_lists)
{
    const dfl_study *const *lists[] = {dfl_smoke_studies, dfl_bs04_studies, dfl_sjp10_studies,
                                       dfl_hvb25_studies};
    size_t total = 0;
    for (size_t l = 0; l < sizeof lists / sizeof lists[0]; l++)
        for (const dfl_study *const *s = lists[l]; *s; s++) {
            cr_assert_eq(dfl_study_find((*s)->name), *s);
            total++;
        }
    cr_assert_eq(total, dfl_study_count());
    for (const dfl_study *const *s = dfl_bs04_studies; *s; s++)
        cr_assert(strncmp((*s)->name, "bs04_", 5) == 0, "%s in the bs04 list", (*s)->name);
    for (const dfl_study *const *s = dfl_hvb25_studies; *s; s++)
        cr_assert(strncmp((*s)->name, "hvb25_", 6) == 0, "%s in the hvb25 list", (*s)->name);
    for (const dfl_study *const *s = dfl_sjp10_studies; *s; s++)
        cr_assert(strncmp((*s)->name, "sjp10_", 6) == 0, "%s in the sjp10 list", (*s)->name);
}
