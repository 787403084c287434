// OpenVDB adapter behind the extern "C" API of field/vdb.h: the grid, its
// two builds, the samplers and the memory bound.
//
// Why C++ here: OpenVDB has no C API.  This file keeps OpenVDB's C++
// surface (templates, shared pointers, exceptions, TBB) out of the rest of
// dflab: no exception crosses the extern "C" boundary (caught()).

#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <new>
#include <vector>

#include <omp.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <openvdb/tools/MeshToVolume.h>

extern "C" {
#include "core/names.h"
#include "geom/polygonize.h"
#include "geom/shape.h"
}
#include "field/vdb.h"

using openvdb::Coord;
using openvdb::FloatGrid;
using openvdb::FloatTree;
using openvdb::Vec3R;

struct dfl_vdb {
    FloatGrid::Ptr grid;
    double voxel;
    int band;
    double shift;              // voxel ijk sits at (ijk + shift) * voxel
    dfl_vdb_sampler sampler;   // the sampler the grid was built for
    double seconds;
    size_t evals;
};

namespace {

using Leaf = FloatTree::LeafNodeType;
using Root = FloatTree::RootNodeType;
using Node2 = Root::ChildNodeType;     // InternalNode<..., 5>: 4096^3 voxels
using Node1 = Node2::ChildNodeType;    // InternalNode<Leaf, 4>: 128^3 voxels
const int kLeaf = (int)Leaf::DIM;      // 8
const int kBlock = (int)Node1::DIM;    // 128
const int kTop = (int)Node2::DIM;      // 4096
// Pruning slack: a block is ruled out only when |f(c)| - L r >= b (1 + 1e-9),
// so rounding in f or in the centre cannot drop a voxel with |f| < b.
const double kSlack = 1e-9;
const double kMaxIndex = 1073741824.0;  // 2^30: far inside OpenVDB's int32 coordinates
// Index coordinates beyond +-(2^31 - 2^20) are clamped to it before sampling
// (dfl_vdb_sample): the samplers' stencils (floor(p) - 1 .. floor(p) + 2,
// the gradient's half steps) then stay in int, and far beyond every node a
// grid within kMaxIndex (plus its 4096^3 top nodes) holds.
const double kFarIndex = 2147483648.0 - 1048576.0;
// At most 2^15 voxels per axis: the band search's first pass then evaluates
// at most 256^3 block centres, whatever the box.
const double kMaxSpan = 32768.0;

std::once_flag g_init_once;
void vdb_init() { std::call_once(g_init_once, [] { openvdb::initialize(); }); }

// The status of the exception being handled; only from a catch block.
dfl_status caught(const char *step, dfl_err *err)
{
    try {
        throw;
    } catch (const std::bad_alloc &) {
        return dfl_err_set(err, DFL_E_NOMEM, "openvdb: out of memory %s", step);
    } catch (const std::exception &e) {
        return dfl_err_set(err, DFL_E_INTERNAL, "openvdb: %s: %.300s", step, e.what());
    } catch (...) {
        return dfl_err_set(err, DFL_E_INTERNAL, "openvdb: unknown exception %s", step);
    }
}

double now() { return omp_get_wtime(); }

int floor_div(int a, int b) { return (a >= 0 ? a / b : -((-a + b - 1) / b)) * b; }

// The index range I of the box (vdb.h: Lattice), or DFL_E_INPUT.
struct range {
    int lo[3], hi[3];
};

dfl_status check_opts(const dfl_vdb_opts *o, bool need_lipschitz, range *r, dfl_err *err)
{
    if (!(std::isfinite(o->voxel) && o->voxel > 0))
        return dfl_err_set(err, DFL_E_INPUT, "openvdb: voxel %g: expected a finite size > 0",
                           o->voxel);
    if (o->band < 1)
        return dfl_err_set(err, DFL_E_INPUT, "openvdb: band %d: expected >= 1 voxel", o->band);
    if (need_lipschitz && !(std::isfinite(o->lipschitz) && o->lipschitz >= 1))
        return dfl_err_set(err, DFL_E_INPUT, "openvdb: lipschitz %g: expected finite >= 1",
                           o->lipschitz);
    const double shift = o->sampler == DFL_VDB_STAGGERED ? -0.5 : 0.0;
    for (int a = 0; a < 3; a++) {
        if (!(std::isfinite(o->lo[a]) && std::isfinite(o->hi[a]) && o->lo[a] < o->hi[a]))
            return dfl_err_set(err, DFL_E_INPUT, "openvdb: box axis %d: expected finite lo < hi",
                               a);
        const double l = std::floor(o->lo[a] / o->voxel - shift) - 1,
                     u = std::ceil(o->hi[a] / o->voxel - shift) + 1;
        if (!(l > -kMaxIndex && u < kMaxIndex))
            return dfl_err_set(err, DFL_E_INPUT,
                               "openvdb: box axis %d is %.3g voxels from the origin (at most"
                               " 2^30)",
                               a, std::fmax(std::fabs(l), std::fabs(u)));
        if (u - l + 1 > kMaxSpan)
            return dfl_err_set(err, DFL_E_INPUT,
                               "openvdb: box axis %d spans %.3g voxels (at most 2^15 = 32768)", a,
                               u - l + 1);
        r->lo[a] = (int)l;
        r->hi[a] = (int)u;
    }
    return DFL_OK;
}

openvdb::math::Transform::Ptr make_xform(double voxel, double shift)
{
    auto x = openvdb::math::Transform::createLinearTransform(voxel);
    if (shift != 0) x->postTranslate(openvdb::Vec3d(shift * voxel));
    return x;
}

dfl_vdb *wrap(FloatGrid::Ptr grid, const dfl_vdb_opts *o, double shift, double t0, size_t evals)
{
    dfl_vdb *g = new dfl_vdb;
    g->grid = std::move(grid);
    g->voxel = o->voxel;
    g->band = o->band;
    g->shift = shift;
    g->sampler = o->sampler;
    g->evals = evals;
    g->seconds = now() - t0;
    return g;
}

// ---- direct fill --------------------------------------------------------

// One pass of the band search: the centres of cubes of `size` voxels at
// origins org (3 ints each) into pts, world units.
void centres(const std::vector<int> &org, int size, double voxel, double shift,
             std::vector<double> &pts)
{
    const double half = 0.5 * (size - 1);
    pts.resize(org.size());
    for (size_t i = 0; i < org.size(); i++) pts[i] = (org[i] + half + shift) * voxel;
}

// Leaves that meet I inside the block at bo, into out (origins).
void block_leaves(const int bo[3], const range &I, std::vector<int> &out)
{
    out.clear();
    int a[3], b[3];
    for (int d = 0; d < 3; d++) {
        a[d] = std::max(bo[d], floor_div(I.lo[d], kLeaf));
        b[d] = std::min(bo[d] + kBlock - kLeaf, floor_div(I.hi[d], kLeaf));
    }
    for (int x = a[0]; x <= b[0]; x += kLeaf)
        for (int y = a[1]; y <= b[1]; y += kLeaf)
            for (int z = a[2]; z <= b[2]; z += kLeaf) {
                out.push_back(x);
                out.push_back(y);
                out.push_back(z);
            }
}

enum verdict { KEEP = 0, OUT_POS, OUT_NEG, NONFINITE };

verdict judge(double f, double reach, double b)
{
    if (!std::isfinite(f)) return NONFINITE;
    if (std::fabs(f) - reach >= b * (1 + kSlack)) return f < 0 ? OUT_NEG : OUT_POS;
    return KEEP;
}

// Fills the 512 voxels of the leaf at o from f: a new leaf (caller owns),
// or nullptr with *tile = -1 (all inside, none active: a -b tile), +1 (all
// outside: nothing), 2 (a non-finite value).
Leaf *fill_leaf(const dfl_shape *s, const int o[3], double voxel, double shift, float bf,
                double b, int *tile)
{
    double pts[3 * Leaf::SIZE], val[Leaf::SIZE];
    for (int dx = 0, n = 0; dx < kLeaf; dx++)
        for (int dy = 0; dy < kLeaf; dy++)
            for (int dz = 0; dz < kLeaf; dz++, n++) {
                pts[3 * n] = (o[0] + dx + shift) * voxel;
                pts[3 * n + 1] = (o[1] + dy + shift) * voxel;
                pts[3 * n + 2] = (o[2] + dz + shift) * voxel;
            }
    s->ops->eval(s->impl, Leaf::SIZE, pts, val, nullptr);
    int nact = 0, nneg = 0;
    for (size_t n = 0; n < Leaf::SIZE; n++) {
        if (!std::isfinite(val[n])) {
            *tile = 2;
            return nullptr;
        }
        nact += std::fabs(val[n]) < b;
        nneg += val[n] < 0;
    }
    if (nact == 0 && nneg == (int)Leaf::SIZE) {
        *tile = -1;
        return nullptr;
    }
    if (nact == 0 && nneg == 0) {
        *tile = 1;
        return nullptr;
    }
    Leaf *leaf = new Leaf(Coord(o[0], o[1], o[2]), bf, false);
    // LeafNode offsets run z fastest, then y, then x: the order of pts
    for (size_t n = 0; n < Leaf::SIZE; n++) {
        if (std::fabs(val[n]) < b)
            leaf->setValueOn((openvdb::Index)n, (float)val[n]);
        else
            leaf->setValueOnly((openvdb::Index)n, val[n] < 0 ? -bf : bf);
    }
    *tile = 0;
    return leaf;
}

dfl_status direct_fill(const dfl_shape *s, const dfl_vdb_opts *o, const range &I, double shift,
                       FloatTree &tree, size_t *evals, dfl_err *err)
{
    const double h = o->voxel, L = o->lipschitz;
    const float bf = (float)(o->band * h);
    const double b = (double)bf;
    const double rblock = L * std::sqrt(3.0) * 0.5 * (kBlock - 1) * h,
                 rleaf = L * std::sqrt(3.0) * 0.5 * (kLeaf - 1) * h;
    std::vector<int> blocks, leaves, kept;
    std::vector<double> pts, val;
    for (int x = floor_div(I.lo[0], kBlock); x <= I.hi[0]; x += kBlock)
        for (int y = floor_div(I.lo[1], kBlock); y <= I.hi[1]; y += kBlock)
            for (int z = floor_div(I.lo[2], kBlock); z <= I.hi[2]; z += kBlock) {
                blocks.push_back(x);
                blocks.push_back(y);
                blocks.push_back(z);
            }
    centres(blocks, kBlock, h, shift, pts);
    const size_t nb = blocks.size() / 3;
    val.resize(nb);
    s->ops->eval(s->impl, nb, pts.data(), val.data(), nullptr);
    *evals = nb;
    for (size_t i = 0; i < nb; i++) {
        const verdict v = judge(val[i], rblock, b);
        if (v == NONFINITE) goto nonfinite;
        if (v == OUT_NEG) tree.addTile(2, Coord(blocks[3 * i], blocks[3 * i + 1], blocks[3 * i + 2]),
                                       -bf, false);
        if (v != KEEP) continue;
        block_leaves(&blocks[3 * i], I, leaves);
        centres(leaves, kLeaf, h, shift, pts);
        const size_t nl = leaves.size() / 3;
        std::vector<double> lv(nl);
        s->ops->eval(s->impl, nl, pts.data(), lv.data(), nullptr);
        *evals += nl;
        for (size_t j = 0; j < nl; j++) {
            const verdict w = judge(lv[j], rleaf, b);
            if (w == NONFINITE) goto nonfinite;
            if (w == OUT_NEG)
                tree.addTile(1, Coord(leaves[3 * j], leaves[3 * j + 1], leaves[3 * j + 2]), -bf,
                             false);
            if (w == KEEP) kept.insert(kept.end(), &leaves[3 * j], &leaves[3 * j] + 3);
        }
    }
    {
        const long nk = (long)(kept.size() / 3);
        std::vector<Leaf *> made((size_t)nk, nullptr);
        std::vector<int> tile((size_t)nk, 0);
        const int threads = o->threads > 0 ? o->threads : omp_get_max_threads();
        // new Leaf may throw bad_alloc: caught per leaf, reported after the loop
        int oom = 0;
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads) reduction(| : oom)
        for (long k = 0; k < nk; k++) {
            try {
                made[(size_t)k] = fill_leaf(s, &kept[3 * (size_t)k], h, shift, bf, b, &tile[(size_t)k]);
            } catch (...) {
                oom = 1;
            }
        }
        *evals += (size_t)nk * Leaf::SIZE;
        bool bad = false;
        for (long k = 0; k < nk; k++) {
            bad |= tile[(size_t)k] == 2;
            if (oom || bad) {
                delete made[(size_t)k];
                continue;
            }
            if (made[(size_t)k])
                tree.addLeaf(made[(size_t)k]);
            else if (tile[(size_t)k] == -1)
                tree.addTile(1, Coord(kept[3 * k], kept[3 * k + 1], kept[3 * k + 2]), -bf, false);
        }
        if (oom) return dfl_err_set(err, DFL_E_NOMEM, "openvdb: out of memory filling the band");
        if (bad) goto nonfinite;
    }
    return DFL_OK;
nonfinite:
    return dfl_err_set(err, DFL_E_NUMERIC,
                       "openvdb: the shape's distance is not finite at a point of the band search");
}

template <class Sampler, class Acc>
inline double samp(const Acc &acc, double px, double py, double pz)
{
    return (double)Sampler::sample(acc, Vec3R(px, py, pz));
}

template <class Sampler>
void sample_with(const dfl_vdb *g, size_t m, const double *pts, double *val, double *grad)
{
    openvdb::tree::ValueAccessor<const FloatTree, false> acc(g->grid->tree());
    const double inv = 1.0 / g->voxel, sh = -g->shift;
    // central differences with step voxel / 2: half a unit in index space
    const double st = 0.5, den = 1.0 / (2 * st * g->voxel);
    for (size_t i = 0; i < m; i++) {
        double px = pts[3 * i] * inv + sh, py = pts[3 * i + 1] * inv + sh,
               pz = pts[3 * i + 2] * inv + sh;
        // OpenVDB's samplers cast floor(p) to int: undefined for NaN and
        // beyond int's range (x86 gives INT_MIN, and an infinity then
        // samples 0 * inf).  Within kFarIndex nothing changes; beyond it
        // only the background is read, so a clamped coordinate samples what
        // the far one would.
        if (!(std::fabs(px) <= kFarIndex && std::fabs(py) <= kFarIndex &&
              std::fabs(pz) <= kFarIndex)) {
            if (std::isnan(px) || std::isnan(py) || std::isnan(pz)) {
                val[i] = NAN;
                if (grad) grad[3 * i] = grad[3 * i + 1] = grad[3 * i + 2] = NAN;
                continue;
            }
            px = std::fmax(-kFarIndex, std::fmin(px, kFarIndex));
            py = std::fmax(-kFarIndex, std::fmin(py, kFarIndex));
            pz = std::fmax(-kFarIndex, std::fmin(pz, kFarIndex));
        }
        val[i] = samp<Sampler>(acc, px, py, pz);
        if (!grad) continue;
        grad[3 * i] = (samp<Sampler>(acc, px + st, py, pz) - samp<Sampler>(acc, px - st, py, pz)) * den;
        grad[3 * i + 1] =
            (samp<Sampler>(acc, px, py + st, pz) - samp<Sampler>(acc, px, py - st, pz)) * den;
        grad[3 * i + 2] =
            (samp<Sampler>(acc, px, py, pz + st) - samp<Sampler>(acc, px, py, pz - st)) * den;
    }
}

// Blocks of `size` voxels (aligned) meeting [lo, hi] on every axis.
double count_blocks(const int lo[3], const int hi[3], int size)
{
    double n = 1;
    for (int a = 0; a < 3; a++)
        n *= (double)((floor_div(hi[a], size) - floor_div(lo[a], size)) / size + 1);
    return n;
}

}  // namespace

extern "C" {

void dfl_vdb_opts_default(dfl_vdb_opts *o)
{
    std::memset(o, 0, sizeof *o);
    o->voxel = 0.05;
    o->band = 3;
    o->sampler = DFL_VDB_BOX;
    for (int a = 0; a < 3; a++) o->lo[a] = -1, o->hi[a] = 1;
    o->lipschitz = 1;
    o->threads = 0;
}

dfl_status dfl_vdb_from_shape(const dfl_shape *shape, const dfl_vdb_opts *o, dfl_vdb **out,
                              dfl_err *err)
{
    range I;
    dfl_status st = check_opts(o, true, &I, err);
    if (st) return st;
    if (!shape || shape->dim != 3)
        return dfl_err_set(err, DFL_E_INPUT, "openvdb: expected a 3D shape");
    const double t0 = now(), shift = o->sampler == DFL_VDB_STAGGERED ? -0.5 : 0.0;
    try {
        vdb_init();
        FloatGrid::Ptr grid = FloatGrid::create((float)(o->band * o->voxel));
        grid->setTransform(make_xform(o->voxel, shift));
        grid->setGridClass(openvdb::GRID_LEVEL_SET);
        size_t evals = 0;
        if ((st = direct_fill(shape, o, I, shift, grid->tree(), &evals, err))) return st;
        *out = wrap(std::move(grid), o, shift, t0, evals);
        return DFL_OK;
    } catch (...) {
        return caught("filling the band", err);
    }
}

dfl_status dfl_vdb_from_mesh(const dfl_trimesh *m, const dfl_vdb_opts *o, dfl_vdb **out,
                             dfl_err *err)
{
    range I;
    dfl_status st = check_opts(o, false, &I, err);
    if (st) return st;
    if (!m || m->ntris == 0) return dfl_err_set(err, DFL_E_INPUT, "openvdb: a mesh without triangles");
    for (size_t i = 0; i < 3 * m->nverts; i++)
        if (!std::isfinite(m->verts[i]))
            return dfl_err_set(err, DFL_E_INPUT, "openvdb: mesh vertex %zu is not finite", i / 3);
    for (size_t i = 0; i < 3 * m->ntris; i++)
        if (m->tris[i] >= m->nverts)
            return dfl_err_set(err, DFL_E_INPUT,
                               "openvdb: triangle %zu names vertex %zu of %zu", i / 3, m->tris[i],
                               m->nverts);
    const double t0 = now(), shift = o->sampler == DFL_VDB_STAGGERED ? -0.5 : 0.0;
    try {
        vdb_init();
        std::vector<openvdb::Vec3s> p(m->nverts);
        std::vector<openvdb::Vec3I> t(m->ntris);
        for (size_t i = 0; i < m->nverts; i++)
            p[i] = openvdb::Vec3s((float)m->verts[3 * i], (float)m->verts[3 * i + 1],
                                  (float)m->verts[3 * i + 2]);
        for (size_t i = 0; i < m->ntris; i++)
            t[i] = openvdb::Vec3I((openvdb::Index32)m->tris[3 * i], (openvdb::Index32)m->tris[3 * i + 1],
                                  (openvdb::Index32)m->tris[3 * i + 2]);
        auto xform = make_xform(o->voxel, shift);
        FloatGrid::Ptr grid = openvdb::tools::meshToLevelSet<FloatGrid>(*xform, p, t, (float)o->band);
        *out = wrap(std::move(grid), o, shift, t0, 0);
        return DFL_OK;
    } catch (...) {
        return caught("in meshToLevelSet", err);
    }
}

void dfl_vdb_free(dfl_vdb *g) { delete g; }

double dfl_vdb_voxel(const dfl_vdb *g) { return g->voxel; }
int dfl_vdb_band(const dfl_vdb *g) { return g->band; }
double dfl_vdb_background(const dfl_vdb *g) { return (double)g->grid->background(); }
dfl_vdb_sampler dfl_vdb_lattice_sampler(const dfl_vdb *g) { return g->sampler; }
size_t dfl_vdb_bytes(const dfl_vdb *g) { return (size_t)g->grid->memUsage(); }
size_t dfl_vdb_active_count(const dfl_vdb *g) { return (size_t)g->grid->activeVoxelCount(); }
size_t dfl_vdb_leaf_count(const dfl_vdb *g) { return (size_t)g->grid->tree().leafCount(); }
double dfl_vdb_build_seconds(const dfl_vdb *g) { return g->seconds; }
size_t dfl_vdb_evals(const dfl_vdb *g) { return g->evals; }

size_t dfl_vdb_active_voxels(const dfl_vdb *g, size_t cap, int *ijk, float *value)
{
    size_t n = 0;
    for (auto it = g->grid->cbeginValueOn(); it && n < cap; ++it) {
        if (!it.isVoxelValue()) continue;  // active tiles: none in a level set
        const Coord c = it.getCoord();
        if (ijk) ijk[3 * n] = c.x(), ijk[3 * n + 1] = c.y(), ijk[3 * n + 2] = c.z();
        if (value) value[n] = *it;
        n++;
    }
    return n;
}

float dfl_vdb_voxel_value(const dfl_vdb *g, const int ijk[3], int *active)
{
    const Coord c(ijk[0], ijk[1], ijk[2]);
    float v;
    const bool on = g->grid->tree().probeValue(c, v);
    if (active) *active = on;
    return v;
}

void dfl_vdb_voxel_centre(const dfl_vdb *g, const int ijk[3], double x[3])
{
    for (int a = 0; a < 3; a++) x[a] = (ijk[a] + g->shift) * g->voxel;
}

void dfl_vdb_sample(const dfl_vdb *g, dfl_vdb_sampler s, size_t m, const double *pts,
                    double *val, double *grad)
{
    if (s == DFL_VDB_QUADRATIC)
        sample_with<openvdb::tools::QuadraticSampler>(g, m, pts, val, grad);
    else
        sample_with<openvdb::tools::BoxSampler>(g, m, pts, val, grad);
}

double dfl_vdb_bytes_bound(const dfl_vdb_opts *o, double *leaves)
{
    range I;
    if (check_opts(o, false, &I, nullptr)) return 0;
    // the mesh build's band reaches band + 1 voxels past a mesh in the box
    int lo[3], hi[3];
    for (int a = 0; a < 3; a++) lo[a] = I.lo[a] - o->band - 1, hi[a] = I.hi[a] + o->band + 1;
    const double nl = count_blocks(lo, hi, kLeaf), n1 = count_blocks(lo, hi, kBlock),
                 n2 = count_blocks(lo, hi, kTop);
    if (leaves) *leaves = count_blocks(I.lo, I.hi, kLeaf);
    double leaf_bytes;
    try {
        Leaf probe(Coord(0), 0.f, false);
        leaf_bytes = (double)probe.memUsage();
    } catch (...) {
        return 1e300;
    }
    // tools::memUsage's count per internal node (openvdb/tools/Count.h)
    const double b1 = Node1::NUM_VALUES * sizeof(Node1::UnionType) +
                      2 * Node1::NodeMaskType::memUsage() + sizeof(Coord),
                 b2 = Node2::NUM_VALUES * sizeof(Node2::UnionType) +
                      2 * Node2::NodeMaskType::memUsage() + sizeof(Coord);
    const double total = nl * leaf_bytes + n1 * b1 + n2 * b2 + sizeof(Root);
    return std::isfinite(total) && total < 1e300 ? total : 1e300;
}

}  // extern "C"
