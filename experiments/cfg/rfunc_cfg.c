/* Config -> rfunc field.  The library reports degenerate geometry without
 * knowing where it came from; every such message is prefixed here with
 * file:line, [section] and key. */
#include "cfg/rfunc_cfg.h"

#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfg/curve_cfg.h"
#include "cfg/field_cfg.h"
#include "cfg/shape_cfg.h"
#include "geom/mesh.h"
#include "geom/surface.h"
#include "rfunc/normalize.h"
#include "rfunc/rfield.h"

/* The curve named by [sec] curve, polygonized to [sec] eps, into the spec:
 * the curve, its polyline and the vertices (a closed curve, first point ==
 * last, drops the repeated point and sets closed). */
static dfl_status curve_polyline(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                                 dfl_err *err)
{
    const char *kind;
    dfl_status st;
    if ((st = dfl_cfg_string(cfg, sec, "curve", &s->curve, err))) return st;
    /* eps >= 1e-12: the polygon needs about L sqrt(kappa / (8 eps)) segments,
     * above 10^6 below 1e-12 for unit-size curves, where the rounding of the
     * coordinates (1e-16 of their size) is of the order of the bound itself;
     * smaller values were accepted and then failed for want of memory. */
    if ((st = dfl_cfg_double(cfg, sec, "eps", 1e-12, 1e300, &s->eps, err))) return st;
    if (dfl_cfg_has(cfg, sec, "closed"))
        return dfl_cfg_reject(cfg, sec, "closed", err,
                              "closed applies to vertices only (a curve's closedness comes from"
                              " the curve)");
    if (!dfl_cfg_has_section(cfg, s->curve))
        return dfl_cfg_reject(cfg, sec, "curve", err, "no section [%s]", s->curve);
    if ((st = dfl_cfg_string(cfg, s->curve, "kind", &kind, err))) return st;
    if (strcmp(kind, "bspline_curve") != 0)
        return dfl_cfg_reject(cfg, sec, "curve", err,
                              "expected a curve (kind = bspline_curve), section [%s] has kind = %s",
                              s->curve, kind);
    if ((st = dfl_curve_from_cfg(cfg, s->curve, &s->bspline, err))) return st;
    if ((st = dfl_polygonize_curve(&s->bspline, s->eps, 0, &s->pl, err)))
        return dfl_cfg_err_at(cfg, sec, "eps", st, err);
    const dfl_polyline *pl = &s->pl;
    size_t np = pl->n;
    const size_t dim = (size_t)pl->dim;
    if (np >= 4 && memcmp(pl->pts, pl->pts + (np - 1) * dim, dim * sizeof *pl->pts) == 0) {
        s->closed = true;
        np--;
    }
    s->v = malloc(np * dim * sizeof *s->v);
    if (!s->v) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    memcpy(s->v, pl->pts, np * dim * sizeof *s->v);
    s->dim = pl->dim;
    s->n = np;
    return DFL_OK;
}

static dfl_status vertex_polyline(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                                  dfl_err *err)
{
    const char *raw;
    dfl_status st;
    if ((st = dfl_cfg_bool_opt(cfg, sec, "closed", false, &s->closed, err))) return st;
    if ((st = dfl_cfg_string(cfg, sec, "vertices", &raw, err))) return st;
    s->dim = dfl_cfg_point_dim(raw);
    if (s->dim != 2 && s->dim != 3)
        return dfl_cfg_reject(cfg, sec, "vertices", err,
                              "expected vertices of 2 or 3 numbers, the first has %d", s->dim);
    return dfl_cfg_points(cfg, sec, "vertices", s->dim, s->closed ? 3 : 2, &s->v, &s->n, err);
}

/* Appends M's triangles to s->tris as 9 coordinates each. */
static dfl_status append_tris(dfl_rfunc_field_spec *s, const dfl_trimesh *M, dfl_err *err)
{
    double *t = realloc(s->tris, (s->ntris + M->ntris) * 9 * sizeof *t);
    if (!t) return dfl_err_set(err, DFL_E_NOMEM, "out of memory");
    s->tris = t;
    for (size_t i = 0; i < M->ntris; i++)
        for (int c = 0; c < 3; c++)
            memcpy(t + (s->ntris + i) * 9 + 3 * c, M->verts + 3 * M->tris[3 * i + c],
                   3 * sizeof *t);
    s->ntris += M->ntris;
    return DFL_OK;
}

/* Appends the triangles of a [shape] kind = mesh section (geom/mesh.h) as
 * they are: a mesh is its triangles, there is nothing to triangulate and no
 * eps; s->mesh stays empty (bs04_surface's patch data is for surfaces). */
static dfl_status mesh_tris(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                            dfl_err *err)
{
    dfl_shape shape;
    dfl_status st = dfl_shape_from_cfg(cfg, s->surface, &shape, err);
    if (st) return dfl_cfg_err_at(cfg, sec, "surface", st, err);
    const dfl_trimesh *M = dfl_shape_mesh_trimesh(&shape);
    assert(M); /* kind = mesh */
    st = append_tris(s, M, err);
    dfl_shape_free(&shape);
    return st;
}

/* Appends the triangles of the surface named by [sec] surface (kind
 * bspline_surface or bezier_surface), triangulated to [sec] eps, or of a
 * mesh (kind = mesh, its own triangles, no eps). */
static dfl_status surface_tris(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                               dfl_err *err)
{
    const char *kind;
    long max_tris;
    dfl_status st;
    if ((st = dfl_cfg_string(cfg, sec, "surface", &s->surface, err))) return st;
    if (!dfl_cfg_has_section(cfg, s->surface))
        return dfl_cfg_reject(cfg, sec, "surface", err, "no section [%s]", s->surface);
    if ((st = dfl_cfg_string(cfg, s->surface, "kind", &kind, err))) return st;
    if (strcmp(kind, "mesh") == 0) return mesh_tris(cfg, sec, s, err);
    if ((st = dfl_cfg_double(cfg, sec, "eps", 1e-300, 1e300, &s->eps, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "max_tris", 200000, 1, 10000000, &max_tris, err)))
        return st;
    if (strcmp(kind, "bspline_surface") != 0 && strcmp(kind, "bezier_surface") != 0)
        return dfl_cfg_reject(cfg, sec, "surface", err,
                              "expected a surface (kind = bspline_surface, bezier_surface or "
                              "mesh),"
                              " section [%s] has kind = %s",
                              s->surface, kind);
    dfl_surface_set S = {0};
    dfl_trimesh M;
    memset(&M, 0, sizeof M);
    if ((st = dfl_surface_from_cfg(cfg, s->surface, kind, &S, err))) return st;
    st = dfl_polygonize_surface(&S, s->eps, (size_t)max_tris, &M, err);
    dfl_surface_set_free(&S);
    if (st) return dfl_cfg_err_at(cfg, sec, "eps", st, err);
    if ((st = append_tris(s, &M, err))) {
        dfl_trimesh_free(&M);
        return st;
    }
    s->mesh = M;
    return DFL_OK;
}

/* The dimension of a part key: dim (2 or 3) of its first point; *dim is
 * set by the first part key read and every later one must agree. */
static dfl_status part_dim(const dfl_cfg *cfg, const char *sec, const char *key, int want,
                           int *dim, dfl_err *err)
{
    if (*dim == 0) *dim = want;
    if (want != 2 && want != 3)
        return dfl_cfg_reject(cfg, sec, key, err, "expected points of 2 or 3 numbers, the first has %d",
                              want);
    if (want != *dim)
        return dfl_cfg_reject(cfg, sec, key, err,
                              "a %dD part in a %dD field (every part must have one dimension)",
                              want, *dim);
    return DFL_OK;
}

/* The parts other than the polyline: region, triangles, surface, points. */
static dfl_status read_other_parts(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                                   bool *any, dfl_err *err)
{
    dfl_status st;
    int dim = s->dim;
    const char *raw;
    if (dfl_cfg_has(cfg, sec, "region")) {
        if ((st = dfl_cfg_string(cfg, sec, "region", &raw, err))) return st;
        if ((st = part_dim(cfg, sec, "region", 2, &dim, err))) return st;
        if (dfl_cfg_point_dim(raw) != 2)
            return dfl_cfg_reject(cfg, sec, "region", err, "expected 2D vertices x y; ...");
        if ((st = dfl_cfg_points(cfg, sec, "region", 2, 3, &s->region, &s->nregion, err)))
            return st;
        *any = true;
    }
    const bool tri = dfl_cfg_has(cfg, sec, "triangles"), surf = dfl_cfg_has(cfg, sec, "surface");
    if (tri) {
        size_t nv;
        if ((st = dfl_cfg_string(cfg, sec, "triangles", &raw, err))) return st;
        if ((st = part_dim(cfg, sec, "triangles", dfl_cfg_point_dim(raw), &dim, err))) return st;
        if (dim != 3) return dfl_cfg_reject(cfg, sec, "triangles", err, "triangles are 3D");
        if ((st = dfl_cfg_points(cfg, sec, "triangles", 3, 3, &s->tris, &nv, err))) return st;
        if (nv % 3)
            return dfl_cfg_reject(cfg, sec, "triangles", err,
                                  "%zu vertices: expected three per triangle", nv);
        s->ntris = nv / 3;
    }
    if (surf) {
        if (s->curve)
            return dfl_cfg_reject(cfg, sec, "surface", err,
                                  "not with curve (both would be polygonized to eps)");
        if ((st = part_dim(cfg, sec, "surface", 3, &dim, err))) return st;
        if ((st = surface_tris(cfg, sec, s, err))) return st;
    }
    if (tri || surf) {
        if ((st = dfl_rfunc_tri_opts_from_cfg(cfg, sec, true, &s->tri, err))) return st;
        *any = true;
    }
    if (dfl_cfg_has(cfg, sec, "points")) {
        if ((st = dfl_cfg_string(cfg, sec, "points", &raw, err))) return st;
        if ((st = part_dim(cfg, sec, "points", dfl_cfg_point_dim(raw), &dim, err))) return st;
        if ((st = dfl_cfg_points(cfg, sec, "points", dim, 1, &s->points, &s->npoints, err)))
            return st;
        *any = true;
    }
    s->dim = dim;
    return DFL_OK;
}

/* The keys of the header into *s (which may own memory on failure). */
static dfl_status read_spec(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *s,
                            dfl_err *err)
{
    long p;
    dfl_status st;
    if ((st = dfl_rfunc_join_from_cfg(cfg, sec, &s->join, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "p", 2, 1, DFL_RFUNC_P_MAX, &p, err))) return st;
    s->p = (int)p;
    if ((st = dfl_rfunc_trim_from_cfg(cfg, sec, &s->trim, err))) return st;
    int corr;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "correction", dfl_rfunc_correction_names,
                               DFL_RFUNC_CORRECTION_COUNT, DFL_RFUNC_CORR_GUARDED, &corr, err)))
        return st;
    s->corr = (dfl_rfunc_correction)corr;
    const bool has_v = dfl_cfg_has(cfg, sec, "vertices"), has_c = dfl_cfg_has(cfg, sec, "curve");
    if (has_v && has_c) {
        char w[600];
        /* name where the curve was given (the later addition, often a --set) */
        dfl_cfg_where(cfg, sec, "curve", w, sizeof w);
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: kind = rfunc takes at most one of 'vertices' (a polyline) or"
                           " 'curve' (a curve section), both are given",
                           w);
    }
    if (has_v && (st = vertex_polyline(cfg, sec, s, err))) return st;
    if (has_c && (st = curve_polyline(cfg, sec, s, err))) return st;
    bool any = has_v || has_c;
    if ((st = read_other_parts(cfg, sec, s, &any, err))) return st;
    if (!any) {
        char w[600];
        snprintf(w, sizeof w, "%s", "");
        dfl_cfg_where(cfg, sec, "kind", w, sizeof w);
        return dfl_err_set(err, DFL_E_INPUT,
                           "%s: kind = rfunc needs parts: 'vertices' (a polyline) or 'curve' (a"
                           " curve section), 'region', 'triangles', 'surface' or 'points';"
                           " neither is given",
                           w);
    }
    return DFL_OK;
}

dfl_status dfl_rfunc_spec_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_field_spec *out,
                                   dfl_err *err)
{
    dfl_rfunc_field_spec s;
    memset(&s, 0, sizeof s);
    s.tri = dfl_rfunc_tri_defaults();
    dfl_status st = read_spec(cfg, sec, &s, err);
    if (st != DFL_OK) dfl_rfunc_spec_free(&s); /* zeroes it */
    *out = s;
    return st;
}

dfl_status dfl_rfunc_spec_from_kind_cfg(const dfl_cfg *cfg, const char *sec, const char *who,
                                        dfl_rfunc_field_spec *out, dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st = dfl_field_kind_from_cfg(cfg, sec, &kind, err);
    if (st) return st;
    if (kind->build != dfl_rfunc_field_from_cfg)
        return dfl_cfg_reject(cfg, sec, "kind", err, "%s needs kind = rfunc, got '%s'", who,
                              kind->name);
    return dfl_rfunc_spec_from_cfg(cfg, sec, out, err);
}

dfl_status dfl_rfunc_field_from_spec(const dfl_cfg *cfg, const char *sec,
                                     const dfl_rfunc_field_spec *spec, dfl_field *out,
                                     dfl_err *err)
{
    dfl_status st = dfl_rfunc_join_check(spec->join, spec->p, err);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, "p", st, err);
    dfl_rfield *r = NULL;
    st = dfl_rfield_new(spec->dim, spec->join, spec->p, &r, err);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, "p", st, err);
    dfl_rfield_set_correction(r, spec->corr);
    const char *key = NULL;
    char what[64] = "";
    if (spec->nregion) {
        st = dfl_rfield_add_region(r, spec->region, spec->nregion, err);
        key = "region";
    }
    if (st == DFL_OK && spec->n) {
        st = dfl_rfield_add_polyline(r, spec->v, spec->n, spec->closed, spec->trim, err);
        key = spec->curve ? "curve" : "vertices";
    }
    for (size_t i = 0; st == DFL_OK && i < spec->ntris; i++) {
        const double *t = spec->tris + 9 * i;
        st = dfl_rfield_add_triangle(r, t, t + 3, t + 6, &spec->tri, err);
        key = spec->surface && !dfl_cfg_has(cfg, sec, "triangles") ? "surface" : "triangles";
        snprintf(what, sizeof what, "triangle %zu", i + 1);
    }
    for (size_t i = 0; st == DFL_OK && i < spec->npoints; i++) {
        st = dfl_rfield_add_point(r, spec->points + i * (size_t)spec->dim, err);
        key = "points";
        snprintf(what, sizeof what, "point %zu", i + 1);
    }
    if (st != DFL_OK) {
        dfl_rfield_free(r);
        if (what[0]) dfl_err_prefix(err, "%s", what);
        return dfl_cfg_err_at(cfg, sec, key, st, err);
    }
    st = dfl_rfield_finish(&r, out, err);
    if (st != DFL_OK) return dfl_cfg_err_at(cfg, sec, spec->curve ? "curve" : "vertices", st, err);
    return DFL_OK;
}

void dfl_rfunc_spec_free(dfl_rfunc_field_spec *spec)
{
    free(spec->v);
    free(spec->region);
    free(spec->points);
    free(spec->tris);
    if (spec->mesh.verts || spec->mesh.tris) dfl_trimesh_free(&spec->mesh);
    dfl_bspline_free(&spec->bspline);
    dfl_polyline_free(&spec->pl);
    memset(spec, 0, sizeof *spec);
}

dfl_status dfl_rfunc_field_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                    dfl_err *err)
{
    dfl_rfunc_field_spec spec;
    dfl_status st = dfl_rfunc_spec_from_cfg(cfg, sec, &spec, err);
    if (st != DFL_OK) return st;
    st = dfl_rfunc_field_from_spec(cfg, sec, &spec, out, err);
    dfl_rfunc_spec_free(&spec);
    return st;
}

dfl_status dfl_rfunc_join_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_join *join,
                                   dfl_err *err)
{
    int j;
    dfl_status st = dfl_cfg_enum_opt(cfg, sec, "join", dfl_rfunc_join_names,
                                     DFL_RFUNC_JOIN_COUNT, DFL_RFUNC_REQUIV, &j, err);
    if (st == DFL_OK) *join = (dfl_rfunc_join)j;
    return st;
}

dfl_status dfl_rfunc_join_p_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_join *join,
                                     int *p, dfl_err *err)
{
    dfl_rfunc_join j;
    long pp;
    dfl_status st;
    if ((st = dfl_rfunc_join_from_cfg(cfg, sec, &j, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "p", 2, 1, DFL_RFUNC_P_MAX, &pp, err))) return st;
    if ((st = dfl_rfunc_join_check(j, (int)pp, err))) return dfl_cfg_err_at(cfg, sec, "p", st, err);
    *join = j;
    *p = (int)pp;
    return DFL_OK;
}

dfl_status dfl_rfunc_trim_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_rfunc_trim *trim,
                                   dfl_err *err)
{
    int t;
    dfl_status st = dfl_cfg_enum_opt(cfg, sec, "trim", dfl_rfunc_trim_names,
                                     DFL_RFUNC_TRIM_COUNT, DFL_RFUNC_TRIM_DISK, &t, err);
    if (st == DFL_OK) *trim = (dfl_rfunc_trim)t;
    return st;
}

dfl_status dfl_rfunc_tri_opts_from_cfg(const dfl_cfg *cfg, const char *sec, bool smooth_key,
                                       dfl_rfunc_tri_opts *out, dfl_err *err)
{
    int trim;
    double a;
    long k;
    bool smooth = false;
    dfl_status st;
    if ((st = dfl_cfg_enum_opt(cfg, sec, "tri_trim", dfl_rfunc_tri_trim_names,
                               DFL_RFUNC_TRI_TRIM_COUNT, DFL_RFUNC_TRI_CONDITIONAL, &trim, err)))
        return st;
    if ((st = dfl_cfg_double_opt(cfg, sec, "a", 0.2, 1e-12, 1e12, &a, err))) return st;
    if ((st = dfl_cfg_int_opt(cfg, sec, "k", 2, 2, 64, &k, err))) return st;
    if (smooth_key && (st = dfl_cfg_bool_opt(cfg, sec, "smooth", false, &smooth, err))) return st;
    dfl_rfunc_tri_opts o = dfl_rfunc_tri_defaults();
    o.trim = (dfl_rfunc_tri_trim)trim;
    o.a = a;
    o.k = (int)k;
    if (smooth_key) o.smooth = smooth;
    *out = o;
    return DFL_OK;
}

dfl_status dfl_rfunc_normalized_keys(const dfl_cfg *cfg, const char *sec, const char **implicit,
                                     double *a, double *b, long *m, dfl_err *err)
{
    static const char *const kinds[] = {"ellipse"};
    int kind;
    dfl_status st;
    if ((st = dfl_cfg_string(cfg, sec, "implicit", implicit, err))) return st;
    if (!dfl_cfg_has_section(cfg, *implicit))
        return dfl_cfg_reject(cfg, sec, "implicit", err, "no section [%s]", *implicit);
    if ((st = dfl_cfg_enum(cfg, *implicit, "kind", kinds, 1, &kind, err))) return st;
    if ((st = dfl_cfg_double(cfg, *implicit, "a", 1e-6, 1e6, a, err))) return st;
    if ((st = dfl_cfg_double(cfg, *implicit, "b", 1e-6, 1e6, b, err))) return st;
    return dfl_cfg_int(cfg, sec, "m", 1, 6, m, err);
}

dfl_status dfl_rfunc_normalized_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_field *out,
                                         dfl_err *err)
{
    const char *imp;
    double a, b;
    long m;
    dfl_rfunc_poly poly;
    dfl_status st = dfl_rfunc_normalized_keys(cfg, sec, &imp, &a, &b, &m, err);
    if (st) return st;
    if ((st = dfl_rfunc_poly_ellipse(a, b, &poly, err)))
        return dfl_cfg_err_at(cfg, sec, "implicit", st, err);
    st = dfl_rfunc_normalized_field(&poly, (int)m, out, err);
    dfl_rfunc_poly_free(&poly);
    return st;
}
