/* io/field_write: the .vti is read back by VTK (tests/io/vtk_check.py), the
 * .exr by the library's decoder; the section an image shows and its
 * orientation are checked pixel by pixel. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "io/exr.h"
#include "io/field_write.h"
#include "util/e2e_util.h"

/* u = A x + B y + C z + D at the lattice nodes, gradient (A, B[, C]),
 * reference u - (0.01 + 0.001 idx). */
#define A 0.5
#define B -2.0
#define C 0.25
#define D 1.0

typedef struct lattice {
    dfl_field_samples s;
    double *u, *gu, *ref;
} lattice;

static void lattice_make(lattice *L, const int dims[3], const double origin[3],
                         const double spacing[3], int gdim)
{
    memset(L, 0, sizeof *L);
    const size_t m = (size_t)dims[0] * (size_t)dims[1] * (size_t)dims[2];
    L->u = malloc(m * sizeof *L->u);
    L->gu = malloc((size_t)gdim * m * sizeof *L->gu);
    L->ref = malloc(m * sizeof *L->ref);
    cr_assert(L->u && L->gu && L->ref);
    for (size_t idx = 0; idx < m; idx++) {
        const size_t i = idx % (size_t)dims[0], j = idx / (size_t)dims[0] % (size_t)dims[1],
                     k = idx / ((size_t)dims[0] * (size_t)dims[1]);
        const double x = origin[0] + (double)i * spacing[0], y = origin[1] + (double)j * spacing[1],
                     z = origin[2] + (double)k * spacing[2];
        L->u[idx] = A * x + B * y + C * z + D;
        L->gu[(size_t)gdim * idx] = A;
        L->gu[(size_t)gdim * idx + 1] = B;
        if (gdim == 3) L->gu[3 * idx + 2] = C;
        L->ref[idx] = L->u[idx] - (0.01 + 0.001 * (double)idx);
    }
    memcpy(L->s.dims, dims, sizeof L->s.dims);
    memcpy(L->s.origin, origin, sizeof L->s.origin);
    memcpy(L->s.spacing, spacing, sizeof L->s.spacing);
    L->s.gdim = gdim;
    L->s.u = L->u;
    L->s.gu = L->gu;
    L->s.ref = L->ref;
}

static void lattice_free(lattice *L)
{
    free(L->u);
    free(L->gu);
    free(L->ref);
}

/* Runs the VTK validator on a .vti of the linear field; its exit status. */
static int vti_check(const char *path, const dfl_field_samples *s, double c, int narrays)
{
    char cmd[8192];
    snprintf(cmd, sizeof cmd,
             "'%s' tests/io/vtk_check.py vti '%s' --dims %d %d %d --origin %.17g %.17g %.17g "
             "--spacing %.17g %.17g %.17g --linear %.17g %.17g %.17g %.17g %s --narrays %d "
             ">/dev/null",
             e2e_python(), path, s->dims[0], s->dims[1], s->dims[2], s->origin[0], s->origin[1],
             s->origin[2], s->spacing[0], s->spacing[1], s->spacing[2], A, B, c, D,
             s->gu ? "--gradient" : "", narrays);
    const int rc = system(cmd);
    return rc == -1 || !WIFEXITED(rc) ? -1 : WEXITSTATUS(rc);
}

/* Checks channel name of the .exr against want(idx) of the lattice node
 * shown at each pixel: image x along axis a0, image y along a1 from the
 * top (largest coordinate), the section at node k0 of axis c. */
static void exr_check(const char *path, const char *name, const lattice *L, int a0, int a1, int c,
                      int k0)
{
    int w, h;
    float *px;
    dfl_err err;
    cr_assert_eq(dfl_exr_read_channel(path, name, &w, &h, &px, &err), DFL_OK, "%s", err.msg);
    cr_assert_eq(w, L->s.dims[a0]);
    cr_assert_eq(h, L->s.dims[a1]);
    const size_t stride[3] = {1, (size_t)L->s.dims[0], (size_t)L->s.dims[0] * L->s.dims[1]};
    for (int r = 0; r < h; r++)
        for (int i = 0; i < w; i++) {
            const size_t idx =
                (size_t)i * stride[a0] + (size_t)(h - 1 - r) * stride[a1] + (size_t)k0 * stride[c];
            const double *g = L->gu + (size_t)L->s.gdim * idx;
            const double gn = L->s.gdim == 3 ? sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2])
                                             : sqrt(g[0] * g[0] + g[1] * g[1]);
            const double want = strcmp(name, "value") == 0       ? L->u[idx]
                                : strcmp(name, "grad_norm") == 0 ? gn
                                                                 : L->u[idx] - L->ref[idx];
            cr_assert_eq(px[(size_t)r * (size_t)w + (size_t)i], (float)want,
                         "%s: %s at pixel (%d, %d) (node %zu)", path, name, i, r, idx);
        }
    free(px);
}

static void path_in(char *buf, size_t size, const char *dir, const char *name)
{
    snprintf(buf, size, "%s/%s", dir, name);
}

static void cleanup(const char *dir, const char *const *names, int n)
{
    char p[8192];
    for (int i = 0; i < n; i++) {
        path_in(p, sizeof p, dir, names[i]);
        remove(p);
    }
    rmdir(dir);
}

typedef struct lattice_case {
    const char *what;
    int dims[3];
    double origin[3], spacing[3];
    int gdim, compress;
    int a0, a1, c, k0; /* image x, image y, section normal and node */
} lattice_case;

/* Writes the case's lattice (gradient and reference) with dfl_field_write
 * and checks both files: the .vti by VTK (value, gradient, grad_norm,
 * error, reference), every channel of the .exr pixel by pixel. */
static void check_case(const lattice_case *k)
{
    char dir[4096], vti[4200], exr[4200];
    e2e_tmpdir(dir, sizeof dir);
    path_in(vti, sizeof vti, dir, "f.vti");
    path_in(exr, sizeof exr, dir, "f.exr");
    lattice L;
    lattice_make(&L, k->dims, k->origin, k->spacing, k->gdim);
    const dfl_field_write_opts o = {1, 1, k->compress, 0};
    dfl_err err;
    cr_assert_eq(dfl_field_write(vti, exr, &L.s, &o, &err), DFL_OK, "%s: %s", k->what, err.msg);
    cr_expect_eq(vti_check(vti, &L.s, k->gdim == 3 ? C : 0.0, 5), 0, "%s: VTK rejected %s",
                 k->what, vti);
    const char *const ch[3] = {"value", "grad_norm", "error"};
    for (int i = 0; i < 3; i++) exr_check(exr, ch[i], &L, k->a0, k->a1, k->c, k->k0);
    cr_expect_eq(e2e_count_entries(dir), 2, "%s", k->what);
    lattice_free(&L);
    cleanup(dir, (const char *const[]){"f.vti", "f.exr"}, 2);
}

/* A 2D lattice (the .vti pads the gradient with z = 0; the .exr is the
 * whole lattice, y up), section planes of 3D space (one node along the
 * normal: the .vti places the plane where it is; the image runs along the
 * other two axes in increasing order) and a volume (its image is the
 * middle section k = dims[2]/2). */
Test(field_write, lattices)
{
    const lattice_case cases[] = {
        {"2D", {5, 4, 1}, {-1, 0.5, 0}, {0.5, 0.25, 1}, 2, 1, 0, 1, 2, 0},
        {"plane y", {4, 1, 3}, {0, 0.75, -1}, {0.5, 1, 0.125}, 3, 0, 0, 2, 1, 0},
        {"plane x", {1, 3, 2}, {0.5, 0, 0}, {1, 0.5, 0.5}, 3, 1, 1, 2, 0, 0},
        {"plane z", {3, 4, 1}, {0, 0, -0.5}, {0.25, 0.5, 1}, 3, 0, 0, 1, 2, 0},
        {"volume", {3, 2, 5}, {0, 0, 0}, {1, 1, 1}, 3, 1, 0, 1, 2, 2},
    };
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) check_case(&cases[i]);
}

/* Without gradient and reference only "value" is written (HALF here); the
 * options choose the files. */
Test(field_write, channels_and_options)
{
    char dir[4096], exr[4200], vti[4200];
    e2e_tmpdir(dir, sizeof dir);
    path_in(exr, sizeof exr, dir, "v.exr");
    path_in(vti, sizeof vti, dir, "v.vti");
    lattice L;
    lattice_make(&L, (int[3]){3, 2, 5}, (double[3]){0, 0, 0}, (double[3]){1, 1, 1}, 3);
    L.s.gu = NULL;
    L.s.ref = NULL;
    dfl_err err;
    /* exr only: no .vti appears */
    const dfl_field_write_opts o = {0, 1, 1, 1};
    cr_assert_eq(dfl_field_write(NULL, exr, &L.s, &o, &err), DFL_OK, "%s", err.msg);
    int w, h;
    float *px = NULL;
    cr_expect_eq(dfl_exr_read_channel(exr, "grad_norm", &w, &h, &px, &err), DFL_E_INPUT);
    cr_expect_eq(dfl_exr_read_channel(exr, "error", &w, &h, &px, &err), DFL_E_INPUT);
    cr_assert_eq(dfl_exr_read_channel(exr, "value", &w, &h, &px, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(px[0], (float)L.u[(size_t)(h - 1) * 3 + 2 * 6]); /* half of a small integer */
    free(px);
    cr_expect_eq(e2e_count_entries(dir), 1);
    /* vti only, value only: one point array */
    const dfl_field_write_opts ov = {1, 0, 0, 0};
    cr_assert_eq(dfl_field_write(vti, NULL, &L.s, &ov, &err), DFL_OK, "%s", err.msg);
    cr_expect_eq(vti_check(vti, &L.s, C, 1), 0, "VTK rejected %s", vti);
    lattice_free(&L);
    cleanup(dir, (const char *const[]){"v.exr", "v.vti"}, 2);
}

/* An unwritable path: DFL_E_IO naming it, no file left. */
Test(field_write, unwritable_path)
{
    char dir[4096], vti[4200];
    e2e_tmpdir(dir, sizeof dir);
    path_in(vti, sizeof vti, dir, "missing/f.vti");
    lattice L;
    lattice_make(&L, (int[3]){2, 2, 1}, (double[3]){0, 0, 0}, (double[3]){1, 1, 1}, 2);
    dfl_err err;
    cr_expect_eq(dfl_field_write_vti(vti, &L.s, 0, &err), DFL_E_IO);
    cr_expect(strstr(err.msg, "missing/f.vti") != NULL, "%s", err.msg);
    cr_expect_eq(dfl_field_write_exr(vti, &L.s, 0, &err), DFL_E_IO);
    cr_expect_eq(e2e_count_entries(dir), 0);
    lattice_free(&L);
    rmdir(dir);
}
