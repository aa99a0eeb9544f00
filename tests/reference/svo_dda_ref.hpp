// Float64 references for sparse-voxel-octree ray traversal tests, written apart from
// shaders/raykit/svo_traverse.glsl (nothing of it is read or copied here). Only std + GLM.
//
// Geometry. The root cube is [root_min, root_min + root_size]^3. At level L (0 = root) it has
// 2^L cells per axis; cell (x,y,z) is the CLOSED box with per-axis bounds
//     cell_bound(root_min.a, root_size, L, i) = root_min.a + root_size * (i / 2^L),  i = x, x+1.
// Every bound in this file comes from that one formula, so neighbouring cells share bit-identical
// faces, a level-L cell's faces equal its ancestors' faces bit for bit, and the DDA and the brute
// force below test bit-identical boxes with the one predicate ray_box_interval().
//
// Ray. A DdaRay is the segment origin + t * dir, t in [0, t_max]: dir need not be unit length and
// may have +0/-0 components (not all zero); t_max may be +infinity. Inputs must be finite.
//
// Hit semantics (DdaHit), over the OCCUPIED voxels, all decided by ray_box_interval():
//   touch  - the smallest t in [0, t_max] where the segment meets an occupied closed box
//            (grazing an edge or corner, or lying in a face plane, counts); t_touch = 0 when the
//            origin is inside or on an occupied voxel.
//   solid  - the smallest entry t over occupied voxels whose intersection with the segment,
//            [t_entry, t_exit] (already clipped to [0, t_max]), is longer than path_tol:
//            (t_exit - t_entry) * |dir| > path_tol. A ray sliding IN a voxel's face plane has a
//            positive-length intersection with that closed box, so it is solid under path_tol
//            alone; pass solid_inset > 0 to measure the length inside the box shrunk by
//            solid_inset on every side instead (t_solid stays the entry t of the unshrunk box).
//   Ties in t are broken towards the lexicographically smallest (x, y, z) cell, so the two
//   functions below return identical DdaHit values. Always t_touch <= t_solid.
// A float32 traversal is acceptable if it returns t in [t_touch - eps, t_solid + eps] on a voxel
// the ray touches, and it may miss only when solid == false.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace rkref {

/// Dense occupancy bitset of 2^(3 depth) cells, 0 <= depth <= 10 (depth 10 takes 128 MiB).
/// get() answers false outside [0, 2^depth)^3; set() ignores such cells.
struct DdaGrid {
    int depth;
    int n;  ///< cells per axis, 2^depth
    std::vector<std::uint64_t> bits;

    explicit DdaGrid(int depth_levels)
        : depth(depth_levels), n(1 << depth_levels),
          bits(((std::size_t(1) << (3 * depth_levels)) + 63) / 64, 0)
    {
    }
    bool inside(int x, int y, int z) const { return x >= 0 && y >= 0 && z >= 0 && x < n && y < n && z < n; }
    std::size_t index(int x, int y, int z) const
    {
        return (((std::size_t(z) << depth) + std::size_t(y)) << depth) + std::size_t(x);
    }
    bool get(int x, int y, int z) const
    {
        if (!inside(x, y, z)) return false;
        const std::size_t i = index(x, y, z);
        return (bits[i >> 6] >> (i & 63)) & 1u;
    }
    bool get(glm::ivec3 c) const { return get(c.x, c.y, c.z); }
    void set(int x, int y, int z, bool v = true)
    {
        if (!inside(x, y, z)) return;
        const std::size_t i = index(x, y, z);
        const std::uint64_t m = std::uint64_t(1) << (i & 63);
        bits[i >> 6] = v ? (bits[i >> 6] | m) : (bits[i >> 6] & ~m);
    }
    /// Occupied cells in x-fastest order (the input brute_first_hit() wants).
    std::vector<glm::ivec3> cells() const
    {
        std::vector<glm::ivec3> out;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    if (get(x, y, z)) out.emplace_back(x, y, z);
        return out;
    }
};

/// The segment origin + t * dir, t in [0, t_max] (see the file comment).
struct DdaRay {
    glm::dvec3 origin;
    glm::dvec3 dir;
    double t_max;
};

/// First touched / first solid occupied voxel (see the file comment). t_* and cell_* are
/// meaningful only when the matching flag is set.
struct DdaHit {
    bool touch = false;
    double t_touch = 0.0;
    glm::ivec3 cell_touch{0};
    bool solid = false;
    double t_solid = 0.0;
    glm::ivec3 cell_solid{0};
};

/// Bound i (0..2^level) of the cells of `level` along one axis (i / 2^level is exact).
inline double cell_bound(double root_min_a, double root_size, int level, int i)
{
    return root_min_a + root_size * (static_cast<double>(i) / static_cast<double>(std::int64_t(1) << level));
}

/// Closed box [lo, hi] of `cell` at `level` (cells outside [0, 2^level) give boxes outside the root).
inline void cell_box(glm::dvec3 root_min, double root_size, int level, glm::ivec3 cell, glm::dvec3& lo, glm::dvec3& hi)
{
    for (int k = 0; k < 3; ++k) {
        lo[k] = cell_bound(root_min[k], root_size, level, cell[k]);
        hi[k] = cell_bound(root_min[k], root_size, level, cell[k] + 1);
    }
}

/// Slab test of the segment against the CLOSED box [lo, hi], clipped to [0, t_max]. Returns true
/// and the parameter interval [t0, t1] (t0 <= t1, t0 finite) when they meet. An axis with
/// dir == 0 (+0 or -0) meets its slab iff lo <= origin <= hi, for every t. A box with lo > hi on
/// some axis is empty. Each slab bound is one rounded division (lo - origin) / dir.
inline bool ray_box_interval(glm::dvec3 lo, glm::dvec3 hi, const DdaRay& r, double& t0, double& t1)
{
    double a = 0.0, b = r.t_max;
    for (int k = 0; k < 3; ++k) {
        if (!(lo[k] <= hi[k])) return false;
        const double o = r.origin[k], d = r.dir[k];
        if (d == 0.0) {
            if (o < lo[k] || o > hi[k]) return false;
            continue;
        }
        double ta = (lo[k] - o) / d, tb = (hi[k] - o) / d;
        if (ta > tb) std::swap(ta, tb);
        a = std::max(a, ta);
        b = std::min(b, tb);
    }
    if (!(a <= b) || !(a < std::numeric_limits<double>::infinity())) return false;
    t0 = a;
    t1 = b;
    return true;
}

/// Whether the segment meets the box of `cell` at `level` grown by `grow` (world units, absolute,
/// may be negative) on every side; its clipped entry t goes to *t_entry when given.
inline bool ray_touches_cell(glm::dvec3 root_min, double root_size, int level, glm::ivec3 cell, const DdaRay& r,
                             double grow, double* t_entry)
{
    glm::dvec3 lo, hi;
    cell_box(root_min, root_size, level, cell, lo, hi);
    double t0, t1;
    if (!ray_box_interval(lo - grow, hi + grow, r, t0, t1)) return false;
    if (t_entry) *t_entry = t0;
    return true;
}

namespace detail {

inline bool cell_less(glm::ivec3 a, glm::ivec3 b)
{
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

/// Folds one occupied cell into h (the one place where the hit semantics are decided).
inline void consider(DdaHit& h, glm::dvec3 root_min, double root_size, int level, glm::ivec3 cell, const DdaRay& r,
                     double len, double path_tol, double solid_inset)
{
    glm::dvec3 lo, hi;
    cell_box(root_min, root_size, level, cell, lo, hi);
    double t0, t1;
    if (!ray_box_interval(lo, hi, r, t0, t1)) return;
    if (!h.touch || t0 < h.t_touch || (t0 == h.t_touch && cell_less(cell, h.cell_touch))) {
        h.touch = true;
        h.t_touch = t0;
        h.cell_touch = cell;
    }
    if (h.solid && (t0 > h.t_solid || (t0 == h.t_solid && !cell_less(cell, h.cell_solid)))) return;
    double s0 = t0, s1 = t1;
    if (solid_inset != 0.0 && !ray_box_interval(lo + solid_inset, hi - solid_inset, r, s0, s1)) return;
    if ((s1 - s0) * len > path_tol) {
        h.solid = true;
        h.t_solid = t0;
        h.cell_solid = cell;
    }
}

}  // namespace detail

/// Brute force: every listed cell (at `level`, 0..20; duplicates and cells outside the root are
/// allowed) is tested with ray_box_interval(). O(cells.size()) per ray, any depth.
inline DdaHit brute_first_hit(const std::vector<glm::ivec3>& cells, int level, glm::dvec3 root_min, double root_size,
                              const DdaRay& r, double path_tol, double solid_inset = 0.0)
{
    DdaHit h;
    const double len = glm::length(r.dir);
    for (const glm::ivec3& c : cells) detail::consider(h, root_min, root_size, level, c, r, len, path_tol, solid_inset);
    return h;
}

/// 3D DDA (Amanatides & Woo) through g, returning exactly brute_first_hit(g.cells(), g.depth, ...).
///
/// How it stays exact: the walk only ENUMERATES candidates; every occupied candidate is decided by
/// detail::consider(), the brute force's own predicate. The walk visits cells C_0, C_1, ... whose
/// parameter intervals [tin, tout] tile the clipped root interval [t_begin, t_end] (tout of one is
/// tin of the next, bit for bit; the last boundary time equals the root's slab time, so the walk
/// cannot leave the grid before t_end). Each crossing time is one rounded division, so over
/// [tin, tout] the ray stays within ~1e-15 * scale of C (scale = max_a |origin_a| + |root_min_a| +
/// root_size). For each visited C, the 3x3x3 neighbours on the sides where the ray comes within
/// eps = 1e-9 * cell + 1e-12 * scale of a face of C are examined too. Any occupied voxel V that
/// ray_box_interval() reports at entry t_V contains p(t_V) up to rounding, and p(t_V) lies near the
/// cell C visited at t_V, so V is C or a neighbour on a side the ray approaches: V is examined.
/// The walk stops once a visited cell starts after t_solid: every voxel entered at t <= t_solid
/// has been examined by then. Needs 1e-12 * scale well below the cell size (cell > ~1e-9 scale).
/// At most 3 * 2^depth cells are visited; 1 to 27 (usually 2 to 4) bit lookups each.
inline DdaHit dda_first_hit(const DdaGrid& g, glm::dvec3 root_min, double root_size, const DdaRay& r,
                            double path_tol, double solid_inset = 0.0)
{
    DdaHit h;
    const int L = g.depth, n = g.n;
    glm::dvec3 rlo, rhi;
    cell_box(root_min, root_size, 0, glm::ivec3(0), rlo, rhi);
    double t_begin, t_end;
    if (!ray_box_interval(rlo, rhi, r, t_begin, t_end)) return h;

    const double len = glm::length(r.dir);
    const double inf = std::numeric_limits<double>::infinity();
    double scale = 0.0;
    for (int k = 0; k < 3; ++k) scale = std::max(scale, std::abs(r.origin[k]) + std::abs(root_min[k]) + root_size);
    const double eps = 1e-9 * std::ldexp(root_size, -L) + 1e-12 * scale;

    auto bound = [&](int k, int i) { return cell_bound(root_min[k], root_size, L, i); };
    auto pos = [&](int k, double t) { return r.dir[k] == 0.0 ? r.origin[k] : r.origin[k] + t * r.dir[k]; };

    // Start cell: the one holding p(t_begin) by the exact bounds (half-open, clamped to the grid).
    glm::ivec3 c;
    int step[3];
    double t_next[3];  // time of the next boundary crossing per axis
    for (int k = 0; k < 3; ++k) {
        const double p = pos(k, t_begin);
        const double f = std::floor((p - root_min[k]) / root_size * n);
        int i = f < 0.0 ? 0 : f > n - 1 ? n - 1 : static_cast<int>(f);
        while (i > 0 && p < bound(k, i)) --i;
        while (i < n - 1 && p >= bound(k, i + 1)) ++i;
        c[k] = i;
        step[k] = r.dir[k] > 0.0 ? 1 : r.dir[k] < 0.0 ? -1 : 0;
        t_next[k] = step[k] == 0 ? inf : (bound(k, i + (step[k] > 0)) - r.origin[k]) / r.dir[k];
    }

    double tin = t_begin;
    for (int it = 0; it < 3 * n; ++it) {  // each iteration moves one axis one cell: <= 3(n-1) moves
        if (h.solid && tin > h.t_solid) break;
        int a = 0;
        if (t_next[1] < t_next[a]) a = 1;
        if (t_next[2] < t_next[a]) a = 2;
        const double tout = std::min(std::max(t_next[a], tin), t_end);

        // Candidates: C and its neighbours on the sides the ray comes within eps of.
        int lo_off[3], hi_off[3];
        for (int k = 0; k < 3; ++k) {
            const double v0 = std::min(pos(k, tin), pos(k, tout)), v1 = std::max(pos(k, tin), pos(k, tout));
            lo_off[k] = (c[k] > 0 && v0 <= bound(k, c[k]) + eps) ? -1 : 0;
            hi_off[k] = (c[k] < n - 1 && v1 >= bound(k, c[k] + 1) - eps) ? 1 : 0;
        }
        for (int dz = lo_off[2]; dz <= hi_off[2]; ++dz)
            for (int dy = lo_off[1]; dy <= hi_off[1]; ++dy)
                for (int dx = lo_off[0]; dx <= hi_off[0]; ++dx) {
                    const glm::ivec3 q = c + glm::ivec3(dx, dy, dz);
                    if (g.get(q)) detail::consider(h, root_min, root_size, L, q, r, len, path_tol, solid_inset);
                }

        if (tout >= t_end) break;
        c[a] += step[a];
        if (c[a] < 0 || c[a] >= n) break;  // unreachable: the last crossing time is t_end's bound
        t_next[a] = (bound(a, c[a] + (step[a] > 0)) - r.origin[a]) / r.dir[a];
        tin = tout;
    }
    return h;
}

}  // namespace rkref
