/* libFuzzer harness: a sweep point's record (point.json) through the
 * strict reader (dfl_point_parse) and then through `dflab merge` of a
 * one-point folder holding it.  Invariants: a parsed record has
 * 0 <= index < npoints <= DFL_POINT_NP_MAX; a merge that succeeds writes a
 * manifest.json that passes the same strict reader (nothing raw pasted).
 *
 * Each input gets a fresh folder under one temporary directory of this
 * process: <tmp>/o.points/pt000/ with the input as point.json and two
 * fixed files (a.csv, config.ini) whose sizes and sha256 the seeds in
 * tests/fuzz/seeds/record/ record, so that mutations of a valid record
 * reach the merge. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fuzz_util.h"
#include "harness/runner.h"
#include "harness/sweep.h"
#include "io/dirs.h"
#include "io/json.h"

static const char A_CSV[] = "point,x\n0,1\n";
static const char CONFIG[] = "[study]\nname = a\n";

static void put(const char *path, const void *data, size_t n)
{
    FILE *fp = fopen(path, "wb");
    if (!fp) abort();
    if (n && fwrite(data, 1, n, fp) != n) abort();
    fclose(fp);
}

static char base[64]; /* this process's folder, removed at exit */

static void remove_base(void) { dfl_dir_remove_tree(base, NULL); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* the parser alone */
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    dfl_point_rec r;
    dfl_err err;
    if (dfl_point_parse(text, size, "point.json", &r, &err) == DFL_OK) {
        if (r.index < 0 || r.index >= r.np || r.np > DFL_POINT_NP_MAX) __builtin_trap();
        dfl_point_rec_free(&r);
    }
    /* the merge of a folder holding it */
    if (!base[0]) {
        snprintf(base, sizeof base, "/tmp/dfl-fuzz-record-XXXXXX");
        if (!mkdtemp(base)) abort();
        atexit(remove_base);
    }
    char out[128], pts[160], pt[192], path[256];
    snprintf(out, sizeof out, "%s/o", base);
    snprintf(pts, sizeof pts, "%s.points", out);
    snprintf(pt, sizeof pt, "%s/pt000", pts);
    dfl_dir_remove_tree(out, NULL);
    dfl_dir_remove_tree(pts, NULL);
    if (mkdir(pts, 0700) != 0 || mkdir(pt, 0700) != 0) abort();
    snprintf(path, sizeof path, "%s/point.json", pt);
    put(path, data, size);
    snprintf(path, sizeof path, "%s/a.csv", pt);
    put(path, A_CSV, strlen(A_CSV));
    snprintf(path, sizeof path, "%s/config.ini", pt);
    put(path, CONFIG, strlen(CONFIG));
    if (dfl_merge(out, 1, "dflab merge o", &err) == DFL_OK) {
        size_t len;
        snprintf(path, sizeof path, "%s/manifest.json", out);
        char *m = dfl_file_read_all(path, &len);
        if (!m || dfl_json_check(m, len, path, &err) != DFL_OK) __builtin_trap();
        free(m);
    }
    return 0;
}
