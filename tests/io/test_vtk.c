/* Tests for src/io/vtk: files are read back by VTK itself (tests/io/vtk_check.py
 * through $DFL_PYTHON) and checked against the analytic function that
 * produced them; the zlib layout is also decoded here independently. */
#include <criterion/criterion.h>

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include "io/vtk.h"
#include "util/e2e_util.h"
#include "util/tmpdir.h"

/* Runs the VTK validator with args; returns its exit status (-1 if it did
 * not exit normally). */
static int run_check(const char *args)
{
    char cmd[8192];
    snprintf(cmd, sizeof cmd, "'%s' tests/io/vtk_check.py %s >/dev/null", e2e_python(), args);
    int rc = system(cmd);
    if (rc == -1 || !WIFEXITED(rc)) return -1;
    return WEXITSTATUS(rc);
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* The analytic test field: u = A x + B y + C z + D, grad u = (A, B, C). */
enum { A = 1, B = 2, C = 3 };
static const double D = 0.125;

typedef struct grid_case {
    int dims[3];
    double origin[3], spacing[3];
    double *value, *grad, *gnorm;
} grid_case;

static void grid_fill(grid_case *g)
{
    size_t n = (size_t)g->dims[0] * g->dims[1] * g->dims[2];
    g->value = malloc(n * sizeof(double));
    g->grad = malloc(3 * n * sizeof(double));
    g->gnorm = malloc(n * sizeof(double));
    cr_assert(g->value && g->grad && g->gnorm);
    for (int k = 0; k < g->dims[2]; k++)
        for (int j = 0; j < g->dims[1]; j++)
            for (int i = 0; i < g->dims[0]; i++) {
                size_t id = (size_t)i + (size_t)g->dims[0] * ((size_t)j + (size_t)g->dims[1] * k);
                double x = g->origin[0] + i * g->spacing[0];
                double y = g->origin[1] + j * g->spacing[1];
                double z = g->origin[2] + k * g->spacing[2];
                g->value[id] = A * x + B * y + C * z + D;
                g->grad[3 * id + 0] = A;
                g->grad[3 * id + 1] = B;
                g->grad[3 * id + 2] = C;
                g->gnorm[id] = sqrt((double)(A * A + B * B + C * C));
            }
}

static void grid_free(grid_case *g)
{
    free(g->value);
    free(g->grad);
    free(g->gnorm);
}

static void write_and_check_vti(grid_case *g, int compress)
{
    char dir[64], path[128], args[2048];
    tmpdir_file(dir, sizeof dir, "field.vti", path, sizeof path);
    grid_fill(g);
    /* gradient first: the writer must not depend on array order */
    dfl_vtk_array arrays[3] = {
        {"gradient", 3, g->grad}, {"value", 1, g->value}, {"grad_norm", 1, g->gnorm}};
    dfl_err err;
    dfl_err_clear(&err);
    dfl_status st = dfl_vti_write(path, g->dims, g->origin, g->spacing, arrays, 3, compress, &err);
    cr_assert_eq(st, DFL_OK, "%s", err.msg);
    cr_assert_eq(tmpdir_count(dir), 1, "temporary file left behind");
    snprintf(args, sizeof args,
             "vti '%s' --dims %d %d %d --origin %.17g %.17g %.17g --spacing %.17g %.17g %.17g "
             "--linear %d %d %d %.17g --gradient --narrays 3",
             path, g->dims[0], g->dims[1], g->dims[2], g->origin[0], g->origin[1], g->origin[2],
             g->spacing[0], g->spacing[1], g->spacing[2], A, B, C, D);
    cr_assert_eq(run_check(args), 0, "VTK validation failed for %s (compress=%d)", path, compress);

    /* Negative control: the validator must reject a wrong formula. */
    snprintf(args, sizeof args,
             "vti '%s' --dims %d %d %d --origin %.17g %.17g %.17g --spacing %.17g %.17g %.17g "
             "--linear %d %d %d %.17g 2>/dev/null >/dev/null",
             path, g->dims[0], g->dims[1], g->dims[2], g->origin[0], g->origin[1], g->origin[2],
             g->spacing[0], g->spacing[1], g->spacing[2], A, C, B, D);
    cr_assert_eq(run_check(args), 1, "validator accepted a wrong field");
    grid_free(g);
    tmpdir_remove(dir);
}

Test(vtk, vti_raw_matches_analytic_field)
{
    grid_case g = {{5, 4, 3}, {-1.25, 0.5, 2.0}, {0.5, 0.25, 1.5}, NULL, NULL, NULL};
    write_and_check_vti(&g, 0);
}

Test(vtk, vti_zlib_matches_analytic_field)
{
    grid_case g = {{5, 4, 3}, {-1.25, 0.5, 2.0}, {0.5, 0.25, 1.5}, NULL, NULL, NULL};
    write_and_check_vti(&g, 1);
}

/* 40*30*20 doubles = 192000 bytes: 6 blocks with a partial last block. */
Test(vtk, vti_zlib_many_blocks)
{
    grid_case g = {{40, 30, 20}, {0.1, -3.0, 7.0}, {0.05, 0.2, 0.3}, NULL, NULL, NULL};
    write_and_check_vti(&g, 1);
}

/* 64*64 doubles = 32768 bytes = exactly one block (last-block size 0). */
Test(vtk, vti_zlib_exact_block_multiple_2d)
{
    grid_case g = {{64, 64, 1}, {-2.0, -2.0, 0.0}, {0.0625, 0.0625, 1.0}, NULL, NULL, NULL};
    write_and_check_vti(&g, 1);
}

/* Decodes the appended block of a compressed file here, without VTK: each
 * array's header must follow [nblocks][blocksize][lastsize][csizes...] and
 * inflate to the original bytes. */
Test(vtk, zlib_layout_decodes_to_input)
{
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "layout.vti", path, sizeof path);
    enum { N = 10000 }; /* 80000 bytes: 3 blocks, last one partial */
    double *v = malloc(N * sizeof *v);
    cr_assert_not_null(v);
    for (int i = 0; i < N; i++) v[i] = sin(0.01 * i) * 1e3 + i;
    int dims[3] = {100, 100, 1};
    double o[3] = {0, 0, 0}, s[3] = {1, 1, 1};
    dfl_vtk_array arr = {"value", 1, v};
    dfl_err err;
    cr_assert_eq(dfl_vti_write(path, dims, o, s, &arr, 1, 1, &err), DFL_OK, "%s", err.msg);

    FILE *fp = fopen(path, "rb");
    cr_assert_not_null(fp);
    fseek(fp, 0, SEEK_END);
    long size = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    unsigned char *buf = malloc((size_t)size + 1);
    cr_assert_eq(fread(buf, 1, (size_t)size, fp), (size_t)size);
    fclose(fp);
    buf[size] = 0;
    cr_assert_not_null(strstr((char *)buf, "header_type=\"UInt64\""));
    cr_assert_not_null(strstr((char *)buf, "compressor=\"vtkZLibDataCompressor\""));
    cr_assert_not_null(strstr((char *)buf, "offset=\"0\""));
    char *ad = strstr((char *)buf, "<AppendedData encoding=\"raw\">");
    cr_assert_not_null(ad);
    unsigned char *p = (unsigned char *)strchr(ad, '_') + 1;
    uint64_t h[3];
    memcpy(h, p, sizeof h);
    const uint64_t bytes = N * sizeof(double);
    cr_assert_eq(h[0], (bytes + DFL_VTK_ZLIB_BLOCK - 1) / DFL_VTK_ZLIB_BLOCK);
    cr_assert_eq(h[1], DFL_VTK_ZLIB_BLOCK);
    cr_assert_eq(h[2], bytes % DFL_VTK_ZLIB_BLOCK);
    unsigned char *z = p + (3 + h[0]) * 8;
    unsigned char *out = malloc(bytes);
    size_t done = 0;
    for (uint64_t b = 0; b < h[0]; b++) {
        uint64_t cs;
        memcpy(&cs, p + 24 + 8 * b, 8);
        uLongf len = (uLongf)(bytes - done);
        cr_assert_eq(uncompress(out + done, &len, z, (uLong)cs), Z_OK);
        cr_assert_eq(len, b + 1 < h[0] ? h[1] : h[2]);
        done += len;
        z += cs;
    }
    cr_assert_eq(done, bytes);
    cr_assert_eq(memcmp(out, v, bytes), 0);
    /* the data is followed directly by the closing tags */
    cr_assert_eq(strncmp((char *)z, "\n  </AppendedData>", 18), 0);
    free(out);
    free(buf);
    free(v);
    tmpdir_remove(dir);
}

/* Raw layout: [uint64 nbytes][data] per array, offsets consecutive. */
Test(vtk, raw_layout_offsets)
{
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "raw.vti", path, sizeof path);
    double v[6] = {1, 2, 3, 4, 5, 6}, g[18];
    for (int i = 0; i < 18; i++) g[i] = -i;
    int dims[3] = {3, 2, 1};
    double o[3] = {0, 0, 0}, s[3] = {1, 1, 1};
    dfl_vtk_array arr[2] = {{"value", 1, v}, {"gradient", 3, g}};
    dfl_err err;
    cr_assert_eq(dfl_vti_write(path, dims, o, s, arr, 2, 0, &err), DFL_OK, "%s", err.msg);
    FILE *fp = fopen(path, "rb");
    unsigned char buf[4096];
    size_t n = fread(buf, 1, sizeof buf - 1, fp);
    fclose(fp);
    buf[n] = 0;
    cr_assert_not_null(strstr((char *)buf, "offset=\"0\""));
    cr_assert_not_null(strstr((char *)buf, "offset=\"56\"")); /* 8 + 6*8 */
    cr_assert_not_null(strstr((char *)buf, "WholeExtent=\"0 2 0 1 0 0\""));
    cr_assert_null(strstr((char *)buf, "compressor="));
    unsigned char *p = (unsigned char *)strchr(strstr((char *)buf, "<AppendedData"), '_') + 1;
    uint64_t len;
    memcpy(&len, p, 8);
    cr_assert_eq(len, sizeof v);
    cr_assert_eq(memcmp(p + 8, v, sizeof v), 0);
    memcpy(&len, p + 56, 8);
    cr_assert_eq(len, sizeof g);
    cr_assert_eq(memcmp(p + 64, g, sizeof g), 0);
    tmpdir_remove(dir);
}

/* PolyData: a helix polyline, two short polylines and a triangulated
 * 3x3 grid, with point data; compared number for number by VTK. */
static void write_and_check_vtp(int compress)
{
    char dir[64], path[128], exp[128], args[512];
    tmpdir_file(dir, sizeof dir, "shape.vtp", path, sizeof path);
    snprintf(exp, sizeof exp, "%s/expected.txt", dir);
    enum { NH = 7, NP = NH + 9, NT = 8 };
    double pts[3 * NP], val[NP], grad[3 * NP];
    for (int i = 0; i < NH; i++) {
        pts[3 * i] = cos(0.7 * i);
        pts[3 * i + 1] = sin(0.7 * i);
        pts[3 * i + 2] = 0.1 * i;
    }
    for (int j = 0; j < 3; j++)
        for (int i = 0; i < 3; i++) {
            int id = NH + i + 3 * j;
            pts[3 * id] = 2.0 + 0.5 * i;
            pts[3 * id + 1] = -1.0 / 3.0 * j;
            pts[3 * id + 2] = 0.0;
        }
    for (int i = 0; i < NP; i++) {
        val[i] = pts[3 * i] - pts[3 * i + 1];
        grad[3 * i] = 1;
        grad[3 * i + 1] = -1;
        grad[3 * i + 2] = 0;
    }
    size_t conn[NH + 3 + 3], off[4] = {0, NH, NH + 3, NH + 6};
    for (int i = 0; i < NH; i++) conn[i] = (size_t)i;
    size_t extra[6] = {NH, NH + 1, NH + 2, NH + 8, NH + 4, NH};
    memcpy(conn + NH, extra, sizeof extra);
    size_t tris[3 * NT];
    int t = 0;
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            size_t a = NH + i + 3 * j, b = a + 1, c = a + 3, d = a + 4;
            size_t q[6] = {a, b, d, a, d, c};
            memcpy(tris + 3 * t, q, sizeof q);
            t += 2;
        }
    dfl_vtk_array arrays[2] = {{"value", 1, val}, {"gradient", 3, grad}};
    dfl_vtp_data d = {NP, pts, 3, off, conn, NT, tris, arrays, 2};
    dfl_err err;
    cr_assert_eq(dfl_vtp_write(path, &d, compress, &err), DFL_OK, "%s", err.msg);

    FILE *fp = fopen(exp, "w");
    cr_assert_not_null(fp);
    fprintf(fp, "points %d\n", NP);
    for (int i = 0; i < NP; i++)
        fprintf(fp, "%.17g %.17g %.17g\n", pts[3 * i], pts[3 * i + 1], pts[3 * i + 2]);
    fprintf(fp, "lines 3\n");
    for (int l = 0; l < 3; l++) {
        fprintf(fp, "%zu", off[l + 1] - off[l]);
        for (size_t k = off[l]; k < off[l + 1]; k++) fprintf(fp, " %zu", conn[k]);
        fputc('\n', fp);
    }
    fprintf(fp, "polys %d\n", NT);
    for (int i = 0; i < NT; i++)
        fprintf(fp, "3 %zu %zu %zu\n", tris[3 * i], tris[3 * i + 1], tris[3 * i + 2]);
    fprintf(fp, "array value 1\n");
    for (int i = 0; i < NP; i++) fprintf(fp, "%.17g\n", val[i]);
    fprintf(fp, "array gradient 3\n");
    for (int i = 0; i < NP; i++)
        fprintf(fp, "%.17g %.17g %.17g\n", grad[3 * i], grad[3 * i + 1], grad[3 * i + 2]);
    fclose(fp);

    snprintf(args, sizeof args, "vtp '%s' '%s'", path, exp);
    cr_assert_eq(run_check(args), 0, "VTK validation failed for %s (compress=%d)", path, compress);

    /* Negative control: a file with a swapped triangle must be rejected. */
    size_t s = tris[0];
    tris[0] = tris[1];
    tris[1] = s;
    cr_assert_eq(dfl_vtp_write(path, &d, compress, &err), DFL_OK, "%s", err.msg);
    snprintf(args, sizeof args, "vtp '%s' '%s' 2>/dev/null >/dev/null", path, exp);
    cr_assert_eq(run_check(args), 1, "validator accepted wrong connectivity");
    tmpdir_remove(dir);
}

Test(vtk, vtp_raw_matches_input) { write_and_check_vtp(0); }
Test(vtk, vtp_zlib_matches_input) { write_and_check_vtp(1); }

Test(vtk, vtp_points_only)
{
    char dir[64], path[128], exp[128], args[512];
    tmpdir_file(dir, sizeof dir, "pts.vtp", path, sizeof path);
    snprintf(exp, sizeof exp, "%s/expected.txt", dir);
    double pts[6] = {0.5, -1, 2, 1e-300, 3.5, -7};
    dfl_vtp_data d = {2, pts, 0, NULL, NULL, 0, NULL, NULL, 0};
    dfl_err err;
    cr_assert_eq(dfl_vtp_write(path, &d, 1, &err), DFL_OK, "%s", err.msg);
    FILE *fp = fopen(exp, "w");
    fprintf(fp, "points 2\n%.17g %.17g %.17g\n%.17g %.17g %.17g\nlines 0\npolys 0\n", pts[0],
            pts[1], pts[2], pts[3], pts[4], pts[5]);
    fclose(fp);
    snprintf(args, sizeof args, "vtp '%s' '%s'", path, exp);
    cr_assert_eq(run_check(args), 0);
    tmpdir_remove(dir);
}

/* A 2 x 2 x 2 grid of zeros at the origin, unit spacing, one array "value":
 * the valid input that the failure tests start from. */
typedef struct zero_grid {
    double v[8];
    int dims[3];
    double o[3], s[3];
    dfl_vtk_array arr;
} zero_grid;

static void zero_grid_init(zero_grid *g)
{
    *g = (zero_grid){.dims = {2, 2, 2}, .s = {1, 1, 1}};
    g->arr = (dfl_vtk_array){"value", 1, g->v};
}

Test(vtk, missing_directory_is_io_error_and_leaves_nothing)
{
    char dir[64], path[160];
    tmpdir_file(dir, sizeof dir, "no/such/dir/f.vti", path, sizeof path);
    double v[1] = {0};
    int dims[3] = {1, 1, 1};
    double o[3] = {0, 0, 0}, s[3] = {1, 1, 1};
    dfl_vtk_array arr = {"value", 1, v};
    dfl_err err;
    dfl_err_clear(&err);
    tmpdir_expect_io_error(dfl_vti_write(path, dims, o, s, &arr, 1, 0, &err), &err, path, dir, 0);
    cr_assert(!file_exists(path));
    dfl_vtp_data d = {1, v, 0, NULL, NULL, 0, NULL, NULL, 0};
    double p3[3] = {0, 0, 0};
    d.points = p3;
    snprintf(path, sizeof path, "%s/no/f.vtp", dir);
    dfl_err_clear(&err);
    tmpdir_expect_io_error(dfl_vtp_write(path, &d, 1, &err), &err, path, dir, 0);
    tmpdir_remove(dir);
}

/* The target is a directory: the temporary file is written, the rename
 * fails, and the temporary must be gone afterwards. */
Test(vtk, failed_rename_removes_temporary)
{
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "target", path, sizeof path);
    cr_assert_eq(mkdir(path, 0700), 0);
    zero_grid g;
    zero_grid_init(&g);
    dfl_err err;
    dfl_err_clear(&err);
    /* only the directory itself may remain */
    tmpdir_expect_io_error(dfl_vti_write(path, g.dims, g.o, g.s, &g.arr, 1, 1, &err), &err, path,
                           dir, 1);
    tmpdir_remove(dir);
}

Test(vtk, invalid_input_rejected_without_file)
{
    char dir[64], path[128];
    tmpdir_file(dir, sizeof dir, "bad.vti", path, sizeof path);
    zero_grid g;
    zero_grid_init(&g);
    const int *dims = g.dims;
    const double *o = g.o, *s = g.s, *v = g.v;
    dfl_err err;
    cr_assert_eq(dfl_vti_write(path, dims, o, s, NULL, 1, 0, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_vti_write(path, dims, o, s, &g.arr, 0, 0, &err), DFL_E_INPUT);
    int bad_dims[3] = {2, 0, 2};
    cr_assert_eq(dfl_vti_write(path, bad_dims, o, s, &g.arr, 1, 0, &err), DFL_E_INPUT);
    double bad_s[3] = {1, 0, 1};
    cr_assert_eq(dfl_vti_write(path, dims, o, bad_s, &g.arr, 1, 0, &err), DFL_E_INPUT);
    dfl_vtk_array two[2] = {{"value", 1, v}, {"value", 1, v}};
    cr_assert_eq(dfl_vti_write(path, dims, o, s, two, 2, 0, &err), DFL_E_INPUT);
    dfl_vtk_array noname = {"", 1, v};
    cr_assert_eq(dfl_vti_write(path, dims, o, s, &noname, 1, 0, &err), DFL_E_INPUT);
    dfl_vtk_array badc = {"value", 0, v};
    cr_assert_eq(dfl_vti_write(path, dims, o, s, &badc, 1, 0, &err), DFL_E_INPUT);

    snprintf(path, sizeof path, "%s/bad.vtp", dir);
    double pts[6] = {0};
    size_t tri[3] = {0, 1, 2}; /* index 2 does not exist */
    dfl_vtp_data d = {2, pts, 0, NULL, NULL, 1, tri, NULL, 0};
    cr_assert_eq(dfl_vtp_write(path, &d, 0, &err), DFL_E_INPUT);
    size_t off[2] = {1, 2}, conn[2] = {0, 1};
    dfl_vtp_data d2 = {2, pts, 1, off, conn, 0, NULL, NULL, 0};
    cr_assert_eq(dfl_vtp_write(path, &d2, 0, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_vtp_write(path, NULL, 0, &err), DFL_E_INPUT);
    cr_assert_eq(tmpdir_count(dir), 0);
    tmpdir_remove(dir);
}

/* Cell counts: (n - 1) per axis of more than one point, 1 for a flat one. */
Test(vtk, vti_ncells_counts_cells_per_axis)
{
    cr_expect_eq(dfl_vti_ncells((int[3]){3, 4, 5}), 2u * 3 * 4);
    cr_expect_eq(dfl_vti_ncells((int[3]){3, 4, 1}), 2u * 3);
    cr_expect_eq(dfl_vti_ncells((int[3]){1, 1, 1}), 1u);
}

/* Cell data: written as <CellData> Float64 arrays; a name shared with a
 * point array or a missing data pointer is refused and nothing is left. */
Test(vtk, vti_cell_data_and_refusals)
{
    char dir[256], path[512];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/c.vti", dir);
    const int dims[3] = {3, 2, 2};
    const double o[3] = {0, 0, 0}, h[3] = {1, 1, 1};
    double u[12] = {0}, lev[2] = {1, 2};
    dfl_vtk_array pa[1] = {{"value", 1, u}}, ca[1] = {{"level", 1, lev}};
    dfl_err err = {0};
    cr_assert_eq(dfl_vti_write_cells(path, dims, o, h, pa, 1, ca, 1, 0, &err), DFL_OK, "%s",
                 err.msg);
    char *x = e2e_slurp(path);
    cr_assert(x);
    const char *cd = strstr(x, "<CellData>");
    cr_assert(cd);
    cr_expect(strstr(cd, "Name=\"level\""), "%s", x);
    free(x);
    unlink(path);
    dfl_vtk_array dup[1] = {{"value", 1, lev}}, nodata[1] = {{"level", 1, NULL}};
    cr_expect_eq(dfl_vti_write_cells(path, dims, o, h, pa, 1, dup, 1, 0, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "'value'"), "%s", err.msg);
    cr_expect_eq(dfl_vti_write_cells(path, dims, o, h, pa, 1, nodata, 1, 0, &err), DFL_E_INPUT);
    cr_expect_eq(access(path, F_OK), -1);
    e2e_rmtree(dir);
}

/* A collection lists its data sets in order with their times (XML-escaped
 * names); a non-finite time or a missing name is refused, nothing left. */
Test(vtk, pvd_lists_data_sets)
{
    char dir[256], path[512];
    e2e_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/s.pvd", dir);
    const dfl_pvd_entry e[2] = {{"a_pt000.vti", 0}, {"b&c.vti", 2.5}};
    dfl_err err = {0};
    cr_assert_eq(dfl_pvd_write(path, e, 2, &err), DFL_OK, "%s", err.msg);
    char *x = e2e_slurp(path);
    cr_assert(x);
    const char *a = strstr(x, "timestep=\"0\" group=\"\" part=\"0\" file=\"a_pt000.vti\"");
    const char *b = strstr(x, "timestep=\"2.5\" group=\"\" part=\"0\" file=\"b&amp;c.vti\"");
    cr_expect(a && b && a < b, "%s", x);
    cr_expect(strstr(x, "<VTKFile type=\"Collection\""), "%s", x);
    free(x);
    unlink(path);
    const dfl_pvd_entry bad[1] = {{"a.vti", NAN}}, noname[1] = {{"", 0}};
    cr_expect_eq(dfl_pvd_write(path, bad, 1, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_pvd_write(path, noname, 1, &err), DFL_E_INPUT);
    cr_expect_eq(access(path, F_OK), -1);
    e2e_rmtree(dir);
}
