/* [field] + [shape] -> the proxy input (src/proxy/input.h) of issue 9.
 *
 * Function index
 *   dfl_proxy_input_from_cfg   the input the keys below pick
 *   dfl_proxy_truth_from_cfg   the ground truth of the same sections
 *
 * Keys of the field section (the rest of it, order, res, filter, ... is the
 * proxy grid's, experiments/cfg/proxy_cfg.c):
 *   input     = parametric | sdf | implicit     (default sdf)
 *   curvature = analytic | fit                  (default analytic; sdf only)
 *   footpoint = paper | robust | paper_against | paper_walk  (default robust;
 *               implicit only; proxy/input_implicit.h: the paper's method
 *               under three readings of its starts, and dflab's)
 *   curvature_fallback = none | plane            (default none: the paper's;
 *               curvature = fit: a cell whose fit fails gets no proxy, or
 *               with plane the tangent plane (curvatures 0), counted as
 *               uncertified; proxy/input_sdf.h)
 *   curvature_clamp = none | focal               (default none: the paper's;
 *               curvature = fit: focal cuts each fitted curvature k to
 *               1 + k d >= 0, proxy/input_sdf.h)
 *   fit_grid  = g, 3..15                        (default 5; curvature = fit)
 *   fit_spacing = h in [1e-6, 1e4]              (default 0.01; curvature = fit)
 *   param_grid  = n, 4..512: parameter-grid starts per patch and direction
 *                 (default 16; parametric)
 *   param_starts = 1..3: nearest grid nodes refined by Newton (default 3;
 *                 1 is the paper's single start, ~2x faster, and misses the
 *                 closest basin at a few cells of a random Bezier patch)
 *   implicit_resolution = n, 8..1024: surface samples (the robust seeds)
 *                 along the longest side for the implicit sphere and torus
 *                 (default 64; kind = implicit reads its own [shape]
 *                 resolution key).  Fewer samples are faster (torus at 16^3
 *                 cells: 16 -> ~17 us, 64 -> ~110 us of CPU per point) and
 *                 stay certified while the spacing is below the reach.
 * Every key is read whatever the input, so none is reported unused.
 *
 * Representations a [shape] kind offers (`input` picks one):
 *   sphere    sdf, parametric (longitude/latitude), implicit (|q|^2 - r^2)
 *   torus     sdf, parametric, implicit (the quartic)
 *   cone      sdf (capped frustum), parametric (its lateral surface, open)
 *   cylinder, plane, box, csg: sdf
 *   bezier_surface, bspline_surface: parametric (key `random_seed` on a
 *             bezier_surface builds a random patch instead of `control`,
 *             see proxy/input_param.h)
 *   implicit  implicit
 * An input the shape lacks: DFL_E_INPUT (exit 2) naming the field
 * section's `input` key, the shape kind and what it offers.
 */
#ifndef DFL_EXPERIMENTS_PROXY_INPUT_CFG_H
#define DFL_EXPERIMENTS_PROXY_INPUT_CFG_H

#include "core/status.h"
#include "field/field.h"
#include "io/config.h"
#include "proxy/input.h"

/* Builds the input into *out (release with dfl_proxy_input_free); *out is
 * untouched on failure. */
dfl_status dfl_proxy_input_from_cfg(const dfl_cfg *cfg, const char *field_sec,
                                    const char *shape_sec, dfl_proxy_input *out, dfl_err *err);

/* The ground truth (proxy/truth.h) for the same sections: the exact SDF of
 * sphere, torus, cylinder, plane, box, csg and cone (the cone's open
 * lateral surface when input = parametric), brute-force-seeded footpoints
 * for bezier_surface / bspline_surface, robust certified footpoints for
 * kind = implicit.  Whatever `input` says for sphere and torus, the truth is
 * their exact SDF (all three representations are the same surface).
 * Release with dfl_field_destroy; *out untouched on failure. */
dfl_status dfl_proxy_truth_from_cfg(const dfl_cfg *cfg, const char *field_sec,
                                    const char *shape_sec, dfl_field *out, dfl_err *err);

#endif
