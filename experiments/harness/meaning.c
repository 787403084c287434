/* The knob and column tables behind `dflab help`.  One line per entry,
 * with the unit in the line; "*" matches any study or section (sections a
 * config names itself: shapes, cases, curves).  Entries are grouped by the
 * module that reads the key, and say what the getter cannot: what the
 * value does.  Lengths are in the config's units (the shapes' coordinates). */
#include "harness/meaning.h"

#include <string.h>

typedef struct knob {
    const char *study, *sec, *key, *meaning;
} knob;

static const knob knobs[] = {
    /* the runner (every study) */
    {"*", "study", "name", "the study this config runs (`dflab list`)"},
    {"*", "study", "allow_nonfinite", "true: a table with NaN/inf values is not an error (exit 0)"},
    {"*", "study", "memory_budget", "refuse a point whose estimated peak memory is above this (GB)"},
    {"*", "study", "work_budget", "refuse a point whose estimated work is above this (hours)"},
    /* compare_methods (experiments/compare/compare_methods.c) */
    {"compare_methods", "study", "methods", "the method sections ([field] sections plus the keys below), in row order"},
    {"compare_methods", "study", "shapes", "the shape sections every method runs on"},
    {"compare_methods", "compare", "grid2d", "nodes per axis of the 2D error grid over the shape's box"},
    {"compare_methods", "compare", "grid3d", "nodes per axis of the 3D error grid over the shape's box"},
    {"compare_methods", "compare", "surface", "error points near the surface (footpoint + t n, |t| <= band)"},
    {"compare_methods", "compare", "medial_draws", "random draws kept when near the medial axis (error points)"},
    {"compare_methods", "compare", "band", "half-width of the near-surface band of the band metrics (length)"},
    {"compare_methods", "compare", "medial_band", "half-width of the medial band: points closer count as near-medial (length)"},
    {"compare_methods", "compare", "pairs", "point pairs straddling cell planes for the C0/C1 jumps"},
    {"compare_methods", "compare", "seed", "seed of the random error points and pairs"},
    {"compare_methods", "compare", "repeats", "timed evaluations of the points; the best time is kept"},
    {"compare_methods", "*", "resolution", "the method's field key swept (res, eps, voxel...); none: one row"},
    {"compare_methods", "*", "values", "the swept key's values, one row each (blank-separated)"},
    {"compare_methods", "*", "dims", "the dimensions (2, 3) the method applies to; others are skipped rows"},
    {"compare_methods", "*", "shape_key", "the method's field key that receives the shape section"},
    {"compare_methods", "*", "shape_kinds", "only shapes of these kinds (default any); others are skipped rows"},
    {"compare_methods", "*", "box", "the method's field keys that receive the box (lo hi); none: no box"},
    {"compare_methods", "*", "distance", "what the method approximates: signed d or unsigned |d|"},
    {"compare_methods", "*", "faces", "where the method's cell faces lie: none, count (N per box) or size (voxels)"},
    /* [output] (harness/field_out.h) */
    {"*", "output", "vti", "write the VTK ImageData volume/image files (.vti)"},
    {"*", "output", "exr", "write the OpenEXR image files (.exr)"},
    {"*", "output", "compress", "zlib-compress the arrays of the .vti files"},
    {"*", "output", "half", "HALF (16-bit) channels in the .exr instead of FLOAT"},
    {"*", "output", "vti_n", "nodes per axis of the study's volume (.vti)"},
    /* [grid] (cfg/grid_cfg.h) and [eval] */
    {"*", "*", "n", "nodes per axis of the sampling grid"},
    {"*", "*", "memory_budget", "most memory the grid's buffers may take (GB)"},
    {"*", "eval", "n", "nodes per axis of the error grid over [lo, hi]^3 (the paper: 217)"},
    {"*", "eval", "lo", "lower corner of the error grid (x y z, length)"},
    {"*", "eval", "hi", "upper corner of the error grid (x y z, length)"},
    {"*", "*", "lo", "lower corner of the box (one value or x y [z], length)"},
    {"*", "*", "hi", "upper corner of the box (one value or x y [z], length)"},
    /* [field] (cfg/field_cfg.h and the kinds' factories) */
    {"*", "*", "kind", "which kind of object the section describes (a field, shape or curve kind)"},
    {"*", "field", "order", "proxy order: 1 (plane proxies) or 2 (curved: sphere/torus/cylinder)"},
    {"*", "field", "res", "cells per axis of the grid (N^3 cells)"},
    {"*", "field", "filter", "proxy decoding filter: nearest, trilinear or hermite"},
    {"*", "field", "storage", "scalar storage of the grid: double / float / half (float64 / float16)"},
    {"*", "field", "position", "what a footpoint's 3 scalars store: displacement from the cell or absolute"},
    {"*", "field", "clip", "the sphere constraint: bound (dflab's), paper (proxy solid in a ball) or off"},
    {"*", "field", "clip_radius", "radius of the sphere constraint, in cell sizes (> 0)"},
    {"*", "field", "signed", "true: signed output (negative inside); false: unsigned, as the paper"},
    {"*", "field", "noise", "footpoint noise length added to every stored footpoint (length)"},
    {"*", "field", "noise_at", "only the cell holding this point (x y z) gets the noise"},
    {"*", "field", "seed", "seed of the random numbers (noise, estimator points)"},
    {"*", "field", "input", "what the proxies are built from: sdf, parametric or implicit"},
    {"*", "field", "curvature", "curvatures of order-2 proxies: analytic or fit (least squares)"},
    {"*", "field", "footpoint", "implicit footpoints: robust (dflab) or the paper's (3 readings)"},
    {"*", "field", "fit_grid", "curvature fit: samples per axis of the fit stencil"},
    {"*", "field", "fit_spacing", "curvature fit: stencil spacing (length)"},
    {"*", "field", "param_grid", "parametric input: start-grid nodes per patch and direction"},
    {"*", "field", "param_starts", "parametric input: nearest start nodes refined by Newton"},
    {"*", "field", "implicit_resolution", "implicit input: surface samples along the longest side"},
    {"*", "field", "method", "grid peer: trilinear0, taylor1 or taylor2 samples of the SDF"},
    {"*", "field", "shape", "the section holding the shape the field approximates"},
    {"*", "field", "implicit", "the section holding the implicit function to normalize"},
    {"*", "field", "m", "normalization order m (appendix A recursion)"},
    {"*", "field", "region", "a convex polygon part (x y; x y; ...)"},
    {"*", "*", "vertices", "polyline vertices (x y[ z]; ...) or vertex indices to measure at"},
    {"*", "field", "closed", "true: the polyline also joins its last vertex to the first"},
    {"*", "field", "curve", "the bspline_curve section polygonized into the polyline"},
    {"*", "field", "triangles", "3D triangle parts, three vertices each (x y z; ...)"},
    {"*", "field", "surface", "a parametric surface section triangulated into triangle parts"},
    {"*", "field", "max_tris", "most triangles of the triangulated surface"},
    {"*", "field", "points", "point parts (x y[ z]; ...)"},
    {"*", "*", "join", "how parts' fields are joined: requiv (eq. 6), rconj (eq. 7), requiv_corrected"},
    {"*", "*", "p", "order of the join (integer; larger: closer to min)"},
    {"*", "*", "trim", "segment trim: disk, strip, or their smooth (eq. 5) forms"},
    {"*", "*", "tri_trim", "triangle trim volume: prism or conditional (eq. 15-16)"},
    {"*", "*", "a", "a length/semi-axis/parameter of the kind (see the kind's header)"},
    {"*", "*", "k", "smoothing width (smooth CSG, length) or the trim/jet exponent k"},
    {"*", "field", "smooth", "true: the triangle trims' smooth composition (eq. 5)"},
    {"*", "field", "correction", "the corrected join's form: guarded (dflab) or eq20 (bs04 literally)"},
    {"*", "*", "eps", "tolerance: polygonization/triangulation bound or fit threshold (length)"},
    /* shapes (cfg/shape_cfg.h, cfg/curve_cfg.h, geom/implicit.h) */
    {"*", "*", "center", "centre of the shape (x y[ z], length)"},
    {"*", "*", "radius", "radius (length)"},
    {"*", "*", "axis", "axis direction (x y z, non-zero)"},
    {"*", "*", "major", "torus major radius R, centre to tube centre (length)"},
    {"*", "*", "minor", "torus minor radius r < R, of the tube (length)"},
    {"*", "*", "b", "second end/semi-axis/parameter of the kind (see the kind's header)"},
    {"*", "*", "c", "Goursat surface constant c (default 11.8: the tangle cube)"},
    {"*", "*", "ra", "cone radius at end a (length)"},
    {"*", "*", "rb", "cone radius at end b (length)"},
    {"*", "*", "half", "box half extents per axis (length, > 0)"},
    {"*", "*", "dim", "dimension of the shape: 2 or 3"},
    {"*", "*", "op", "CSG operation: union, intersection, difference (or smooth_*)"},
    {"*", "*", "surface", "implicit surface: torus, goursat, genus2, sphere or ellipsoid"},
    {"*", "*", "solver", "footpoint solver of the implicit surface: newton or ceres"},
    {"*", "*", "resolution", "surface sample nodes along the longest side (footpoint seeds)"},
    {"*", "*", "order", "B-spline order k (degree k - 1)"},
    {"*", "*", "order_u", "surface order in u (degree + 1)"},
    {"*", "*", "order_v", "surface order in v (degree + 1)"},
    {"*", "*", "nu", "control points in u"},
    {"*", "*", "nv", "control points in v"},
    {"*", "*", "control", "control points (x y[ z]; ...)"},
    {"*", "*", "closed", "true: a periodic curve through its control points wrapped around"},
    {"*", "*", "distance", "signed or unsigned distance to the curve"},
    {"*", "*", "patches", "number of Bezier patches"},
    {"*", "*", "continuity", "checked continuity across patch edges: any, C0 or G1"},
    {"*", "*", "backend", "footpoint solver: newton or ceres"},
    {"*", "*", "samples", "samples per cell/segment/knot span/circle (see the study's header)"},
    {"*", "*", "candidates", "initial guesses refined per footpoint query"},
    {"*", "*", "random_seed", "seed of a random Bezier patch (instead of control)"},
    {"*", "*", "random_order", "order of the random Bezier patch"},
    {"*", "*", "random_half", "half width of the random patch's parameter square (length)"},
    {"*", "*", "random_amp", "height amplitude of the random patch (length)"},
    /* PHT fits (cfg/pht_cfg.h, sjp10) */
    {"*", "*", "max_level", "deepest T-mesh level a fit may refine to (cell = box / 2^level)"},
    {"*", "*", "split", "cell split: cross (2^dim children) or binary (2)"},
    {"*", "*", "estimator", "error estimator points: random, grid or gradient"},
    {"*", "*", "seed", "seed of the random numbers"},
    {"*", "*", "grade", "1: also split coarse neighbours that own a refined cell's data (dflab)"},
    {"*", "*", "peaks", "1: estimators also test cell centres and face midpoints (dflab)"},
    {"*", "*", "shape", "the section holding the shape fitted"},
    {"*", "*", "ref", "the section holding the validation reference shape"},
    {"*", "*", "val_n", "validation nodes per axis of the case's box"},
    {"*", "*", "midpoints", "also validate at the (n-1)^dim cell midpoints"},
    {"*", "*", "band", "band half-width |d| <= band of the band metrics (length)"},
    {"*", "*", "cache", "true: exact validation values computed once and kept"},
    {"*", "*", "cell_val", "also the per-cell validation protocol (cv_ columns)"},
    {"*", "*", "uniform_levels", "levels of the uniform Hermite grids beside the fits (2^level cells/axis)"},
    {"*", "*", "deltas", "offsets delta (length; negative: inside)"},
    {"*", "*", "grid_n", "marching grid nodes per axis of the level sets"},
    {"*", "*", "offset_samples", "samples of the untrimmed offset curve"},
    {"*", "*", "cut_lo", "lower corner of the 3D cutting region (length)"},
    {"*", "*", "cut_hi", "upper corner of the 3D cutting region (length)"},
    {"*", "*", "plane_axis", "axis normal to the cutting plane (0, 1, 2)"},
    {"*", "*", "plane_at", "coordinate of the cutting plane (length)"},
    /* bs04 case and curve sections */
    {"*", "*", "rays", "ray origins along the curve (2 rays each)"},
    {"*", "*", "cap_rays", "rays around each end point of an open curve"},
    {"*", "*", "grid", "the [grid]-style section of the case's images"},
    {"*", "*", "curve", "the bspline_curve section of the case (polygonized with eps)"},
    {"*", "*", "levels", "offsets delta of the level-set measurements (length, > 0)"},
    /* smoke */
    {"smoke", "perturb", "scale", "u = (1 + scale) d + offset: relative scale error of the test field"},
    {"smoke", "perturb", "offset", "u = (1 + scale) d + offset: constant offset (length)"},
    {"smoke", "metrics", "band", "band half-width |d| <= band of the band metrics (length)"},
    /* hvb25 */
    {"*", "study", "reference", "the section of the reference shape (ground truth)"},
    {"*", "study", "filters", "decode the one grid with each of these filters (one row each)"},
    {"*", "study", "medial", "medial-region threshold: footpoint jump in cell sizes"},
    {"hvb25_render", "study", "reps", "frames traced per filter; the best time is kept"},
    {"hvb25_render", "study", "false_hit_tol", "a hit farther than this from the truth is false (cell sizes)"},
    {"*", "camera", "eye", "camera position (x y z, length)"},
    {"*", "camera", "target", "point the camera looks at (x y z, length)"},
    {"*", "camera", "up", "camera up direction (x y z)"},
    {"*", "camera", "fov", "vertical field of view (degrees)"},
    {"*", "camera", "width", "frame width (pixels)"},
    {"*", "camera", "height", "frame height (pixels)"},
    {"*", "trace", "tmax", "longest ray (length)"},
    {"*", "trace", "eps", "hit when the field is below this (length)"},
    {"*", "trace", "step_scale", "step = step_scale x field value (0 < s <= 1)"},
    {"*", "trace", "max_steps", "steps per ray before it counts as exhausted"},
    {"*", "trace", "box", "true: clip rays to the grid's box"},
    /* sjp10 */
    {"*", "study", "cases", "case sections, one set of rows each"},
    {"*", "study", "fit", "section of the (2D) fit options"},
    {"*", "study", "fit3", "section of the 3D fit options"},
    {"*", "study", "rules", "fit rules of the pht rows: dflab (grade, peaks) and/or paper"},
    {"*", "study", "uniform_samples", "estimator points per uniform-grid cell"},
    {"*", "study", "refine", "Illinois steps moving each level-set vertex onto f = delta"},
    {"*", "study", "image_n", "nodes per axis of the .vti/.exr image"},
    {"*", "study", "graph_n", "nodes per axis of the graph surface z = f(x, y)"},
    {"sjp10_3d", "study", "eps", "fit thresholds (estimator error, length), one fit each"},
    {"sjp10_cells", "study", "eps", "fit thresholds (estimator error, length), one fit each"},
    /* bs04 [study] keys */
    {"*", "study", "alpha", "angle between the two segments at their vertex (degrees)"},
    {"*", "study", "length", "segment length L (length)"},
    {"*", "study", "parts", "the segments' fields: exact, disk, disk_smooth, strip, strip_smooth"},
    {"*", "study", "radii", "circle/sphere radii (gradbounds: relative to L; triangle: length)"},
    {"bs04_gradbounds", "study", "samples", "directions per circle"},
    {"bs04_gradbounds", "study", "fd_rel", "finite-difference step relative to r (the |grad u| check)"},
    {"bs04_gradbounds", "study", "profile_alpha", "angles whose circle profiles are written (degrees)"},
    {"bs04_gradbounds", "study", "profile_samples", "directions per radius in a profile"},
    {"bs04_gradbounds", "study", "fig5_p", "orders p of the Fig. 5 table"},
    {"bs04_gradbounds", "study", "fig5_nphi", "phi values in [0, 90] degrees of the Fig. 5 table"},
    {"bs04_corrected", "study", "sector_nr", "radii sampled in the hatched sector"},
    {"bs04_corrected", "study", "sector_nt", "directions sampled in the hatched sector"},
    {"bs04_corrected", "study", "sector_rmax", "outer radius of the sector samples (relative to L)"},
    {"bs04_corrected", "study", "band", "band 0 < d <= band of the grid metrics (length)"},
    {"bs04_corrected", "study", "vertex_radius", "nodes closer to the vertex form the vertex set (length)"},
    {"bs04_corrected", "study", "case_theta", "direction of the case point (degrees)"},
    {"bs04_corrected", "study", "case_r", "distance of the case point from the vertex (relative to L)"},
    {"bs04_corrected", "study", "onset_rmax", "search radius for eq. 20's first NaN (relative to L)"},
    {"*", "study", "smax", "crossings are searched in [0, smax delta] (relative to delta)"},
    {"*", "study", "steps", "bracketing samples per ray"},
    {"*", "study", "rounds", "16-fold bracket refinements per crossing"},
    {"*", "study", "valid_tol", "relative tolerance of the true-offset test of a ray"},
    {"*", "study", "max_joints", "joint rays start at no more than this many polygon vertices"},
    {"*", "study", "curve_samples", "samples per segment of the on-curve maximum search"},
    {"*", "study", "curve_rounds", "refinement rounds of the on-curve maximum search"},
    {"*", "study", "fractions", "interior points a + l (b - a) of every segment, l in (0, 1)"},
    {"*", "study", "K", "jet order (Taylor terms along each ray)"},
    {"*", "study", "tol", "zero test of a jet coefficient (relative to the length scale)"},
    {"*", "study", "fan", "rays per free end point over the outward half-plane"},
    {"*", "study", "points", "boundary points on the ellipse"},
    {"*", "study", "bands", "band widths |d| <= band of the band metrics (length, increasing)"},
    {"*", "study", "delta", "normal offset of the boundary samples (length)"},
    {"*", "study", "boundary_samples", "boundary samples per part"},
    {"*", "study", "curves", "curve sections, one row each"},
    {"*", "study", "fit_eps", "eps values of the fitted growth exponent (log-log slope)"},
    {"bs04_polygonization", "study", "samples", "samples per segment when measuring the deviation"},
    {"*", "study", "paper_curve", "the curve the paper's counts are for"},
    {"*", "study", "paper_eps", "the eps values of the paper's counts"},
    {"*", "study", "paper_segments", "the paper's segment counts (copied beside ours)"},
    {"*", "study", "volume", "sample the [grid] volume and write it"},
    {"*", "study", "slices", "section planes (axis at; ...)"},
    {"*", "study", "slice_n", "nodes per axis of a section plane"},
    {"*", "study", "slice_lo", "lower corner of the section planes (in-plane, length)"},
    {"*", "study", "slice_hi", "upper corner of the section planes (in-plane, length)"},
    {"*", "study", "compress", "zlib-compress the .vtp/.vti files"},
    {"bs04_triangle", "study", "samples", "Fibonacci points on each sphere"},
    {"*", "study", "theory_samples", "angles of the closed form's extremes"},
    {"*", "study", "dihedral", "dihedral angle between the two triangles (degrees, not 180)"},
    {"*", "study", "apex", "apex position: L zc (length)"},
    {"*", "study", "section", "z of the section plane through the edge (0 < z < 1)"},
    {"bs04_triedge", "study", "radius", "radius of the circle around the edge (length)"},
    {"bs04_triedge", "study", "samples", "directions on the circle"},
    {"bs04_triedge", "*", "a", "conditional trim parameter a (eq. 15-16)"},
    {"bs04_triedge", "*", "k", "conditional trim exponent k (eq. 15-16)"},
};

static bool match(const char *pat, const char *s)
{
    return strcmp(pat, "*") == 0 || strcmp(pat, s) == 0;
}

const char *dfl_key_meaning(const char *study, const char *sec, const char *key)
{
    /* specificity: study named (2) + section named (1); the highest wins */
    int best = -1;
    const char *m = "";
    for (size_t i = 0; i < sizeof knobs / sizeof knobs[0]; i++) {
        const knob *k = &knobs[i];
        if (strcmp(k->key, key) != 0 || !match(k->study, study) || !match(k->sec, sec)) continue;
        const int s = 2 * (strcmp(k->study, "*") != 0) + (strcmp(k->sec, "*") != 0);
        if (s > best) best = s, m = k->meaning;
    }
    return m;
}

typedef struct column {
    const char *study, *col, *meaning;
} column;

static const column columns[] = {
    {"*", "point", "sweep point index (0-based; the config's comma lists, last axis fastest)"},
    {"*", "<section>.<key>", "one column per swept key: its value at this point"},
    {"*", "vti", "the row's volume/image file (empty: not written)"},
    /* hvb25_accuracy */
    {"hvb25_accuracy", "field_kind", "the field measured: proxy, gridpeer, ..."},
    {"hvb25_accuracy", "order", "proxy order (1, 2)"},
    {"hvb25_accuracy", "res", "cells per axis of the grid"},
    {"hvb25_accuracy", "storage", "scalar storage: double / float / half"},
    {"hvb25_accuracy", "scalars", "stored scalars of the whole grid"},
    {"hvb25_accuracy", "bytes", "stored bytes (scalars x size, plus sign bytes)"},
    {"hvb25_accuracy", "gen_seconds", "time to build the field from its input (s, wall clock)"},
    {"hvb25_accuracy", "gen_ns_per_cell", "build time per cell (ns)"},
    {"hvb25_accuracy", "uncertified", "footpoints the method could not certify"},
    {"hvb25_accuracy", "failed", "footpoints that failed (non-finite)"},
    {"hvb25_accuracy", "moved", "cells whose centre was on the surface (moved off it)"},
    {"hvb25_accuracy", "clamped", "cells with a scalar clamped to the storage range"},
    {"hvb25_accuracy", "wrong_footpoints", "stored footpoints that are not closest points by the truth"},
    {"hvb25_accuracy", "filter", "decoding filter of the row"},
    {"hvb25_accuracy", "clip", "sphere-constraint radius used (length; 0: none)"},
    {"hvb25_accuracy", "clip_kind", "the constraint's formula: bound, paper, off"},
    {"hvb25_accuracy", "signed", "1: signed decoding (error against d), 0: unsigned (against |d|)"},
    {"hvb25_accuracy", "band", "band half-width of the *_band metrics (length)"},
    {"hvb25_accuracy", "eval_n", "nodes per axis of the error grid"},
    {"hvb25_accuracy", "l1", "mean |u - ref| over the error grid (length)"},
    {"hvb25_accuracy", "mse", "mean (u - ref)^2 (length^2)"},
    {"hvb25_accuracy", "rms", "sqrt(mse) (length)"},
    {"hvb25_accuracy", "linf", "max |u - ref| (length; +inf with a non-finite value)"},
    {"hvb25_accuracy", "*_band", "the same metric over |d| <= band"},
    {"hvb25_accuracy", "*_off", "the same metric off the medial region"},
    {"hvb25_accuracy", "count", "nodes measured (count_band, count_off: in those sets)"},
    {"hvb25_accuracy", "nonfinite", "nodes whose value was not finite (errors of +inf)"},
    {"hvb25_accuracy", "medial", "nodes in the medial region"},
    {"hvb25_accuracy", "worst_*", "the node of the largest error: position, d, error, footpoint jump"},
    {"hvb25_accuracy", "eval_seconds", "decoding time over the whole error grid (s)"},
    {"hvb25_accuracy", "eval_ns_per_query", "decoding time per node (ns)"},
    /* sjp10_3d, sjp10_cells, sjp10_fig1 */
    {"sjp10", "case", "the case section of the row"},
    {"sjp10", "method", "pht (adaptive fit) or uniform (Hermite grid)"},
    {"sjp10", "rule", "fit rules: dflab (grade, peaks) or paper"},
    {"sjp10", "eps", "the fit's threshold (length; nan for uniform rows)"},
    {"sjp10", "uniform_level", "level of the uniform grid (2^level cells per axis; -1: pht)"},
    {"sjp10", "max_level", "the deepest level the fit was allowed"},
    {"sjp10", "levels", "refinement iterations the fit ran (meshes T^0 .. T^(levels-1)): without "
                        "grading the deepest level + 1; grading (rule dflab) adds iterations that "
                        "only split coarse neighbours, so it can exceed max_level"},
    {"sjp10", "max_cell_level", "the deepest leaf level of the final T-mesh (<= max_level)"},
    {"sjp10", "capped_cells", "leaf cells above eps at max_level (0 iff converged)"},
    {"sjp10", "reason", "why the fit stopped: none (converged), level_cap, estimator"},
    {"sjp10", "est_max", "largest estimator error of a leaf cell (length)"},
    {"sjp10", "est_mean", "mean estimator error over the leaf cells (length)"},
    {"sjp10", "medial_vertices", "base vertices whose data came from a medial tie"},
    {"sjp10", "cells", "leaf cells of the final T-mesh"},
    {"sjp10", "base_vertices", "base (non-hanging) vertices"},
    {"sjp10", "dofs", "degrees of freedom (4 per base vertex in 2D, 8 in 3D)"},
    {"sjp10", "converged", "1: every cell's estimate met eps; 0: max_level stopped the fit"},
    {"sjp10", "val_*", "validation errors |f - d| on the node grid: max, mean, rms, gradient"},
    {"sjp10", "cv_*", "the per-cell validation protocol (pht/validate.h)"},
    {"sjp10", "t_*", "wall-clock times (s)"},
};

static bool column_of(const char *pat, const char *study)
{
    return strcmp(pat, "*") == 0 || strncmp(study, pat, strlen(pat)) == 0;
}

bool dfl_study_columns(const dfl_study *study, FILE *out)
{
    size_t own = 0;
    for (size_t i = 0; i < sizeof columns / sizeof columns[0]; i++)
        own += strcmp(columns[i].study, "*") != 0 && column_of(columns[i].study, study->name);
    if (!own) {
        fprintf(stderr, "dflab: error: help %s --columns: no column glossary for this study yet "
                        "(its header comment lists the columns)\n", study->name);
        return false;
    }
    fprintf(out, "%s: the columns of %s.csv (a * stands for several)\n\n", study->name,
            study->name);
    for (int pass = 0; pass < 2; pass++)
        for (size_t i = 0; i < sizeof columns / sizeof columns[0]; i++) {
            const column *c = &columns[i];
            if ((strcmp(c->study, "*") == 0) != (pass == 1) || !column_of(c->study, study->name))
                continue;
            fprintf(out, "  %-22s %s\n", c->col, c->meaning);
        }
    return true;
}
