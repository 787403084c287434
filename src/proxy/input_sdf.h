/* Proxy input from a signed distance function (hvb25 Sec. 5.2).
 *
 * Function index
 *   dfl_proxy_curv_method   analytic (SDF Hessian) | fit (proxy/curvfit.h)
 *   dfl_curvfit_opts        grid g and spacing of curvature = fit
 *   dfl_proxy_input_sdf     wrap a dfl_shape as a proxy input
 *
 * Footpoint (the paper's): p = x - f(x) grad f(x), n = grad f(x) / |grad f(x)|,
 * d = f(x), one batched evaluation of the shape per chunk of points.  Exact
 * for exact SDFs (sphere, torus, cylinder, plane, cone, box) up to rounding;
 * for CSG of SDFs f is a bound of the distance inside a union's
 * complement etc., and p is then the paper's approximation, not the closest
 * point.  certified = 1 when f and its gradient are finite and
 * ||grad f| - 1| <= 1e-6 (the SDF's own claim: there is no certificate).
 *
 * Curvature:
 *   analytic: Goldman's formula (hvb25 ref. [6]; geom/curvature.h's
 *     dfl_curvature_implicit) with grad = n and the SDF's Hessian at p
 *     (geom/shape.h's dfl_shape_hessian: closed form for sphere, torus,
 *     cylinder, plane and exact CSG of them, else six order-2 jets);
 *     shapes without either give NAN curvatures and certified = 0.
 *   fit: the paper's cubic fit on a g x g tangent grid (proxy/curvfit.h);
 *     where it fails (fewer than 10 grid nodes whose normal line meets the
 *     surface: a boundary, a mesh's hole) the curvatures are NAN, or, with
 *     plane_fallback, 0 (the tangent plane); certified = 0 either way.
 *     With focal_clamp the fitted curvatures are cut to 1 + k d >= 0.
 *
 * Thread safety: the input is read-only after construction; queries run
 * concurrently; nothing allocates per point (chunks of 64 on the stack).
 */
#ifndef DFL_PROXY_INPUT_SDF_H
#define DFL_PROXY_INPUT_SDF_H

#include "core/status.h"
#include "geom/shape.h"
#include "proxy/input.h"

typedef enum dfl_proxy_curv_method {
    DFL_PROXY_CURV_ANALYTIC = 0,
    DFL_PROXY_CURV_FIT = 1
} dfl_proxy_curv_method;

/* Options of curvature = fit: a g x g grid (g odd, 3..15) of spacing h > 0
 * on the tangent plane. */
typedef struct dfl_curvfit_opts {
    int g;
    double spacing;
    int plane_fallback; /* 0 (the paper's): a failed fit gives NAN curvatures,
                           certified = 0, and the builder stores no proxy;
                           1: curvatures 0 (the tangent plane at p, an
                           order-2 proxy without bend), certified = 0, so
                           the grid counts it as uncertified */
    int focal_clamp;    /* 0 (the paper's): the fitted curvatures as fitted;
                           1: each principal curvature k cut to 1 + k d >= 0
                           (d the signed distance of x along n): p is the
                           closest point from x only if x is not past a
                           centre of curvature, so a larger bend contradicts
                           the footpoint (a mesh's crease, fitted at the
                           stencil's scale), and its proxy turns inside out
                           at x (errors of 2 |d| measured on Wuson) */
} dfl_curvfit_opts;

/* Takes ownership of *shape (3D; zeroed on success and on failure).  fit
 * may be NULL unless curv == DFL_PROXY_CURV_FIT.  DFL_E_INPUT for a 2D
 * shape or bad fit options, DFL_E_NOMEM. */
dfl_status dfl_proxy_input_sdf(dfl_shape *shape, dfl_proxy_curv_method curv,
                               const dfl_curvfit_opts *fit, dfl_proxy_input *out, dfl_err *err);

#endif
