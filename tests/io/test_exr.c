/* Tests for src/io/exr.  Images of known patterns are read back three ways:
 * through dfl_exr_read_channel (the library's decoder), through a minimal
 * independent parser of the file bytes written here (header, channel list,
 * chunk table, ZIP predictor/interleave), which catches symmetric
 * writer/reader mistakes such as a row flip or a channel mix-up, and through
 * the `exrheader` tool when it is installed. */
#include <criterion/criterion.h>

#include <Imath/half.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include "io/exr.h"
#include "util/tmpdir.h"

enum { W = 37, H = 45 }; /* H > 16: several ZIP chunks, the last one partial */

/* Three smooth, distinguishable patterns; channel c of pixel (x, y). */
static float pattern(int c, int x, int y)
{
    switch (c) {
    case 0: return (float)((x - 2.5 * y) / 7.0 + 1e-3 * x * y);            /* "value" */
    case 1: return (float)(1.0 + 0.5 * sin(0.3 * x) * cos(0.2 * y));       /* "grad_norm" */
    default: return (float)(1e-4 * (x + 1) * (y - 20) + 0.01 * (x == 3)); /* "error" */
    }
}

/* Given in non-sorted order on purpose; sorted they are error, grad_norm, value. */
static const char *const NAMES[3] = {"value", "grad_norm", "error"};
static const char *const SORTED[3] = {"error", "grad_norm", "value"};

static float *make_channel(int c)
{
    float *d = malloc((size_t)W * H * sizeof *d);
    cr_assert_not_null(d);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) d[(size_t)y * W + x] = pattern(c, x, y);
    return d;
}

/* Writes the three patterns to <new tmpdir>/img.exr (HALF storage if half),
 * the six special values over the first pixels of channel sc; d receives
 * the channels (caller frees).  Only the image may be left in dir. */
static void write_patterns(char *dir, size_t dsize, char *path, size_t psize, int sc,
                           const float special[6], int half, float *d[3])
{
    tmpdir_file(dir, dsize, "img.exr", path, psize);
    for (int c = 0; c < 3; c++) d[c] = make_channel(c);
    memcpy(d[sc], special, 6 * sizeof *special);
    dfl_exr_channel ch[3] = {{NAMES[0], d[0]}, {NAMES[1], d[1]}, {NAMES[2], d[2]}};
    dfl_err err;
    dfl_err_clear(&err);
    cr_assert_eq(dfl_exr_write(path, W, H, ch, 3, half, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(tmpdir_count(dir), 1, "temporary file left behind");
}

/* Channel name of a W x H image through the library's decoder (caller frees). */
static float *read_back(const char *path, const char *name)
{
    int w = 0, h = 0;
    float *r = NULL;
    dfl_err err;
    cr_assert_eq(dfl_exr_read_channel(path, name, &w, &h, &r, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(w, W);
    cr_assert_eq(h, H);
    return r;
}

/* --- Independent parser of the written file ---------------------------- */

typedef struct raw_exr {
    int nch;
    char names[8][64];
    int ptype[8]; /* 1 half, 2 float */
    int compression, xmin, ymin, xmax, ymax;
    float *pix[8]; /* decoded pixels per channel in file order */
} raw_exr;

static int32_t rd_i32(const unsigned char *p)
{
    return (int32_t)((uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
                     (uint32_t)p[3] << 24);
}

static void raw_exr_free(raw_exr *r)
{
    for (int c = 0; c < r->nch; c++) free(r->pix[c]);
}

/* Parses a single-part scanline ZIP file (16 lines per chunk). */
static void raw_exr_read(const char *path, raw_exr *r)
{
    memset(r, 0, sizeof *r);
    FILE *fp = fopen(path, "rb");
    cr_assert_not_null(fp);
    fseek(fp, 0, SEEK_END);
    long size = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    unsigned char *b = malloc((size_t)size);
    cr_assert_eq(fread(b, 1, (size_t)size, fp), (size_t)size);
    fclose(fp);
    cr_assert_eq(rd_i32(b), 20000630, "bad EXR magic");
    cr_assert_eq(b[4], 2, "EXR version");
    cr_assert_eq(b[5] & 0x02, 0, "tiled flag set");
    size_t p = 8;
    r->compression = -1;
    while (b[p]) { /* attributes: name\0 type\0 size value */
        const char *name = (const char *)b + p;
        p += strlen(name) + 1;
        const char *type = (const char *)b + p;
        p += strlen(type) + 1;
        int32_t sz = rd_i32(b + p);
        p += 4;
        const unsigned char *v = b + p;
        if (!strcmp(name, "channels")) {
            cr_assert_str_eq(type, "chlist");
            size_t q = 0;
            while (v[q]) {
                cr_assert_lt(r->nch, 8);
                snprintf(r->names[r->nch], 64, "%s", (const char *)v + q);
                q += strlen((const char *)v + q) + 1;
                r->ptype[r->nch] = rd_i32(v + q);
                cr_assert_eq(rd_i32(v + q + 8), 1, "x sampling");
                cr_assert_eq(rd_i32(v + q + 12), 1, "y sampling");
                q += 16;
                r->nch++;
            }
        } else if (!strcmp(name, "compression")) {
            r->compression = v[0];
        } else if (!strcmp(name, "dataWindow")) {
            r->xmin = rd_i32(v);
            r->ymin = rd_i32(v + 4);
            r->xmax = rd_i32(v + 8);
            r->ymax = rd_i32(v + 12);
        }
        p += (size_t)sz;
    }
    p++;
    cr_assert_eq(r->compression, 3, "not ZIP (3) compression");
    int w = r->xmax - r->xmin + 1, h = r->ymax - r->ymin + 1;
    cr_assert(w > 0 && h > 0);
    int nchunks = (h + 15) / 16;
    size_t rowbytes = 0;
    for (int c = 0; c < r->nch; c++) {
        cr_assert(r->ptype[c] == 1 || r->ptype[c] == 2);
        rowbytes += (size_t)w * (r->ptype[c] == 1 ? 2 : 4);
        r->pix[c] = malloc((size_t)w * h * sizeof(float));
    }
    unsigned char *raw = malloc(rowbytes * 16), *tmp = malloc(rowbytes * 16);
    for (int k = 0; k < nchunks; k++) {
        uint64_t off;
        memcpy(&off, b + p + 8 * (size_t)k, 8);
        cr_assert_lt(off, (uint64_t)size);
        int32_t y = rd_i32(b + off), packed = rd_i32(b + off + 4);
        cr_assert_eq(y, r->ymin + 16 * k, "chunk %d starts at y=%d", k, y);
        int lines = h - 16 * k < 16 ? h - 16 * k : 16;
        size_t n = rowbytes * (size_t)lines;
        if ((size_t)packed == n) { /* stored uncompressed when ZIP does not help */
            memcpy(raw, b + off + 8, n);
        } else {
            uLongf len = (uLongf)n;
            cr_assert_eq(uncompress(tmp, &len, b + off + 8, (uLong)packed), Z_OK);
            cr_assert_eq(len, n);
            for (size_t i = 1; i < n; i++) tmp[i] = (unsigned char)(tmp[i - 1] + tmp[i] - 128);
            const unsigned char *t1 = tmp, *t2 = tmp + (n + 1) / 2;
            for (size_t i = 0; i < n; i++) raw[i] = (i % 2 == 0) ? *t1++ : *t2++;
        }
        const unsigned char *q = raw; /* per line, per channel, w values */
        for (int l = 0; l < lines; l++)
            for (int c = 0; c < r->nch; c++)
                for (int x = 0; x < w; x++) {
                    float f;
                    if (r->ptype[c] == 2) {
                        memcpy(&f, q, 4);
                        q += 4;
                    } else {
                        f = imath_half_to_float((imath_half_bits_t)(q[0] | q[1] << 8));
                        q += 2;
                    }
                    r->pix[c][(size_t)(16 * k + l) * w + x] = f;
                }
    }
    free(raw);
    free(tmp);
    free(b);
}

/* --- exrheader ----------------------------------------------------------- */

/* Output of `exrheader path` in buf; returns 0 when exrheader is missing. */
static int exrheader(const char *path, char *buf, size_t size)
{
    if (system("command -v exrheader >/dev/null 2>&1") != 0) return 0;
    char cmd[512];
    snprintf(cmd, sizeof cmd, "exrheader '%s' 2>&1", path);
    FILE *pp = popen(cmd, "r");
    cr_assert_not_null(pp);
    size_t n = fread(buf, 1, size - 1, pp);
    buf[n] = 0;
    cr_assert_eq(pclose(pp), 0, "exrheader failed: %s", buf);
    return 1;
}

static void check_exrheader(const char *path, const char *type_name)
{
    static char out[16384];
    if (!exrheader(path, out, sizeof out)) {
        cr_log_warn("exrheader not installed: header check skipped");
        return;
    }
    char want[512];
    snprintf(want, sizeof want,
             "channels (type chlist):\n    %s, %s, sampling 1 1, plinear\n"
             "    %s, %s, sampling 1 1, plinear\n    %s, %s, sampling 1 1, plinear\n",
             SORTED[0], type_name, SORTED[1], type_name, SORTED[2], type_name);
    cr_assert_not_null(strstr(out, want), "exrheader output:\n%s\nlacks:\n%s", out, want);
    snprintf(want, sizeof want, "dataWindow (type box2i): (0 0) - (%d %d)", W - 1, H - 1);
    cr_assert_not_null(strstr(out, want), "%s", out);
    cr_assert_not_null(strstr(out, "compression (type compression): zip"), "%s", out);
    cr_assert_not_null(strstr(out, "\"scanlineimage\""), "%s", out);
}

/* End of a pattern test: exrheader's view of the header, then frees raw
 * and d and removes dir. */
static void finish_patterns(raw_exr *raw, const char *path, const char *type_name, float *d[3],
                            const char *dir)
{
    raw_exr_free(raw);
    check_exrheader(path, type_name);
    for (int c = 0; c < 3; c++) free(d[c]);
    tmpdir_remove(dir);
}

/* --- tests ---------------------------------------------------------------- */

Test(exr, float_roundtrip_is_exact)
{
    char dir[64], path[128];
    float *d[3];
    /* special values must survive a lossless float file bit for bit */
    const float special[6] = {-0.0f, 1e-40f, INFINITY, -INFINITY, NAN, 3.4e38f};
    write_patterns(dir, sizeof dir, path, sizeof path, 2, special, 0, d);

    for (int c = 0; c < 3; c++) {
        float *r = read_back(path, NAMES[c]);
        cr_assert_eq(memcmp(r, d[c], (size_t)W * H * sizeof(float)), 0, "channel %s differs",
                     NAMES[c]);
        free(r);
    }

    raw_exr raw;
    raw_exr_read(path, &raw);
    cr_assert_eq(raw.nch, 3);
    cr_assert_eq(raw.xmin, 0);
    cr_assert_eq(raw.ymin, 0);
    cr_assert_eq(raw.xmax, W - 1);
    cr_assert_eq(raw.ymax, H - 1);
    for (int c = 0; c < 3; c++) {
        cr_assert_str_eq(raw.names[c], SORTED[c]);
        cr_assert_eq(raw.ptype[c], 2);
        int src = -1;
        for (int k = 0; k < 3; k++)
            if (!strcmp(NAMES[k], SORTED[c])) src = k;
        /* file row y must be caller row y (row 0 at the top) */
        cr_assert_eq(memcmp(raw.pix[c], d[src], (size_t)W * H * sizeof(float)), 0,
                     "raw channel %s differs", SORTED[c]);
    }
    finish_patterns(&raw, path, "32-bit floating-point", d, dir);
}

/* Half storage: each value must be the round-to-nearest-even half of the
 * input, i.e. within 2^-11 relative (normal range, 11 significant bits) or
 * 2^-25 absolute (subnormal range, spacing 2^-24), and equal to Imath's
 * own conversion; beyond the half range values become +-inf. */
Test(exr, half_roundtrip_within_half_rounding)
{
    char dir[64], path[128];
    float *d[3];
    const float special[6] = {1e6f, -1e6f, 65504.0f, 3e-6f, -0.0f, 6.2e-5f};
    write_patterns(dir, sizeof dir, path, sizeof path, 1, special, 1, d);

    raw_exr raw;
    raw_exr_read(path, &raw);
    for (int c = 0; c < 3; c++) {
        float *r = read_back(path, NAMES[c]);
        int fc = -1;
        for (int k = 0; k < 3; k++)
            if (!strcmp(raw.names[k], NAMES[c])) fc = k;
        cr_assert_geq(fc, 0);
        cr_assert_eq(raw.ptype[fc], 1, "channel %s not HALF", NAMES[c]);
        for (size_t i = 0; i < (size_t)W * H; i++) {
            float v = d[c][i], got = r[i];
            float rne = imath_half_to_float(imath_float_to_half(v));
            cr_assert(memcmp(&got, &rne, sizeof got) == 0, "%s[%zu]: %.9g -> %.9g, Imath %.9g",
                      NAMES[c], i, v, got, rne);
            cr_assert(memcmp(&got, &raw.pix[fc][i], sizeof got) == 0);
            if (fabsf(v) >= 65520.0f) { /* max + half ulp: ties to even = inf */
                cr_assert(isinf(got) && signbit(got) == signbit(v));
            } else if (fabsf(v) >= 0x1p-14f) {
                cr_assert_leq(fabsf(got - v), 0x1p-11f * fabsf(v), "%s[%zu]", NAMES[c], i);
            } else {
                cr_assert_leq(fabsf(got - v), 0x1p-25f, "%s[%zu]", NAMES[c], i);
            }
        }
        free(r);
    }
    cr_assert(isinf(raw.pix[1][0]) && raw.pix[1][0] > 0);
    cr_assert_eq(raw.pix[1][2], 65504.0f);
    finish_patterns(&raw, path, "16-bit floating-point", d, dir);
}

/* 1x1 and 1-row images: the smallest chunks. */
Test(exr, tiny_images)
{
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "t.exr", path, sizeof path);
    float one = -2.75f, row[5] = {1, 2, 3, 4, 5};
    dfl_exr_channel c1 = {"value", &one}, c5 = {"value", row};
    dfl_err err;
    int w, h;
    float *r;
    cr_assert_eq(dfl_exr_write(path, 1, 1, &c1, 1, 0, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_exr_read_channel(path, "value", &w, &h, &r, &err), DFL_OK, "%s", err.msg);
    cr_assert(w == 1 && h == 1 && r[0] == one);
    free(r);
    cr_assert_eq(dfl_exr_write(path, 1, 5, &c5, 1, 1, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_exr_read_channel(path, "value", &w, &h, &r, &err), DFL_OK, "%s", err.msg);
    cr_assert(w == 1 && h == 5);
    for (int i = 0; i < 5; i++) cr_assert_eq(r[i], row[i]); /* small integers are exact halves */
    free(r);
    tmpdir_remove(dir);
}

Test(exr, read_errors)
{
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "none.exr", path, sizeof path);
    dfl_err err;
    int w = 7, h = 7;
    float *r = (float *)&w;
    cr_assert_eq(dfl_exr_read_channel(path, "value", &w, &h, &r, &err), DFL_E_IO);
    cr_assert_not_null(strstr(err.msg, path));
    cr_assert(r == NULL && w == 0 && h == 0);

    float px[4] = {1, 2, 3, 4};
    dfl_exr_channel ch = {"value", px};
    snprintf(path, sizeof path, "%s/ok.exr", dir);
    cr_assert_eq(dfl_exr_write(path, 2, 2, &ch, 1, 0, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(dfl_exr_read_channel(path, "error", &w, &h, &r, &err), DFL_E_INPUT);
    cr_assert_not_null(strstr(err.msg, "error"));

    snprintf(path, sizeof path, "%s/junk.exr", dir);
    FILE *fp = fopen(path, "w");
    fputs("this is not an EXR file at all", fp);
    fclose(fp);
    cr_assert_eq(dfl_exr_read_channel(path, "value", &w, &h, &r, &err), DFL_E_IO);
    cr_assert(r == NULL);
    tmpdir_remove(dir);
}

/* Writes a 2 x 2 image to <tmpdir>/name (a directory made there first when
 * target_is_dir) and expects an I/O error that leaves `left` entries. */
static void expect_io_failure(const char *name, int target_is_dir, int left)
{
    char dir[64], path[160];
    tmpdir_file(dir, sizeof dir, name, path, sizeof path);
    if (target_is_dir) cr_assert_eq(mkdir(path, 0700), 0);
    float px[4] = {1, 2, 3, 4};
    dfl_exr_channel ch = {"value", px};
    dfl_err err;
    dfl_err_clear(&err);
    tmpdir_expect_io_error(dfl_exr_write(path, 2, 2, &ch, 1, 0, &err), &err, path, dir, left);
    tmpdir_remove(dir);
}

Test(exr, missing_directory_is_io_error_and_leaves_nothing)
{
    expect_io_failure("no/such/dir/img.exr", 0, 0);
}

/* The target is a directory: the image is written to the temporary name,
 * the rename fails, and the temporary must be removed (only the directory
 * itself may remain). */
Test(exr, failed_rename_removes_temporary) { expect_io_failure("target.exr", 1, 1); }

Test(exr, invalid_input_rejected_without_file)
{
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "bad.exr", path, sizeof path);
    float px[4] = {1, 2, 3, 4};
    dfl_exr_channel ch = {"value", px};
    dfl_exr_channel dup[2] = {{"value", px}, {"value", px}};
    dfl_exr_channel noname = {"", px}, nodata = {"value", NULL};
    dfl_err err;
    cr_assert_eq(dfl_exr_write(path, 2, 2, NULL, 1, 0, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_exr_write(path, 2, 2, &ch, 0, 0, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_exr_write(path, 0, 2, &ch, 1, 0, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_exr_write(path, 2, -1, &ch, 1, 0, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_exr_write(path, 2, 2, dup, 2, 0, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_exr_write(path, 2, 2, &noname, 1, 0, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_exr_write(path, 2, 2, &nodata, 1, 0, &err), DFL_E_INPUT);
    cr_assert_eq(tmpdir_count(dir), 0);
    tmpdir_remove(dir);
}

/* Channel names longer than 31 bytes need the long-name flag. */
Test(exr, long_channel_name)
{
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "long.exr", path, sizeof path);
    const char *name = "a_channel_name_longer_than_31_bytes_for_sure";
    float px[6] = {1, 2, 3, 4, 5, 6};
    dfl_exr_channel ch[2] = {{name, px}, {"b", px}};
    dfl_err err;
    cr_assert_eq(dfl_exr_write(path, 3, 2, ch, 2, 0, &err), DFL_OK, "%s", err.msg);
    int w, h;
    float *r;
    cr_assert_eq(dfl_exr_read_channel(path, name, &w, &h, &r, &err), DFL_OK, "%s", err.msg);
    cr_assert(w == 3 && h == 2 && memcmp(r, px, sizeof px) == 0);
    free(r);
    tmpdir_remove(dir);
}
