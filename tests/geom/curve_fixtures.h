/* Curves shared by the footpoint, curve SDF and curve shape tests, and a
 * brute-force footpoint search independent of the solvers. */
#ifndef DFL_TESTS_GEOM_CURVE_FIXTURES_H
#define DFL_TESTS_GEOM_CURVE_FIXTURES_H

#include "core/rng.h"
#include "geom/bspline.h"
#include "geom/curve_sdf.h"

/* The 'S' of configs/shapes/S.ini (open, clamped cubic, 9 points). */
void cf_make_S(dfl_bspline *c);
/* A closed periodic cubic symmetric about both axes, listed
 * counter-clockwise: points on the x axis inside it are on the medial
 * axis. */
void cf_make_blob(dfl_bspline *c);
/* cf_make_blob into *c and its SDF with default options (asserted). */
dfl_curve_sdf *cf_blob_sdf(dfl_bspline *c);
/* An open cubic space curve (a rising spiral, 7 points). */
void cf_make_space(dfl_bspline *c);
/* Distance from x to c by dense sampling (1e5) and golden-section
 * refinement of the best sample; its parameter to *tbest (may be NULL). */
double cf_brute_curve(const dfl_bspline *c, const double *x, double *tbest);

#endif
