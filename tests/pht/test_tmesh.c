/* Hierarchical T-meshes (pht/tmesh.c): counts on small hand-made meshes,
 * the classification against a brute-force reading of the rules on random
 * refinements (both rules, 2D and 3D), and point location. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "pht/pht_fixtures.h"
#include "pht/tmesh.h"

static dfl_tmesh *unit_mesh(int dim)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    dfl_tmesh *m;
    cr_assert_eq(dfl_tmesh_new(dim, lo, hi, &m, NULL), DFL_OK);
    return m;
}

static size_t find_vertex(const dfl_tmesh *m, double x, double y)
{
    for (size_t v = 0; v < dfl_tmesh_nverts(m); v++) {
        dfl_tmesh_vertex t;
        dfl_tmesh_vertex_get(m, v, &t);
        if (t.x[0] == x && t.x[1] == y) return v;
    }
    cr_assert_fail("no vertex at (%g, %g)", x, y);
    return 0;
}

Test(pht_tmesh, one_cell_and_a_cross_split)
{
    dfl_tmesh *m = unit_mesh(2);
    cr_assert_eq(dfl_tmesh_nleaves(m), 1);
    cr_assert_eq(dfl_tmesh_nverts(m), 4);
    cr_assert_eq(dfl_tmesh_nbase(m), 4);
    size_t root = 0;
    cr_assert_eq(dfl_tmesh_refine(m, 1, &root, DFL_PHT_SPLIT_CROSS, NULL), DFL_OK);
    cr_assert_eq(dfl_tmesh_nleaves(m), 4);
    cr_assert_eq(dfl_tmesh_nverts(m), 9);
    cr_assert_eq(dfl_tmesh_nbase(m), 9);
    /* refine the lower-left child: two T-junctions on the coarse edges */
    size_t ll = dfl_tmesh_leaves(m)[0];
    dfl_tmesh_cell c;
    dfl_tmesh_cell_get(m, ll, &c);
    cr_assert(c.lo[0] == 0 && c.lo[1] == 0 && c.hi[0] == 0.5 && c.hi[1] == 0.5);
    cr_assert_eq(dfl_tmesh_refine(m, 1, &ll, DFL_PHT_SPLIT_CROSS, NULL), DFL_OK);
    cr_assert_eq(dfl_tmesh_nleaves(m), 7);
    cr_assert_eq(dfl_tmesh_nverts(m), 14);
    cr_assert_eq(dfl_tmesh_nbase(m), 12);
    dfl_tmesh_vertex t;
    dfl_tmesh_vertex_get(m, find_vertex(m, 0.5, 0.25), &t);
    cr_assert_eq(t.kind, DFL_TMESH_EDGE);
    cr_assert_eq(t.axis, 1);
    cr_assert_eq(t.dep[0], find_vertex(m, 0.5, 0.0));
    cr_assert_eq(t.dep[1], find_vertex(m, 0.5, 0.5));
    dfl_tmesh_vertex_get(m, find_vertex(m, 0.25, 0.5), &t);
    cr_assert_eq(t.kind, DFL_TMESH_EDGE);
    cr_assert_eq(t.axis, 0);
    dfl_tmesh_vertex_get(m, find_vertex(m, 0.25, 0.25), &t);
    cr_assert_eq(t.kind, DFL_TMESH_BASE);
    size_t n;
    dfl_tmesh_order(m, &n);
    cr_assert_eq(n, 2);
    cr_assert_eq(dfl_tmesh_max_level(m), 2);
    /* refining an inner cell is an input error */
    cr_assert_eq(dfl_tmesh_refine(m, 1, &root, DFL_PHT_SPLIT_CROSS, NULL), DFL_E_INPUT);
    dfl_tmesh_free(m);
}

Test(pht_tmesh, binary_split_takes_the_longest_side)
{
    const double lo[2] = {0, 0}, hi[2] = {1, 3};
    dfl_tmesh *m;
    cr_assert_eq(dfl_tmesh_new(2, lo, hi, &m, NULL), DFL_OK);
    size_t root = 0;
    cr_assert_eq(dfl_tmesh_refine(m, 1, &root, DFL_PHT_SPLIT_BINARY, NULL), DFL_OK);
    dfl_tmesh_cell c;
    dfl_tmesh_cell_get(m, 0, &c);
    cr_assert_eq(c.split_axis, 1);
    dfl_tmesh_cell_get(m, dfl_tmesh_leaves(m)[0], &c);
    cr_assert(c.hi[0] == 1.0 && c.hi[1] == 1.5);
    cr_assert_eq(dfl_tmesh_nbase(m), 6);
    dfl_tmesh_free(m);
}

Test(pht_tmesh, three_d_cross_split_of_one_octant)
{
    dfl_tmesh *m = unit_mesh(3);
    size_t root = 0;
    cr_assert_eq(dfl_tmesh_refine(m, 1, &root, DFL_PHT_SPLIT_CROSS, NULL), DFL_OK);
    cr_assert_eq(dfl_tmesh_nverts(m), 27);
    cr_assert_eq(dfl_tmesh_nbase(m), 27);
    size_t c0 = dfl_tmesh_leaves(m)[0];
    cr_assert_eq(dfl_tmesh_refine(m, 1, &c0, DFL_PHT_SPLIT_CROSS, NULL), DFL_OK);
    cr_assert_eq(dfl_tmesh_nverts(m), 27 + 19);
    /* the centre of the refined octant's interior face x = 1/2 is inside the
     * face of the neighbouring octant: FACE-hanging with normal x */
    for (size_t v = 0; v < dfl_tmesh_nverts(m); v++) {
        dfl_tmesh_vertex t;
        dfl_tmesh_vertex_get(m, v, &t);
        if (t.x[0] == 0.5 && t.x[1] == 0.25 && t.x[2] == 0.25) {
            cr_assert_eq(t.kind, DFL_TMESH_FACE);
            cr_assert_eq(t.axis, 0);
        }
        if (t.x[0] == 0.25 && t.x[1] == 0.25 && t.x[2] == 0.25) cr_assert_eq(t.kind, DFL_TMESH_BASE);
        if (t.x[0] == 0.0 && t.x[1] == 0.25 && t.x[2] == 0.5) {
            cr_assert_eq(t.kind, DFL_TMESH_EDGE);
            cr_assert_eq(t.axis, 1);
        }
    }
    dfl_tmesh_free(m);
}

/* Brute force: the leaves whose closed box contains the vertex and the
 * orthant point v + delta * sign; v must be a corner of all of them to be
 * base, else hanging on an element of the largest one. */
static void check_classification(const dfl_tmesh *m)
{
    int dim = dfl_tmesh_dim(m);
    size_t nl = dfl_tmesh_nleaves(m), nbase = 0;
    const size_t *leaves = dfl_tmesh_leaves(m);
    dfl_tmesh_cell *cells = malloc(nl * sizeof *cells);
    for (size_t i = 0; i < nl; i++) dfl_tmesh_cell_get(m, leaves[i], &cells[i]);
    for (size_t v = 0; v < dfl_tmesh_nverts(m); v++) {
        dfl_tmesh_vertex t;
        dfl_tmesh_vertex_get(m, v, &t);
        double best_vol = -1;
        int best_inner = 0;
        for (size_t i = 0; i < nl; i++) {
            const dfl_tmesh_cell *c = &cells[i];
            int touch = 1, inner = 0;
            double vol = 1;
            for (int j = 0; j < dim; j++) {
                if (t.x[j] < c->lo[j] || t.x[j] > c->hi[j]) touch = 0;
                if (t.x[j] > c->lo[j] && t.x[j] < c->hi[j]) inner++;
                vol *= c->hi[j] - c->lo[j];
            }
            if (touch && inner && vol > best_vol) {
                best_vol = vol;
                best_inner = inner;
            }
        }
        if (best_vol < 0) {
            cr_assert_eq(t.kind, DFL_TMESH_BASE, "vertex %zu should be base", v);
            nbase++;
            continue;
        }
        cr_assert_eq(t.kind, best_inner == 1 ? DFL_TMESH_EDGE : DFL_TMESH_FACE,
                     "vertex %zu kind %d, expected inner %d", v, t.kind, best_inner);
        /* its dependencies span a segment / rectangle through it */
        int nd = best_inner == 1 ? 2 : 4;
        for (int e = 0; e < nd; e++) {
            dfl_tmesh_vertex q;
            dfl_tmesh_vertex_get(m, t.dep[e], &q);
            if (t.kind == DFL_TMESH_EDGE) {
                for (int j = 0; j < dim; j++)
                    if (j != t.axis) cr_assert_eq(q.x[j], t.x[j]);
                cr_assert(e ? q.x[t.axis] > t.x[t.axis] : q.x[t.axis] < t.x[t.axis]);
            } else {
                cr_assert_eq(q.x[t.axis], t.x[t.axis]);
            }
        }
    }
    cr_assert_eq(nbase, dfl_tmesh_nbase(m));
    /* the order lists every hanging vertex once, after its dependencies */
    size_t n;
    const size_t *order = dfl_tmesh_order(m, &n);
    cr_assert_eq(n + nbase, dfl_tmesh_nverts(m));
    unsigned char *seen = calloc(dfl_tmesh_nverts(m), 1);
    for (size_t i = 0; i < n; i++) {
        dfl_tmesh_vertex t;
        dfl_tmesh_vertex_get(m, order[i], &t);
        for (int e = 0; e < (t.kind == DFL_TMESH_EDGE ? 2 : 4); e++) {
            dfl_tmesh_vertex q;
            dfl_tmesh_vertex_get(m, t.dep[e], &q);
            cr_assert(q.kind == DFL_TMESH_BASE || seen[t.dep[e]]);
        }
        seen[order[i]] = 1;
    }
    free(seen);
    free(cells);
}

static void check_locate(const dfl_tmesh *m, uint64_t seed)
{
    int dim = dfl_tmesh_dim(m);
    for (int k = 0; k < 200; k++) {
        double x[3];
        for (int j = 0; j < dim; j++) x[j] = dfl_rng_splitmix(&seed, 0, 1);
        dfl_tmesh_cell c;
        dfl_tmesh_cell_get(m, dfl_tmesh_locate(m, x, NULL), &c);
        cr_assert_eq(c.nchild, 0);
        for (int j = 0; j < dim; j++) cr_assert(c.lo[j] <= x[j] && x[j] <= c.hi[j]);
    }
    /* a corner with a direction: the cell entered along dir */
    double x[3] = {0.5, 0.5, 0.5}, dir[3] = {-1, -1, -1};
    dfl_tmesh_cell c;
    dfl_tmesh_cell_get(m, dfl_tmesh_locate(m, x, dir), &c);
    for (int j = 0; j < dim; j++) cr_assert_eq(c.hi[j], 0.5);
    dfl_tmesh_cell_get(m, dfl_tmesh_locate(m, x, NULL), &c);
    for (int j = 0; j < dim; j++) cr_assert_eq(c.lo[j], 0.5);
}

Test(pht_tmesh, classification_matches_brute_force)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int rule = 0; rule < DFL_PHT_SPLIT_COUNT; rule++)
            for (uint64_t seed = 1; seed <= 3; seed++) {
                dfl_tmesh *m = unit_mesh(dim);
                size_t root = 0;
                cr_assert_eq(dfl_tmesh_refine(m, 1, &root, DFL_PHT_SPLIT_CROSS, NULL), DFL_OK);
                int rounds = dim == 2 ? (rule ? 8 : 4) : (rule ? 6 : 2);
                pf_random_refine(m, (dfl_pht_split)rule, rounds, 0.35, seed * 7 + (uint64_t)dim);
                check_classification(m);
                check_locate(m, seed);
                cr_assert(dfl_tmesh_bytes(m) > 0);
                dfl_tmesh_free(m);
            }
}

Test(pht_tmesh, split_names)
{
    cr_assert_str_eq(dfl_pht_split_name(DFL_PHT_SPLIT_BINARY), "binary");
    dfl_pht_split r = DFL_PHT_SPLIT_BINARY;
    dfl_err err;
    cr_assert_eq(dfl_pht_split_parse("cross", &r, &err), DFL_OK);
    cr_assert_eq(r, DFL_PHT_SPLIT_CROSS);
    cr_assert_eq(dfl_pht_split_parse("quad", &r, &err), DFL_E_INPUT);
    cr_assert_eq(r, DFL_PHT_SPLIT_CROSS);
    cr_assert(strstr(err.msg, "'quad'") && strstr(err.msg, "cross|binary"), "%s", err.msg);
    cr_assert_str_eq(dfl_pht_split_name((dfl_pht_split)DFL_PHT_SPLIT_COUNT), "?");
    cr_assert_str_eq(dfl_tmesh_vertex_kind_name(DFL_TMESH_FACE), "face");
}

/* tmesh.h: binary splits cut the longest side in world units, ties to the
 * lowest axis: a square (cube) root splits along x; after that the halves'
 * longest side is y (2D) and the next tie of a cube half (y, z) goes to y. */
Test(pht_tmesh, binary_ties_go_to_the_lowest_axis)
{
    for (int dim = 2; dim <= 3; dim++) {
        const double lo[3] = {-1, -1, -1}, hi[3] = {1, 1, 1};
        dfl_tmesh *m;
        cr_assert_eq(dfl_tmesh_new(dim, lo, hi, &m, NULL), DFL_OK);
        size_t root = 0;
        cr_assert_eq(dfl_tmesh_refine(m, 1, &root, DFL_PHT_SPLIT_BINARY, NULL), DFL_OK);
        dfl_tmesh_cell c;
        dfl_tmesh_cell_get(m, 0, &c);
        cr_expect_eq(c.split_axis, 0, "dim %d: root", dim);
        size_t leaf = dfl_tmesh_leaves(m)[0];
        cr_assert_eq(dfl_tmesh_refine(m, 1, &leaf, DFL_PHT_SPLIT_BINARY, NULL), DFL_OK);
        dfl_tmesh_cell_get(m, leaf, &c);
        cr_expect_eq(c.split_axis, 1, "dim %d: half", dim);
        dfl_tmesh_free(m);
    }
}

/* tmesh.h: corners live on a lattice of 2^DFL_TMESH_BITS steps per axis,
 * so a binary split needs a side of at least 2 steps: after
 * DFL_TMESH_BITS halvings of every axis (dim * DFL_TMESH_BITS splits of the
 * lowest-corner cell) the cell is one step wide and one more split is
 * DFL_E_INPUT naming the lattice resolution. */
Test(pht_tmesh, binary_split_stops_at_one_lattice_step)
{
    const double lo[2] = {0, 0}, hi[2] = {1, 1};
    dfl_tmesh *m;
    cr_assert_eq(dfl_tmesh_new(2, lo, hi, &m, NULL), DFL_OK);
    size_t id = 0;
    for (int s = 0; s < 2 * DFL_TMESH_BITS; s++) {
        cr_assert_eq(dfl_tmesh_refine(m, 1, &id, DFL_PHT_SPLIT_BINARY, NULL), DFL_OK, "split %d", s);
        dfl_tmesh_cell c;
        dfl_tmesh_cell_get(m, id, &c);
        id = c.child; /* the low half */
    }
    dfl_tmesh_cell c;
    dfl_tmesh_cell_get(m, id, &c);
    cr_expect_eq(c.level, 2 * DFL_TMESH_BITS);
    cr_expect_eq(c.hi[0], ldexp(1.0, -DFL_TMESH_BITS));
    cr_expect_eq(c.hi[1], ldexp(1.0, -DFL_TMESH_BITS));
    dfl_err err;
    cr_expect_eq(dfl_tmesh_refine(m, 1, &id, DFL_PHT_SPLIT_BINARY, &err), DFL_E_INPUT);
    cr_expect(strstr(err.msg, "lattice resolution"), "%s", err.msg);
    dfl_tmesh_free(m);
}
