/* The teaching page's C API: dflab's own 2D R-function fields (rfunc/),
 * exact distances (geom/segdist), jets and normalization orders
 * (field/normorder) and the eq. 13-14 bounds (rfunc/gradbound), in a shape
 * that JavaScript can call through WebAssembly: plain ints and doubles,
 * arrays in the module's heap, one opaque scene per view.
 *
 *   dflw_scene_new / dflw_scene_free   a scene: one 2D open polyline field
 *   dflw_scene_error                   the last failure's one-line message
 *   dflw_two_segments                  the two-segment panel's vertices
 *   dflw_two_bisector                  and the outer bisector of its joint
 *   dflw_scene_polyline                (re)builds the field of a polyline
 *   dflw_scene_exact                   (re)builds it from exact segment distances
 *   dflw_scene_curve                   (re)builds it from a B-spline curve
 *   dflw_scene_vertices                the polyline the field is built on
 *   dflw_eval                          u and grad u at points (as probe)
 *   dflw_grid                          u, exact d and |grad u| on a grid
 *   dflw_dist                          exact d at points
 *   dflw_jet                           d1..dK along a ray (as probe --jet)
 *   dflw_order                         measured normalization order
 *   dflw_bounds                        eq. 13-14 band against phi
 *   dflw_ring                          |grad u| on a circle (angle order)
 *   dflw_bulge                         joint bulge along a direction
 *   dflw_curve_bulge                   the bs04_bulging study's ray measure
 *
 * Nothing here computes a formula of its own: every number comes from the
 * library.  Functions returning int return 0 on success and the
 * dfl_status code otherwise, with the message in dflw_scene_error; a
 * scene whose field failed to build keeps no field (evaluations then
 * write NAN).  Not thread-safe per scene (the page is single-threaded).
 */
#ifndef DFL_WEB_DFLWEB_H
#define DFL_WEB_DFLWEB_H

typedef struct dflw_scene dflw_scene;

/* A scene without a field; NULL when out of memory.  Free with
 * dflw_scene_free (NULL allowed). */
dflw_scene *dflw_scene_new(void);
void dflw_scene_free(dflw_scene *s);

/* Message of the last failure ("" after a success); owned by the scene. */
const char *dflw_scene_error(const dflw_scene *s);

/* The two-segment panel's geometry for the angle alpha (degrees, in
 * [10, 350]; clamped) between the segments: vertex (0.5, 0.6), both arms
 * of length 0.4 pointing downwards symmetric about the vertical (alpha =
 * 180 is a straight line).  Writes v[0..5] = a, vertex, b. */
void dflw_two_segments(double alpha_deg, double *v);

/* The unit direction dir[0..1] of the outer bisector of that joint: the
 * bisector of the reflex side, which is the hatched sector (the closest
 * point of both segments is the vertex, d = |x - vertex|).  Upwards
 * (0, 1) for alpha <= 180, downwards (0, -1) for alpha > 180 (alpha
 * clamped as above).  Upwards at alpha > 180 runs on the convex side,
 * where the closest points lie on the arms (d = t sin(beta) at distance
 * t from the vertex, beta = (360 - alpha)/2), so t/c - 1 there is not
 * the bulge of dflw_bulge's doc. */
void dflw_two_bisector(double alpha_deg, double *dir);

/* Builds the field of the open 2D polyline v[0..2n-1] with the join,
 * order p and trim (codes of rfunc/join.h and rfunc/segment.h), exactly
 * as `[field] kind = rfunc` with these vertices does
 * (dfl_rfield_polyline, fast path on).  DFL_E_INPUT for bad codes,
 * degenerate geometry or a (join, p) pair the library rejects. */
int dflw_scene_polyline(dflw_scene *s, const double *v, int n, int join, int p, int trim);

/* The same polyline with the segments' exact distances as the parts
 * (rfunc/exact_polyline: no trim, no jets), the setting in which eq. 13-14
 * are exact.  No `dflab probe` config builds this field. */
int dflw_scene_exact(dflw_scene *s, const double *v, int n, int join, int p);

/* Builds the field of the open clamped B-spline of order `order` through
 * control points cp[0..2ncp-1] (uniform knots), polygonized with the
 * Hausdorff bound eps (geom/polygonize) as `kind = rfunc` with `curve`
 * and `eps` does. */
int dflw_scene_curve(dflw_scene *s, const double *cp, int ncp, int order, double eps, int join,
                     int p, int trim);

/* Number of vertices of the scene's polyline (0 without a field) and a
 * pointer to its 2n coordinates (owned by the scene). */
int dflw_scene_nvertices(const dflw_scene *s);
const double *dflw_scene_vertices(const dflw_scene *s);

/* u and grad u at m points pts[2i], pts[2i+1] (val[i], grad[2i..2i+1]),
 * one dfl_field_eval1 per point like `dflab probe`. */
void dflw_eval(const dflw_scene *s, int m, const double *pts, double *val, double *grad);

/* nx*ny nodes of [x0, x1] x [y0, y1] at cell centres, row j = 0 at the
 * top (y1), in one batch: u, the exact distance d to the polyline
 * (min over its segments) and |grad u| (floats; any may be NULL). */
void dflw_grid(const dflw_scene *s, int nx, int ny, double x0, double y0, double x1, double y1,
               float *u, float *d, float *gnorm);

/* The exact distance from m points pts[2i], pts[2i+1] to the scene's
 * polyline (min over its segments, as dflw_grid's d) into d[i]; NAN
 * without a field. */
void dflw_dist(const dflw_scene *s, int m, const double *pts, double *d);

/* d_k = k-th derivative of s -> u(x + s dir) at 0+ for k = 1..K (K <=
 * 24) into d[0..K-1], as `dflab probe --jet K`. */
int dflw_jet(dflw_scene *s, const double *x, const double *dir, int K, double *d);

/* Normalization order of u at x along the unit dir (field/normorder,
 * sigma = +1, length scale L, zero tolerance tol, jet order K): returns
 * the order (>= -1; see dfl_normorder), or -2 on failure (message set).
 * *k_first receives the first derivative order that breaks eq. 1. */
int dflw_order(dflw_scene *s, const double *x, const double *dir, int K, double L, double tol,
               int *k_first);

/* eq. 13-14: for n angles phi_i = i (pi/2) / (n - 1) (n >= 2), lo[i] =
 * |F1 - F2|, hi[i] = F1 + F2 of join (requiv or rconj) at order p.
 * DFL_E_INPUT for the corrected join or a bad p (nothing written). */
int dflw_bounds(dflw_scene *s, int join, int p, int n, double *lo, double *hi);

/* |grad u| at n points of the circle of radius r around c, at the angles
 * 2 pi i / n, into g; phi[i] = atan2(h2, h1) of the two exact segment
 * distances there when the polyline has exactly two segments (NAN
 * otherwise; phi may be NULL). */
void dflw_ring(const dflw_scene *s, const double *c, double r, int n, double *g, double *phi);

/* Bulge of the level set u = c along the ray from vertex v in the unit
 * direction dir: the distance t at which u(v + t dir) = c (bisection on
 * [0, tmax]), returned as t / c - 1 (0 for an exact distance's level
 * set; 2^(1/p) - 1 in the hatched sector of R-equivalence).  NAN when u
 * does not reach c on [0, tmax]. */
double dflw_bulge(const dflw_scene *s, const double *v, const double *dir, double c, double tmax);

/* The bulge measure of the bs04_bulging study (field/curveprobe) for the
 * scene built by dflw_scene_curve: rays along the normals of the exact
 * B-spline (nside origins, ncap rays per end, +-N at every interior vertex
 * of the polyline), the first crossing of u = delta on each (search in
 * [0, 8 delta], 128 samples, 6 refinements, offset tolerance 1e-6 as in
 * bs04_bulging.ini), r = (s - delta) / delta.  out[0..3] = max r over all
 * valid rays, over the joint rays, over the side rays, over the cap rays.
 * DFL_E_INPUT when the scene has no curve. */
int dflw_curve_bulge(dflw_scene *s, double delta, int nside, int ncap, double *out);

#endif
