/* `dflab probe` prints numbers as the CSVs do: the shortest text that
 * strtod reads back to the same double (io/table.h).  The circle of radius
 * 0.5 at the origin at x = (1.2, 0): value 1.2 - 0.5, which is the double
 * nearest 0.7 (1.2 = 1.1999999999999999556, less 0.5 exactly), so the
 * value prints as "0.7", not 0.69999999999999996; the gradient is (1, 0). */
#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/e2e_util.h"

Test(e2e_probe_format, shortest_round_trip_numbers)
{
    char dir[256], cfg[512], pts[512], args[2048], path[600];
    e2e_tmpdir(dir, sizeof dir);
    e2e_write(dir, "c.ini",
              "[study]\nname = smoke\n[shape]\nkind = circle\ncenter = 0 0\nradius = 0.5\n"
              "[field]\nkind = exact\n[grid]\nn = 3\n",
              cfg, sizeof cfg);
    e2e_write(dir, "p.csv", "x,y\n1.2,0\n0.1,0.2\n", pts, sizeof pts);
    cr_assert_eq(1.2 - 0.5, 0.7); /* the premise */
    snprintf(args, sizeof args, "probe %s --points %s", cfg, pts);
    cr_assert_eq(e2e_dflab(dir, args), 0);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    char *out = e2e_slurp(path);
    cr_assert(out);
    cr_expect(strstr(out, "\n1.2,0,0,0.7,1,0,0\n"), "%s", out);
    /* every number reads back and is printed again the same way */
    const char *line = strchr(out, '\n') + 1;
    for (char *tok = strtok((char *)line, ",\n"); tok; tok = strtok(NULL, ",\n")) {
        char again[64];
        snprintf(again, sizeof again, "%.17g", strtod(tok, NULL));
        cr_expect(strtod(again, NULL) == strtod(tok, NULL), "%s", tok);
        cr_expect(strlen(tok) <= strlen(again), "%s longer than %%.17g", tok);
    }
    free(out);
    cr_expect_eq(e2e_rmtree(dir), 0);
}
