/* The registry: one row per study folder (a paper, or compare/), each its
 * folder name and the NULL-terminated list that the folder defines
 * (bs04/bs04.h, ...).  Add a folder: create experiments/<folder>/ with its
 * list and add one row to `groups` below.  Study names are unique and
 * begin with their folder's name (tests/experiments/harness checks every
 * row, whatever the rows are). */
#include <stdio.h>
#include <string.h>

#include "bs04/bs04.h"
#include "compare/compare.h"
#include "hvb25/hvb25.h"
#include "harness/experiment.h"
#include "io/path.h"
#include "sjp10/sjp10.h"
#include "smoke/smoke.h"

static const dfl_study_group groups[] = {
    {"smoke", dfl_smoke_studies},
    {"bs04", dfl_bs04_studies},
    {"sjp10", dfl_sjp10_studies},
    {"hvb25", dfl_hvb25_studies},
    {"compare", dfl_compare_studies},
};
#define NGROUPS (sizeof groups / sizeof groups[0])

const dfl_study_group *dfl_study_groups(size_t *count)
{
    *count = NGROUPS;
    return groups;
}

size_t dfl_study_count(void)
{
    size_t n = 0;
    for (size_t g = 0; g < NGROUPS; g++)
        for (const dfl_study *const *s = groups[g].studies; *s; s++) n++;
    return n;
}

const dfl_study *dfl_study_at(size_t i)
{
    for (size_t g = 0; g < NGROUPS; g++)
        for (const dfl_study *const *s = groups[g].studies; *s; s++)
            if (i-- == 0) return *s;
    return NULL;
}

const dfl_study *dfl_study_find(const char *name)
{
    for (size_t g = 0; g < NGROUPS; g++)
        for (const dfl_study *const *s = groups[g].studies; *s; s++)
            if (strcmp((*s)->name, name) == 0) return *s;
    return NULL;
}

const char *dfl_study_path(const dfl_study_ctx *ctx, const char *stem, const char *ext, char *buf,
                           size_t size)
{
    snprintf(buf, size, "%s/%s%s.%s", ctx->stage_dir, stem, ctx->tag, ext);
    return buf;
}

dfl_status dfl_study_put_file(dfl_table *t, const char *col, const dfl_study_ctx *ctx,
                              const char *stem, const char *ext, bool written, dfl_err *err)
{
    char path[4400];
    const char *name = written ? dfl_path_base(dfl_study_path(ctx, stem, ext, path, sizeof path))
                               : "";
    return dfl_table_set_string(t, col, name, err);
}

const char *dfl_study_tag(size_t point, size_t npoints, char *buf, size_t size)
{
    if (npoints > 1)
        snprintf(buf, size, "_pt%03zu", point);
    else if (size)
        buf[0] = '\0';
    return buf;
}

const char *dfl_study_path_at(const dfl_study_ctx *ctx, size_t point, const char *stem,
                              const char *ext, char *buf, size_t size)
{
    char tag[32];
    dfl_study_tag(point, ctx->npoints, tag, sizeof tag);
    snprintf(buf, size, "%s/%s%s.%s", ctx->stage_dir, stem, tag, ext);
    return buf;
}
