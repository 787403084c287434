#include <criterion/criterion.h>
#include <openexr.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/exr.h"
#include "io/meta_attrs.h"
#include "io/vtk.h"
#include "util/e2e_util.h"

static const char *names[] = {"dflab_study", "dflab_sweep"};
static const char *values[] = {"smoke", "grid.n=8 shape.kind=\"a<b>&c\""};

/* FieldData goes into the header; the appended data (addressed from its
 * own start) is byte for byte what it was; a second call adds nothing. */
Test(meta_attrs, vtk_field_data_before_the_appended_data)
{
    char dir[256], path[512];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/f.vti", dir);
    const int dims[3] = {3, 2, 1};
    const double o[3] = {0, 0, 0}, sp[3] = {1, 1, 1}, v[6] = {1, 2, 3, 4, 5, 6};
    const dfl_vtk_array a = {"value", 1, v};
    dfl_err err;
    cr_assert_eq(dfl_vti_write(path, dims, o, sp, &a, 1, 1, &err), DFL_OK, "%s", err.msg);
    char *before = e2e_slurp(path);
    cr_assert_eq(dfl_vtk_add_field_data(path, 2, names, values, &err), DFL_OK, "%s", err.msg);
    char *after = e2e_slurp(path);
    cr_assert(strstr(after, "<FieldData>") != NULL);
    cr_expect(strstr(after, "Name=\"dflab_sweep\"") != NULL);
    cr_expect(strstr(after, "115 109 111 107 101 0") != NULL, "smoke as codes: %s", after);
    const char *ab = strstr(before, "<AppendedData"), *aa = strstr(after, "<AppendedData");
    cr_assert(ab && aa);
    cr_expect_eq(strlen(aa), strlen(ab));
    cr_assert_eq(dfl_vtk_add_field_data(path, 2, names, values, &err), DFL_OK);
    char *again = e2e_slurp(path);
    cr_expect_str_eq(again, after);
    free(before), free(after), free(again);
    snprintf(path, sizeof path, "%s/none.vti", dir);
    cr_expect_eq(dfl_vtk_add_field_data(path, 2, names, values, &err), DFL_E_IO);
    cr_expect(strstr(err.msg, "none.vti") != NULL);
    cr_expect_eq(e2e_rmtree(dir), 0);
}

/* Attributes added, pixels unchanged (HALF too), nothing left beside. */
Test(meta_attrs, exr_attributes_and_same_pixels)
{
    char dir[256], path[512];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/f.exr", dir);
    float px[40 * 70];
    for (int i = 0; i < 40 * 70; i++) px[i] = (float)i * 0.25f - 3.0f;
    const dfl_exr_channel ch = {"value", px};
    dfl_err err;
    for (int half = 0; half < 2; half++) {
        cr_assert_eq(dfl_exr_write(path, 40, 70, &ch, 1, half, &err), DFL_OK, "%s", err.msg);
        float *before = NULL, *after = NULL;
        int w, h;
        cr_assert_eq(dfl_exr_read_channel(path, "value", &w, &h, &before, &err), DFL_OK);
        cr_assert_eq(dfl_exr_add_attrs(path, 2, names, values, &err), DFL_OK, "%s", err.msg);
        cr_assert_eq(dfl_exr_read_channel(path, "value", &w, &h, &after, &err), DFL_OK, "%s",
                     err.msg);
        cr_expect_eq(w * h, 40 * 70);
        cr_expect_eq(memcmp(before, after, sizeof px), 0);
        free(before), free(after);
        exr_context_t c = NULL;
        cr_assert_eq(exr_start_read(&c, path, NULL), EXR_ERR_SUCCESS);
        int32_t len = 0;
        const char *got = NULL;
        cr_assert_eq(exr_attr_get_string(c, 0, "dflab_sweep", &len, &got), EXR_ERR_SUCCESS);
        cr_expect_str_eq(got, values[1]);
        exr_finish(&c);
    }
    cr_expect_eq(e2e_count_entries(dir), 1);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
