/* harness: the table cell naming a file of a sweep point
 * (dfl_study_put_file) and the buffers of a sampled field
 * (dfl_field_bufs). */
#include <criterion/criterion.h>
#include <string.h>

#include "harness/experiment.h"
#include "harness/field_out.h"
#include "io/table.h"

Test(study_files, put_file_is_the_base_of_study_path)
{
    dfl_study_ctx ctx = {.stage_dir = "results/x.stage.12/sub", .tag = "_pt003", .point = 3,
                         .npoints = 5, .threads = 1};
    dfl_table *t = dfl_table_new();
    dfl_err err = {0};
    cr_assert_eq(dfl_table_row(t, &err), DFL_OK);
    cr_assert_eq(dfl_study_put_file(t, "vti", &ctx, "field_a", "vti", true, &err), DFL_OK);
    cr_assert_eq(dfl_study_put_file(t, "vtp", &ctx, "mesh", "vtp", false, &err), DFL_OK);
    cr_expect_str_eq(dfl_table_get(t, 0, "vti"), "field_a_pt003.vti");
    cr_expect_str_eq(dfl_table_get(t, 0, "vtp"), ""); /* not written: an empty cell */
    char path[256];
    const char *full = dfl_study_path(&ctx, "field_a", "vti", path, sizeof path);
    cr_expect_str_eq(full, "results/x.stage.12/sub/field_a_pt003.vti");
    cr_expect(strstr(full, dfl_table_get(t, 0, "vti")) == full + strlen(full) - 17);
    /* one point: no tag */
    ctx.tag = "";
    cr_assert_eq(dfl_study_put_file(t, "one", &ctx, "mesh", "vtp", true, &err), DFL_OK);
    cr_expect_str_eq(dfl_table_get(t, 0, "one"), "mesh.vtp");
    dfl_table_free(t);
    /* the table's failure comes through */
    t = dfl_table_new();
    cr_expect_eq(dfl_study_put_file(t, "vti", &ctx, "a", "vti", true, &err), DFL_E_INTERNAL);
    dfl_table_free(t);
}

Test(study_files, field_bufs_sizes_and_free)
{
    dfl_field_bufs b;
    cr_assert(dfl_field_bufs_alloc(&b, 1000, 3, true));
    cr_assert(b.u && b.gu && b.ref);
    /* the whole of each buffer is writable (ASan checks the bounds) */
    for (size_t i = 0; i < 1000; i++) b.u[i] = b.ref[i] = (double)i;
    for (size_t i = 0; i < 3000; i++) b.gu[i] = (double)i;
    dfl_field_bufs_free(&b);
    cr_expect(!b.u && !b.gu && !b.ref);
    dfl_field_bufs_free(&b); /* twice is safe */
    cr_assert(dfl_field_bufs_alloc(&b, 10, 2, false));
    cr_expect(b.u && b.gu && b.ref == NULL);
    for (size_t i = 0; i < 20; i++) b.gu[i] = 1.0;
    dfl_field_bufs_free(&b);
    dfl_field_bufs z = {0};
    dfl_field_bufs_free(&z); /* a zeroed struct */
}
