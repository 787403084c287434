/* libFuzzer harness: the INI loader and every typed getter.
 *
 * The input is INI text.  It is parsed twice -- from memory
 * (dfl_cfg_parse_string, which stops at a NUL) and from a file through the
 * FILE reader (io/lines.h's rules, NULs included) -- and every entry of a
 * successful parse goes through each getter, dfl_cfg_set and the
 * locations.  The name lives in a directory that does not exist, so that a
 * relative include cannot reach real files.  Built by `make fuzz`
 * (tests/fuzz/fuzz.mk). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_util.h"
#include "io/config.h"
#include "io/config_impl.h"
#include "io/lines.h"

static void getters(dfl_cfg *c)
{
    dfl_err err;
    static const char *const names[] = {"a", "b", "circle"};
    for (size_t i = 0; i < c->n; i++) {
        const char *s = c->e[i].sec, *k = c->e[i].key, *str;
        long l;
        double d, v[3], *pts;
        bool b;
        int e;
        size_t n;
        dfl_cfg_string(c, s, k, &str, &err);
        dfl_cfg_int(c, s, k, -1000, 1000, &l, &err);
        dfl_cfg_double(c, s, k, -1e300, 1e300, &d, &err);
        dfl_cfg_bool(c, s, k, &b, &err);
        dfl_cfg_enum(c, s, k, names, 3, &e, &err);
        dfl_cfg_vec(c, s, k, 2, v, &err);
        dfl_cfg_vec(c, s, k, 3, v, &err);
        for (int dim = 2; dim <= 3; dim++)
            if (dfl_cfg_points(c, s, k, dim, 1, &pts, &n, &err) == DFL_OK) free(pts);
        if (dfl_cfg_doubles(c, s, k, 0, &pts, &n, &err) == DFL_OK) free(pts);
        dfl_cfg_point_dim(c->e[i].value);
        char w[256];
        dfl_cfg_where(c, s, k, w, sizeof w);
        dfl_cfg_reject(c, s, k, &err, "x%d", 1);
    }
    dfl_cfg_check_used(c, &err);
    if (c->n > 0) {
        char a[512];
        snprintf(a, sizeof a, "%s.%s=%s", c->e[0].sec, c->e[0].key, c->e[c->n - 1].value);
        dfl_cfg_set(c, a, &err);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    dfl_cfg *c = NULL;
    dfl_err err;
    if (dfl_cfg_parse_string("/nonexistent-dir/fuzz.ini", text, &c, &err) == DFL_OK) {
        getters(c);
        dfl_cfg_free(c);
    }
    /* the CLI escapes every message; an escaped text holds no control byte */
    char esc[4 * DFL_ERR_MSG_MAX];
    dfl_text_escape(text, esc, sizeof esc);
    for (const char *q = esc; *q; q++)
        if ((unsigned char)*q < 0x20 || *q == 0x7f) __builtin_trap();
    free(text);
    /* the FILE path, through a file in memory */
    char path[64];
    snprintf(path, sizeof path, "/tmp/dflab-fuzz-config.%ld.ini", (long)getpid());
    FILE *fp = fopen(path, "wb");
    if (!fp) return 0;
    fwrite(data, 1, size, fp);
    fclose(fp);
    if (dfl_cfg_load(path, &c, &err) == DFL_OK) dfl_cfg_free(c);
    unlink(path);
    return 0;
}
