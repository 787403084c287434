/* The list of studies.  Add a study: define `const dfl_study dfl_study_X`
 * in its own file under experiments/ and add it to the two lists below. */
#include <stdio.h>
#include <string.h>

#include "experiment.h"

extern const dfl_study dfl_study_smoke;
extern const dfl_study dfl_study_bs04_gradbounds;
extern const dfl_study dfl_study_bs04_corrected;
extern const dfl_study dfl_study_bs04_normalization;
extern const dfl_study dfl_study_bs04_fields;
extern const dfl_study dfl_study_bs04_recursive;
extern const dfl_study dfl_study_bs04_polygonization;
extern const dfl_study dfl_study_bs04_bulging;
extern const dfl_study dfl_study_bs04_scurve;
extern const dfl_study dfl_study_bs04_spacecurves;
extern const dfl_study dfl_study_bs04_triangle;
extern const dfl_study dfl_study_bs04_triedge;
extern const dfl_study dfl_study_bs04_surface;
extern const dfl_study dfl_study_bs04_hetero;

static const dfl_study *const all_studies[] = {
    &dfl_study_smoke,
    &dfl_study_bs04_gradbounds,
    &dfl_study_bs04_corrected,
    &dfl_study_bs04_normalization,
    &dfl_study_bs04_fields,
    &dfl_study_bs04_recursive,
    &dfl_study_bs04_polygonization,
    &dfl_study_bs04_bulging,
    &dfl_study_bs04_scurve,
    &dfl_study_bs04_spacecurves,
    &dfl_study_bs04_triangle,
    &dfl_study_bs04_triedge,
    &dfl_study_bs04_surface,
    &dfl_study_bs04_hetero,
    NULL,
};

const dfl_study *const *dfl_studies(void) { return all_studies; }

const dfl_study *dfl_study_find(const char *name)
{
    for (const dfl_study *const *s = all_studies; *s; s++)
        if (strcmp((*s)->name, name) == 0) return *s;
    return NULL;
}

const char *dfl_study_path(const dfl_study_ctx *ctx, const char *stem, const char *ext, char *buf,
                           size_t size)
{
    snprintf(buf, size, "%s/%s%s.%s", ctx->stage_dir, stem, ctx->tag, ext);
    return buf;
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
