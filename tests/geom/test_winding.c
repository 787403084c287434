/* geom/winding.h.  Expected values: closed forms (a cube face subtends
 * 1/6 of the sphere from the centre; a closed mesh winds 1 inside and 0
 * outside), the sign rule, and antisymmetry under reorientation. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdint.h>

#include "core/rng.h"
#include "geom/winding.h"
#include "mesh_fixtures.h"

Test(winding, cube_face_from_the_centre_is_a_sixth)
{
    dfl_trimesh m;
    mf_cube(&m);
    const double o[3] = {0, 0, 0};
    for (int f = 0; f < 6; f++) {
        double w = dfl_winding_brute(m.verts, m.tris + 6 * f, 2, o);
        cr_expect_float_eq(w, 1.0 / 6.0, 1e-15, "face %d: %.17g", f, w);
    }
    dfl_trimesh_free(&m);
}

Test(winding, sign_and_reorientation)
{
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
    const double below[3] = {0.2, 0.2, -1}, above[3] = {0.2, 0.2, 1};
    /* normal (b-a)x(c-a) = +z: seen counter-clockwise from below */
    cr_expect(dfl_winding_triangle(below, a, b, c) > 0);
    cr_expect(dfl_winding_triangle(above, a, b, c) < 0);
    cr_expect_eq(dfl_winding_triangle(below, a, b, c), -dfl_winding_triangle(below, a, c, b));
    /* approaching the triangle's interior the solid angle tends to 2 pi */
    const double near[3] = {0.2, 0.2, -1e-12};
    cr_expect_float_eq(dfl_winding_triangle(near, a, b, c), 0.5, 1e-9);
}

Test(winding, closed_meshes_wind_once_inside_and_never_outside)
{
    dfl_trimesh m[2];
    mf_octahedron(&m[0]);
    mf_cube(&m[1]);
    uint64_t s = 3;
    for (int k = 0; k < 2; k++)
        for (int it = 0; it < 500; it++) {
            double x[3];
            for (int j = 0; j < 3; j++) x[j] = dfl_rng_splitmix(&s, -2, 2);
            double l1 = fabs(x[0]) + fabs(x[1]) + fabs(x[2]);
            double linf = fmax(fmax(fabs(x[0]), fabs(x[1])), fabs(x[2]));
            double in = k == 0 ? 1 - l1 : 1 - linf; /* > 0 inside */
            if (fabs(in) < 1e-6) continue;
            double w = dfl_winding_brute(m[k].verts, m[k].tris, m[k].ntris, x);
            cr_expect_float_eq(w, in > 0 ? 1.0 : 0.0, 1e-13, "mesh %d at (%g %g %g): %.17g", k,
                               x[0], x[1], x[2], w);
        }
    dfl_trimesh_free(&m[0]);
    dfl_trimesh_free(&m[1]);
}
