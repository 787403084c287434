/* Config -> bs04 R-function objects (rfunc/): the `[field] kind = rfunc`
 * factory, the parsed field description it builds from, and the readers
 * of the join, trim and triangle-trim keys that studies share.
 *
 *   dfl_rfunc_spec_from_cfg      [sec] -> dfl_rfunc_field_spec (parsed, owned)
 *   dfl_rfunc_spec_from_kind_cfg the same after checking kind = rfunc
 *   dfl_rfunc_field_from_spec    spec -> dfl_field (rfunc/rfield.h)
 *   dfl_rfunc_field_from_cfg     both: the field-kind factory (field_cfg.h)
 *   dfl_rfunc_normalized_from_cfg  the `kind = normalized` factory (appendix A)
 *   dfl_rfunc_normalized_keys    its keys
 *   dfl_rfunc_spec_free
 *   dfl_rfunc_join_from_cfg      key join
 *   dfl_rfunc_join_p_from_cfg    keys join and p, checked together
 *   dfl_rfunc_trim_from_cfg      key trim
 *   dfl_rfunc_tri_opts_from_cfg  keys tri_trim, a, k [, smooth]
 *
 * Keys of a `kind = rfunc` section (the caller has read `kind`).  Parts, at
 * least one kind, all of one dimension, joined in this order (the order
 * matters for rconj only): region, polyline (vertices or curve),
 * triangles, surface, points.
 *   region   = x0 y0; x1 y1; ...   a convex polygon region (2D, >= 3
 *              vertices; rfunc/region.h), 0 on the whole region
 *   triangles = x y z; x y z; x y z; ...   3D triangles, three vertices each
 *   surface  = <section>           a bspline_surface or bezier_surface
 *              section, triangulated with Hausdorff bound eps (key eps;
 *              max_tris caps it, default 200000): bs04's triangulated
 *              surfaces; not with curve (both would read eps); or a
 *              [shape] kind = mesh section, whose triangles are taken as
 *              they are (no eps, no max_tris)
 *   tri_trim, a, k, smooth         the triangles' trims (with triangles or
 *              surface; dfl_rfunc_tri_opts_from_cfg)
 *   points   = x y[ z]; ...        point parts (rfunc/region.h)
 *   vertices = x0 y0; x1 y1; ...   a 2D polyline, or x y z; ... (3D space
 *              polyline; the dimension is the number of values of the
 *              first vertex), at least 2 vertices (3 when closed), no two
 *              consecutive vertices equal
 *   closed   = false | true        with vertices only: adds the segment
 *              from the last vertex back to the first
 *   curve    = <section>           instead of vertices: a [section] with
 *              kind = bspline_curve (experiments/cfg/curve_cfg.h), polygonized
 *              with Hausdorff bound
 *   eps      = <max deviation>     > 0, required with curve; a closed curve
 *              (first point == last) gives a closed polyline
 *   join     = requiv | rconj | requiv_corrected     default requiv
 *   p        = integer 1..64       default 2; rconj needs p >= 2
 *   trim     = disk | disk_smooth | strip | strip_smooth   default disk
 *   correction = guarded | eq20    default guarded; the corrected join's
 *              form (rfunc/join.h): dflab's guard, or bs04's eq. 20
 *              literally (NaN where its radicand <= 0); ignored by the
 *              other joins
 * Domain (rfunc/domain.h): coordinates beyond 1e100 and degenerate
 * polylines (tiny segments, A-B-A backtracks, collinear closed ones) are
 * rejected at key vertices (or curve) naming the vertex or segment.
 * The accepted join and trim names are the lists of rfunc/join.h and
 * rfunc/segment.h.  The field is unsigned (bs04's approximate distance to
 * the set), 0 on the polyline.  Errors: DFL_E_INPUT naming file:line,
 * [section] and key.
 */
#ifndef DFL_EXPERIMENTS_RFUNC_CFG_H
#define DFL_EXPERIMENTS_RFUNC_CFG_H

#include <stdbool.h>
#include <stddef.h>

#include "core/status.h"
#include "field/field.h"
#include "geom/bspline.h"
#include "geom/polygonize.h"
#include "io/config.h"
#include "rfunc/join.h"
#include "rfunc/segment.h"
#include "rfunc/tri3d.h"

/* What a `kind = rfunc` section says, as parsed (before the field is built). */
typedef struct dfl_rfunc_field_spec {
    dfl_rfunc_join join;
    int p;               /* 1..DFL_RFUNC_P_MAX; not yet checked against join */
    dfl_rfunc_trim trim;
    dfl_rfunc_correction corr; /* key correction (corrected join only) */
    int dim;             /* 2 or 3 */
    bool closed;         /* the polyline closes (key closed, or a closed curve) */
    double *v;           /* n*dim vertices of the joined polyline (owned); a
                            closed one does not repeat its first vertex */
    size_t n;
    const char *curve;   /* the curve section, or NULL for vertices or no
                            polyline (n = 0) (points
                            into the config: valid while it lives) */
    double eps;          /* with curve: the polygonization bound; else 0 */
    dfl_bspline bspline; /* with curve: the curve (owned; zeroed otherwise) */
    dfl_polyline pl;     /* with curve: its polygonization as
                            dfl_polygonize_curve returned it (parameters t,
                            bound; a closed curve repeats its first point) */
    double *region;      /* 2*nregion region vertices (owned), or NULL */
    size_t nregion;
    double *points;      /* npoints*dim point parts (owned), or NULL */
    size_t npoints;
    double *tris;        /* 9*ntris triangle corners (owned; inline
                            triangles, then the surface's), or NULL */
    size_t ntris;
    dfl_rfunc_tri_opts tri; /* with triangles or surface */
    const char *surface; /* the surface section, or NULL */
    dfl_trimesh mesh;    /* with surface: its triangulation (owned; zeroed
                            otherwise); bound = the certified bound */
} dfl_rfunc_field_spec;

/* Reads [sec] (the keys above) into *out, polygonizing the curve when one
 * is named.  Every value is checked on its own (p in range, known names,
 * point lists); the pair (join, p) is checked when the field is built, so
 * that a study can report rconj with p = 1 instead of failing.  On failure
 * *out is zeroed and owns nothing. */
dfl_status dfl_rfunc_spec_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *out,
                                   dfl_err *err);

/* [sec] kind must be rfunc (else DFL_E_INPUT at key kind naming who, the
 * study that needs it), then dfl_rfunc_spec_from_cfg. */
dfl_status dfl_rfunc_spec_from_kind_cfg(const dfl_cfg *cfg, const char *sec, const char *who,
                                        dfl_rfunc_field_spec *out, dfl_err *err);

/* The field of spec (read from [sec] of cfg, which names the key in
 * errors): DFL_E_INPUT for a (join, p) pair rfunc/join.h rejects (at key p)
 * or degenerate geometry (at vertices or curve).  *out is untouched on
 * failure; release it with dfl_field_destroy. */
dfl_status dfl_rfunc_field_from_spec(const dfl_cfg *cfg, const char *sec,
                                     const dfl_rfunc_field_spec *spec, dfl_field *out,
                                     dfl_err *err);

/* Frees what spec owns and zeroes it; safe on a zeroed spec. */
void dfl_rfunc_spec_free(dfl_rfunc_field_spec *spec);

/* The `kind = rfunc` factory: dfl_rfunc_spec_from_cfg, then
 * dfl_rfunc_field_from_spec.  *out is untouched on failure. */
dfl_status dfl_rfunc_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                    dfl_err *err);

/* The `kind = normalized` factory (field_cfg.h): bs04 appendix A's
 * recursive normalization (rfunc/normalize.h) of an implicit function,
 * keys implicit = <section> (kind = ellipse with semi-axes a, b > 0: f =
 * x^2/a^2 + y^2/b^2 - 1) and m = order 1..6.  Errors name file:line and
 * key; *out is untouched on failure. */
dfl_status dfl_rfunc_normalized_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                         dfl_err *err);

/* The keys of a kind = normalized section: the implicit section's name,
 * its semi-axes and m (read and checked as the factory reads them). */
dfl_status dfl_rfunc_normalized_keys(const dfl_cfg *cfg, const char *sec, const char **implicit,
                                     double *a, double *b, long *m, dfl_err *err);

/* [sec] join (one of dfl_rfunc_join_names; default requiv). */
dfl_status dfl_rfunc_join_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_join *join,
                                   dfl_err *err);

/* [sec] join (default requiv) and p (1..DFL_RFUNC_P_MAX, default 2),
 * checked together by dfl_rfunc_join_check (error at key p).  Outputs are
 * written only on success. */
dfl_status dfl_rfunc_join_p_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_join *join,
                                     int *p, dfl_err *err);

/* [sec] trim (one of dfl_rfunc_trim_names; default disk). */
dfl_status dfl_rfunc_trim_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_trim *trim,
                                   dfl_err *err);

/* [sec] tri_trim (prism | conditional, default conditional), a (default
 * 0.2, in [1e-12, 1e12]), k (default 2, 2..64) and, when smooth_key,
 * smooth (default false) into *out, starting from dfl_rfunc_tri_defaults.
 * Ranges only: dfl_rfunc_tri_init checks the rest (k even). */
dfl_status dfl_rfunc_tri_opts_from_cfg(const dfl_cfg *cfg, const char *sec, bool smooth_key,
                                       dfl_rfunc_tri_opts *out, dfl_err *err);

#endif
