/* Field costs from keys (field_cost.h).  Kept apart from the factories so
 * that estimating never builds: the runner calls this before any field
 * exists. */
#include "cfg/field_cost.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "cfg/field_cfg.h"
#include "cfg/curve_cfg.h"
#include "cfg/pht_cfg.h"
#include "cfg/proxy_cfg.h"
#include "cfg/vdb_cfg.h"
#include "field/gridpeer.h"
#include "geom/polygonize.h"
#include "proxy/decode.h"
#include "proxy/store.h"

static const char *kind_of(const dfl_cfg *cfg, const char *sec)
{
    const char *k = NULL;
    if (!dfl_cfg_has(cfg, sec, "kind") || dfl_cfg_string(cfg, sec, "kind", &k, NULL)) return "";
    return k;
}

/* depth bounds CSG nesting (and ends a cycle, which the shape reader
 * reports): beyond it a shape counts as the dearest class */
static dfl_cost_class shape_class(const dfl_cfg *cfg, const char *sec, int depth)
{
    for (; depth < 8 && sec && dfl_cfg_has_section(cfg, sec); depth++) {
        const char *k = kind_of(cfg, sec);
        if (!strcmp(k, "implicit") || !strcmp(k, "bezier_surface") ||
            !strcmp(k, "bspline_surface") || !strcmp(k, "bspline_curve"))
            return DFL_COST_FOOTPOINT;
        if (!strcmp(k, "mesh")) return DFL_COST_EXACT;
        if (strcmp(k, "csg") != 0) return *k ? DFL_COST_CHEAP : DFL_COST_EXACT;
        /* csg: the dearer of its operands, bounded by the depth */
        const char *a = NULL, *b = NULL;
        if (dfl_cfg_string(cfg, sec, "a", &a, NULL) || dfl_cfg_string(cfg, sec, "b", &b, NULL))
            return DFL_COST_EXACT;
        if (shape_class(cfg, b, depth + 1) == DFL_COST_FOOTPOINT) return DFL_COST_FOOTPOINT;
        sec = a;
    }
    return depth >= 8 ? DFL_COST_FOOTPOINT : DFL_COST_EXACT;
}

dfl_cost_class dfl_shape_cost_class(const dfl_cfg *cfg, const char *sec)
{
    return shape_class(cfg, sec, 0);
}

int dfl_shape_dim_guess(const dfl_cfg *cfg, const char *sec)
{
    for (int depth = 0; depth < 8 && sec && dfl_cfg_has_section(cfg, sec); depth++) {
        const char *k = kind_of(cfg, sec);
        if (!strcmp(k, "circle") || !strcmp(k, "ellipse")) return 2;
        if (!strcmp(k, "bspline_curve")) {
            const char *raw;
            if (dfl_cfg_has(cfg, sec, "control") && !dfl_cfg_string(cfg, sec, "control", &raw, NULL))
                return dfl_cfg_point_dim(raw) == 3 ? 3 : 2;
            return 2;
        }
        if (!strcmp(k, "plane") || !strcmp(k, "box") || !strcmp(k, "segment")) {
            long d = !strcmp(k, "segment") ? 2 : 3;
            if (dfl_cfg_has(cfg, sec, "dim") && dfl_cfg_int(cfg, sec, "dim", 2, 3, &d, NULL))
                d = 3;
            return (int)d;
        }
        if (strcmp(k, "csg") != 0 || dfl_cfg_string(cfg, sec, "a", &sec, NULL)) return 3;
    }
    return 3;
}

double dfl_mesh_bytes_bound(double tris, int is_signed)
{
    double b = tris * DFL_MESH_TRI_BYTES + DFL_MESH_FIXED_BYTES;
    if (is_signed) b += tris * DFL_MESH_ANCHOR_TRI_BYTES + DFL_MESH_ANCHOR_FIXED_BYTES;
    return b;
}

/* The fewest bytes a triangle takes in a file of extension ext (header). */
static double min_tri_bytes(const char *ext)
{
    if (!strcasecmp(ext, "stl")) return 36;
    if (!strcasecmp(ext, "ac")) return 6;
    if (!strcasecmp(ext, "obj") || !strcasecmp(ext, "off")) return 2;
    return 1;
}

/* One pass over a text file, no allocation (header): OBJ, every line
 * whose first word starts with 'f' ("f", and "fo" which some readers take
 * for a face) with its backslash continuations gives its words but two;
 * AC3D, every "refs k" k - 2, and with a "subdiv s" anywhere
 * (Assimp subdivides: a k-gon becomes k quads, each further level 4 of
 * each) 2 k 4^(s - 1) for the largest s.  0 when the file cannot be read
 * or a count after "refs" or "subdiv" is not a plain number (the size's
 * bound then stands). */
static int scan_faces(const char *path, int ac, double *tris, int *subdiv)
{
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    double t = 0, sumk = 0, smax = 0;
    char word[8];
    int ch, wl = 0, nword = 0, face = 0, cont = 0;
    double num = -1; /* the number after "refs"/"subdiv" (-1: none yet) */
    int kw = 0;      /* 1 after "refs", 2 after "subdiv" */
    int unsure = 0;  /* a count that is not a plain number */
    for (;;) {
        ch = fgetc(f);
        const int end = ch == EOF || ch == '\n' || ch == '\r';
        if (ch == '\\') cont = 1;
        else if (!end && ch != ' ' && ch != '\t') cont = 0;
        if (end || ch == ' ' || ch == '\t' || ch == '\\') {
            if (wl > 0) { /* a word ended */
                word[wl < 8 ? wl : 7] = '\0';
                if (nword == 0) {
                    face = !ac && word[0] == 'f';
                    kw = ac && wl == 4 && !memcmp(word, "refs", 4)     ? 1
                         : ac && wl == 6 && !memcmp(word, "subdiv", 6) ? 2
                                                                       : 0;
                } else if (nword == 1 && kw && num < 0) {
                    unsure = 1; /* "refs 3x": Assimp's reading may differ */
                } else if (nword == 1 && kw) {
                    if (kw == 1) t += fmax(num - 2, 0), sumk += num;
                    else smax = fmax(smax, num);
                }
                nword++;
                wl = 0;
                num = -1;
            }
            if (end && !(cont && ch != EOF)) {
                if (face) t += fmax(nword - 3, 0); /* "f" and k indices: k - 2 */
                nword = 0, face = 0, kw = 0;
            }
            if (ch == EOF) break;
            continue;
        }
        if (wl < 8) word[wl] = (char)ch;
        if (wl == 0 && nword == 1) num = 0;
        if (num >= 0) num = ch >= '0' && ch <= '9' ? 10 * num + (ch - '0') : -1;
        wl++;
    }
    fclose(f);
    if (unsure) return 0;
    *tris = smax > 0 ? 2 * sumk * pow(4, smax - 1) : t;
    *subdiv = smax > 0;
    return 1;
}

dfl_status dfl_mesh_file_tris_bound(const char *path, double *tris, double *file_bytes,
                                    dfl_err *err)
{
    struct stat sb;
    if (stat(path, &sb) != 0)
        return dfl_err_set(err, DFL_E_INPUT, "%s: %s", path, strerror(errno));
    if (!S_ISREG(sb.st_mode)) return dfl_err_set(err, DFL_E_INPUT, "%s: not a regular file", path);
    const double size = (double)sb.st_size;
    const char *base = strrchr(path, '/'), *dot;
    base = base ? base + 1 : path;
    dot = strrchr(base, '.');
    const char *ext = dot ? dot + 1 : "";
    *file_bytes = size;
    *tris = floor(size / min_tri_bytes(ext));
    if (!strcasecmp(ext, "stl") && sb.st_size >= 84 && (sb.st_size - 84) % 50 == 0) {
        /* binary: the little-endian count after the 80-byte header */
        unsigned char h[84];
        FILE *f = fopen(path, "rb");
        const int ok = f && fread(h, 1, sizeof h, f) == sizeof h;
        if (f) fclose(f);
        const uint32_t n = ok ? (uint32_t)h[80] | (uint32_t)h[81] << 8 | (uint32_t)h[82] << 16 |
                                    (uint32_t)h[83] << 24
                              : 0;
        if (ok && (double)n * 50 + 84 == size) *tris = n;
    }
    if (!strcasecmp(ext, "obj") || !strcasecmp(ext, "ac")) {
        double t;
        int sub = 0;
        /* a subdivided AC3D file can give more triangles than bytes */
        if (scan_faces(path, !strcasecmp(ext, "ac"), &t, &sub)) *tris = sub ? t : fmin(*tris, t);
    }
    return DFL_OK;
}

static dfl_status shape_cost(const dfl_cfg *cfg, const char *sec, int depth, dfl_cost *c,
                             dfl_err *err);

/* the mesh's structures for at most tris triangles (header) */
static void mesh_struct_cost(const dfl_cfg *cfg, const char *sec, const char *key, double tris,
                             dfl_cost *c)
{
    const char *d = "signed";
    if (dfl_cfg_has(cfg, sec, "distance")) dfl_cfg_string(cfg, sec, "distance", &d, NULL);
    const int is_signed = strcmp(d, "unsigned") != 0;
    dfl_cost_add_bytes(c, sec, key, dfl_mesh_bytes_bound(tris, is_signed),
                       "a mesh of up to %.3g triangles, its BVH%s", tris,
                       is_signed ? " and winding anchors (signed)" : "");
    dfl_cost_add_work(c, sec, key, DFL_COST_EXACT, tris, "%.3g triangles read and indexed", tris);
    if (is_signed)
        dfl_cost_add_work(c, sec, key, DFL_COST_EXACT, 512 * tris + 1048576,
                          "the winding anchors of %.3g triangles built", tris);
}

/* The reader's polygonize grid (experiments/cfg/shape_cfg.c mesh_source):
 * its cubes a side and nodes; 0 when a key is bad (err set) or hi <= lo
 * (err untouched: the reader names it), else 1. */
static int poly_grid(const dfl_cfg *cfg, const char *sec, double *cube, double *nodes,
                     long *refine, dfl_status *st, dfl_err *err)
{
    long n = 96;
    double lo[3], hi[3], ext = 0.0;
    static const double mone[3] = {-1, -1, -1}, one[3] = {1, 1, 1};
    *st = dfl_cfg_int_opt(cfg, sec, "resolution", 96, 8, 1024, &n, err);
    if (!*st) *st = dfl_cfg_int_opt(cfg, sec, "refine", 8, 0, 100, refine, err);
    if (!*st) *st = dfl_cfg_vec_opt(cfg, sec, "lo", 3, mone, lo, err);
    if (!*st) *st = dfl_cfg_vec_opt(cfg, sec, "hi", 3, one, hi, err);
    if (*st) return 0;
    for (int j = 0; j < 3; j++) {
        if (!(hi[j] > lo[j])) return 0;
        ext = fmax(ext, hi[j] - lo[j]);
    }
    *nodes = 1;
    for (int j = 0; j < 3; j++) {
        cube[j] = fmax(2.0, ceil((hi[j] - lo[j]) / ext * (double)(n - 1)) + 1.0) - 1;
        *nodes *= cube[j] + 1;
    }
    return 1;
}

dfl_status dfl_mesh_tris_bound(const dfl_cfg *cfg, const char *sec, double *tris, dfl_err *err)
{
    *tris = -1;
    if (dfl_cfg_has(cfg, sec, "file")) {
        char path[4096];
        double size;
        if (!dfl_cfg_path_value(cfg, sec, "file", path, sizeof path, NULL) &&
            dfl_mesh_file_tris_bound(path, tris, &size, NULL))
            *tris = -1; /* the reader names it */
        return DFL_OK;
    }
    const char *src;
    if (!dfl_cfg_has(cfg, sec, "polygonize") ||
        dfl_cfg_string(cfg, sec, "polygonize", &src, NULL) || !dfl_cfg_has_section(cfg, src))
        return DFL_OK;
    double cube[3], nodes;
    long refine;
    dfl_status st;
    if (poly_grid(cfg, sec, cube, &nodes, &refine, &st, err))
        *tris = 12 * (cube[0] * cube[1] + cube[1] * cube[2] + cube[2] * cube[0]);
    return st;
}

static dfl_status mesh_cost(const dfl_cfg *cfg, const char *sec, int depth, dfl_cost *c,
                            dfl_err *err)
{
    if (dfl_cfg_has(cfg, sec, "file")) {
        char path[4096];
        double tris, size;
        if (dfl_cfg_path_value(cfg, sec, "file", path, sizeof path, NULL) ||
            dfl_mesh_file_tris_bound(path, &tris, &size, NULL))
            return DFL_OK; /* the reader names it */
        dfl_cost_add_bytes(c, sec, "file", size, "the mesh file's %.3g bytes", size);
        mesh_struct_cost(cfg, sec, "file", tris, c);
        return DFL_OK;
    }
    const char *src;
    if (!dfl_cfg_has(cfg, sec, "polygonize") ||
        dfl_cfg_string(cfg, sec, "polygonize", &src, NULL) || !dfl_cfg_has_section(cfg, src))
        return DFL_OK;
    double cube[3], nodes, tris;
    long refine;
    dfl_status st;
    if (!poly_grid(cfg, sec, cube, &nodes, &refine, &st, err)) return st;
    dfl_cost_add_bytes(c, sec, "resolution", 24 * nodes,
                       "the marching-cubes lattice of %.3g nodes", nodes);
    /* an implicit surface is sampled through its defining function
     * (field/isomesh.h dfl_shape_isomesh), any other shape by its SDF */
    const dfl_cost_class cls =
        !strcmp(kind_of(cfg, src), "implicit") ? DFL_COST_CHEAP : dfl_shape_cost_class(cfg, src);
    dfl_cost_add_work(c, sec, "resolution", cls,
                      nodes * (1 + 7 * (double)refine), "%.3g samples of the polygonized shape",
                      nodes * (1 + 7 * (double)refine));
    if ((st = shape_cost(cfg, src, depth + 1, c, err))) return st;
    if ((st = dfl_mesh_tris_bound(cfg, sec, &tris, err))) return st;
    mesh_struct_cost(cfg, sec, "resolution", tris, c);
    return DFL_OK;
}

static dfl_status shape_cost(const dfl_cfg *cfg, const char *sec, int depth, dfl_cost *c,
                             dfl_err *err)
{
    if (depth >= 8 || !sec || !dfl_cfg_has_section(cfg, sec)) return DFL_OK;
    const char *k = kind_of(cfg, sec);
    if (!strcmp(k, "mesh")) return mesh_cost(cfg, sec, depth, c, err);
    if (strcmp(k, "csg") != 0) return DFL_OK;
    const char *a = NULL, *b = NULL;
    if (dfl_cfg_has(cfg, sec, "a")) dfl_cfg_string(cfg, sec, "a", &a, NULL);
    if (dfl_cfg_has(cfg, sec, "b")) dfl_cfg_string(cfg, sec, "b", &b, NULL);
    dfl_status st = shape_cost(cfg, a, depth + 1, c, err);
    return st ? st : shape_cost(cfg, b, depth + 1, c, err);
}

dfl_status dfl_shape_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    return shape_cost(cfg, sec, 0, c, err);
}

static dfl_status proxy_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    dfl_proxy_cfg p;
    dfl_status st = dfl_proxy_cfg_read(cfg, sec, &p, err);
    if (st) return st;
    const double r = p.build.res, cells = r * r * r;
    const int ns = DFL_PROXY_NSCALAR(p.build.order);
    dfl_cost_add_bytes(c, sec, "res", cells * (ns * (double)dfl_proxy_storage_size(p.build.storage) + 1),
                       "a proxy grid of %.0f^3 cells, order %d, %s", r, p.build.order,
                       dfl_proxy_storage_name(p.build.storage));
    const char *input = "sdf", *shape = "shape";
    if (dfl_cfg_has(cfg, sec, "input")) dfl_cfg_string(cfg, sec, "input", &input, NULL);
    if (dfl_cfg_has(cfg, sec, "shape")) dfl_cfg_string(cfg, sec, "shape", &shape, NULL);
    const dfl_cost_class cls =
        strcmp(input, "sdf") ? DFL_COST_FOOTPOINT : dfl_shape_cost_class(cfg, shape);
    dfl_cost_add_work(c, sec, "res", cls, cells * (p.build.order == 2 ? 2 : 1),
                      "%.3g %s footpoints", cells, input);
    return DFL_OK;
}

static dfl_status gridpeer_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    int kind = DFL_GRIDPEER_TAYLOR1, storage = DFL_GRIDPEER_FLOAT64;
    long n = 16;
    const char *shape = "shape";
    dfl_status st = dfl_cfg_enum_opt(cfg, sec, "method", dfl_gridpeer_kind_names,
                                     DFL_GRIDPEER_KIND_COUNT, kind, &kind, err);
    if (!st) st = dfl_cfg_enum_opt(cfg, sec, "storage", dfl_gridpeer_storage_names,
                                   DFL_GRIDPEER_STORAGE_COUNT, storage, &storage, err);
    if (!st) st = dfl_cfg_int_opt(cfg, sec, "res", 16, 1, 1024, &n, err);
    if (!st) st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape, err);
    if (st) return st;
    if (kind == DFL_GRIDPEER_TRICUBIC && n < 4)
        return dfl_cfg_reject(cfg, sec, "res", err, "expected res >= 4 for tricubic, got %ld", n);
    const double scalars = (double)dfl_gridpeer_scalars((dfl_gridpeer_kind)kind, (int)n);
    /* the build keeps float64 values before a float16 grid is packed;
     * tricubic keeps its coefficients as doubles (either storage: the
     * halves' values) and their (n + 2)^3 extension with the ghosts, plus
     * a prefilter line of 3n doubles per thread (negligible) */
    double bytes = scalars * (storage == DFL_GRIDPEER_FLOAT64 ? 8 : 10);
    if (kind == DFL_GRIDPEER_TRICUBIC) bytes = scalars * 8 + 8.0 * pow((double)n + 2, 3);
    dfl_cost_add_bytes(c, sec, "res", bytes, "a grid peer of %ld^3 cells (%.3g scalars)", n,
                       scalars);
    const double nodes = (double)(n + 1) * (n + 1) * (n + 1);
    dfl_cost_add_work(c, sec, "res", dfl_shape_cost_class(cfg, shape), nodes,
                      "%.3g distances", nodes);
    return DFL_OK;
}

double dfl_pht_fit_bytes_bound(const dfl_pht_fit_opts *o, int dim, double *leaves)
{
    const double n = ldexp(1.0, o->split == DFL_PHT_SPLIT_BINARY ? o->max_level
                                                                 : dim * o->max_level);
    const double fan = ldexp(1.0, o->split == DFL_PHT_SPLIT_BINARY ? 1 : dim);
    if (leaves) *leaves = n;
    return n * fan / (fan - 1) * DFL_PHT_CELL_BYTES(dim);
}

static dfl_status pht_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    const char *shape = "shape";
    dfl_status st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape, err);
    if (st) return st;
    const int dim = dfl_shape_dim_guess(cfg, shape);
    dfl_pht_fit_opts o;
    if ((st = dfl_pht_opts_from_cfg(cfg, sec, dim, &o, err))) return st;
    double leaves;
    const double bytes = dfl_pht_fit_bytes_bound(&o, dim, &leaves);
    dfl_cost_add_bytes(c, sec, "max_level", bytes,
                       "a PHT mesh of up to %.3g cells (max_level = %d in %dD)", leaves,
                       o.max_level, dim);
    dfl_cost_add_work(c, sec, "max_level", dfl_shape_cost_class(cfg, shape),
                      leaves * (o.samples + 1), "%.3g estimator points and footpoints",
                      leaves * (o.samples + 1));
    return DFL_OK;
}

static dfl_status vdb_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    dfl_vdb_cfg v;
    dfl_status st = dfl_vdb_cfg_read(cfg, sec, &v, err);
    if (st) return st;
    double leaves;
    const double grid = dfl_vdb_bytes_bound(&v.opts, &leaves);
    dfl_cost_add_bytes(c, sec, "voxel", grid,
                       "an OpenVDB grid of up to %.3g leaves of 8^3 voxels (voxel %g)", leaves,
                       v.opts.voxel);
    const dfl_cost_class cls = dfl_shape_cost_class(cfg, v.shape);
    if (v.build == DFL_VDB_DIRECT) {
        const double evals = leaves * (512 + 1) + leaves / 4096 + 1;
        dfl_cost_add_work(c, sec, "voxel", cls, evals, "%.3g distances of the band search", evals);
        return DFL_OK;
    }
    /* mesh: the voxel lattice of the box sampled, marched, refined */
    double nodes = 1;
    for (int a = 0; a < 3; a++) nodes *= floor((v.opts.hi[a] - v.opts.lo[a]) / v.opts.voxel) + 3;
    dfl_cost_add_bytes(c, sec, "voxel", 24 * nodes,
                       "the marching-cubes lattice of %.3g nodes and its mesh", nodes);
    dfl_cost_add_work(c, sec, "voxel", cls, nodes * (1 + 30 * 7),
                      "%.3g distances of the marching-cubes mesh", nodes * (1 + 30 * 7));
    return DFL_OK;
}

/* Entries of a point list "x y; x y; ..." (blank entries, e.g. after a
 * trailing ';', do not count); the factory parses and checks them. */
static double count_points(const char *raw)
{
    double n = 0;
    int in = 0;
    for (const char *p = raw; *p; p++) {
        if (*p == ';') in = 0;
        else if (*p != ' ' && *p != '\t' && !in) in = 1, n++;
    }
    return n;
}

dfl_status dfl_rfunc_parts_bound(const dfl_cfg *cfg, const char *sec, double *parts,
                                 const char **key, dfl_err *err)
{
    double n = 0, big = -1;
    const char *raw;
    dfl_status st = DFL_OK;
    *key = "vertices";
#define PART(k, count)                       \
    do {                                     \
        const double c_ = (count);           \
        n += c_;                             \
        if (c_ > big) big = c_, *key = (k);  \
    } while (0)
    if (dfl_cfg_has(cfg, sec, "vertices") && !dfl_cfg_string(cfg, sec, "vertices", &raw, NULL))
        PART("vertices", count_points(raw)); /* n - 1 segments, n when closed */
    /* vertices and curve together: the factory refuses the pair, naming it */
    if (dfl_cfg_has(cfg, sec, "curve") && !dfl_cfg_has(cfg, sec, "vertices")) {
        const char *csec;
        double eps;
        dfl_bspline c;
        if ((st = dfl_cfg_string(cfg, sec, "curve", &csec, err))) return st;
        if ((st = dfl_cfg_double(cfg, sec, "eps", 1e-12, 1e300, &eps, err))) return st;
        /* a missing or wrong section: the factory names it */
        if (dfl_cfg_has_section(cfg, csec) && dfl_cfg_has(cfg, csec, "kind") &&
            !dfl_cfg_string(cfg, csec, "kind", &raw, NULL) && !strcmp(raw, "bspline_curve")) {
            if ((st = dfl_curve_from_cfg(cfg, csec, &c, err))) return st;
            PART("eps", dfl_polygonize_curve_segments_bound(&c, eps) + 1);
            dfl_bspline_free(&c);
        }
    }
    if (dfl_cfg_has(cfg, sec, "triangles") && !dfl_cfg_string(cfg, sec, "triangles", &raw, NULL))
        PART("triangles", count_points(raw) / 3);
    const char *surf = NULL;
    if (dfl_cfg_has(cfg, sec, "surface") && !dfl_cfg_string(cfg, sec, "surface", &surf, NULL) &&
        dfl_cfg_has_section(cfg, surf) && !strcmp(kind_of(cfg, surf), "mesh")) {
        double t; /* a mesh's triangles as they are: no eps, no max_tris */
        if ((st = dfl_mesh_tris_bound(cfg, surf, &t, err))) return st;
        if (t >= 0) PART("surface", t);
    } else if (dfl_cfg_has(cfg, sec, "surface")) {
        long max_tris;
        if ((st = dfl_cfg_int_opt(cfg, sec, "max_tris", 200000, 1, 10000000, &max_tris, err)))
            return st;
        PART("max_tris", (double)max_tris);
    }
    if (dfl_cfg_has(cfg, sec, "points") && !dfl_cfg_string(cfg, sec, "points", &raw, NULL))
        PART("points", count_points(raw));
    if (dfl_cfg_has(cfg, sec, "region")) PART("region", 1);
#undef PART
    *parts = n;
    return DFL_OK;
}

static dfl_status rfunc_cost(const dfl_cfg *cfg, const char *sec, dfl_cost *c, dfl_err *err)
{
    double parts;
    const char *key;
    dfl_status st = dfl_rfunc_parts_bound(cfg, sec, &parts, &key, err);
    if (st) return st;
    dfl_cost_add_bytes(c, sec, key, parts * DFL_RFUNC_PART_BYTES,
                       "an R-function field of up to %.3g parts", parts);
    dfl_cost_add_work(c, sec, key, DFL_COST_CHEAP, parts, "%.3g parts set up", parts);
    /* surface = a mesh section: the mesh shape, held while its triangles
     * are copied */
    const char *surf;
    if (dfl_cfg_has(cfg, sec, "surface") && !dfl_cfg_string(cfg, sec, "surface", &surf, NULL) &&
        dfl_cfg_has_section(cfg, surf) && !strcmp(kind_of(cfg, surf), "mesh"))
        return dfl_shape_cost(cfg, surf, c, err);
    return DFL_OK;
}

int dfl_field_dim_guess(const dfl_cfg *cfg, const char *sec)
{
    const char *k = kind_of(cfg, sec), *raw, *shape = "shape";
    if (!strcmp(k, "normalized")) return 2;
    if (!strcmp(k, "rfunc")) {
        static const char *const keys[] = {"vertices", "triangles", "points", "region"};
        if (dfl_cfg_has(cfg, sec, "surface")) return 3;
        for (int i = 0; i < 4; i++)
            if (dfl_cfg_has(cfg, sec, keys[i]) && !dfl_cfg_string(cfg, sec, keys[i], &raw, NULL))
                return dfl_cfg_point_dim(raw) == 3 ? 3 : 2;
        if (dfl_cfg_has(cfg, sec, "curve") && !dfl_cfg_string(cfg, sec, "curve", &raw, NULL))
            return dfl_shape_dim_guess(cfg, raw); /* its control points' */
        return 2;
    }
    if (dfl_cfg_has(cfg, sec, "shape")) dfl_cfg_string(cfg, sec, "shape", &shape, NULL);
    return dfl_shape_dim_guess(cfg, shape);
}

dfl_status dfl_field_eval_cost(const dfl_cfg *cfg, const char *sec, dfl_cost_class *cls,
                               double *units, dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st = dfl_field_kind_from_cfg(cfg, sec, &kind, err);
    if (st) return st;
    *cls = DFL_COST_DECODE;
    *units = 1;
    if (!strcmp(kind->name, "exact")) {
        const char *shape = "shape";
        if ((st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape, err))) return st;
        /* an unknown kind is named here, before a caller sizes anything by
         * the dimension dfl_shape_dim_guess can only guess for it */
        int k;
        if (dfl_cfg_has_section(cfg, shape) &&
            (st = dfl_cfg_enum(cfg, shape, "kind", dfl_shape_kind_names, DFL_SHAPE_KIND_COUNT, &k,
                               err)))
            return st;
        *cls = dfl_shape_cost_class(cfg, shape);
    } else if (!strcmp(kind->name, "rfunc")) {
        const char *key;
        *cls = DFL_COST_CHEAP;
        st = dfl_rfunc_parts_bound(cfg, sec, units, &key, err);
        *units += DFL_RFUNC_EVAL_UNITS;
    } else if (!strcmp(kind->name, "normalized")) {
        long m = 1;
        if (dfl_cfg_has(cfg, sec, "m") && (st = dfl_cfg_int(cfg, sec, "m", 1, 6, &m, err)))
            return st;
        *cls = DFL_COST_CHEAP;
        *units = pow(m * (m + 1) / 2.0 + 2, 4);
    }
    return st;
}

dfl_status dfl_field_cost_from_cfg(const dfl_cfg *cfg, const char *sec, dfl_cost *cost,
                                   dfl_err *err)
{
    const dfl_field_kind *kind;
    dfl_status st = dfl_field_kind_from_cfg(cfg, sec, &kind, err);
    if (st) return st;
    if (!strcmp(kind->name, "rfunc")) return rfunc_cost(cfg, sec, cost, err);
    if (!strcmp(kind->name, "proxy")) st = proxy_cost(cfg, sec, cost, err);
    else if (!strcmp(kind->name, "gridpeer")) st = gridpeer_cost(cfg, sec, cost, err);
    else if (!strcmp(kind->name, "pht")) st = pht_cost(cfg, sec, cost, err);
    else if (!strcmp(kind->name, "openvdb")) st = vdb_cost(cfg, sec, cost, err);
    else if (strcmp(kind->name, "exact") != 0) return DFL_OK;
    /* the field's shape, built by its factory and held with it */
    const char *shape = "shape";
    if (!st) st = dfl_cfg_string_opt(cfg, sec, "shape", "shape", &shape, err);
    return st ? st : dfl_shape_cost(cfg, shape, cost, err);
}
