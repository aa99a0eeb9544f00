// raykit — svo_build.hpp: triangle mesh -> packed sparse voxel octree (docs/svo-format.md).
// C++ only, GLM only, no exceptions (errors through SvoStatus).
//
//   raykit::SvoTree tree;  raykit::SvoStatus st;  raykit::SvoBuildStats stats;
//   raykit::SvoBuildOptions opt;  opt.depth = 11;
//   if (!raykit::build_svo(mesh_data.view(), opt, tree, st, &stats)) log(st.message);
//
// What it computes (the definition the tests check against an independent brute-force oracle):
// - Root cube: automatic = the smallest cube centred on the bounding box of the usable triangles;
//   or the caller's fixed cube.
// - Lattice: every vertex coordinate is snapped to an integer lattice of 2^(depth + 16) steps per
//   root edge (svo_snap_coordinate: 16 sub-voxel bits; 2^-17 voxel of rounding at most, and none
//   for coordinates already on the lattice, e.g. far from the origin where float spacing is
//   coarser). All decisions below are exact integer arithmetic on the snapped triangle.
// - Surface: voxel (i,j,k) is occupied iff the closed snapped triangle intersects the closed box
//   [i, i+1] x [j, j+1] x [k, k+1] (voxel units) for some triangle: the 13-axis separating-axis
//   test, exact (svo_triangle_box_overlap). Touching counts, so a triangle on a split plane marks
//   the voxels on both sides, and a closed mesh gives a closed, 6-connected-leak-free shell.
// - Solid: surface voxels plus every voxel whose centre is inside the mesh by crossing parity along
//   +x (svo_centre_ray_crosses: exact point-in-projected-triangle with a top-left tie rule, so a ray
//   through a shared edge or vertex counts once). Needs a closed mesh.
// - Attributes: colour = the base colour (factor x texture, filtered over the part of the triangle
//   inside the voxel: the clipped polygon is fanned into triangles, each sampled at its centroid
//   with a trilinear mip level matching its texel footprint, weighted by 3D area), normal = area-
//   weighted interpolated vertex normal (or face normal), material = that of the largest area.
//   Inner nodes: area-weighted means of their children (LOD; a normal that cancels takes the
//   heaviest leaf's, as a leaf's takes its largest contribution's). Interior (solid-fill) voxels take the
//   base colour of the material whose surface opens their span and carry a zero weight.
//   A triangle without texture and vertex normals (or whose normals are not stored) has constant
//   colour and normal, so only its area inside each voxel is computed (in closed form where the
//   voxel's column lies inside the triangle's shadow); the weights are the same up to float rounding.
// Cost: O(triangles x chunks touched + voxels touched), parallel over 32^3-voxel chunks; the
// packer reads each chunk's leaves in place and finds bricks in parallel.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "raykit/svo_mesh.hpp"

namespace raykit {

/// Sub-voxel bits of the snapping lattice.
constexpr uint32_t kSvoSubvoxelBits = 16;

namespace svo_detail {
__extension__ typedef __int128 i128;

/// Morton key of a cell (21 bits per axis), bit 3l = x bit l, 3l+1 = y, 3l+2 = z.
inline uint64_t spread3(uint32_t v)
{
    uint64_t x = v & 0x1FFFFFu;
    x = (x | (x << 32)) & 0x1F00000000FFFFull;
    x = (x | (x << 16)) & 0x1F0000FF0000FFull;
    x = (x | (x << 8)) & 0x100F00F00F00F00Full;
    x = (x | (x << 4)) & 0x10C30C30C30C30C3ull;
    x = (x | (x << 2)) & 0x1249249249249249ull;
    return x;
}
inline uint64_t morton(uint32_t x, uint32_t y, uint32_t z) { return spread3(x) | (spread3(y) << 1) | (spread3(z) << 2); }
}  // namespace svo_detail

/// svo_morton: the Morton key of voxel `cell` (bits 3l, 3l+1, 3l+2 = bit l of x, y, z), the order
/// of voxels in a tree. Exact for coordinates < 2^21.
inline uint64_t svo_morton(glm::uvec3 cell) { return svo_detail::morton(cell.x, cell.y, cell.z); }

/// svo_snap_coordinate: a mesh coordinate on the builder's lattice (2^(depth+16) steps per root
/// edge, 0 at root_min): llround((p - root_min) * (2^(depth+16) / root_size)) in double.
/// Exact when p - root_min is a multiple of the step; otherwise rounded to nearest (<= 1/2 step).
inline int64_t svo_snap_coordinate(float p, float root_min, float root_size, uint32_t depth);

namespace svo_detail {
/// The unrounded lattice position of svo_snap_coordinate (double).
inline double lattice_position(float p, float root_min, float root_size, uint32_t depth)
{
    const double scale = std::ldexp(1.0, static_cast<int>(depth + kSvoSubvoxelBits)) / static_cast<double>(root_size);
    return (static_cast<double>(p) - static_cast<double>(root_min)) * scale;
}
}  // namespace svo_detail

inline int64_t svo_snap_coordinate(float p, float root_min, float root_size, uint32_t depth)
{
    return std::llround(svo_detail::lattice_position(p, root_min, root_size, depth));
}

namespace svo_detail {

/// The separating-axis data of one lattice triangle (|coordinate| < 2^40): its plane n.x = d
/// (n = (v1 - v0) x (v2 - v0)) and, for the 9 axes e_i x unit_k (e_i = v_{i+1} - v_i), the axis's
/// two non-zero components and the triangle's projection interval. Every product is exact in
/// 128-bit integers (coordinates < 2^41 after differences, |n| < 2^83, projections < 2^124).
struct SatTriangle {
    struct Axis { int64_t au, aw; i128 tlo, thi; int ka, kb; };  // au on axis ka, aw on axis kb
    i128 n[3];
    i128 d;
    Axis ax[3][3];  // ax[k][i] = e_i x unit_k

    explicit SatTriangle(const int64_t (*v)[3])
    {
        int64_t e[3][3];
        for (int i = 0; i < 3; ++i)
            for (int a = 0; a < 3; ++a) e[i][a] = v[(i + 1) % 3][a] - v[i][a];
        // n = e0 x (v2 - v0) = e0 x -e2.
        n[0] = (i128)e[0][1] * -e[2][2] - (i128)e[0][2] * -e[2][1];
        n[1] = (i128)e[0][2] * -e[2][0] - (i128)e[0][0] * -e[2][2];
        n[2] = (i128)e[0][0] * -e[2][1] - (i128)e[0][1] * -e[2][0];
        d = 0;
        for (int a = 0; a < 3; ++a) d += n[a] * v[0][a];
        for (int k = 0; k < 3; ++k)
            for (int i = 0; i < 3; ++i) {
                Axis& A = ax[k][i];
                A.ka = (k + 1) % 3;
                A.kb = (k + 2) % 3;
                A.au = e[i][A.kb];  // e_i x unit_k: e[kb] on axis ka, -e[ka] on axis kb
                A.aw = -e[i][A.ka];
                for (int j = 0; j < 3; ++j) {
                    const i128 p = (i128)A.au * v[j][A.ka] + (i128)A.aw * v[j][A.kb];
                    if (j == 0 || p < A.tlo) A.tlo = p;
                    if (j == 0 || p > A.thi) A.thi = p;
                }
            }
    }
    /// Whether the box [bmin, bmin + size]^3 and the triangle overlap on axis A (touching counts).
    static bool axis_ok(const Axis& A, const int64_t bmin[3], int64_t size)
    {
        const i128 base = (i128)A.au * bmin[A.ka] + (i128)A.aw * bmin[A.kb];
        const i128 blo = base + (i128)std::min<int64_t>(A.au, 0) * size + (i128)std::min<int64_t>(A.aw, 0) * size;
        const i128 bhi = base + (i128)std::max<int64_t>(A.au, 0) * size + (i128)std::max<int64_t>(A.aw, 0) * size;
        return !(A.thi < blo || A.tlo > bhi);
    }
    /// Whether the triangle's plane passes through the box (touching counts).
    bool plane_ok(const int64_t bmin[3], int64_t size) const
    {
        i128 lo = 0, hi = 0;
        for (int a = 0; a < 3; ++a) {
            const i128 p0 = n[a] * bmin[a], p1 = n[a] * (bmin[a] + size);
            lo += p0 < p1 ? p0 : p1;
            hi += p0 < p1 ? p1 : p0;
        }
        return !(d < lo || d > hi);
    }
};

}  // namespace svo_detail

/// svo_triangle_box_overlap: whether the closed triangle v[0..2] and the closed axis-aligned box
/// [box_min, box_min + box_size]^3 intersect, both in lattice integers (|coordinate| < 2^40).
/// The 13 separating axes (3 box normals, the triangle normal, 9 edge x box-axis cross products),
/// each decided exactly in 128-bit integers: touching counts as overlap. A degenerate (collinear)
/// triangle is tested as the segment it is. Cost: ~40 integer multiplies. (The builder sweeps
/// whole cell ranges with the same svo_detail::SatTriangle.)
inline bool svo_triangle_box_overlap(const int64_t v[3][3], const int64_t box_min[3], int64_t box_size)
{
    for (int a = 0; a < 3; ++a) {  // box normals: bounding-box overlap
        const int64_t lo = std::min(v[0][a], std::min(v[1][a], v[2][a]));
        const int64_t hi = std::max(v[0][a], std::max(v[1][a], v[2][a]));
        if (hi < box_min[a] || lo > box_min[a] + box_size) return false;
    }
    const svo_detail::SatTriangle T(v);
    if (!T.plane_ok(box_min, box_size)) return false;
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 3; ++i)
            if (!svo_detail::SatTriangle::axis_ok(T.ax[k][i], box_min, box_size)) return false;
    return true;
}

/// svo_centre_ray_crosses: whether the ray from lattice point (px, py, pz) along +x crosses the
/// triangle v (lattice integers), and where (x_out, in lattice units). Exact point-in-triangle of
/// (py, pz) in the triangle's yz projection with a top-left rule: after orienting the projection
/// counter-clockwise, a point on an edge a->b counts iff (b.z - a.z) < 0, or the edge is
/// horizontal with (b.y - a.y) > 0, so that a ray through an edge shared by two triangles of one
/// sheet, or through a shared vertex, crosses exactly one of them. Triangles parallel to x (zero
/// projected area) are never crossed. The crossing counts only when x_out > px (the caller
/// compares; x_out is the plane's x at (py, pz) in double). Cost: ~12 integer multiplies.
inline bool svo_centre_ray_crosses(const int64_t v[3][3], int64_t py, int64_t pz, double& x_out)
{
    using svo_detail::i128;
    const int64_t ay = v[0][1], az = v[0][2];
    const i128 area = (i128)(v[1][1] - ay) * (v[2][2] - az) - (i128)(v[1][2] - az) * (v[2][1] - ay);
    if (area == 0) return false;
    const int s = area > 0 ? 1 : -1;
    for (int i = 0; i < 3; ++i) {
        const int i0 = i, i1 = s > 0 ? (i + 1) % 3 : (i + 2) % 3;  // walk counter-clockwise
        const int64_t dy = v[i1][1] - v[i0][1], dz = v[i1][2] - v[i0][2];
        const i128 ef = (i128)dy * (pz - v[i0][2]) - (i128)dz * (py - v[i0][1]);
        if (ef < 0) return false;
        if (ef == 0 && !(dz < 0 || (dz == 0 && dy > 0))) return false;
    }
    // Plane x at (py, pz): n.x * x = n.v0 - n.y * py - n.z * pz, with n = (v1-v0) x (v2-v0).
    double e1[3], e2[3];
    for (int a = 0; a < 3; ++a) {
        e1[a] = static_cast<double>(v[1][a] - v[0][a]);
        e2[a] = static_cast<double>(v[2][a] - v[0][a]);
    }
    const double nx = e1[1] * e2[2] - e1[2] * e2[1];
    const double ny = e1[2] * e2[0] - e1[0] * e2[2];
    const double nz = e1[0] * e2[1] - e1[1] * e2[0];
    x_out = static_cast<double>(v[0][0]) -
            (ny * static_cast<double>(py - v[0][1]) + nz * static_cast<double>(pz - v[0][2])) / nx;
    return true;
}

namespace svo_detail {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// One usable triangle on the lattice, with what attribute sampling needs.
struct Tri {
    int64_t v[3][3];
    uint32_t src;       // index of the source triangle
    uint16_t material;
};

/// A texture prepared for area filtering: linear RGBA float mip chain (box filtered).
struct Texture {
    struct Level { int w = 0, h = 0; std::vector<glm::vec4> px; };
    std::vector<Level> levels;
    SvoWrap wrap_s = SvoWrap::repeat, wrap_t = SvoWrap::repeat;

    static float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

    void prepare(const SvoImageView& im)
    {
        levels.clear();
        wrap_s = im.wrap_s;
        wrap_t = im.wrap_t;
        if (!im.pixels || im.width <= 0 || im.height <= 0 || im.channels < 1 || im.channels > 4) return;
        const size_t stride = im.row_stride ? im.row_stride : static_cast<size_t>(im.width) * static_cast<size_t>(im.channels);
        float lut[256];
        for (int i = 0; i < 256; ++i) lut[i] = im.srgb ? srgb_to_linear(static_cast<float>(i) / 255.0f) : static_cast<float>(i) / 255.0f;
        Level l0;
        l0.w = im.width;
        l0.h = im.height;
        l0.px.resize(static_cast<size_t>(l0.w) * static_cast<size_t>(l0.h));
        for (int y = 0; y < l0.h; ++y) {
            const uint8_t* row = im.pixels + static_cast<size_t>(y) * stride;
            for (int x = 0; x < l0.w; ++x) {
                const uint8_t* p = row + static_cast<size_t>(x) * static_cast<size_t>(im.channels);
                glm::vec4 c;
                if (im.channels <= 2) {
                    c = glm::vec4(lut[p[0]], lut[p[0]], lut[p[0]], im.channels == 2 ? static_cast<float>(p[1]) / 255.0f : 1.0f);
                } else {
                    c = glm::vec4(lut[p[0]], lut[p[1]], lut[p[2]], im.channels == 4 ? static_cast<float>(p[3]) / 255.0f : 1.0f);
                }
                l0.px[static_cast<size_t>(y) * static_cast<size_t>(l0.w) + static_cast<size_t>(x)] = c;
            }
        }
        levels.push_back(std::move(l0));
        while (levels.back().w > 1 || levels.back().h > 1) {
            const Level& s = levels.back();
            Level d;
            d.w = std::max(1, s.w / 2);
            d.h = std::max(1, s.h / 2);
            d.px.resize(static_cast<size_t>(d.w) * static_cast<size_t>(d.h));
            for (int y = 0; y < d.h; ++y)
                for (int x = 0; x < d.w; ++x) {
                    glm::vec4 sum(0.0f);
                    int n = 0;
                    for (int dy = 0; dy < 2; ++dy)
                        for (int dx = 0; dx < 2; ++dx) {
                            const int sx = std::min(2 * x + dx, s.w - 1), sy = std::min(2 * y + dy, s.h - 1);
                            sum += s.px[static_cast<size_t>(sy) * static_cast<size_t>(s.w) + static_cast<size_t>(sx)];
                            ++n;
                        }
                    d.px[static_cast<size_t>(y) * static_cast<size_t>(d.w) + static_cast<size_t>(x)] = sum / static_cast<float>(n);
                }
            levels.push_back(std::move(d));
        }
    }
    uint64_t bytes() const
    {
        uint64_t b = 0;
        for (const Level& l : levels) b += l.px.size() * sizeof(glm::vec4);
        return b;
    }
    static int wrap(int i, int n, SvoWrap m)
    {
        if (m == SvoWrap::clamp) return std::min(std::max(i, 0), n - 1);
        if (m == SvoWrap::mirror) {
            const int p = 2 * n;
            int k = i % p;
            if (k < 0) k += p;
            return k < n ? k : p - 1 - k;
        }
        int k = i % n;
        return k < 0 ? k + n : k;
    }
    glm::vec4 bilinear(const Level& l, double u, double v) const
    {
        const double x = u * l.w - 0.5, y = v * l.h - 0.5;
        const double fx = std::floor(x), fy = std::floor(y);
        const float tx = static_cast<float>(x - fx), ty = static_cast<float>(y - fy);
        // Fold huge coordinates first so the int conversion cannot overflow.
        const double px = std::fmod(fx, 2.0 * l.w), py = std::fmod(fy, 2.0 * l.h);
        const int x0 = static_cast<int>(px), y0 = static_cast<int>(py);
        auto at = [&](int xi, int yi) {
            return l.px[static_cast<size_t>(wrap(yi, l.h, wrap_t)) * static_cast<size_t>(l.w) + static_cast<size_t>(wrap(xi, l.w, wrap_s))];
        };
        const glm::vec4 a = glm::mix(at(x0, y0), at(x0 + 1, y0), tx);
        const glm::vec4 b = glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), tx);
        return glm::mix(a, b, ty);
    }
    /// Trilinear sample at (u, v) with a footprint of `texels` level-0 texels across.
    glm::vec4 sample(double u, double v, double texels) const
    {
        if (levels.empty()) return glm::vec4(1.0f);
        if (!std::isfinite(u) || !std::isfinite(v)) return levels.back().px[0];
        const double lod = texels > 1.0 ? std::log2(texels) : 0.0;
        const int top = static_cast<int>(levels.size()) - 1;
        if (lod >= top) return levels.back().px[0];
        const int l = static_cast<int>(lod);
        const float f = static_cast<float>(lod - l);
        const glm::vec4 a = bilinear(levels[static_cast<size_t>(l)], u, v);
        if (f <= 0.0f) return a;
        return glm::mix(a, bilinear(levels[static_cast<size_t>(l + 1)], u, v), f);
    }
};

/// The mesh, validated and snapped, plus what attribute evaluation needs.
struct Prepared {
    uint32_t depth = 0;
    float root_min[3] = {0, 0, 0};
    float root_size = 0;
    std::vector<Tri> tris;
    const SvoMesh* mesh = nullptr;
    std::vector<SvoMaterial> materials;      // table (index = material id)
    std::vector<int> material_texture;       // texture per material, -1 none
    std::vector<Texture> textures;
    bool has_normals = false;
    uint32_t attributes = 0;
    std::vector<Tri> outside;  // solid fill: triangles outside the root still count in the parity

    glm::vec3 vertex_attr3(const float* base, size_t stride, uint32_t i) const
    {
        const float* p = reinterpret_cast<const float*>(reinterpret_cast<const uint8_t*>(base) + static_cast<size_t>(i) * stride);
        return glm::vec3(p[0], p[1], p[2]);
    }
    glm::vec2 vertex_attr2(const float* base, size_t stride, uint32_t i) const
    {
        const float* p = reinterpret_cast<const float*>(reinterpret_cast<const uint8_t*>(base) + static_cast<size_t>(i) * stride);
        return glm::vec2(p[0], p[1]);
    }
    uint32_t index(uint32_t tri, int k) const
    {
        return mesh->indices ? mesh->indices[3u * tri + static_cast<uint32_t>(k)] : 3u * tri + static_cast<uint32_t>(k);
    }
};

/// Per-voxel accumulation while voxelising a chunk. Contributions with area are summed weighted
/// by it; while a voxel has none, col/nrm hold the plain sums of its touch-only (zero-area)
/// contributions, which the first contribution with area discards. 56 bytes: a chunk's array is
/// touched at random, so its size is what the voxelising loop waits on.
struct Accum {
    float area;        // sum of areas (voxel^2 units)
    float touch;       // number of touch-only contributions (used while area == 0)
    glm::vec4 col;
    glm::vec3 nrm;
    float best_area;
    glm::vec3 best_nrm;  // the normal of the largest contribution (where opposite faces cancel)
    uint16_t best_mat;
    uint8_t used;

    void add_area(float total, const glm::vec4& c, const glm::vec3& n, uint16_t mat)
    {
        if (total > 0.0f) {
            if (!(area > 0.0f)) { col = glm::vec4(0.0f); nrm = glm::vec3(0.0f); }
            area += total;
            col += c * total;
            nrm += n * total;
            if (total > best_area) { best_area = total; best_mat = mat; best_nrm = n; }
        }
        used = 1;
    }
    void add_touch(const glm::vec4& c, const glm::vec3& n, uint16_t mat)
    {
        if (!(area > 0.0f)) {
            touch += 1.0f;
            col += c;
            nrm += n;
        }
        if (best_area <= 0.0f && !used) best_mat = mat;
        used = 1;
    }
};

/// A leaf (or node) with its attributes, in Morton order.
struct Leaf {
    uint64_t key;
    float weight;      // area of surface inside (voxel^2 at the leaf level); 0 for interior
    uint32_t color;    // rk_svo_pack_color
    uint32_t normal;   // rk_svo_pack_normal
    uint16_t material;
};

/// Runs body(i) for i in [0, n) on the caller's parallel-for or a pool of `threads` threads.
inline void parallel_for(const SvoBuildOptions& opt, size_t n, const std::function<void(size_t)>& body)
{
    if (n == 0) return;
    if (opt.parallel_for) { opt.parallel_for(n, body); return; }
    unsigned t = opt.threads > 0 ? static_cast<unsigned>(opt.threads) : std::max(1u, std::thread::hardware_concurrency());
    t = static_cast<unsigned>(std::min<size_t>(t, n));
    if (t <= 1) { for (size_t i = 0; i < n; ++i) body(i); return; }
    std::atomic<size_t> next{0};
    auto worker = [&]() { for (size_t i; (i = next.fetch_add(1)) < n;) body(i); };
    std::vector<std::thread> pool;
    pool.reserve(t - 1);
    for (unsigned k = 1; k < t; ++k) pool.emplace_back(worker);
    worker();
    for (std::thread& th : pool) th.join();
}

/// sRGB <-> 8-bit without pow, bit-identical to rk_svo_pack_color / rk_svo_unpack_color: decoding
/// is a 256-entry table of rk_srgb_decode; encoding counts the thresholds (the smallest float that
/// rk_svo_pack_unorm8(rk_srgb_encode(x)) maps to code k, found once by bisection on float bits;
/// the map is monotone) below x, starting from a 4096-bucket table of lower bounds.
struct SrgbTables {
    float decode[256];
    float threshold[256];  // threshold[k]: smallest x with code >= k (k = 1..255)
    SrgbTables()
    {
        for (int i = 0; i < 256; ++i) decode[i] = rk_srgb_decode(static_cast<float>(i) / 255.0f);
        threshold[0] = 0.0f;
        for (uint32_t k = 1; k < 256; ++k) {
            uint32_t lo = 0, hi = 0x3F800000u;  // bit patterns of 0 and 1
            while (lo < hi) {
                const uint32_t mid = lo + (hi - lo) / 2;
                float x;
                std::memcpy(&x, &mid, 4);
                if (rk_svo_pack_unorm8(rk_srgb_encode(x)) >= k) hi = mid; else lo = mid + 1;
            }
            std::memcpy(&threshold[k], &lo, 4);
        }
        for (uint32_t i = 0; i <= 4096; ++i) {
            const float x = static_cast<float>(i) / 4096.0f;
            uint32_t c = 0;
            while (c < 255u && threshold[c + 1] <= x) ++c;
            bucket[i] = static_cast<uint8_t>(c);
        }
    }
    uint8_t bucket[4097];  // code at x = i / 4096: a lower bound for the codes of [i, i+1) / 4096
    uint32_t encode8(float x) const
    {
        if (!(x > 0.0f)) return 0u;
        if (x >= 1.0f) return 255u;
        uint32_t c = bucket[static_cast<uint32_t>(x * 4096.0f)];
        while (c < 255u && threshold[c + 1] <= x) ++c;  // a few steps at most (sRGB's slope is <= 3295)
        return c;
    }
    uint32_t pack(const glm::vec4& c) const
    {
        return encode8(c.x) | (encode8(c.y) << 8) | (encode8(c.z) << 16) | (rk_svo_pack_unorm8(c.w) << 24);
    }
    glm::vec4 unpack(uint32_t w) const
    {
        return glm::vec4(decode[w & 0xFFu], decode[(w >> 8) & 0xFFu], decode[(w >> 16) & 0xFFu], static_cast<float>(w >> 24) / 255.0f);
    }
    static const SrgbTables& get()
    {
        static const SrgbTables t;
        return t;
    }
};

}  // namespace svo_detail

/// estimate_svo_memory: an upper estimate of the builder's peak memory in bytes for this mesh and
/// these options (what SvoBuildOptions::memory_budget is checked against before building), or 0
/// with `st` set when the mesh or options are invalid. Surface voxels are bounded per triangle by
/// its area and perimeter in voxels; solid fill adds the bounding volume of the mesh. Cost:
/// O(triangles).
inline uint64_t estimate_svo_memory(const SvoMesh& mesh, const SvoBuildOptions& opt, SvoStatus& st);

namespace svo_detail {

inline bool resolve_depth(const SvoBuildOptions& opt, float extent, uint32_t& depth, SvoStatus& st)
{
    if (opt.voxel_size != 0.0f) {
        if (!std::isfinite(opt.voxel_size) || !(opt.voxel_size > 0.0f))
            return st.fail(SvoError::invalid_argument, "voxel_size must be 0 (use depth) or finite and > 0");
        int d = 1;
        while (d < static_cast<int>(RK_SVO_MAX_DEPTH) && static_cast<double>(extent) / std::ldexp(1.0, d) > opt.voxel_size) ++d;
        if (static_cast<double>(extent) / std::ldexp(1.0, d) > opt.voxel_size)
        {
            char msg[160];
            std::snprintf(msg, sizeof msg, "voxel_size %g needs more than %u levels for a root of %g", static_cast<double>(opt.voxel_size),
                          RK_SVO_MAX_DEPTH, static_cast<double>(extent));
            return st.fail(SvoError::invalid_argument, msg);
        }
        depth = static_cast<uint32_t>(d);
        return true;
    }
    if (opt.depth < 1 || opt.depth > static_cast<int>(RK_SVO_MAX_DEPTH))
        return st.fail(SvoError::invalid_argument, "depth " + std::to_string(opt.depth) + " is outside 1.." + std::to_string(RK_SVO_MAX_DEPTH));
    depth = static_cast<uint32_t>(opt.depth);
    return true;
}

/// Validates the mesh and options, picks the root cube, snaps the triangles.
inline bool prepare(const SvoMesh& mesh, const SvoBuildOptions& opt, Prepared& P, SvoBuildStats& stats, SvoStatus& st, bool snap)
{
    if (opt.pointer_bits < 4 || opt.pointer_bits > 23)
        return st.fail(SvoError::invalid_argument, "pointer_bits " + std::to_string(opt.pointer_bits) + " is outside 4..23");
    if (opt.attributes & ~(RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL))
        return st.fail(SvoError::invalid_argument, "unknown attribute bits " + std::to_string(opt.attributes));
    if (mesh.triangle_count > 0 && !mesh.positions) return st.fail(SvoError::invalid_argument, "mesh has triangles but no positions");
    if (mesh.triangle_count > 0xFFFFFFFFull) return st.fail(SvoError::too_large, "more than 2^32 triangles");
    P.mesh = &mesh;
    stats.triangles_in = mesh.triangle_count;
    const size_t pstride = mesh.position_stride ? mesh.position_stride : 3 * sizeof(float);
    // Usable triangles: indices in range, finite positions.
    std::vector<uint32_t> usable;
    usable.reserve(mesh.triangle_count);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (size_t t = 0; t < mesh.triangle_count; ++t) {
        bool ok = true, finite = true;
        glm::vec3 p[3];
        for (int k = 0; k < 3 && ok; ++k) {
            const uint64_t i = mesh.indices ? mesh.indices[3 * t + static_cast<size_t>(k)] : 3 * t + static_cast<size_t>(k);
            if (i >= mesh.vertex_count) { ok = false; break; }
            p[k] = P.vertex_attr3(mesh.positions, pstride, static_cast<uint32_t>(i));
            if (!std::isfinite(p[k].x) || !std::isfinite(p[k].y) || !std::isfinite(p[k].z)) finite = false;
        }
        if (!ok) { ++stats.skipped_bad_index; continue; }
        if (!finite) { ++stats.skipped_non_finite; continue; }
        usable.push_back(static_cast<uint32_t>(t));
        for (int k = 0; k < 3; ++k) { lo = glm::min(lo, p[k]); hi = glm::max(hi, p[k]); }
    }
    if (opt.fixed_bounds) {
        if (!(opt.bounds_size > 0.0f) || !std::isfinite(opt.bounds_size) || !std::isfinite(opt.bounds_min.x) ||
            !std::isfinite(opt.bounds_min.y) || !std::isfinite(opt.bounds_min.z))
            return st.fail(SvoError::invalid_argument, "fixed bounds need a finite bounds_min and a finite bounds_size > 0");
        for (int a = 0; a < 3; ++a) P.root_min[a] = opt.bounds_min[a];
        P.root_size = opt.bounds_size;
    } else if (!usable.empty()) {
        const glm::vec3 ext = hi - lo;
        float size = std::max(ext.x, std::max(ext.y, ext.z));
        if (!(size > 0.0f) || !std::isfinite(size)) size = std::max(1.0f, std::fabs(lo.x) * 1e-6f);
        for (int a = 0; a < 3; ++a) P.root_min[a] = (lo[a] + hi[a]) * 0.5f - size * 0.5f;
        // Keep the cube covering the box after the float rounding of the centre.
        for (int a = 0; a < 3; ++a) {
            P.root_min[a] = std::min(P.root_min[a], lo[a]);
            while (P.root_min[a] + size < hi[a]) size = std::nextafter(size, INFINITY);  // grows only: earlier axes stay covered
        }
        P.root_size = size;
    }
    if (usable.empty()) return st.fail(SvoError::empty_mesh, "no usable triangle (" + std::to_string(stats.skipped_bad_index) +
                                                                  " with a bad index, " + std::to_string(stats.skipped_non_finite) +
                                                                  " with a non-finite position, of " + std::to_string(mesh.triangle_count) + ")");
    if (!resolve_depth(opt, P.root_size, P.depth, st)) return false;
    // Materials.
    const size_t nmat = std::max<size_t>(1, mesh.materials ? mesh.material_count : 0);
    if (nmat > 65535) return st.fail(SvoError::too_large, "more than 65535 materials");
    P.materials.assign(nmat, SvoMaterial{});
    P.material_texture.assign(nmat, -1);
    if (mesh.materials)
        for (size_t m = 0; m < mesh.material_count; ++m) {
            P.materials[m] = mesh.materials[m].values;
            const int tex = mesh.materials[m].base_color_texture;
            P.material_texture[m] = (tex >= 0 && static_cast<size_t>(tex) < mesh.texture_count && mesh.uvs) ? tex : -1;
        }
    for (size_t m = 0; m < P.materials.size(); ++m) {
        const SvoMaterial& mv = P.materials[m];
        const bool fin = std::isfinite(mv.base_color.x) && std::isfinite(mv.base_color.y) && std::isfinite(mv.base_color.z) &&
                         std::isfinite(mv.base_color.w) && std::isfinite(mv.reflectance) && std::isfinite(mv.absorption.x) &&
                         std::isfinite(mv.absorption.y) && std::isfinite(mv.absorption.z);
        if (!fin || !(mv.ior > 0.0f) || !std::isfinite(mv.ior))
            return st.fail(SvoError::invalid_argument, "material " + std::to_string(m) + " has a non-finite value or an ior <= 0");
    }
    P.attributes = opt.attributes;
    P.has_normals = mesh.normals != nullptr;
    if (!snap) {
        stats.triangles_used = usable.size();
        return true;
    }
    // Snap to the lattice. Coordinates beyond +-2^40 (far outside fixed bounds) are rejected.
    const int64_t side = int64_t(1) << (P.depth + kSvoSubvoxelBits);
    const double limit = std::ldexp(1.0, 40);
    P.tris.reserve(usable.size());
    for (uint32_t t : usable) {
        svo_detail::Tri tri;
        tri.src = t;
        tri.material = mesh.material_ids ? mesh.material_ids[t] : uint16_t(0);
        if (tri.material >= nmat) tri.material = 0;
        bool far = false;
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 p = P.vertex_attr3(mesh.positions, pstride, P.index(t, k));
            for (int a = 0; a < 3; ++a) {
                const double q = lattice_position(p[a], P.root_min[a], P.root_size, P.depth);
                if (!(std::fabs(q) < limit)) { far = true; break; }
                tri.v[k][a] = std::llround(q);  // = svo_snap_coordinate
            }
        }
        if (far) { ++stats.skipped_outside; continue; }
        bool outside = false;
        for (int a = 0; a < 3; ++a) {
            const int64_t l = std::min(tri.v[0][a], std::min(tri.v[1][a], tri.v[2][a]));
            const int64_t h = std::max(tri.v[0][a], std::max(tri.v[1][a], tri.v[2][a]));
            if (h < 0 || l > side) outside = true;
        }
        if (outside) {
            ++stats.skipped_outside;
            if (opt.fill == SvoFill::solid) P.outside.push_back(tri);
            continue;
        }
        const int64_t e1[3] = {tri.v[1][0] - tri.v[0][0], tri.v[1][1] - tri.v[0][1], tri.v[1][2] - tri.v[0][2]};
        const int64_t e2[3] = {tri.v[2][0] - tri.v[0][0], tri.v[2][1] - tri.v[0][1], tri.v[2][2] - tri.v[0][2]};
        const i128 n0 = (i128)e1[1] * e2[2] - (i128)e1[2] * e2[1];
        const i128 n1 = (i128)e1[2] * e2[0] - (i128)e1[0] * e2[2];
        const i128 n2 = (i128)e1[0] * e2[1] - (i128)e1[1] * e2[0];
        if (n0 == 0 && n1 == 0 && n2 == 0) { ++stats.skipped_degenerate; continue; }
        P.tris.push_back(tri);
    }
    stats.triangles_used = P.tris.size();
    if (P.tris.empty() && P.outside.empty())
        return st.fail(SvoError::empty_mesh, "no usable triangle: " + std::to_string(stats.skipped_degenerate) + " degenerate, " +
                                                 std::to_string(stats.skipped_outside) + " outside the bounds, " +
                                                 std::to_string(stats.skipped_bad_index) + " with a bad index, " +
                                                 std::to_string(stats.skipped_non_finite) + " non-finite, of " +
                                                 std::to_string(mesh.triangle_count));
    return true;
}

/// Bytes per leaf voxel the builder holds at its peak: the Morton-sorted leaves (each chunk's in a
/// vector of its own; 10 % for their headers and the bricks' records), the attribute streams (4 bytes per stream per node, 1.34
/// nodes per voxel on surfaces), the bricks' attribute sums (~80 bytes per 12 voxels) and the
/// structure.
inline double peak_bytes_per_voxel(uint32_t attributes)
{
    return 1.1 * sizeof(Leaf) + 4.0 * 1.34 * static_cast<double>(bitCount(attributes)) + 8.0 + 1.5;
}

/// An upper estimate of the leaf voxels: per triangle, sqrt(3) x its area in voxels (a plane
/// through a grid touches at most that many cells per unit area) plus rims along its perimeter;
/// solid fill adds the mesh's bounding volume.
inline double estimate_voxels(const Prepared& P, const SvoBuildOptions& opt, const SvoMesh& mesh)
{
    const size_t pstride = mesh.position_stride ? mesh.position_stride : 3 * sizeof(float);
    const double vox = static_cast<double>(P.root_size) / std::ldexp(1.0, static_cast<int>(P.depth));
    double voxels = 0;
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    const size_t n = mesh.triangle_count;
    for (size_t t = 0; t < n; ++t) {
        glm::dvec3 p[3];
        bool ok = true;
        for (int k = 0; k < 3; ++k) {
            const uint64_t i = mesh.indices ? mesh.indices[3 * t + static_cast<size_t>(k)] : 3 * t + static_cast<size_t>(k);
            if (i >= mesh.vertex_count) { ok = false; break; }
            p[k] = glm::dvec3(P.vertex_attr3(mesh.positions, pstride, static_cast<uint32_t>(i))) / vox;
            if (!std::isfinite(p[k].x + p[k].y + p[k].z)) ok = false;
        }
        if (!ok) continue;
        const double area = 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
        const double perim = glm::length(p[1] - p[0]) + glm::length(p[2] - p[1]) + glm::length(p[0] - p[2]);
        // sqrt(3) x area: the most cells a plane crosses per unit area; closed boxes add the
        // neighbours touched along the edges (shared by two triangles) and at the corners.
        voxels += std::sqrt(3.0) * area + 1.5 * perim + 8.0;
        for (int k = 0; k < 3; ++k) { lo = glm::min(lo, p[k]); hi = glm::max(hi, p[k]); }
    }
    const double cells = std::ldexp(1.0, 3 * static_cast<int>(P.depth));
    if (opt.fill == SvoFill::solid) {
        const glm::dvec3 e = glm::max(hi - lo + 2.0, glm::dvec3(1.0));
        voxels += e.x * e.y * e.z;
    }
    return std::min(voxels, cells);
}

/// Peak bytes for the estimated voxels; `voxels_out` (may be null) receives the voxel estimate.
inline uint64_t estimate(const Prepared& P, const SvoBuildOptions& opt, const SvoMesh& mesh, double* voxels_out = nullptr)
{
    const size_t n = mesh.triangle_count;
    const double voxels = estimate_voxels(P, opt, mesh);
    if (voxels_out) *voxels_out = voxels;
    double bytes = voxels * peak_bytes_per_voxel(opt.attributes);
    bytes += static_cast<double>(2 * n) * (sizeof(Tri) + 16.0);  // triangles + chunk bins
    const unsigned t = opt.threads > 0 ? static_cast<unsigned>(opt.threads) : std::max(1u, std::thread::hardware_concurrency());
    bytes += static_cast<double>(t) * 32768.0 * (sizeof(Accum) + 4.0);
    for (size_t i = 0; i < mesh.texture_count; ++i)
        bytes += static_cast<double>(mesh.textures[i].width) * mesh.textures[i].height * sizeof(glm::vec4) * 4.0 / 3.0;
    return static_cast<uint64_t>(bytes) + (1u << 20);
}

}  // namespace svo_detail

inline uint64_t estimate_svo_memory(const SvoMesh& mesh, const SvoBuildOptions& opt, SvoStatus& st)
{
    svo_detail::Prepared P;
    SvoBuildStats stats;
    if (!svo_detail::prepare(mesh, opt, P, stats, st, false)) return 0;
    return svo_detail::estimate(P, opt, mesh);
}

namespace svo_detail {

/// 2D clip of a convex polygon (u, v) to the half-plane a u + b v + c >= 0.
inline int clip2(const float (*in)[2], int n, float (*out)[2], float a, float b, float c)
{
    int m = 0;
    for (int i = 0; i < n; ++i) {
        const float* p = in[i];
        const float* q = in[i + 1 < n ? i + 1 : 0];
        const float dp = a * p[0] + b * p[1] + c, dq = a * q[0] + b * q[1] + c;
        if (dp >= 0.0f) { out[m][0] = p[0]; out[m][1] = p[1]; ++m; }
        if ((dp > 0.0f && dq < 0.0f) || (dp < 0.0f && dq > 0.0f)) {
            const float t = dp / (dp - dq);
            out[m][0] = p[0] + (q[0] - p[0]) * t;
            out[m][1] = p[1] + (q[1] - p[1]) * t;
            ++m;
        }
    }
    return m;
}

/// 2D clip of a convex polygon (u, v) to the strip 0 <= f <= 1, f = a u + b v + c, in one pass:
/// the same polygon as clip2 to f >= 0 then to 1 - f >= 0 (a vertex on a boundary is kept, an
/// edge crossing a boundary strictly gets the crossing point), with f evaluated once per vertex.
inline int clip_slab(const float (*in)[2], int n, float (*out)[2], float a, float b, float c)
{
    float f[8];
    for (int i = 0; i < n; ++i) f[i] = a * in[i][0] + b * in[i][1] + c;
    int m = 0;
    auto cross = [&](int i, int j, float level) {
        const float t = (level - f[i]) / (f[j] - f[i]);
        out[m][0] = in[i][0] + (in[j][0] - in[i][0]) * t;
        out[m][1] = in[i][1] + (in[j][1] - in[i][1]) * t;
        ++m;
    };
    for (int i = 0; i < n; ++i) {
        const int j = i + 1 < n ? i + 1 : 0;
        const float fp = f[i], fq = f[j];
        if (fp >= 0.0f && fp <= 1.0f) { out[m][0] = in[i][0]; out[m][1] = in[i][1]; ++m; }
        const bool c0 = (fp < 0.0f && fq > 0.0f) || (fp > 0.0f && fq < 0.0f);
        const bool c1 = (fp < 1.0f && fq > 1.0f) || (fp > 1.0f && fq < 1.0f);
        if (fq > fp) {  // rising: level 0 is met first
            if (c0) cross(i, j, 0.0f);
            if (c1) cross(i, j, 1.0f);
        } else {
            if (c1) cross(i, j, 1.0f);
            if (c0) cross(i, j, 0.0f);
        }
    }
    return m;
}

/// The area of {(x, y) in [0, 1]^2 : 0 <= a x + b y + c <= 1} (|a|, |b| <= 1), in closed form:
/// f = a x + b y + c over the unit square is distributed as the sum of two uniform variables of
/// widths |a| and |b|, whose CDF is piecewise quadratic. The same area as clipping the square to
/// the strip, up to float rounding.
inline float strip_area(float a, float b, float c)
{
    float lo = std::fabs(a), hi = std::fabs(b);
    if (lo > hi) std::swap(lo, hi);
    // The strip's ends above the square's lowest f, each summed from its largest term down, so
    // that tiny slopes are not lost in rounding c first.
    const float drop = std::min(a, 0.0f) + std::min(b, 0.0f);
    const float t1 = (1.0f - c) - drop, t0 = -c - drop;
    if (!(hi > 0.0f)) return t0 <= 0.0f && t1 >= 0.0f ? 1.0f : 0.0f;  // f is constant
    auto cdf = [&](float t) {  // area where f - min(f) <= t
        if (!(t > 0.0f)) return 0.0f;
        if (t >= lo + hi) return 1.0f;
        // (r / lo) (r / hi) / 2, not r^2 / (2 lo hi): lo hi underflows for tiny slopes.
        if (t >= hi) { const float r = lo + hi - t; return 1.0f - 0.5f * (r / lo) * (r / hi); }  // r < lo, so lo > 0
        if (t >= lo) return (t - 0.5f * lo) / hi;
        return 0.5f * (t / lo) * (t / hi);  // t < lo, so lo > 0
    };
    return cdf(t1) - cdf(t0);
}

/// One triangle's attribute evaluation, set up once per (chunk, triangle). The part of the
/// triangle inside a voxel is clipped in the projection onto the plane of the two non-dominant
/// axes: the triangle is clipped to the voxel's column square once per column, then to the strip
/// where the triangle's plane lies within the voxel's extent along the dominant axis; areas scale
/// by |n| / |n_w| back to 3D, barycentrics are an affine function of the projected position.
struct TriFrame {
    const Prepared* P = nullptr;
    const Tri* tri = nullptr;
    int u = 0, v = 1, w = 2;
    double pu[3], pv[3];   // projected vertices, chunk-relative voxel units
    double pa = 0, pb = 0, pc = 0;  // plane: w = pa u + pb v + pc
    double scale = 1;      // 3D area / projected area
    double bu[3], bv[3], bc[3];  // barycentric k = bc[k] + bu[k] u + bv[k] v
    glm::vec3 face{0.0f, 0.0f, 1.0f};
    glm::vec3 vn[3];
    bool has_vn = false;
    bool want_color = true, want_normal = true;  // streams that will be stored
    const Texture* tex = nullptr;
    glm::dvec2 uv[3];
    double texel_per_area = 0;  // texels per unit of 3D area (voxel units)
    glm::vec4 factor{1.0f};
    int64_t col_u = INT64_MIN, col_v = INT64_MIN;
    float sq[8][2];
    int nsq = 0;
    bool col_inside = false;  // the column's square lies inside the projected triangle (sq is the square)

    bool setup(const Prepared& prep, const Tri& t, const double tv[3][3])
    {
        P = &prep;
        tri = &t;
        col_u = col_v = INT64_MIN;
        const glm::dvec3 p0(tv[0][0], tv[0][1], tv[0][2]), p1(tv[1][0], tv[1][1], tv[1][2]), p2(tv[2][0], tv[2][1], tv[2][2]);
        const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
        w = 0;
        for (int k = 1; k < 3; ++k)
            if (std::fabs(n[k]) > std::fabs(n[w])) w = k;
        u = (w + 1) % 3;
        v = (w + 2) % 3;
        if (!(std::fabs(n[w]) > 0.0)) return false;
        for (int k = 0; k < 3; ++k) { pu[k] = tv[k][u]; pv[k] = tv[k][v]; }
        pa = -n[u] / n[w];
        pb = -n[v] / n[w];
        pc = tv[0][w] - pa * pu[0] - pb * pv[0];
        const double nl = glm::length(n);
        scale = nl / std::fabs(n[w]);
        face = glm::vec3(n / nl);
        const double det = (pu[1] - pu[0]) * (pv[2] - pv[0]) - (pu[2] - pu[0]) * (pv[1] - pv[0]);
        // b1 = ((u - u0)(v2 - v0) - (u2 - u0)(v - v0)) / det, b2 = ((u1 - u0)(v - v0) - (u - u0)(v1 - v0)) / det.
        bu[1] = (pv[2] - pv[0]) / det;
        bv[1] = -(pu[2] - pu[0]) / det;
        bc[1] = -(pu[0] * bu[1] + pv[0] * bv[1]);
        bu[2] = -(pv[1] - pv[0]) / det;
        bv[2] = (pu[1] - pu[0]) / det;
        bc[2] = -(pu[0] * bu[2] + pv[0] * bv[2]);
        bu[0] = -bu[1] - bu[2];
        bv[0] = -bv[1] - bv[2];
        bc[0] = 1.0 - bc[1] - bc[2];
        const SvoMesh& m = *P->mesh;
        const int mat = t.material;
        factor = P->materials[static_cast<size_t>(mat)].base_color;
        has_vn = P->has_normals;
        want_color = (P->attributes & RK_SVO_ATTR_COLOR) != 0;
        want_normal = (P->attributes & RK_SVO_ATTR_NORMAL) != 0;
        if (has_vn) {
            const size_t nstride = m.normal_stride ? m.normal_stride : 3 * sizeof(float);
            for (int k = 0; k < 3; ++k) vn[k] = P->vertex_attr3(m.normals, nstride, P->index(t.src, k));
        }
        const int texi = P->material_texture[static_cast<size_t>(mat)];
        tex = texi >= 0 && !P->textures[static_cast<size_t>(texi)].levels.empty() ? &P->textures[static_cast<size_t>(texi)] : nullptr;
        texel_per_area = 0;
        if (tex) {
            const size_t ustride = m.uv_stride ? m.uv_stride : 2 * sizeof(float);
            for (int k = 0; k < 3; ++k) uv[k] = glm::dvec2(P->vertex_attr2(m.uvs, ustride, P->index(t.src, k)));
            const glm::dvec2 d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
            texel_per_area = std::fabs(d1.x * d2.y - d1.y * d2.x) * tex->levels[0].w * tex->levels[0].h / nl;
        }
        return true;
    }

    /// The shading normal at the polygon's centroid (gu, gv): interpolated normals are linear in the
    /// barycentrics, so this is their area-weighted mean over the polygon (normalised once); the
    /// face normal without vertex normals (or when the normal stream is not stored).
    glm::vec3 normal_at(double gu, double gv) const
    {
        if (!(has_vn && want_normal)) return face;
        glm::vec3 s(0.0f);
        for (int k = 0; k < 3; ++k) s += vn[k] * static_cast<float>(bc[k] + bu[k] * gu + bv[k] * gv);
        const float l = glm::length(s);
        return l > 1e-30f && std::isfinite(l) ? s / l : face;
    }

    /// contribute() for a voxel whose full column square the triangle covers inside the voxel
    /// (untextured colour): the same sums as the general path with the polygon = the unit square.
    void contribute_full(int cu, int cv, Accum& acc) const
    {
        const glm::vec3 nrm = normal_at(cu + 0.5, cv + 0.5);
        acc.add_area(static_cast<float>(scale), factor, nrm, tri->material);
    }

    glm::dvec2 uv_at(double gu, double gv) const
    {
        glm::dvec2 r(0.0);
        for (int k = 0; k < 3; ++k) r += uv[k] * (bc[k] + bu[k] * gu + bv[k] * gv);
        return r;
    }

    /// Adds the contribution to voxel `cell` (chunk-local integer coordinates).
    void contribute(const int cell[3], Accum& acc)
    {
        const int cu = cell[u], cv = cell[v], cw = cell[w];
        if (cu != col_u || cv != col_v) {
            col_u = cu;
            col_v = cv;
            // Inside: every corner of the square on the inner side of every edge (barycentrics >= 0,
            // in double): then triangle ∩ square is the square itself and needs no clipping.
            bool cuts[3] = {false, false, false};  // edge k has a corner of the square outside
            for (int c = 0; c < 4; ++c) {
                const double qu = cu + double(c & 1), qv = cv + double(c >> 1);
                for (int k = 0; k < 3; ++k) cuts[k] = cuts[k] || !(bc[k] + bu[k] * qu + bv[k] * qv >= 0.0);
            }
            const int ncuts = int(cuts[0]) + int(cuts[1]) + int(cuts[2]);
            col_inside = ncuts == 0;
            static const float unit[4][2] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
            if (col_inside) {
                std::memcpy(sq, unit, sizeof unit);
                nsq = 4;
            } else if (ncuts < 3) {
                // One or two edges cross the square: clip the square to their half-planes.
                float b1[8][2];
                const float(*src)[2] = unit;
                int n = 4, done = 0;
                for (int k = 0; k < 3; ++k) {
                    if (!cuts[k]) continue;
                    float(*dst)[2] = ++done == ncuts ? sq : b1;
                    n = clip2(src, n, dst, static_cast<float>(bu[k]), static_cast<float>(bv[k]),
                              static_cast<float>(bc[k] + bu[k] * cu + bv[k] * cv));
                    src = dst;
                }
                nsq = n;
            } else {
                // All three: the triangle is small against the square; clip it to the square.
                float tri2[3][2], b1[8][2], b2[8][2];
                for (int k = 0; k < 3; ++k) {
                    tri2[k][0] = static_cast<float>(pu[k] - cu);
                    tri2[k][1] = static_cast<float>(pv[k] - cv);
                }
                int n = clip2(tri2, 3, b1, 1.0f, 0.0f, 0.0f);
                n = clip2(b1, n, b2, -1.0f, 0.0f, 1.0f);
                n = clip2(b2, n, b1, 0.0f, 1.0f, 0.0f);
                n = clip2(b1, n, sq, 0.0f, -1.0f, 1.0f);
                nsq = n;
            }
        }
        // Strip 0 <= pa u' + pb v' + c0 <= 1 in column-local coordinates.
        const float a = static_cast<float>(pa), b = static_cast<float>(pb);
        const float c0 = static_cast<float>(pa * cu + pb * cv + pc - cw);
        if (col_inside && !(tex && want_color) && c0 + std::min(a, 0.0f) + std::min(b, 0.0f) >= 0.0f &&
            c0 + std::max(a, 0.0f) + std::max(b, 0.0f) <= 1.0f) {
            // The whole square lies in the strip: the triangle crosses the voxel from side to side
            // over its full column square. Area 1 (projected), centroid at the square's centre.
            contribute_full(cu, cv, acc);
            return;
        }
        if (!(tex && want_color) && !(has_vn && want_normal)) {
            // Colour and normal are constant over the triangle: only the area is needed.
            float ar;
            if (col_inside) {
                ar = strip_area(a, b, c0);
            } else {
                float poly[16][2];
                const int n = clip_slab(sq, nsq, poly, a, b, c0);
                float twice = 0.0f;
                for (int k = 1; k + 1 < n; ++k)
                    twice += std::fabs((poly[k][0] - poly[0][0]) * (poly[k + 1][1] - poly[0][1]) -
                                       (poly[k + 1][0] - poly[0][0]) * (poly[k][1] - poly[0][1]));
                ar = 0.5f * twice;
            }
            if (ar > 0.0f) acc.add_area(static_cast<float>(ar * scale), factor, face, tri->material);
            else acc.add_touch(factor, face, tri->material);
            return;
        }
        float poly[16][2];
        const int n = clip_slab(sq, nsq, poly, a, b, c0);
        // Fan: projected areas, centroid.
        float area2f = 0.0f, cxf = 0.0f, cyf = 0.0f;  // the polygon lies in the unit square: float suffices
        glm::vec4 csum(0.0f);
        for (int k = 1; k + 1 < n; ++k) {
            const float ar = 0.5f * std::fabs((poly[k][0] - poly[0][0]) * (poly[k + 1][1] - poly[0][1]) -
                                              (poly[k + 1][0] - poly[0][0]) * (poly[k][1] - poly[0][1]));
            if (!(ar > 0.0f)) continue;
            cxf += (poly[0][0] + poly[k][0] + poly[k + 1][0]) * ar;
            cyf += (poly[0][1] + poly[k][1] + poly[k + 1][1]) * ar;
            area2f += ar;
            if (tex && want_color) {
                // Split the piece into 4^s congruent sub-triangles until each spans about a texel
                // (s <= 4), sampling each at its centroid with the mip level of its footprint: an
                // area average that stays inside the polygon. Texel extent of a triangle of area A ~ sqrt(2A).
                const double ar3 = ar * scale;
                const double foot = std::sqrt(std::max(0.0, 2.0 * ar3 * texel_per_area));
                const int sub = foot > 1.0 ? std::min(4, static_cast<int>(std::ceil(std::log2(foot)))) : 0;
                const int g = 1 << sub;
                const double sub_foot = foot / g;
                const glm::dvec2 t0 = uv_at(cu + static_cast<double>(poly[0][0]), cv + static_cast<double>(poly[0][1]));
                const glm::dvec2 du = (uv_at(cu + static_cast<double>(poly[k][0]), cv + static_cast<double>(poly[k][1])) - t0) / static_cast<double>(g);
                const glm::dvec2 dv = (uv_at(cu + static_cast<double>(poly[k + 1][0]), cv + static_cast<double>(poly[k + 1][1])) - t0) / static_cast<double>(g);
                glm::vec4 acc_s(0.0f);
                for (int i = 0; i < g; ++i)
                    for (int j = 0; i + j < g; ++j) {
                        const glm::dvec2 up = t0 + du * (i + 1.0 / 3.0) + dv * (j + 1.0 / 3.0);
                        acc_s += tex->sample(up.x, up.y, sub_foot);
                        if (i + j + 1 < g) {
                            const glm::dvec2 dn = t0 + du * (i + 2.0 / 3.0) + dv * (j + 2.0 / 3.0);
                            acc_s += tex->sample(dn.x, dn.y, sub_foot);
                        }
                    }
                csum += acc_s * (ar / static_cast<float>(g * g));
            }
        }
        const double area2 = area2f;
        double cx = static_cast<double>(cxf) / 3.0, cy = static_cast<double>(cyf) / 3.0;
        const bool touch = !(area2 > 0.0);
        if (touch) {
            // Touching only (an edge or a corner on the box): one sample at the touching points' mean.
            cx = cy = 0.0;
            for (int k = 0; k < n; ++k) { cx += poly[k][0]; cy += poly[k][1]; }
            if (n > 0) { cx /= n; cy /= n; }
        } else {
            cx /= area2;
            cy /= area2;
        }
        const double gu = cu + cx, gv = cv + cy;
        glm::vec4 col = factor;
        if (tex && want_color) col *= touch ? tex->sample(uv_at(gu, gv).x, uv_at(gu, gv).y, 0.0) : csum / static_cast<float>(area2);
        const glm::vec3 nrm = normal_at(gu, gv);
        const float total = static_cast<float>(area2 * scale);
        if (!touch) acc.add_area(total, col, nrm, tri->material);
        else acc.add_touch(col, nrm, tri->material);
    }
};

/// Voxelises the triangles of one chunk (cells [org, org + 2^cs)^3) into sorted leaves.
struct ChunkWork {
    std::vector<Accum> acc;        // by local Morton index
    std::vector<uint64_t> touched; // bitmap of used accumulators
};

/// Calls f(cell) for every cell of size 2^shift lattice units (cell c spans [c 2^shift,
/// (c+1) 2^shift] per axis) within [lo, hi] (cells, inclusive) whose closed box the closed
/// triangle v overlaps: columns along the triangle's dominant axis, three edge axes per column,
/// the plane and six edge axes per cell (skipped in columns inside the triangle's shadow, where they
/// cannot separate), all exact (the same 13 axes as svo_triangle_box_overlap). A box's projection
/// on an axis is the projection of its corner plus a constant per cell size, and steps by a
/// constant from cell to cell along a column, so each per-cell test is an i128 add and two compares.
template <class F>
inline void for_each_overlap(const int64_t (&v)[3][3], uint32_t shift, const int64_t lo_in[3], const int64_t hi_in[3], F&& f)
{
    const int64_t S = int64_t(1) << shift;
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        const int64_t mn = std::min(v[0][a], std::min(v[1][a], v[2][a]));
        const int64_t mx = std::max(v[0][a], std::max(v[1][a], v[2][a]));
        // Cell c touches [mn, mx] iff c S <= mx and (c + 1) S >= mn (arithmetic shifts floor).
        lo[a] = std::max<int64_t>(lo_in[a], ((mn + (S - 1)) >> shift) - 1);
        hi[a] = std::min<int64_t>(hi_in[a], mx >> shift);
        if (lo[a] > hi[a]) return;
    }
    const SatTriangle T(v);
    const i128 (&n)[3] = T.n;
    const double nd[3] = {static_cast<double>(n[0]), static_cast<double>(n[1]), static_cast<double>(n[2])};
    int w = 0;
    for (int a = 1; a < 3; ++a)
        if (std::fabs(nd[a]) > std::fabs(nd[w])) w = a;
    const int u = (w + 1) % 3, vv = (w + 2) % 3;
    // Per axis: the box [b, b + S] projects to [p(b) + olo, p(b) + ohi] with p(b) = au b[ka] +
    // aw b[kb]; it overlaps the triangle's interval iff tlo - ohi <= p(b) <= thi - olo, and lies
    // inside it iff tlo - olo <= p(b) <= thi - ohi.
    struct Lim { i128 lo, hi, in_lo, in_hi; int64_t cu, cv, cw; };  // cu/cv/cw: p's coefficient along u, vv, w (|.| < 2^41)
    auto limits = [&](const SatTriangle::Axis& A) {
        const i128 olo = (i128)std::min<int64_t>(A.au, 0) * S + (i128)std::min<int64_t>(A.aw, 0) * S;
        const i128 ohi = (i128)std::max<int64_t>(A.au, 0) * S + (i128)std::max<int64_t>(A.aw, 0) * S;
        auto coef = [&](int X) { return (A.ka == X ? A.au : 0) + (A.kb == X ? A.aw : 0); };  // ka != kb: one term
        return Lim{A.tlo - ohi, A.thi - olo, A.tlo - olo, A.thi - ohi, coef(u), coef(vv), coef(w)};
    };
    // Column axes (e_i x unit_w: no w component) and cell axes (e_i x unit_u, e_i x unit_vv).
    Lim col[3], cell[6];
    for (int i = 0; i < 3; ++i) {
        col[i] = limits(T.ax[w][i]);
        cell[i] = limits(T.ax[u][i]);
        cell[3 + i] = limits(T.ax[vv][i]);
    }
    // The plane: the box's n-projection is [n.b + plo, n.b + phi]; it touches d iff
    // d - phi <= n.b <= d - plo.
    i128 plo = 0, phi = 0;
    for (int a = 0; a < 3; ++a) {
        const i128 ns = n[a] * S;
        (ns < 0 ? plo : phi) += ns;
    }
    const i128 plane_lo = T.d - phi, plane_hi = T.d - plo;
    const i128 nstep = n[w] * S;
    const double inv_s = 1.0 / static_cast<double>(S);
    const double dd = static_cast<double>(T.d), inv_nw = 1.0 / nd[w];
    for (int64_t cu = lo[u]; cu <= hi[u]; ++cu) {
        const int64_t bu = cu * S;
        for (int64_t cv = lo[vv]; cv <= hi[vv]; ++cv) {
            const int64_t bv = cv * S;
            // The three edge axes perpendicular to the dominant axis depend on the column only. When
            // the column's square lies inside all three of their intervals, the square lies inside the
            // triangle's shadow along w (the strips between each edge and the opposite vertex meet in
            // the triangle): then a cell overlaps the triangle iff it overlaps its plane, and the six
            // per-cell edge axes are skipped.
            bool inside = true, out = false;
            for (int i = 0; i < 3; ++i) {
                const i128 p = (i128)col[i].cu * bu + (i128)col[i].cv * bv;
                out = out || p < col[i].lo || p > col[i].hi;
                inside = inside && p >= col[i].in_lo && p <= col[i].in_hi;
            }
            if (out) continue;
            // The plane's w range over the column's square (double), plus one cell of margin; the
            // exact plane test below decides.
            double wlo = INFINITY, whi = -INFINITY;
            for (int cc = 0; cc < 4; ++cc) {
                const double pu = static_cast<double>(bu + ((cc & 1) ? S : 0));
                const double pv = static_cast<double>(bv + ((cc & 2) ? S : 0));
                const double pw = (dd - nd[u] * pu - nd[vv] * pv) * inv_nw;
                wlo = std::min(wlo, pw);
                whi = std::max(whi, pw);
            }
            // Cell cw can touch the plane over this column iff cw S <= whi and (cw + 1) S >= wlo;
            // a relative slack of 2^-20 cell covers the double rounding (the exact test decides).
            int64_t k0 = lo[w], k1 = hi[w];
            if (std::isfinite(wlo) && std::isfinite(whi) && std::fabs(wlo) < 1e15 && std::fabs(whi) < 1e15) {
                const double slack = 1e-6 + (std::fabs(wlo) + std::fabs(whi)) * inv_s * 1e-12;
                const double a0 = wlo * inv_s - slack, a1 = whi * inv_s + slack;  // |a| < 2^50: exact floor/ceil via int64
                int64_t c0 = static_cast<int64_t>(a0), c1 = static_cast<int64_t>(a1);
                if (static_cast<double>(c0) < a0) ++c0;  // ceil
                if (static_cast<double>(c1) > a1) --c1;  // floor
                k0 = std::max<int64_t>(k0, c0 - 1);
                k1 = std::min<int64_t>(k1, c1);
            }
            if (k0 > k1) continue;
            const int64_t bw0 = k0 * S;
            i128 nb = n[u] * bu + n[vv] * bv + n[w] * bw0;
            i128 eb[6] = {0, 0, 0, 0, 0, 0};
            if (!inside)
                for (int i = 0; i < 6; ++i) eb[i] = (i128)cell[i].cu * bu + (i128)cell[i].cv * bv + (i128)cell[i].cw * bw0;
            for (int64_t cw = k0; cw <= k1; ++cw, nb += nstep) {
                bool ok = nb >= plane_lo && nb <= plane_hi;
                if (!inside) {
                    for (int i = 0; i < 6; ++i) {
                        ok = ok && eb[i] >= cell[i].lo && eb[i] <= cell[i].hi;
                        eb[i] += (i128)cell[i].cw * S;
                    }
                }
                if (!ok) continue;
                int64_t c[3];
                c[u] = cu;
                c[vv] = cv;
                c[w] = cw;
                f(c);
            }
        }
    }
}

/// Voxelises the triangles of one chunk (cells [org, org + 2^cs)^3) into Morton-sorted leaves.
inline void voxelize_chunk(const Prepared& P, const uint32_t* tri_ids, size_t ntri, const uint32_t org[3], uint32_t cs,
                           ChunkWork& W, std::vector<Leaf>& out)
{
    const uint32_t side = 1u << cs;
    const size_t cells = size_t(1) << (3 * cs);
    if (W.acc.size() < cells) {
        W.acc.assign(cells, Accum{});
        W.touched.assign((cells + 63) / 64, 0u);
    }
    const double inv_s = 1.0 / static_cast<double>(int64_t(1) << kSvoSubvoxelBits);
    const bool attrs = P.attributes != 0;
    static const struct Morton5 {  // chunk-local Morton keys (cs <= 5)
        uint32_t m[32];
        Morton5() { for (uint32_t i = 0; i < 32; ++i) m[i] = static_cast<uint32_t>(spread3(i)); }
    } morton5;
    const int64_t lo[3] = {org[0], org[1], org[2]};
    const int64_t hi[3] = {int64_t(org[0]) + side - 1, int64_t(org[1]) + side - 1, int64_t(org[2]) + side - 1};
    for (size_t ti = 0; ti < ntri; ++ti) {
        const Tri& tri = P.tris[tri_ids[ti]];
        double tv[3][3];  // voxel units relative to the chunk origin
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) tv[k][a] = static_cast<double>(tri.v[k][a]) * inv_s - static_cast<double>(lo[a]);
        TriFrame F;
        const bool frame = attrs && F.setup(P, tri, tv);
        for_each_overlap(tri.v, kSvoSubvoxelBits, lo, hi, [&](const int64_t c[3]) {
            const int cell[3] = {static_cast<int>(c[0] - lo[0]), static_cast<int>(c[1] - lo[1]), static_cast<int>(c[2] - lo[2])};
            const uint32_t li = morton5.m[cell[0]] | (morton5.m[cell[1]] << 1) | (morton5.m[cell[2]] << 2);
            Accum& A = W.acc[li];
            W.touched[li >> 6] |= uint64_t(1) << (li & 63u);
            if (frame) {
                F.contribute(cell, A);
            } else {
                // No attributes (or a triangle too thin for the double-precision frame): occupancy
                // only, with the material's colour as a touch sample.
                A.add_touch(attrs ? P.materials[tri.material].base_color : glm::vec4(0.0f), glm::vec3(0.0f), tri.material);
            }
        });
    }
    // Emit in Morton order: the chunk's key, then the local Morton index (bitmap scan).
    const SrgbTables& srgb = SrgbTables::get();
    const bool want_normal = (P.attributes & RK_SVO_ATTR_NORMAL) != 0;
    const uint64_t chunk_key = morton(org[0] >> cs, org[1] >> cs, org[2] >> cs) << (3 * cs);
    size_t count = 0;
    for (size_t wi = 0; wi < (cells + 63) / 64; ++wi) count += static_cast<size_t>(__builtin_popcountll(W.touched[wi]));
    out.reserve(out.size() + count);
    for (size_t wi = 0; wi < (cells + 63) / 64; ++wi) {
        for (uint64_t bits = W.touched[wi]; bits; bits &= bits - 1) {
            const uint32_t li = static_cast<uint32_t>(wi * 64 + static_cast<size_t>(__builtin_ctzll(bits)));
            Accum& A = W.acc[li];
            Leaf l;
            l.key = chunk_key | li;
            if (A.area > 0.0f) {
                l.weight = A.area;
                l.color = srgb.pack(A.col / A.area);
                // Opposite faces in one voxel (both sides of a thin part) cancel: then the normal of
                // the largest contribution, not whatever direction the rounding leaves.
                l.normal = want_normal ? rk_svo_pack_normal(glm::length(A.nrm) > 1e-3f * A.area ? A.nrm : A.best_nrm) : 0u;
            } else {
                l.weight = 0.0f;
                l.color = srgb.pack(A.col / std::max(A.touch, 1.0f));
                l.normal = want_normal ? rk_svo_pack_normal(A.nrm) : 0u;
            }
            l.material = A.best_mat;
            out.push_back(l);
            A = Accum{};
        }
        W.touched[wi] = 0;
    }
}

}  // namespace svo_detail

/// build_svo: voxelises `mesh` and packs it (see the top of this file for the exact definition and
/// docs/svo-format.md for the layout). Returns false with `st` set when the options are invalid,
/// the mesh has no usable triangle, the memory estimate or the measured use exceeds
/// opt.memory_budget, the tree exceeds the format's limits, or progress() cancelled. `stats` (may
/// be null) receives counts of skipped triangles, voxels, memory and times.
inline bool build_svo(const SvoMesh& mesh, const SvoBuildOptions& opt, SvoTree& out, SvoStatus& st, SvoBuildStats* stats_out = nullptr);

namespace svo_detail {

/// Tracks the builder's big allocations against the budget.
struct Memory {
    uint64_t live = 0, peak = 0, budget = 0;
    bool add(uint64_t b, SvoStatus& st, const char* what)
    {
        live += b;
        peak = std::max(peak, live);
        if (budget && live > budget)
            return st.fail(SvoError::budget_exceeded, std::string("memory budget of ") + std::to_string(budget >> 20) +
                                                          " MiB exceeded while " + what + " (" + std::to_string(live >> 20) + " MiB in use)");
        return true;
    }
    void sub(uint64_t b) { live -= std::min(live, b); }
};

/// Solid fill: voxels whose centre is inside by +x crossing parity, minus the surface ones.
inline bool solid_fill(const Prepared& P, const SvoBuildOptions& opt, const std::vector<Leaf>& surface, std::vector<Leaf>& interior,
                       Memory& mem, SvoStatus& st)
{
    const int64_t S = int64_t(1) << kSvoSubvoxelBits;
    const uint32_t side = 1u << P.depth;
    // Crossings per row (j, k): gathered per triangle over the rows its yz box covers.
    struct Cross { uint64_t row; double x; uint16_t mat; };
    const size_t ntris = P.tris.size() + P.outside.size();
    std::vector<std::vector<Cross>> per_tri(ntris);
    std::atomic<uint64_t> total{0};
    parallel_for(opt, ntris, [&](size_t t) {
        const Tri& tri = t < P.tris.size() ? P.tris[t] : P.outside[t - P.tris.size()];
        int64_t lo[3], hi[3];
        for (int a = 1; a < 3; ++a) {
            const int64_t mn = std::min(tri.v[0][a], std::min(tri.v[1][a], tri.v[2][a]));
            const int64_t mx = std::max(tri.v[0][a], std::max(tri.v[1][a], tri.v[2][a]));
            // Rows whose centre (j + 1/2) S lies in [mn, mx].
            lo[a] = std::max<int64_t>(0, (mn - S / 2 + S - 1) >= 0 ? (mn - S / 2 + S - 1) / S : 0);
            hi[a] = std::min<int64_t>(side - 1, (mx - S / 2) >= 0 ? (mx - S / 2) / S : -1);
        }
        std::vector<Cross>& c = per_tri[t];
        for (int64_t j = lo[1]; j <= hi[1]; ++j)
            for (int64_t k = lo[2]; k <= hi[2]; ++k) {
                double x;
                if (svo_centre_ray_crosses(tri.v, j * S + S / 2, k * S + S / 2, x))
                    c.push_back({static_cast<uint64_t>(j) | (static_cast<uint64_t>(k) << 32), x, tri.material});
            }
        total += c.size();
    });
    if (!mem.add(total * sizeof(Cross), st, "collecting crossings for the solid fill")) return false;
    std::vector<Cross> all;
    all.reserve(total);
    for (auto& v : per_tri) { all.insert(all.end(), v.begin(), v.end()); std::vector<Cross>().swap(v); }
    std::sort(all.begin(), all.end(), [](const Cross& a, const Cross& b) { return a.row != b.row ? a.row < b.row : a.x < b.x; });
    // Inside voxels: centre x in (x_2m, x_2m+1) for the sorted crossings of a row, i.e. an odd
    // number of crossings ahead.
    std::vector<Leaf> cand;
    uint64_t cand_bytes = 0;
    for (size_t i = 0; i < all.size();) {
        size_t e = i;
        while (e < all.size() && all[e].row == all[i].row) ++e;
        const uint32_t j = static_cast<uint32_t>(all[i].row & 0xFFFFFFFFu), k = static_cast<uint32_t>(all[i].row >> 32);
        const size_t n = e - i;
        // Crossings x_0 < ... < x_{n-1}: a centre in (x_{m-1}, x_m) has n - m crossings ahead, so
        // it is inside iff n - m is odd (x_{-1} = -inf). Centres are (x + 1/2) S.
        const double hs = static_cast<double>(S) / 2, sd = static_cast<double>(S);
        for (size_t m = (n % 2 == 1) ? 0 : 1; m < n; m += 2) {
            const double xa = m == 0 ? -INFINITY : all[i + m - 1].x, xb = all[i + m].x;
            const int64_t i0 = m == 0 ? 0 : std::max<int64_t>(0, static_cast<int64_t>(std::floor((xa - hs) / sd)) + 1);
            const int64_t i1 = std::min<int64_t>(static_cast<int64_t>(side) - 1, static_cast<int64_t>(std::ceil((xb - hs) / sd)) - 1);
            const uint16_t mat = all[i + (m == 0 ? m : m - 1)].mat;  // the surface that opens the span
            for (int64_t x = i0; x <= i1; ++x) {
                Leaf l;
                l.key = morton(static_cast<uint32_t>(x), j, k);
                l.weight = 0.0f;
                l.color = rk_svo_pack_color(P.materials[mat].base_color);
                l.normal = rk_svo_pack_normal(glm::vec3(0.0f));
                l.material = mat;
                cand.push_back(l);
                if (cand.size() * sizeof(Leaf) > cand_bytes + (64u << 20)) {
                    if (!mem.add(cand.size() * sizeof(Leaf) - cand_bytes, st, "filling the interior")) return false;
                    cand_bytes = cand.size() * sizeof(Leaf);
                }
            }
        }
        i = e;
    }
    mem.sub(total * sizeof(Cross));
    std::vector<Cross>().swap(all);
    std::sort(cand.begin(), cand.end(), [](const Leaf& a, const Leaf& b) { return a.key < b.key; });
    interior.clear();
    size_t s = 0;
    for (const Leaf& l : cand) {
        while (s < surface.size() && surface[s].key < l.key) ++s;
        if (s < surface.size() && surface[s].key == l.key) continue;
        interior.push_back(l);
    }
    mem.sub(cand_bytes);
    return true;
}

}  // namespace svo_detail
}  // namespace raykit

#include "raykit/detail/svo_pack.hpp"
