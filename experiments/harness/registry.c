/* The registry: one row per paper, each a NULL-terminated list that the
 * paper's folder defines (bs04/bs04.h, ...).  Add a paper: create
 * experiments/<paper>/ with its list and add one row to `papers` below.
 * Study names are unique across papers (tests/experiments/harness checks). */
#include <stdio.h>
#include <string.h>

#include "bs04/bs04.h"
#include "hvb25/hvb25.h"
#include "harness/experiment.h"
#include "io/path.h"
#include "sjp10/sjp10.h"
#include "smoke/smoke.h"

static const dfl_study *const *const papers[] = {
    dfl_smoke_studies,
    dfl_bs04_studies,
    dfl_sjp10_studies,
    dfl_hvb25_studies,
    NULL,
};

size_t dfl_study_count(void)
{
    size_t n = 0;
    for (const dfl_study *const *const *p = papers; *p; p++)
        for (const dfl_study *const *s = *p; *s; s++) n++;
    return n;
}

const dfl_study *dfl_study_at(size_t i)
{
    for (const dfl_study *const *const *p = papers; *p; p++)
        for (const dfl_study *const *s = *p; *s; s++)
            if (i-- == 0) return *s;
    return NULL;
}

const dfl_study *dfl_study_find(const char *name)
{
    for (const dfl_study *const *const *p = papers; *p; p++)
        for (const dfl_study *const *s = *p; *s; s++)
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
