#include "field/meshdist.h"

#include <assert.h>
#include <math.h>

double dfl_meshdist_eval(const dfl_trimesh *M, const double *x)
{
    double best = INFINITY;
    for (size_t t = 0; t < M->ntris; t++) {
        const size_t *v = M->tris + 3 * t;
        best = fmin(best, dfl_point_triangle_dist(x, M->verts + 3 * v[0], M->verts + 3 * v[1],
                                                  M->verts + 3 * v[2]));
    }
    return best;
}

/* Every node is independent of the others: the schedule (dynamic chunks
 * of 64 nodes) changes only the speed, never a value. */
void dfl_meshdist_sample(const dfl_trimesh *M, const dfl_grid *g, int threads, double *out)
{
    assert(g->dim == 3);
    const long m = (long)dfl_grid_size(g);
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads > 0 ? threads : 1)
    for (long i = 0; i < m; i++) {
        double x[3];
        dfl_grid_node(g, (size_t)i, x);
        out[i] = dfl_meshdist_eval(M, x);
    }
}
