/* The name lists of rfunc's enums (join.h, segment.h, tri3d.h): codes in
 * list order, name <-> code both ways (util/names_check.h), the properties
 * the trim list carries, and the config spellings users write. */
#include <criterion/criterion.h>
#include <string.h>

#include "rfunc/join.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"
#include "util/names_check.h"

Test(rfunc_names, joins)
{
    cr_assert_eq(DFL_RFUNC_JOIN_COUNT, 3);
    cr_expect_eq((int)DFL_RFUNC_REQUIV, 0);
    cr_expect_eq((int)DFL_RFUNC_RCONJ, 1);
    cr_expect_eq((int)DFL_RFUNC_REQUIV_CORRECTED, 2);
    dfl_err err;
    NAMES_CHECK(dfl_rfunc_join, DFL_RFUNC_JOIN_COUNT, dfl_rfunc_join_names, dfl_rfunc_join_name,
                dfl_rfunc_join_parse, "requiv|rconj|requiv_corrected", "REQUIV", DFL_RFUNC_RCONJ,
                err);
    cr_expect_eq(dfl_rfunc_join_check((dfl_rfunc_join)3, 2, &err), DFL_E_INPUT);
}

Test(rfunc_names, trims_and_their_properties)
{
    cr_assert_eq(DFL_RFUNC_TRIM_COUNT, 4);
    const struct {
        dfl_rfunc_trim code;
        int value;
        int smooth, strip;
    } want[] = {{DFL_RFUNC_TRIM_DISK, 0, 0, 0},
                {DFL_RFUNC_TRIM_DISK_SMOOTH, 1, 1, 0},
                {DFL_RFUNC_TRIM_STRIP, 2, 0, 1},
                {DFL_RFUNC_TRIM_STRIP_SMOOTH, 3, 1, 1}};
    for (int i = 0; i < 4; i++) {
        cr_expect_eq((int)want[i].code, want[i].value);
        cr_expect_eq(dfl_rfunc_trim_smooth(want[i].code), want[i].smooth, "trim %d", i);
        cr_expect_eq(dfl_rfunc_trim_strip(want[i].code), want[i].strip, "trim %d", i);
    }
    dfl_err err;
    NAMES_CHECK(dfl_rfunc_trim, DFL_RFUNC_TRIM_COUNT, dfl_rfunc_trim_names, dfl_rfunc_trim_name,
                dfl_rfunc_trim_parse, "disk|disk_smooth|strip|strip_smooth", "box",
                DFL_RFUNC_TRIM_STRIP, err);
    cr_expect_eq(dfl_rfunc_trim_smooth((dfl_rfunc_trim)4), 0);
    cr_expect_eq(dfl_rfunc_trim_strip((dfl_rfunc_trim)-1), 0);
    /* a segment refuses a code outside the list */
    const double a[2] = {0, 0}, b[2] = {1, 0};
    dfl_rfunc_seg s;
    cr_expect_eq(dfl_rfunc_seg_init(2, a, b, (dfl_rfunc_trim)4, &s, &err), DFL_E_INPUT);
}

Test(rfunc_names, triangle_trims)
{
    cr_assert_eq(DFL_RFUNC_TRI_TRIM_COUNT, 2);
    cr_expect_eq((int)DFL_RFUNC_TRI_PRISM, 0);
    cr_expect_eq((int)DFL_RFUNC_TRI_CONDITIONAL, 1);
    dfl_err err;
    NAMES_CHECK(dfl_rfunc_tri_trim, DFL_RFUNC_TRI_TRIM_COUNT, dfl_rfunc_tri_trim_names,
                dfl_rfunc_tri_trim_name, dfl_rfunc_tri_trim_parse, "prism|conditional",
                "prismatic", DFL_RFUNC_TRI_CONDITIONAL, err);
}
