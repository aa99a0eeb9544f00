// Brute-force references for the octree builder (raykit/svo_build.hpp), written apart from it:
// nothing here calls or copies the builder's predicates. Only the definition is shared:
//
// - Lattice: a coordinate p snaps to q = llround((double(p) - double(root_min)) *
//   (2^(depth+16) / double(root_size))); voxel (i,j,k), 0 <= i,j,k < 2^depth, is the CLOSED box
//   [i S, (i+1) S] x [j S, (j+1) S] x [k S, (k+1) S] with S = 2^16 lattice units.
// - Skipped triangles: an index >= vertex count, a non-finite coordinate, or collinear snapped
//   vertices (zero cross product).
// - Surface: voxel occupied iff some kept CLOSED snapped triangle meets its CLOSED box.
// - Solid: surface plus voxels whose centre has an odd number of triangles crossed by the ray
//   centre + t (1,0,0), t > 0: (c.y, c.z) inside the triangle's yz projection and crossing x > c.x.
//   A centre exactly on a projected edge or vertex is decided by simulation of simplicity: the
//   point is moved to (c.y + e, c.z + e^2) for an infinitesimal e > 0 (so every tie is decided the
//   same way for the two triangles sharing an edge); projections of zero area are never crossed.
//
// All decisions are exact: 64-bit lattice integers, 128-bit products. Coordinates must lie in
// (-2^40, 2^40) for the overlap predicates and (-2^36, 2^36) for the solid reference.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "raykit/svo_mesh.hpp"

namespace ref_svo {

using i64 = std::int64_t;
__extension__ typedef __int128 i128;

constexpr i64 kSub = i64(1) << 16;  ///< lattice units per voxel edge

inline i64 floor_div(i64 a, i64 b)  // b > 0
{
    const i64 q = a / b;
    return (a % b != 0 && a < 0) ? q - 1 : q;
}

inline i128 abs128(i128 a) { return a < 0 ? -a : a; }

// ---- lattice and snapping --------------------------------------------------------------------

struct Lattice {
    double root_min[3];
    double scale;  ///< 2^(depth+16) / root_size
    int depth;
    i64 cells;     ///< 2^depth voxels per axis
};

inline Lattice make_lattice(glm::vec3 root_min, float root_size, int depth)
{
    Lattice L;
    for (int a = 0; a < 3; ++a) L.root_min[a] = static_cast<double>(root_min[a]);
    L.scale = std::ldexp(1.0, depth + 16) / static_cast<double>(root_size);
    L.depth = depth;
    L.cells = i64(1) << depth;
    return L;
}

inline i64 snap(const Lattice& L, float p, int axis) { return std::llround((static_cast<double>(p) - L.root_min[axis]) * L.scale); }

struct ITri {
    i64 v[3][3];  ///< v[vertex][axis]
};

/// Whether three lattice points are collinear (exact).
inline bool collinear(const i64 v[3][3])
{
    const i128 a[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    const i128 b[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    return a[1] * b[2] - a[2] * b[1] == 0 && a[2] * b[0] - a[0] * b[2] == 0 && a[0] * b[1] - a[1] * b[0] == 0;
}

/// The mesh's triangles on the lattice, with the counts of each kind of skipped triangle.
struct Snapped {
    std::vector<ITri> tris;
    std::size_t bad_index = 0, non_finite = 0, degenerate = 0;
};

inline Snapped snap_mesh(const raykit::SvoMeshData& m, const Lattice& L)
{
    Snapped s;
    const std::size_t nv = m.positions.size();
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const std::uint32_t id[3] = {m.indices[t], m.indices[t + 1], m.indices[t + 2]};
        if (id[0] >= nv || id[1] >= nv || id[2] >= nv) {
            ++s.bad_index;
            continue;
        }
        bool finite = true;
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) finite = finite && std::isfinite(m.positions[id[k]][a]);
        if (!finite) {
            ++s.non_finite;
            continue;
        }
        ITri tri;
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) tri.v[k][a] = snap(L, m.positions[id[k]][a], a);
        if (collinear(tri.v)) {
            ++s.degenerate;
            continue;
        }
        s.tris.push_back(tri);
    }
    return s;
}

// ---- exact triangle / closed box overlap: two independent methods ----------------------------

/// Separating-axis test (Akenine-Möller's 13 axes: 3 box normals, the triangle normal, the 9
/// cross products of a triangle edge with a box axis) with the box projected as the interval of
/// its corners. Closed sets: the pair is disjoint iff some axis separates the projections strictly.
/// Exact in 128-bit integers for |coordinates| < 2^40. Valid for collinear triangles too.
inline bool tri_box_sat(const i64 v[3][3], const i64 lo[3], const i64 hi[3])
{
    for (int a = 0; a < 3; ++a) {
        const i64 mn = std::min({v[0][a], v[1][a], v[2][a]}), mx = std::max({v[0][a], v[1][a], v[2][a]});
        if (mn > hi[a] || mx < lo[a]) return false;
    }
    auto separates = [&](const i128 ax[3]) {
        i128 p[3];
        for (int k = 0; k < 3; ++k) p[k] = ax[0] * v[k][0] + ax[1] * v[k][1] + ax[2] * v[k][2];
        i128 blo = 0, bhi = 0;
        for (int a = 0; a < 3; ++a) {
            blo += ax[a] * (ax[a] >= 0 ? lo[a] : hi[a]);
            bhi += ax[a] * (ax[a] >= 0 ? hi[a] : lo[a]);
        }
        const i128 pmin = std::min({p[0], p[1], p[2]}), pmax = std::max({p[0], p[1], p[2]});
        return pmin > bhi || pmax < blo;
    };
    i128 e[3][3];
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) e[k][a] = static_cast<i128>(v[(k + 1) % 3][a]) - v[k][a];
    const i128 n[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                       e[0][0] * e[1][1] - e[0][1] * e[1][0]};
    if (separates(n)) return false;
    for (int k = 0; k < 3; ++k) {
        const i128 ax0[3] = {0, -e[k][2], e[k][1]};  // (1,0,0) x e
        const i128 ax1[3] = {e[k][2], 0, -e[k][0]};  // (0,1,0) x e
        const i128 ax2[3] = {-e[k][1], e[k][0], 0};  // (0,0,1) x e
        if (separates(ax0) || separates(ax1) || separates(ax2)) return false;
    }
    return true;
}

/// Second method, sharing nothing with the first: the intersection is the set of barycentric
/// (s, t) with s, t >= 0, s + t <= 1 and lo <= v0 + s e1 + t e2 <= hi, a bounded 2D polygon; it is
/// non-empty iff one of its vertices exists, i.e. the crossing point of some two of the 9
/// constraint lines satisfies all 9 (rational, compared exactly by cross-multiplying).
/// Exact for |coordinates| < 2^40. Cost: 36 line pairs x 9 checks.
inline bool tri_box_lp(const i64 v[3][3], const i64 lo[3], const i64 hi[3])
{
    // Constraints a s + b t <= c.
    i128 A[9], B[9], C[9];
    A[0] = -1, B[0] = 0, C[0] = 0;
    A[1] = 0, B[1] = -1, C[1] = 0;
    A[2] = 1, B[2] = 1, C[2] = 1;
    for (int k = 0; k < 3; ++k) {
        const i128 e1 = static_cast<i128>(v[1][k]) - v[0][k], e2 = static_cast<i128>(v[2][k]) - v[0][k];
        A[3 + 2 * k] = e1, B[3 + 2 * k] = e2, C[3 + 2 * k] = static_cast<i128>(hi[k]) - v[0][k];
        A[4 + 2 * k] = -e1, B[4 + 2 * k] = -e2, C[4 + 2 * k] = static_cast<i128>(v[0][k]) - lo[k];
    }
    for (int p = 0; p < 9; ++p)
        for (int q = p + 1; q < 9; ++q) {
            i128 det = A[p] * B[q] - A[q] * B[p];
            if (det == 0) continue;
            i128 sn = C[p] * B[q] - C[q] * B[p], tn = A[p] * C[q] - A[q] * C[p];
            if (det < 0) det = -det, sn = -sn, tn = -tn;
            bool ok = true;
            for (int r = 0; r < 9 && ok; ++r) ok = A[r] * sn + B[r] * tn <= C[r] * det;
            if (ok) return true;
        }
    return false;
}

// ---- dense reference voxeliser ---------------------------------------------------------------

/// Voxel key: i | j << 21 | k << 42.
inline std::uint64_t key(i64 i, i64 j, i64 k)
{
    return static_cast<std::uint64_t>(i) | (static_cast<std::uint64_t>(j) << 21) | (static_cast<std::uint64_t>(k) << 42);
}
inline glm::ivec3 unkey(std::uint64_t kk)
{
    return glm::ivec3(static_cast<int>(kk & 0x1FFFFF), static_cast<int>((kk >> 21) & 0x1FFFFF), static_cast<int>(kk >> 42));
}

/// Voxel index range [lo, hi] (clamped to the grid) whose closed boxes meet [mn, mx] on one axis.
inline void voxel_range(i64 mn, i64 mx, i64 cells, i64& lo, i64& hi)
{
    lo = std::max<i64>(0, floor_div(mn - 1, kSub));
    hi = std::min<i64>(cells - 1, floor_div(mx, kSub));
}

/// Appends to `out` every voxel of the grid (2^depth per axis, or the sub-range [rlo, rhi] when
/// given) whose closed box meets the triangle: each voxel of the triangle's bounding range is
/// tested with tri_box_sat. `prefilter` skips voxels whose centre is clearly (by 1e-9 relative
/// margin, in double) farther from the triangle's plane than the box reaches; the exact test
/// decides the rest. Unsorted.
inline void voxelize_triangle(const ITri& t, i64 cells, std::vector<std::uint64_t>& out, bool prefilter = true)
{
    i64 lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
        voxel_range(std::min({t.v[0][a], t.v[1][a], t.v[2][a]}), std::max({t.v[0][a], t.v[1][a], t.v[2][a]}), cells, lo[a], hi[a]);
    double n[3];
    {
        const double e1[3] = {double(t.v[1][0] - t.v[0][0]), double(t.v[1][1] - t.v[0][1]), double(t.v[1][2] - t.v[0][2])};
        const double e2[3] = {double(t.v[2][0] - t.v[0][0]), double(t.v[2][1] - t.v[0][1]), double(t.v[2][2] - t.v[0][2])};
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    }
    const double half = 0.5 * static_cast<double>(kSub);
    const double reach = (std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2])) * half;
    for (i64 k = lo[2]; k <= hi[2]; ++k)
        for (i64 j = lo[1]; j <= hi[1]; ++j)
            for (i64 i = lo[0]; i <= hi[0]; ++i) {
                const i64 blo[3] = {i * kSub, j * kSub, k * kSub};
                const i64 bhi[3] = {blo[0] + kSub, blo[1] + kSub, blo[2] + kSub};
                if (prefilter) {
                    double d = 0.0, mag = 0.0;
                    for (int a = 0; a < 3; ++a) {
                        const double c = static_cast<double>(blo[a] - t.v[0][a]) + half;
                        d += n[a] * c;
                        mag += std::abs(n[a] * c);
                    }
                    if (std::abs(d) > reach + 1e-9 * (mag + reach)) continue;
                }
                if (tri_box_sat(t.v, blo, bhi)) out.push_back(key(i, j, k));
            }
}

inline void sort_unique(std::vector<std::uint64_t>& v)
{
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
}

/// The surface voxel set of the snapped mesh at lattice depth `depth`: sorted keys.
/// Cost: sum over triangles of their bounding voxel ranges (meant for depth <= 8, or small
/// triangles at any depth).
inline std::vector<std::uint64_t> surface_voxels(const Snapped& s, int depth, bool prefilter = true)
{
    std::vector<std::uint64_t> out;
    for (const ITri& t : s.tris) voxelize_triangle(t, i64(1) << depth, out, prefilter);
    sort_unique(out);
    return out;
}

// ---- solid fill reference --------------------------------------------------------------------

struct SolidRef {
    std::vector<std::uint64_t> inside;  ///< sorted keys of voxels whose centre has odd crossing parity
    std::size_t tie_points = 0;   ///< (column, triangle) pairs with the centre exactly on a projected edge/vertex
    std::size_t flat_points = 0;  ///< (column, triangle) pairs with the centre on a zero-area projection
};

/// Crossing parity of every voxel centre (surface voxels included: the caller unites with the
/// surface set). Every kept triangle counts, wherever it lies. Cost: for each triangle, the
/// columns of its yz bounding range, then 2^depth comparisons per crossing.
inline SolidRef inside_voxels(const Snapped& s, int depth)
{
    const i64 n = i64(1) << depth;
    struct Crossing { i128 num, den; };
    std::vector<std::vector<Crossing>> col(static_cast<std::size_t>(n * n));
    SolidRef r;
    for (const ITri& t : s.tris) {
        // Projection to (y, z); orientation = the x component of the normal.
        const i64* a = t.v[0];
        const i64* b = t.v[1];
        const i64* c = t.v[2];
        i128 o = static_cast<i128>(b[1] - a[1]) * (c[2] - a[2]) - static_cast<i128>(b[2] - a[2]) * (c[1] - a[1]);
        i64 lo[3], hi[3];
        for (int ax = 1; ax < 3; ++ax) {
            const i64 mn = std::min({a[ax], b[ax], c[ax]}), mx = std::max({a[ax], b[ax], c[ax]});
            lo[ax] = std::max<i64>(0, floor_div(mn, kSub) - 1);
            hi[ax] = std::min<i64>(n - 1, floor_div(mx, kSub));
        }
        if (o < 0) {
            std::swap(b, c);
            o = -o;
        }
        const i64* vtx[3] = {a, b, c};
        for (i64 k = lo[2]; k <= hi[2]; ++k)
            for (i64 j = lo[1]; j <= hi[1]; ++j) {
                const i64 py = j * kSub + kSub / 2, pz = k * kSub + kSub / 2;
                if (o == 0) {
                    // Zero-area projection: never crossed; note when the centre lies on it.
                    bool on = true;
                    for (int e = 0; e < 3 && on; ++e) {
                        const i64* p0 = vtx[e];
                        const i64* p1 = vtx[(e + 1) % 3];
                        on = static_cast<i128>(p1[1] - p0[1]) * (pz - p0[2]) - static_cast<i128>(p1[2] - p0[2]) * (py - p0[1]) == 0;
                    }
                    const bool in_box = py >= std::min({a[1], b[1], c[1]}) && py <= std::max({a[1], b[1], c[1]}) &&
                                        pz >= std::min({a[2], b[2], c[2]}) && pz <= std::max({a[2], b[2], c[2]});
                    if (on && in_box) ++r.flat_points;
                    continue;
                }
                bool inside = true, closed_inside = true, tie = false;
                for (int e = 0; e < 3; ++e) {
                    const i64* p0 = vtx[e];
                    const i64* p1 = vtx[(e + 1) % 3];
                    const i64 dy = p1[1] - p0[1], dz = p1[2] - p0[2];
                    const i128 w = static_cast<i128>(dy) * (pz - p0[2]) - static_cast<i128>(dz) * (py - p0[1]);
                    // Perturbed point (py + e, pz + e^2): w + dy e^2 - dz e.
                    const bool pos = w > 0 || (w == 0 && (dz < 0 || (dz == 0 && dy > 0)));
                    inside = inside && pos;
                    closed_inside = closed_inside && w >= 0;
                    tie = tie || w == 0;
                }
                if (closed_inside && tie) ++r.tie_points;
                if (!inside) continue;
                // Plane: n . (X - a) = 0 with n = (b - a) x (c - a), n.x = o > 0.
                const i128 ny = static_cast<i128>(b[2] - a[2]) * (c[0] - a[0]) - static_cast<i128>(b[0] - a[0]) * (c[2] - a[2]);
                const i128 nz = static_cast<i128>(b[0] - a[0]) * (c[1] - a[1]) - static_cast<i128>(b[1] - a[1]) * (c[0] - a[0]);
                const i128 num = static_cast<i128>(a[0]) * o - ny * (py - a[1]) - nz * (pz - a[2]);
                col[static_cast<std::size_t>(k * n + j)].push_back({num, o});
            }
    }
    for (i64 k = 0; k < n; ++k)
        for (i64 j = 0; j < n; ++j) {
            const auto& cs = col[static_cast<std::size_t>(k * n + j)];
            if (cs.empty()) continue;
            for (i64 i = 0; i < n; ++i) {
                const i128 cx = i * kSub + kSub / 2;
                int count = 0;
                for (const Crossing& x : cs) count += x.num > cx * x.den;
                if (count & 1) r.inside.push_back(key(i, j, k));
            }
        }
    sort_unique(r.inside);
    return r;
}

// ---- dense grids: DDA and flood fill ---------------------------------------------------------

/// Dense occupancy grid (n^3 bytes, index i + n (j + n k)) from sorted or unsorted keys.
inline std::vector<std::uint8_t> dense(const std::vector<std::uint64_t>& keys, int n)
{
    std::vector<std::uint8_t> g(static_cast<std::size_t>(n) * n * n, 0);
    for (std::uint64_t kk : keys) {
        const glm::ivec3 c = unkey(kk);
        g[static_cast<std::size_t>(c.x) + static_cast<std::size_t>(n) * (c.y + static_cast<std::size_t>(n) * c.z)] = 1;
    }
    return g;
}

/// Amanatides & Woo 3D DDA through an n^3 grid (voxel units, grid = [0, n]^3) along the segment
/// a -> b, clipped to the grid: calls visit(i, j, k) for each voxel in order, one axis step at a
/// time (6-connected), until visit returns true (then returns true) or the segment ends.
template <class F>
bool dda(int n, glm::dvec3 a, glm::dvec3 b, F&& visit)
{
    const glm::dvec3 d = b - a;
    double t0 = 0.0, t1 = 1.0;
    for (int ax = 0; ax < 3; ++ax) {
        if (d[ax] == 0.0) {
            if (a[ax] < 0.0 || a[ax] > n) return false;
            continue;
        }
        double ta = (0.0 - a[ax]) / d[ax], tb = (n - a[ax]) / d[ax];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    if (t0 > t1) return false;
    const glm::dvec3 p = a + t0 * d;
    glm::ivec3 c, step;
    glm::dvec3 tmax, tdelta;
    for (int ax = 0; ax < 3; ++ax) {
        c[ax] = std::min(n - 1, std::max(0, static_cast<int>(std::floor(p[ax]))));
        step[ax] = d[ax] > 0 ? 1 : (d[ax] < 0 ? -1 : 0);
        if (step[ax] == 0) {
            tmax[ax] = tdelta[ax] = 1e300;
        } else {
            const double next = step[ax] > 0 ? c[ax] + 1.0 : static_cast<double>(c[ax]);
            tmax[ax] = (next - a[ax]) / d[ax];
            tdelta[ax] = std::abs(1.0 / d[ax]);
        }
    }
    for (;;) {
        if (visit(c.x, c.y, c.z)) return true;
        int ax = 0;
        if (tmax[1] < tmax[ax]) ax = 1;
        if (tmax[2] < tmax[ax]) ax = 2;
        if (tmax[ax] > t1) return false;
        c[ax] += step[ax];
        if (c[ax] < 0 || c[ax] >= n) return false;
        tmax[ax] += tdelta[ax];
    }
}

/// 6-connected flood fill over the empty cells (occ == 0) of an n^3 grid, seeded from every empty
/// cell on the grid's boundary: 1 for each cell reached ("outside"), 0 otherwise. Runs on a copy
/// padded by an empty layer (where the fill starts) and a blocked layer (so no bounds checks).
inline std::vector<std::uint8_t> flood_outside(const std::vector<std::uint8_t>& occ, int n)
{
    const std::size_t P = static_cast<std::size_t>(n) + 4, P2 = P * P;
    std::vector<std::uint8_t> g(P2 * P, 0);  // 0 empty, 1 blocked or occupied, 2 reached
    for (std::size_t k = 0; k < P; ++k)
        for (std::size_t j = 0; j < P; ++j)
            for (std::size_t i = 0; i < P; ++i) {
                const bool frame = i == 0 || j == 0 || k == 0 || i == P - 1 || j == P - 1 || k == P - 1;
                const bool inner = i >= 2 && j >= 2 && k >= 2 && i < P - 2 && j < P - 2 && k < P - 2;
                if (frame) g[i + P * j + P2 * k] = 1;
                else if (inner) g[i + P * j + P2 * k] = occ[(i - 2) + static_cast<std::size_t>(n) * ((j - 2) + static_cast<std::size_t>(n) * (k - 2))] ? 1 : 0;
            }
    std::vector<std::size_t> stack{1 + P + P2};
    g[stack[0]] = 2;
    const std::size_t step[6] = {1, P, P2, 0 - std::size_t(1), 0 - P, 0 - P2};
    while (!stack.empty()) {
        const std::size_t id = stack.back();
        stack.pop_back();
        for (std::size_t s : step) {
            const std::size_t m = id + s;
            if (g[m] == 0) {
                g[m] = 2;
                stack.push_back(m);
            }
        }
    }
    std::vector<std::uint8_t> out(occ.size(), 0);
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                out[static_cast<std::size_t>(i) + static_cast<std::size_t>(n) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(n) * static_cast<std::size_t>(k))] =
                    g[static_cast<std::size_t>(i + 2) + P * static_cast<std::size_t>(j + 2) + P2 * static_cast<std::size_t>(k + 2)] == 2;
    return out;
}

}  // namespace ref_svo
