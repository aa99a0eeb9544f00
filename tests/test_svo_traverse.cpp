// rk_svo_trace (shaders/raykit/svo_traverse.glsl, C++ build) against the float64 brute-force
// references of tests/reference/svo_dda_ref.hpp (a dense-grid DDA and a voxel-list slab test,
// written apart from the traversal): over 10^6 rays of every adversarial family of
// svo_trace_rays.hpp and rays aimed at voxels on random trees (depths 1..8, far pointers),
// voxelised meshes (surface and solid, a mesh far from the origin), depth-16 trees and grazing
// rays over a depth-16 strip, each hit must be
//   - an occupied voxel (or non-empty node at max_level) that the exact ray touches,
//   - entered where the exact ray enters it: the hit point on the node's surface within kTol root
//     sizes (plus 8 float ULPs of the origin's distance for far origins: its rounding and t's),
//   - no later than the first voxel the exact ray passes through by more than kTol (zero missed
//     voxels) and no earlier than the first voxel it touches,
// a miss is allowed only when the exact ray passes through no voxel by more than kTol, the face
// normal is the entry face, the attribute index is the builder's, and the iteration bound is
// never reached. rk_svo_trace must also read no attribute word (ReadsNoAttributeWords). The LOD
// build is tested in parts/test_svo_traverse/lod.cpp, linked into this same executable with
// RK_SVO_TRAVERSE_LOD=1.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "raykit/svo_build.hpp"
#include "raykit/svo_traverse.hpp"
#include "reference/svo_dda_ref.hpp"
#include "reference/svo_meshes.hpp"
#include "svo_test_pack.hpp"
#include "svo_trace_rays.hpp"

using namespace raykit;

namespace {

/// Position tolerance in root sizes: float32 rounding of positions in [1, 2) (2^-23 each) through
/// a handful of operations; the measured worst case is printed by every test.
constexpr double kTol = 2e-6;

struct Stats {
    long rays = 0, hits = 0, misses = 0, bad = 0;
    uint32_t max_iter = 0;
    double worst_pos = 0.0;  ///< worst distance of a hit point from its node's surface (root sizes), near origins
    std::map<int, long> per_family_bad;
};

rkref::DdaRay to_ref(const svotrace::Ray& r)
{
    return rkref::DdaRay{glm::dvec3(r.origin), glm::dvec3(r.dir), double(r.t_max)};
}

/// The axis through whose face the exact ray enters `cell` (at `level`): the largest slab entry t.
int entry_axis(glm::ivec3 cell, uint32_t level, const SvoTree& t, const svotrace::Ray& r)
{
    const double cs = double(t.root_size) / double(1u << level);
    int best = 0;
    double best_t = -1e300;
    for (int a = 0; a < 3; ++a) {
        if (r.dir[a] == 0.0f) continue;
        const double lo = double(t.root_min[a]) + cs * cell[a];
        const double ta = (lo - double(r.origin[a])) / double(r.dir[a]), tb = (lo + cs - double(r.origin[a])) / double(r.dir[a]);
        if (std::min(ta, tb) > best_t) {
            best_t = std::min(ta, tb);
            best = a;
        }
    }
    return best;
}

/// Checks one traced ray against the oracle's answer `ref` (computed on the occupancy of `level`).
/// `occupied(cell)` says whether the reported node exists. Records failures in `st`.
/// Whether axis `ax` is a face through which the exact ray enters the box [lo, lo + cs]^3: its
/// slab entry is the last one, up to the conditioning of near-ties (an edge or corner entry has
/// several entry faces; a position tolerance e is a t tolerance of e / |dir_a| on axis a).
bool entry_face_ok(glm::dvec3 lo, double cs, glm::dvec3 o, glm::dvec3 d, int ax, double e)
{
    double te[3];
    for (int a = 0; a < 3; ++a)
        te[a] = d[a] == 0.0 ? -1e300 : (d[a] > 0.0 ? lo[a] - o[a] : lo[a] + cs - o[a]) / d[a];
    int best = 0;
    for (int a = 1; a < 3; ++a)
        if (te[a] > te[best]) best = a;
    if (ax == best) return true;
    if (d[ax] == 0.0) return false;
    return te[ax] >= te[best] - 2.0 * e / std::abs(d[ax]) - 2.0 * e / std::abs(d[best]);
}

/// The position tolerance of a ray in root sizes: kTol, plus 8 float ULPs of the origin's distance
/// from the root's centre (the rounding of a far origin, documented in svo_traverse.glsl).
double ray_tol(const svotrace::Ray& r, const SvoTree& t)
{
    const double rs = double(t.root_size);
    return kTol + 8.0 * 0x1p-24 * glm::length(glm::dvec3(r.origin) - (glm::dvec3(t.root_min) + 0.5 * rs)) / rs;
}

template <class Occupied>
void check_ray(const char* what, const svotrace::Ray& ray, const rk_svo_trace_hit& h, const rkref::DdaHit& ref,
               const SvoTree& t, uint32_t level, Occupied&& occupied, Stats& st)
{
    ++st.rays;
    st.max_iter = std::max(st.max_iter, h.iterations);
    const glm::dvec3 o(ray.origin), d(ray.dir);
    const double dl = glm::length(d);
    const double rs = double(t.root_size);
    const glm::dvec3 rmin(t.root_min);
    const double dist = glm::length(o - (rmin + 0.5 * rs)) / rs;
    const double tol = ray_tol(ray, t);
    std::string why;
    bool ok = std::isfinite(h.t) && h.iterations < rk_svo_trace_iteration_bound(svo_trace_tree(t));
    if (!ok) why = "non-finite t or iteration bound reached";
    if (ok && h.hit) {
        ++st.hits;
        const double cs = rs / double(1u << h.level);
        const glm::dvec3 lo = rmin + cs * glm::dvec3(h.cell);
        const glm::dvec3 p = o + double(h.t) * d;
        const double sd = svotrace::surface_distance(p, lo, cs, h.t == 0.0f) / rs;
        if (dist < 10.0) st.worst_pos = std::max(st.worst_pos, sd);
        const double n_dot_d = glm::dot(glm::dvec3(h.normal), d);
        const int ax = h.normal.x != 0.0f ? 0 : (h.normal.y != 0.0f ? 1 : 2);
        // The entry face: the hit point is on the plane of the face the normal names.
        if (h.level != level) why = "wrong level";
        else if (!occupied(h.cell)) why = "empty node reported";
        else if (sd > tol) why = "hit point off the node's surface";
        else if (!(glm::length(glm::dvec3(h.normal)) == 1.0 && n_dot_d <= 0.0)) why = "normal not facing the ray";
        else if (h.t > 0.0f && !entry_face_ok(lo, cs, o, d, ax, tol * rs)) why = "normal not an entry face";
        else if (!rkref::ray_touches_cell(rmin, rs, int(level), glm::ivec3(h.cell), to_ref(ray), tol * rs, nullptr))
            why = "hit a node the exact ray does not come near";
        // (Together, the two checks above say the hit is no earlier than the exact ray can reach
        // an occupied node: its hit point is on the surface of one the ray touches within tol.)
        // t comparisons with another voxel are made along that voxel's entry axis: a ray at a
        // shallow angle to a face turns a position rounding of e into a t error of e / |dir_axis|
        // (conditioning, not error). The same voxel needs no comparison: the surface check holds.
        else if (ref.solid && glm::ivec3(h.cell) != ref.cell_solid &&
                 (double(h.t) - ref.t_solid) * std::abs(d[entry_axis(ref.cell_solid, level, t, ray)]) / rs >
                     tol + 8.0 * 0x1p-24 * ref.t_solid * dl / rs)
            why = "missed a voxel";
        ok = why.empty();
    } else if (ok) {
        ++st.misses;
        if (ref.solid) {
            ok = false;
            why = "missed a voxel the ray passes through";
        }
    }
    if (!ok) {
        ++st.per_family_bad[ray.family];
        if (st.bad < 6) {
            std::ostringstream s;
            s.precision(9);
            s << what << " [" << svotrace::family_names[ray.family] << "] " << why << ": o=(" << o.x << "," << o.y << ","
              << o.z << ") d=(" << d.x << "," << d.y << "," << d.z << ") t_max=" << ray.t_max << " | trace hit=" << h.hit
              << " t=" << h.t << " L" << h.level << " (" << h.cell.x << "," << h.cell.y << "," << h.cell.z << ") n=("
              << h.normal.x << "," << h.normal.y << "," << h.normal.z << ") it=" << h.iterations
              << " | ref touch=" << ref.touch << " t=" << ref.t_touch << " (" << ref.cell_touch.x << ","
              << ref.cell_touch.y << "," << ref.cell_touch.z << ") solid=" << ref.solid << " t=" << ref.t_solid << " ("
              << ref.cell_solid.x << "," << ref.cell_solid.y << "," << ref.cell_solid.z << ")";
            ADD_FAILURE() << s.str();
        }
        ++st.bad;
    }
}

void report(const char* what, const Stats& st)
{
    std::printf("[trace] %-32s %8ld rays (%ld hits, %ld misses): %ld failures, worst hit-point offset %.2e root (origins within 10 root sizes), "
                "max %u iterations\n",
                what, st.rays, st.hits, st.misses, st.bad, st.worst_pos, st.max_iter);
    for (const auto& kv : st.per_family_bad)
        std::printf("        %ld failures in family '%s'\n", kv.second, svotrace::family_names[kv.first]);
}

/// Occupancy of a tree at `level` (<= depth) as a dense grid, from the packed words.
rkref::DdaGrid grid_of(const SvoTree& t, uint32_t level)
{
    rkref::DdaGrid g(static_cast<int>(level));
    const uint32_t sh = t.depth - level;
    svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t) { g.set(int(c.x >> sh), int(c.y >> sh), int(c.z >> sh)); });
    return g;
}

/// Traces `rays` through `t` (stopping at `max_level`) and checks each against the dense DDA.
Stats run_dense(const char* what, const SvoTree& t, const std::vector<svotrace::Ray>& rays, uint32_t max_level = ~0u,
                bool check_attr = true)
{
    const rk_svo_tree tree = svo_trace_tree(t, max_level);
    const uint32_t level = tree.max_level;
    const rkref::DdaGrid g = grid_of(t, level);
    std::map<uint64_t, uint64_t> attr_of;  // Morton key -> attribute index (full depth)
    if (check_attr && level == t.depth)
        svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t a) { attr_of[svotest::morton3(c)] = a; });
    const std::vector<uint32_t> words = t.gpu_words();
    Stats st;
    const double rs = double(t.root_size);
    long attr_bad = 0;
    for (const svotrace::Ray& r : rays) {
        const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, r.origin, r.dir, r.t_max, glm::vec2(0.0f));
        const double tol = ray_tol(r, t);
        const rkref::DdaHit ref = rkref::dda_first_hit(g, glm::dvec3(t.root_min), rs, to_ref(r), 4.0 * tol * rs, tol * rs);
        check_ray(what, r, h, ref, t, level, [&](glm::uvec3 c) { return g.get(int(c.x), int(c.y), int(c.z)); }, st);
        if (h.hit && !attr_of.empty()) {
            const auto it = attr_of.find(svotest::morton3(h.cell));
            if (it == attr_of.end() || it->second != rk_svo_trace_attr(words.data(), tree, h)) ++attr_bad;
        }
    }
    report(what, st);
    EXPECT_EQ(st.bad, 0) << what;
    EXPECT_EQ(attr_bad, 0) << what << ": attribute index differs from svo_for_each_voxel's";
    return st;
}

}  // namespace

/// For parts/test_svo_traverse/lod.cpp: this translation unit's (RK_SVO_TRAVERSE_LOD=0) answer for a
/// ray, so that test can show the two builds coexist with their own behaviour.
bool svo_trace_default_build(const SvoTree& t, glm::vec3 origin, glm::vec3 dir, float t_max, glm::vec2 cone, uint32_t* level)
{
    static_assert(RK_SVO_TRAVERSE_LOD == 0, "the default build");
    const std::vector<uint32_t> words = t.gpu_words();
    const rk_svo_trace_hit h = rk_svo_trace(words.data(), svo_trace_tree(t), origin, dir, t_max, cone);
    *level = h.level;
    return h.hit;
}

TEST(SvoTrace, RandomTreesAgainstDenseDda)
{
    // Depths 1..8, one cell to half full (at most 12,000 cells), near and forced-far pointers: 40
    // trees, 25k rays each (10^6), a fifth of them aimed at voxels.
    long total = 0;
    uint32_t max_iter = 0;
    for (uint32_t depth = 1; depth <= 8; ++depth) {
        const size_t side3 = size_t(1) << (3 * depth);
        const size_t counts[] = {1, std::max<size_t>(1, side3 / 200), std::max<size_t>(1, side3 / 20), side3 / 4, side3 / 2};
        for (int k = 0; k < 5; ++k) {
            const size_t n = std::min<size_t>(counts[k], 12000);
            svotest::PackOptions po;
            po.pointer_bits = (k & 1) ? 4 : 23;
            SvoTree t = svotest::pack_cells(depth, svotest::random_cells(depth, n, 31 * depth + k), po);
            t.root_min = glm::vec3(-2.0f, 0.5f, 8.0f);
            t.root_size = 4.0f;
            // The adversarial families, and rays aimed at voxels (random rays miss a sparse tree).
            std::vector<svotrace::Ray> rays = svotrace::make_rays(20000, t.root_min, t.root_size, depth, 1000 * depth + k);
            std::vector<glm::ivec3> cells;
            svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t) { cells.push_back(glm::ivec3(c)); });
            const auto aimed = svotrace::aimed_rays(cells, t.root_min, t.root_size, depth, 5000, 77 * depth + k);
            rays.insert(rays.end(), aimed.begin(), aimed.end());
            char what[64];
            std::snprintf(what, sizeof what, "random d%u %zu cells pb%u", depth, n, po.pointer_bits);
            const Stats st = run_dense(what, t, rays);
            // At least half the aimed rays hit (the random ones alone can do so on dense trees).
            const rk_svo_tree tr = svo_trace_tree(t);
            const std::vector<uint32_t> words = t.gpu_words();
            long aimed_hits = 0;
            for (const svotrace::Ray& r : aimed)
                aimed_hits += rk_svo_trace(words.data(), tr, r.origin, r.dir, r.t_max, glm::vec2(0.0f)).hit ? 1 : 0;
            EXPECT_GT(aimed_hits, 2500) << what;
            // Empty space is crossed at the coarsest level that is empty: through a one-voxel tree
            // a ray takes a few iterations per level (measured at most 26 at depth 8), never a
            // walk over leaf cells (a DDA would take up to 3 x 2^depth).
            if (n == 1) {
                EXPECT_LE(st.max_iter, 4u * depth + 2u) << what;
            }
            total += st.rays;
            max_iter = std::max(max_iter, st.max_iter);
        }
    }
    EXPECT_GE(total, 1000000);
    std::printf("[trace] random trees: %ld rays, max %u iterations (bound 16 x 2^depth)\n", total, max_iter);
}

TEST(SvoTrace, VoxelisedMeshesAgainstDenseDda)
{
    struct Build { const char* name; SvoMeshData mesh; int depth; SvoFill fill; };
    std::vector<Build> builds;
    builds.push_back({"torus d8 surface", rkmesh::torus(48, 24), 8, SvoFill::surface});
    builds.push_back({"menger d7 solid", rkmesh::menger_sponge(2), 7, SvoFill::solid});
    builds.push_back({"figure d9 surface", rkmesh::figure(), 9, SvoFill::surface});
    builds.push_back({"icosphere d8 solid", rkmesh::icosphere(3), 8, SvoFill::solid});
    // Far from the origin: a torus centred at (3e4, -2e4, 1e4).
    builds.push_back({"far torus d8", rkmesh::transformed(rkmesh::torus(32, 16), 1.0, glm::dvec3(3e4, -2e4, 1e4)), 8,
                      SvoFill::surface});
    for (Build& b : builds) {
        SvoTree t;
        std::string why;
        ASSERT_TRUE(svotrace::build_colour_tree(b.mesh, b.depth, b.fill, t, why)) << b.name << ": " << why;
        run_dense(b.name, t, svotrace::make_rays(40000, t.root_min, t.root_size, t.depth, 17));
    }
}

TEST(SvoTrace, MaxLevelStopsAtCoarseNodes)
{
    SvoTree t;
    std::string why;
    ASSERT_TRUE(svotrace::build_colour_tree(rkmesh::figure(), 9, SvoFill::surface, t, why)) << why;
    for (uint32_t level : {0u, 1u, 3u, 6u, 7u, 8u}) {
        char what[48];
        std::snprintf(what, sizeof what, "figure d9 max_level %u", level);
        run_dense(what, t, svotrace::make_rays(20000, t.root_min, t.root_size, level, 3 + level), level);
    }
}

TEST(SvoTrace, Depth16AgainstBruteForce)
{
    // Random sparse trees and a voxelised sphere at depth 16; the voxel-list slab test is the oracle.
    std::vector<std::pair<std::string, SvoTree>> trees;
    for (uint64_t seed : {1u, 2u}) {
        SvoTree t = svotest::pack_cells(16, svotest::random_cells(16, 2500, seed));
        t.root_min = glm::vec3(-1024.0f, -1024.0f, -1024.0f);
        t.root_size = 2048.0f;
        trees.emplace_back("random d16 seed " + std::to_string(seed), std::move(t));
    }
    {
        SvoBuildOptions opt;
        opt.depth = 16;
        opt.fixed_bounds = true;
        opt.bounds_min = glm::vec3(-2048.0f + 0.37f);
        opt.bounds_size = 4096.0f;
        opt.attributes = RK_SVO_ATTR_COLOR;
        SvoTree t;
        SvoStatus s;
        const SvoMeshData mesh = rkmesh::icosphere(1);
        ASSERT_TRUE(build_svo(mesh.view(), opt, t, s)) << s.message;
        trees.emplace_back("icosphere d16", std::move(t));
    }
    for (auto& [name, t] : trees) {
        std::vector<glm::ivec3> cells;
        svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t) { cells.push_back(glm::ivec3(c)); });
        const rk_svo_tree tree = svo_trace_tree(t);
        const std::vector<uint32_t> words = t.gpu_words();
        const double rs = double(t.root_size);
        // Rays aimed at voxels (a random ray through a 2^48-cell grid misses a few thousand
        // voxels), plus the adversarial families.
        std::vector<svotrace::Ray> rays = svotrace::make_rays(6000, t.root_min, t.root_size, 16, 5);
        const std::vector<svotrace::Ray> aimed = svotrace::aimed_rays(cells, t.root_min, t.root_size, 16, 6000, 9);
        rays.insert(rays.end(), aimed.begin(), aimed.end());
        Stats st;
        for (const svotrace::Ray& r : rays) {
            const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, r.origin, r.dir, r.t_max, glm::vec2(0.0f));
            const rkref::DdaHit ref =
                rkref::brute_first_hit(cells, 16, glm::dvec3(t.root_min), rs, to_ref(r), 4.0 * ray_tol(r, t) * rs,
                                       ray_tol(r, t) * rs);
            check_ray(name.c_str(), r, h, ref, t, 16,
                      [&](glm::uvec3 c) { return std::find(cells.begin(), cells.end(), glm::ivec3(c)) != cells.end(); }, st);
        }
        report(name.c_str(), st);
        EXPECT_EQ(st.bad, 0) << name;
        EXPECT_GT(st.hits, 5000) << name;
    }
}

TEST(SvoTrace, GrazingRaysStayUnderTheIterationBound)
{
    // The costliest rays: sliding just above a flat wall of voxels at depth 11, through every brick
    // along it, and along the wall's diagonal.
    SvoBuildOptions opt;
    opt.depth = 11;
    opt.attributes = 0;
    SvoTree t;
    SvoStatus s;
    const SvoMeshData wall = rkmesh::axis_quad(2, 0.0, glm::dvec2(-1.0), glm::dvec2(1.0));
    opt.fixed_bounds = true;
    opt.bounds_min = glm::vec3(-1.0f);
    opt.bounds_size = 2.0f;
    ASSERT_TRUE(build_svo(wall.view(), opt, t, s)) << s.message;
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    const float cell = 2.0f / 2048.0f;
    uint32_t worst = 0;
    long hits = 0;
    for (int i = 0; i < 2000; ++i) {
        const float z = cell * (1.0f + 0.001f * float(i % 7));  // just above the voxels at z in [-cell, cell]
        const float a = 0.0001f * float(i);
        const glm::vec3 o(-1.5f, -1.5f + 0.001f * float(i % 100), z);
        const glm::vec3 d(std::cos(a), std::sin(a) + 1.0f, (i % 2) ? 0.0f : -1e-7f);
        const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, o, d, std::numeric_limits<float>::max(), glm::vec2(0.0f));
        worst = std::max(worst, h.iterations);
        hits += h.hit;
        ASSERT_LT(h.iterations, rk_svo_trace_iteration_bound(tree)) << "ray " << i;
    }
    std::printf("[trace] grazing rays over a depth-11 wall: max %u iterations (bound %u), %ld hits\n", worst,
                rk_svo_trace_iteration_bound(tree), hits);
    EXPECT_GT(worst, 2000u * 3u);  // about 4 per leaf cell along the diagonal: the expensive case
}

TEST(SvoTrace, GrazingRaysAtDepth16AgainstBruteForce)
{
    // A strip of wall at depth 16 (2^16 cells long, 2 wide), rays sliding just above it along its
    // length: 2 iterations per leaf cell, 131,000 in all, eight times a fixed bound of 16,384 (which
    // left holes from depth 14). The default bound, 16 x 2^depth, must let every one finish, and its
    // hits must be the brute force's.
    SvoBuildOptions opt;
    opt.depth = 16;
    opt.attributes = 0;
    opt.fixed_bounds = true;
    opt.bounds_min = glm::vec3(-1.0f);
    opt.bounds_size = 2.0f;
    const double cell = 2.0 / 65536.0;
    const SvoMeshData strip = rkmesh::axis_quad(2, 0.0, glm::dvec2(-1.0, -cell), glm::dvec2(1.0, cell));
    SvoTree t;
    SvoStatus s;
    ASSERT_TRUE(build_svo(strip.view(), opt, t, s)) << s.message;
    const rk_svo_tree tree = svo_trace_tree(t);
    EXPECT_EQ(rk_svo_trace_iteration_bound(tree), 16u << 16u);
    const std::vector<uint32_t> words = t.gpu_words();
    std::vector<glm::ivec3> cells;
    svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t) { cells.push_back(glm::ivec3(c)); });
    ASSERT_GT(cells.size(), 65536u * 2u);
    Stats st;
    uint32_t worst = 0;
    const float fc = float(cell);
    for (int i = 0; i < 160; ++i) {
        // Just above the strip's top (z = cell), sinking by 0 to ~2 cells over its length, so that
        // some rays land far along it and the rest pass over all of it; some run along x exactly.
        const float z = fc * (1.0f + 0.002f * float(i % 5));
        const float sink = (i % 4 == 0) ? 0.0f : -fc * 0.5f * float(i % 8) / 2.5f;
        const glm::vec3 o(-1.25f, fc * (float(i % 7) - 3.0f) * 0.3f, z);
        const glm::vec3 d(1.0f, (i % 3 == 0) ? 0.0f : 1e-7f * float(i % 5), sink);
        const svotrace::Ray r{o, d, std::numeric_limits<float>::max(), 0};
        const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, o, d, r.t_max, glm::vec2(0.0f));
        worst = std::max(worst, h.iterations);
        const rkref::DdaHit ref =
            rkref::brute_first_hit(cells, 16, glm::dvec3(t.root_min), double(t.root_size), to_ref(r),
                                   4.0 * ray_tol(r, t) * double(t.root_size), ray_tol(r, t) * double(t.root_size));
        check_ray("strip d16", r, h, ref, t, 16, [&](glm::uvec3 c) {
            return std::find(cells.begin(), cells.end(), glm::ivec3(c)) != cells.end();
        }, st);
    }
    report("grazing strip d16", st);
    std::printf("[trace] grazing rays over a depth-16 strip: max %u iterations (bound %u)\n", worst,
                rk_svo_trace_iteration_bound(tree));
    EXPECT_EQ(st.bad, 0);
    EXPECT_GT(worst, 100000u);  // the long slides the old fixed bound cut short
    EXPECT_GT(st.hits, 40);
    EXPECT_LT(st.hits, 150);  // and rays that pass over the whole strip
}

TEST(SvoTrace, NoNanForHostileInputs)
{
    SvoTree t = svotest::pack_cells(6, svotest::random_cells(6, 4000, 3));
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    const float big = std::numeric_limits<float>::max();
    const float vals[] = {0.0f, -0.0f, 1e-45f, -1e-45f, 1e-38f, 1.0f, -1.0f, 0.5f, 3.0f, 1e30f, -1e30f, big, -big, 2.5f};
    long n = 0, hits = 0;
    for (float ox : vals)
        for (float oy : {0.5f, 2.0f, -1e30f})
            for (float dx : vals)
                for (float dy : vals)
                    for (float tm : {0.0f, -1.0f, 1.0f, big}) {
                        const glm::vec3 o(ox, oy, 2.5f), d(dx, dy, 0.25f);
                        const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, o, d, tm, glm::vec2(0.0f));
                        ++n;
                        hits += h.hit;
                        ASSERT_TRUE(std::isfinite(h.t) && std::isfinite(h.normal.x) && std::isfinite(h.normal.y) &&
                                    std::isfinite(h.normal.z))
                            << ox << " " << oy << " " << dx << " " << dy << " " << tm;
                        ASSERT_LT(h.iterations, rk_svo_trace_iteration_bound(tree));
                        if (tm < 0.0f) {
                            ASSERT_FALSE(h.hit);
                        }
                    }
    // A zero direction misses; so does a degenerate tree.
    EXPECT_FALSE(rk_svo_trace(words.data(), tree, glm::vec3(2.0f), glm::vec3(0.0f), big, glm::vec2(0.0f)).hit);
    rk_svo_tree bad = tree;
    bad.root_size = 0.0f;
    EXPECT_FALSE(rk_svo_trace(words.data(), bad, glm::vec3(-5.0f), glm::vec3(1.0f), big, glm::vec2(0.0f)).hit);
    bad = tree;
    bad.depth = 21;
    EXPECT_FALSE(rk_svo_trace(words.data(), bad, glm::vec3(-5.0f), glm::vec3(1.0f), big, glm::vec2(0.0f)).hit);
    std::printf("[trace] %ld hostile inputs, %ld hits, all outputs finite\n", n, hits);
    EXPECT_GT(hits, 0);
}

TEST(SvoTrace, StopsSoonAfterTMax)
{
    // A ray whose t_max ends before its voxel (early termination against a depth buffer, a shadow
    // ray to a point light) misses, and stops within a few iterations of passing t_max instead of
    // walking on to the root's exit: it walks the full ray's path up to t_max, then at most 3
    // advances to its parent's exit, where the t_max test stops it (the full ray may have found its
    // voxel 1 iteration after that point). So at most 2 iterations more than the full ray.
    SvoTree t;
    std::string why;
    ASSERT_TRUE(svotrace::build_colour_tree(rkmesh::torus(48, 24), 9, SvoFill::surface, t, why)) << why;
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    long rays = 0, worst_extra = -1000;
    double full = 0.0, early = 0.0;
    for (const svotrace::Ray& r : svotrace::make_rays(20000, t.root_min, t.root_size, t.depth, 8)) {
        const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, r.origin, r.dir, r.t_max, glm::vec2(0.0f));
        if (!h.hit || !(h.t > 0.0f) || r.family == 9) continue;
        for (float f : {0.25f, 0.9f, 0.999f}) {
            const rk_svo_trace_hit e = rk_svo_trace(words.data(), tree, r.origin, r.dir, h.t * f, glm::vec2(0.0f));
            if (e.hit) continue;  // (a lattice tie may still enter the voxel's face before t_max)
            ++rays;
            worst_extra = std::max(worst_extra, long(e.iterations) - long(h.iterations));
            full += h.iterations;
            early += e.iterations;
        }
    }
    std::printf("[trace] t_max before the hit: %ld rays, %.0f%% of the full rays' iterations, at most %ld more than the "
                "full ray\n", rays, 100.0 * early / full, worst_extra);
    EXPECT_GT(rays, 5000);
    EXPECT_LE(worst_extra, 2);
    EXPECT_LT(early, 0.9 * full);
}

TEST(SvoTrace, ReadsNoAttributeWords)
{
    // rk_svo_trace reads geometry only: with every brick_base word (where attribute indices come
    // from) overwritten, each field of each answer is the same, while rk_svo_trace_attr, which
    // reads them, changes. (The attribute streams themselves are other buffers it never sees.)
    SvoTree t;
    std::string why;
    ASSERT_TRUE(svotrace::build_colour_tree(rkmesh::figure(), 9, SvoFill::surface, t, why)) << why;
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    std::vector<uint32_t> poisoned = words;
    ASSERT_LT(tree.brick_base_word, poisoned.size());
    for (size_t i = tree.brick_base_word; i < poisoned.size(); ++i) poisoned[i] = 0x7F00FF00u ^ uint32_t(i * 2654435761u);
    long hits = 0, attr_changed = 0;
    for (const svotrace::Ray& r : svotrace::make_rays(20000, t.root_min, t.root_size, t.depth, 41)) {
        const rk_svo_trace_hit a = rk_svo_trace(words.data(), tree, r.origin, r.dir, r.t_max, glm::vec2(0.0f));
        const rk_svo_trace_hit b = rk_svo_trace(poisoned.data(), tree, r.origin, r.dir, r.t_max, glm::vec2(0.0f));
        ASSERT_EQ(a.hit, b.hit);
        ASSERT_EQ(std::memcmp(&a.t, &b.t, sizeof a.t), 0);
        ASSERT_TRUE(a.level == b.level && a.cell == b.cell && a.normal == b.normal && a.node == b.node &&
                    a.brick_bit == b.brick_bit && a.brick_mask == b.brick_mask && a.iterations == b.iterations);
        if (!a.hit) continue;
        ++hits;
        attr_changed += rk_svo_trace_attr(words.data(), tree, a) != rk_svo_trace_attr(poisoned.data(), tree, b);
    }
    std::printf("[trace] brick_base words overwritten: %ld hits, all answers the same; %ld attribute indices changed\n",
                hits, attr_changed);
    EXPECT_GT(hits, 2000);
    EXPECT_GT(attr_changed, hits / 2);
}

TEST(SvoTrace, ShaderDefaultsMatchTheHeader)
{
    // svo_traverse.hpp names its namespace from the macro defaults before including the .glsl; the
    // shader's own defaults must be the same values.
    std::ifstream f(std::string(RAYKIT_SHADER_DIR) + "/raykit/svo_traverse.glsl");
    ASSERT_TRUE(f.good());
    std::stringstream ss;
    ss << f.rdbuf();
    const std::string src = ss.str();
    EXPECT_NE(src.find("#define RK_SVO_TRAVERSE_LOD 0\n"), std::string::npos);
    EXPECT_NE(src.find("#define RK_SVO_TRAVERSE_MAX_ITER 0\n"), std::string::npos);
    static_assert(RK_SVO_TRAVERSE_LOD == 0 && RK_SVO_TRAVERSE_MAX_ITER == 0, "this translation unit uses the defaults");
}
