/* Proxy grids (hvb25 Sec. 5): N^3 cells over a box, one proxy per cell
 * centre, built from any proxy input (proxy/input.h) and stored in double,
 * float or half precision (proxy/store.h).
 *
 * Function index
 *   dfl_proxy_build_opts          order, res, box, storage, position, noise
 *   dfl_proxy_build_opts_default  order 1, res 16, [-1, 1]^3, double,
 *                                 displacement, no noise
 *   dfl_proxy_grid                the grid: stored scalars, signs, counts
 *   dfl_proxy_grid_build          builds a grid from an input (parallel)
 *   dfl_proxy_grid_alloc          an empty grid of given shape (for loaders)
 *   dfl_proxy_grid_free           releases the grid's buffers
 *   dfl_proxy_cell_centre         x_c of cell c
 *   dfl_proxy_cell_size           max_j h_j, the length clip radii refer to
 *   dfl_proxy_cell_decode[_ijk]   the decoded proxy of cell c or (i,j,k) (decode.h)
 *   dfl_proxy_grid_scalars        stored scalars (the bytes study counts these)
 *
 * Cells: c = i + N (j + N k), cell (i,j,k) spans lo + [i, i+1] h per axis,
 * h_j = (hi_j - lo_j) / N, centre lo + (i + 1/2) h.
 *
 * Storage: DFL_PROXY_NSCALAR(order) scalars per cell in the storage type,
 * cell after cell (data[c * nscalar + q]).  When the input has an inside,
 * order 1 also keeps one sign byte per cell (side[c] = +1 outside, -1
 * inside; the 3 scalars of the paper's order 1 cannot carry the side);
 * order 2 carries it in t's length (decode.h).
 *
 * Cell centres on the surface: the normal of a proxy is p - x_c, so a
 * footpoint closer to x_c than delta moves to x_c - delta n (decode.h),
 * n the input's normal, an error of at most 2 delta in that cell.  delta
 * is scale-aware: delta_0 = h * 2^-40 | 2^-20 | 2^-10 (double, float,
 * half), at least the storage's smallest normal value, and for absolute
 * footpoints at least 2 ulp (in the storage) of max_j |x_c,j|; when the
 * stored (rounded) displacement is shorter than delta / 2, delta doubles,
 * at most 8 times (2^8 delta_0).  Such cells are counted in stats.moved;
 * a cell whose displacement does not survive any try is stored as NaN and
 * counted in stats.failed.  Every other cell decodes to a finite proxy.
 *
 * Range (store.h): scalars beyond what the storage keeps finite are capped
 * and the cell is counted in stats.clamped: a displacement is shortened
 * along itself, an absolute coordinate clamped to the largest finite value
 * F_s, a curvature to +-min(F_s, 2^64 / h).
 *
 * Noise (the footpoint-noise study): with noise > 0 each footpoint moves by
 * noise * w, w uniform on the unit sphere from SplitMix64 seeded by
 * seed + cell index (the same grid for any thread count), before encoding:
 * the order-1 normal p - x_c moves with it, curvatures and t do not.
 * noise_cell >= 0 moves only that cell's footpoint (index i + N (j + N k),
 * the paper's variant: hvb25 Sec. 7 moved one footpoint by hand); -1 (the
 * default) moves every footpoint.
 */
#ifndef DFL_PROXY_PROXY_H
#define DFL_PROXY_PROXY_H

#include <stddef.h>
#include <stdint.h>

#include "proxy/decode.h"
#include "proxy/input.h"
#include "proxy/store.h"

typedef struct dfl_proxy_build_opts {
    int order;                    /* 1 or 2 */
    int res;                      /* N >= 1 */
    double lo[3], hi[3];          /* box, lo < hi per axis */
    dfl_proxy_storage storage;
    dfl_proxy_position position;
    double noise;                 /* footpoint noise length >= 0 */
    long noise_cell;              /* -1: noise on every cell; else that cell only, < N^3 */
    uint64_t seed;
} dfl_proxy_build_opts;

void dfl_proxy_build_opts_default(dfl_proxy_build_opts *o);

typedef struct dfl_proxy_stats {
    size_t uncertified;  /* cells whose footpoint the input did not certify */
    size_t failed;       /* cells the input gave no finite answer (stored NaN) */
    size_t moved;        /* cell centres on the surface (see above) */
    size_t clamped;      /* cells with a scalar capped to the storage's range */
} dfl_proxy_stats;

typedef struct dfl_proxy_grid {
    int order, res, nscalar;
    double lo[3], hi[3], h[3];
    dfl_proxy_storage storage;
    dfl_proxy_position position;
    int has_inside;               /* the input's d is signed (negative inside) */
    size_t ncells;                /* res^3 */
    void *data;                   /* ncells * nscalar scalars of `storage` */
    signed char *side;            /* order 1 with has_inside: ncells signs, else NULL */
    dfl_proxy_stats stats;
} dfl_proxy_grid;

/* Builds the grid of in with options o into *out (zeroed first).  Queries
 * the input in chunks of 256 cells in parallel (OpenMP, static schedule;
 * the grid is the same at any thread count), one buffer per thread.
 * Errors: DFL_E_INPUT for bad options (order not 1|2, res < 1 or res^3
 * overflow, lo >= hi, noise < 0 or not finite, noise_cell < -1 or >= N^3) or a NULL input; an input's
 * error status is passed on (first failing chunk's message); DFL_E_NOMEM.
 * On error *out holds no buffers.  Order 2 asks the input for curvature; a
 * non-finite curvature counts the cell as failed. */
dfl_status dfl_proxy_grid_build(const dfl_proxy_input *in, const dfl_proxy_build_opts *o,
                                dfl_proxy_grid *out, dfl_err *err);

/* A grid of the shape o describes with zeroed data (and sides when
 * with_side, all +1), stats zero, has_inside as given.  Errors as above. */
dfl_status dfl_proxy_grid_alloc(const dfl_proxy_build_opts *o, int has_inside, int with_side,
                                dfl_proxy_grid *out, dfl_err *err);

/* Frees the buffers and zeroes *g; g may be NULL or already freed. */
void dfl_proxy_grid_free(dfl_proxy_grid *g);

static inline void dfl_proxy_cell_centre(const dfl_proxy_grid *g, size_t c, double x[3])
{
    const size_t n = (size_t)g->res;
    const size_t i = c % n, j = (c / n) % n, k = c / (n * n);
    x[0] = g->lo[0] + ((double)i + 0.5) * g->h[0];
    x[1] = g->lo[1] + ((double)j + 0.5) * g->h[1];
    x[2] = g->lo[2] + ((double)k + 0.5) * g->h[2];
}

static inline double dfl_proxy_cell_size(const dfl_proxy_grid *g)
{
    double h = g->h[0];
    if (g->h[1] > h) h = g->h[1];
    if (g->h[2] > h) h = g->h[2];
    return h;
}

/* The decoded proxy of cell c (0 <= c < ncells). */
void dfl_proxy_cell_decode(const dfl_proxy_grid *g, size_t c, dfl_proxy_geom *out);
/* Cell c's stored scalars as double (one storage switch per cell). */
static inline void dfl_proxy_cell_load(const dfl_proxy_grid *g, size_t c, double *s)
{
    const int ns = g->nscalar;
    const size_t b = c * (size_t)ns;
    switch (g->storage) {
    case DFL_PROXY_DOUBLE:
        for (int q = 0; q < ns; q++) s[q] = ((const double *)g->data)[b + (size_t)q];
        break;
    case DFL_PROXY_FLOAT:
        for (int q = 0; q < ns; q++) s[q] = ((const float *)g->data)[b + (size_t)q];
        break;
    default:
        for (int q = 0; q < ns; q++)
            s[q] = imath_half_to_float(((const uint16_t *)g->data)[b + (size_t)q]);
    }
}

/* dfl_proxy_cell_decode for cell (i, j, k), each in [0, res) (no index
 * division; inline, the filters' hot path). */
static inline void dfl_proxy_cell_decode_ijk(const dfl_proxy_grid *g, size_t i, size_t j, size_t k,
                               dfl_proxy_geom *out)
{
    const size_t n = (size_t)g->res, c = i + n * (j + n * k);
    double s[DFL_PROXY_NSCALAR_MAX];
    dfl_proxy_cell_load(g, c, s);
    const double xc[3] = {g->lo[0] + ((double)i + 0.5) * g->h[0],
                          g->lo[1] + ((double)j + 0.5) * g->h[1],
                          g->lo[2] + ((double)k + 0.5) * g->h[2]};
    dfl_proxy_decode(g->order, g->position, xc, s, g->side ? g->side[c] : 1, out);
}

/* ncells * nscalar. */
static inline size_t dfl_proxy_grid_scalars(const dfl_proxy_grid *g)
{
    return g->ncells * (size_t)g->nscalar;
}

#endif
