/* The name lists of rfunc's enums (join.h, segment.h, tri3d.h): codes in
 * list order, name <-> code both ways, the properties the trim list
 * carries, and the config spellings users write. */
#include <criterion/criterion.h>
#include <string.h>

#include "rfunc/join.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"

Test(rfunc_names, joins)
{
    cr_assert_eq(DFL_RFUNC_JOIN_COUNT, 3);
    const struct {
        dfl_rfunc_join code;
        int value;
        const char *name;
    } want[] = {{DFL_RFUNC_REQUIV, 0, "requiv"},
                {DFL_RFUNC_RCONJ, 1, "rconj"},
                {DFL_RFUNC_REQUIV_CORRECTED, 2, "requiv_corrected"}};
    for (int i = 0; i < 3; i++) {
        cr_expect_eq((int)want[i].code, want[i].value);
        cr_expect_str_eq(dfl_rfunc_join_name(want[i].code), want[i].name);
        cr_expect_str_eq(dfl_rfunc_join_names[i], want[i].name);
        dfl_rfunc_join j = (dfl_rfunc_join)-1;
        cr_expect_eq(dfl_rfunc_join_parse(want[i].name, &j, NULL), DFL_OK);
        cr_expect_eq(j, want[i].code);
    }
    cr_expect_str_eq(dfl_rfunc_join_name((dfl_rfunc_join)3), "?");
    cr_expect_str_eq(dfl_rfunc_join_name((dfl_rfunc_join)-1), "?");
    dfl_rfunc_join j = DFL_RFUNC_RCONJ;
    dfl_err err;
    cr_expect_eq(dfl_rfunc_join_parse("REQUIV", &j, &err), DFL_E_INPUT);
    cr_expect_eq(j, DFL_RFUNC_RCONJ);
    cr_expect(strstr(err.msg, "'REQUIV'") && strstr(err.msg, "requiv|rconj|requiv_corrected"),
              "%s", err.msg);
    cr_expect_eq(dfl_rfunc_join_check((dfl_rfunc_join)3, 2, &err), DFL_E_INPUT);
}

Test(rfunc_names, trims_and_their_properties)
{
    cr_assert_eq(DFL_RFUNC_TRIM_COUNT, 4);
    const struct {
        dfl_rfunc_trim code;
        int value;
        const char *name;
        int smooth, strip;
    } want[] = {{DFL_RFUNC_TRIM_DISK, 0, "disk", 0, 0},
                {DFL_RFUNC_TRIM_DISK_SMOOTH, 1, "disk_smooth", 1, 0},
                {DFL_RFUNC_TRIM_STRIP, 2, "strip", 0, 1},
                {DFL_RFUNC_TRIM_STRIP_SMOOTH, 3, "strip_smooth", 1, 1}};
    for (int i = 0; i < 4; i++) {
        cr_expect_eq((int)want[i].code, want[i].value);
        cr_expect_str_eq(dfl_rfunc_trim_name(want[i].code), want[i].name);
        cr_expect_str_eq(dfl_rfunc_trim_names[i], want[i].name);
        cr_expect_eq(dfl_rfunc_trim_smooth(want[i].code), want[i].smooth, "%s", want[i].name);
        cr_expect_eq(dfl_rfunc_trim_strip(want[i].code), want[i].strip, "%s", want[i].name);
        dfl_rfunc_trim t = (dfl_rfunc_trim)-1;
        cr_expect_eq(dfl_rfunc_trim_parse(want[i].name, &t, NULL), DFL_OK);
        cr_expect_eq(t, want[i].code);
    }
    cr_expect_str_eq(dfl_rfunc_trim_name((dfl_rfunc_trim)4), "?");
    cr_expect_eq(dfl_rfunc_trim_smooth((dfl_rfunc_trim)4), 0);
    cr_expect_eq(dfl_rfunc_trim_strip((dfl_rfunc_trim)-1), 0);
    dfl_rfunc_trim t = DFL_RFUNC_TRIM_STRIP;
    dfl_err err;
    cr_expect_eq(dfl_rfunc_trim_parse("box", &t, &err), DFL_E_INPUT);
    cr_expect_eq(t, DFL_RFUNC_TRIM_STRIP);
    cr_expect(strstr(err.msg, "disk|disk_smooth|strip|strip_smooth"), "%s", err.msg);
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
    cr_expect_str_eq(dfl_rfunc_tri_trim_name(DFL_RFUNC_TRI_PRISM), "prism");
    cr_expect_str_eq(dfl_rfunc_tri_trim_name(DFL_RFUNC_TRI_CONDITIONAL), "conditional");
    cr_expect_str_eq(dfl_rfunc_tri_trim_name((dfl_rfunc_tri_trim)2), "?");
    dfl_rfunc_tri_trim t = DFL_RFUNC_TRI_PRISM;
    cr_expect_eq(dfl_rfunc_tri_trim_parse("conditional", &t, NULL), DFL_OK);
    cr_expect_eq(t, DFL_RFUNC_TRI_CONDITIONAL);
    dfl_err err;
    cr_expect_eq(dfl_rfunc_tri_trim_parse("prismatic", &t, &err), DFL_E_INPUT);
    cr_expect_eq(t, DFL_RFUNC_TRI_CONDITIONAL);
    cr_expect(strstr(err.msg, "prism|conditional"), "%s", err.msg);
}
