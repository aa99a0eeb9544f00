// Voxelisation tests of raykit/svo_build.hpp against the brute-force oracle of
// tests/reference/svo_ref.hpp (written apart from the builder): the exact voxel sets, not "close".
// Surface at depths 1..7 on every mesh of tests/reference/svo_meshes.hpp, split-plane quads,
// slivers, degenerate and invalid triangles, meshes far from the origin, fixed bounds that clip,
// depth 16, the public overlap predicate on adversarial pairs, watertightness (flood fill, DDA) at
// depths 5..8, and solid fill.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "raykit/svo_build.hpp"
#include "raykit/svo_file.hpp"
#include "raykit/svo_traverse.hpp"
#include "reference/svo_meshes.hpp"
#include "reference/svo_ref.hpp"

using namespace raykit;
using ref_svo::i64;

namespace {

struct Built {
    bool ok = false;
    SvoStatus st;
    SvoTree tree;
    SvoBuildStats stats;
    std::vector<std::uint64_t> voxels;  // sorted ref_svo keys
};

SvoBuildOptions options(int depth, SvoFill fill = SvoFill::surface)
{
    SvoBuildOptions o;
    o.depth = depth;
    o.fill = fill;
    o.attributes = 0;
    return o;
}

Built build(const SvoMeshData& m, const SvoBuildOptions& o)
{
    Built b;
    b.ok = build_svo(m.view(), o, b.tree, b.st, &b.stats);
    if (b.ok) {
        svo_for_each_voxel(b.tree, [&](glm::uvec3 c, std::uint64_t) { b.voxels.push_back(ref_svo::key(c.x, c.y, c.z)); });
        std::sort(b.voxels.begin(), b.voxels.end());
    }
    return b;
}

ref_svo::Lattice lattice_of(const SvoTree& t) { return ref_svo::make_lattice(t.root_min, t.root_size, static_cast<int>(t.depth)); }

std::string tri_str(const ref_svo::ITri& t)
{
    std::ostringstream s;
    s << "{";
    for (int k = 0; k < 3; ++k) s << (k ? ", " : "") << "(" << t.v[k][0] << "," << t.v[k][1] << "," << t.v[k][2] << ")";
    s << "}";
    return s.str();
}

/// Equal sorted sets; otherwise counts, and the first few voxels in either difference with the
/// snapped triangles near them (a reproducer: lattice triangle + voxel).
::testing::AssertionResult same_voxels(const std::vector<std::uint64_t>& got, const std::vector<std::uint64_t>& want,
                                       const ref_svo::Snapped& s, const std::string& what)
{
    if (got == want) return ::testing::AssertionSuccess();
    std::vector<std::uint64_t> extra, missing;
    std::set_difference(got.begin(), got.end(), want.begin(), want.end(), std::back_inserter(extra));
    std::set_difference(want.begin(), want.end(), got.begin(), got.end(), std::back_inserter(missing));
    std::ostringstream o;
    o << what << ": builder " << got.size() << " voxels, oracle " << want.size() << "; " << extra.size()
      << " only in builder, " << missing.size() << " only in oracle";
    auto show = [&](const std::vector<std::uint64_t>& v, const char* label) {
        for (std::size_t n = 0; n < v.size() && n < 4; ++n) {
            const glm::ivec3 c = ref_svo::unkey(v[n]);
            o << "\n  " << label << " voxel (" << c.x << "," << c.y << "," << c.z << ")";
            const i64 lo[3] = {c.x * ref_svo::kSub, c.y * ref_svo::kSub, c.z * ref_svo::kSub};
            const i64 hi[3] = {lo[0] + ref_svo::kSub, lo[1] + ref_svo::kSub, lo[2] + ref_svo::kSub};
            int shown = 0;
            for (const auto& t : s.tris) {
                bool near = true;
                for (int a = 0; a < 3 && near; ++a)
                    near = std::min({t.v[0][a], t.v[1][a], t.v[2][a]}) <= hi[a] + ref_svo::kSub &&
                           std::max({t.v[0][a], t.v[1][a], t.v[2][a]}) >= lo[a] - ref_svo::kSub;
                if (!near || shown >= 3) continue;
                ++shown;
                o << "\n    tri " << tri_str(t) << " sat=" << ref_svo::tri_box_sat(t.v, lo, hi)
                  << " lp=" << ref_svo::tri_box_lp(t.v, lo, hi);
            }
        }
    };
    show(extra, "builder-only");
    show(missing, "oracle-only");
    return ::testing::AssertionFailure() << o.str();
}

/// Builds `m` and compares its surface voxels with the oracle's (on the tree's own root cube).
void expect_surface_matches(const SvoMeshData& m, const SvoBuildOptions& o, const std::string& what, Built* keep = nullptr)
{
    Built b = build(m, o);
    ASSERT_TRUE(b.ok) << what << ": " << b.st.message;
    const ref_svo::Snapped s = ref_svo::snap_mesh(m, lattice_of(b.tree));
    const auto want = ref_svo::surface_voxels(s, static_cast<int>(b.tree.depth));
    EXPECT_TRUE(same_voxels(b.voxels, want, s, what));
    EXPECT_EQ(b.tree.voxel_count, b.voxels.size()) << what;
    EXPECT_EQ(b.stats.surface_voxels, want.size()) << what;
    EXPECT_EQ(b.stats.triangles_used + b.stats.skipped_outside, s.tris.size()) << what;
    if (!o.fixed_bounds) {
        EXPECT_EQ(b.stats.skipped_outside, 0u) << what;
    }
    EXPECT_EQ(b.stats.skipped_degenerate, s.degenerate) << what;
    if (keep) *keep = std::move(b);
}

struct NamedMesh {
    std::string name;
    SvoMeshData mesh;
};

std::vector<NamedMesh> all_meshes()
{
    using glm::dvec3;
    std::vector<NamedMesh> v;
    v.push_back({"uv_sphere(24,12)", rkmesh::uv_sphere(24, 12)});
    v.push_back({"icosphere(2)", rkmesh::icosphere(2, 0.8, dvec3(0.1, -0.2, 0.3))});
    v.push_back({"torus(24,12)", rkmesh::torus(24, 12, 1.0, 0.35)});
    v.push_back({"box", rkmesh::box(dvec3(0.1, 0.2, 0.3), dvec3(0.9, 0.7, 0.8))});
    v.push_back({"box rotated", rkmesh::box(dvec3(-0.4, -0.3, -0.2), dvec3(0.5, 0.3, 0.25), dvec3(0.3, 0.5, 0.7))});
    v.push_back({"thin_wall x", rkmesh::thin_wall(1.0, 1e-3, 0)});
    v.push_back({"thin_wall z", rkmesh::thin_wall(1.0, 1e-5, 2, dvec3(0.3, 0.1, 0.0))});
    v.push_back({"menger(2)", rkmesh::menger_sponge(2)});
    v.push_back({"axis_quad x", rkmesh::axis_quad(0, 0.25, {-0.5, -0.5}, {0.5, 0.5})});
    v.push_back({"slivers", rkmesh::slivers(60, 11)});
    v.push_back({"random_soup", rkmesh::random_soup(150, 3)});
    v.push_back({"textured_quad", rkmesh::textured_quad()});
    return v;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The oracle itself: the two exact overlap methods agree, and known cases come out right.

TEST(SvoOracle, OverlapMethodsAgreeAndKnownCases)
{
    // Box [0,4]^3.
    const i64 lo[3] = {0, 0, 0}, hi[3] = {4, 4, 4};
    auto both = [&](std::initializer_list<i64> c) {
        i64 v[3][3];
        auto it = c.begin();
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) v[k][a] = *it++;
        const bool s = ref_svo::tri_box_sat(v, lo, hi), l = ref_svo::tri_box_lp(v, lo, hi);
        EXPECT_EQ(s, l);
        return s;
    };
    EXPECT_TRUE(both({4, 4, 4, 9, 4, 4, 4, 9, 4}));      // vertex on a corner
    EXPECT_FALSE(both({5, 5, 5, 9, 5, 5, 5, 9, 5}));     // one unit beyond
    EXPECT_TRUE(both({-3, 2, 4, 9, 2, 4, 3, 9, 4}));     // lying on the face z = 4
    EXPECT_FALSE(both({-3, 2, 5, 9, 2, 5, 3, 9, 5}));    // parallel to it, one unit above
    EXPECT_TRUE(both({6, 0, 0, 0, 6, 0, 0, 0, 6}));      // plane x+y+z = 6 cuts the box
    EXPECT_TRUE(both({12, 0, 0, 0, 12, 0, 0, 0, 12}));   // x+y+z = 12: touches the corner (4,4,4)
    EXPECT_FALSE(both({13, 0, 0, 0, 13, 0, 0, 0, 13}));  // x+y+z = 13: misses
    EXPECT_TRUE(both({8, -1, 2, -1, 8, 2, 20, 20, 2}));  // edge x+y = 7 crosses the box
    EXPECT_TRUE(both({8, 0, 2, 0, 8, 2, 20, 20, 2}));    // edge x+y = 8 touches the edge at (4,4)
    EXPECT_FALSE(both({9, 0, 2, 0, 9, 2, 20, 20, 2}));   // edge x+y = 9 misses
    // The plane passes through the box but the triangle does not reach it (needs an edge axis).
    EXPECT_FALSE(both({5, -2, 2, 9, -2, 2, 5, 3, 7}));
    EXPECT_TRUE(both({4, -2, 2, 9, -2, 2, 4, 3, 7}));

    // Random small-integer pairs: the methods agree everywhere, and both outcomes are common.
    rkmesh::Rng rng(42);
    long agree = 0, yes = 0;
    for (int n = 0; n < 30000; ++n) {
        i64 v[3][3], blo[3], bhi[3];
        for (int a = 0; a < 3; ++a) {
            blo[a] = static_cast<i64>(rng.next() % 5) - 2;
            bhi[a] = blo[a] + 1 + static_cast<i64>(rng.next() % 3);
        }
        for (auto& p : v)
            for (auto& x : p) x = static_cast<i64>(rng.next() % 13) - 5;
        const bool s = ref_svo::tri_box_sat(v, blo, bhi);
        agree += s == ref_svo::tri_box_lp(v, blo, bhi);
        yes += s;
    }
    EXPECT_EQ(agree, 30000);
    EXPECT_GT(yes, 3000);
    EXPECT_LT(yes, 27000);

    // The double prefilter of the voxeliser changes nothing.
    const ref_svo::Lattice L = ref_svo::make_lattice(glm::vec3(-1.0f), 2.0f, 5);
    for (const auto& nm : all_meshes()) {
        const auto s = ref_svo::snap_mesh(nm.mesh, L);
        EXPECT_EQ(ref_svo::surface_voxels(s, 5, true), ref_svo::surface_voxels(s, 5, false)) << nm.name;
    }
}

TEST(SvoMeshes, ClosedOutwardAndCounted)
{
    const double pi = rkmesh::kPi;
    struct C {
        const char* name;
        SvoMeshData m;
        std::size_t tris;
        double volume, tol;
    };
    const C cases[] = {
        {"uv_sphere", rkmesh::uv_sphere(64, 32, 1.0), rkmesh::uv_sphere_triangles(64, 32), 4.0 / 3.0 * pi, 0.02},
        {"icosphere", rkmesh::icosphere(4, 2.0), rkmesh::icosphere_triangles(4), 4.0 / 3.0 * pi * 8.0, 0.01},
        {"torus", rkmesh::torus(64, 32, 1.0, 0.3), rkmesh::torus_triangles(64, 32), 2.0 * pi * pi * 1.0 * 0.09, 0.01},
        {"box", rkmesh::box({0, 0, 0}, {1, 2, 3}, {0.4, 0.2, 0.1}), 12, 6.0, 1e-5},
        {"thin_wall", rkmesh::thin_wall(2.0, 0.01, 1), 12, 0.04, 1e-4},
        {"menger1", rkmesh::menger_sponge(1), rkmesh::menger_triangles(1), 20.0 / 27.0, 1e-5},
        {"menger2", rkmesh::menger_sponge(2), rkmesh::menger_triangles(2), 400.0 / 729.0, 1e-5},
        {"menger3", rkmesh::menger_sponge(3), rkmesh::menger_triangles(3), 8000.0 / 19683.0, 1e-5},
    };
    for (const auto& c : cases) {
        EXPECT_TRUE(rkmesh::edges_paired(c.m)) << c.name;
        EXPECT_EQ(rkmesh::triangle_count(c.m), c.tris) << c.name;
        EXPECT_NEAR(rkmesh::signed_volume(c.m) / c.volume, 1.0, c.tol) << c.name;
    }
    EXPECT_EQ(rkmesh::menger_triangles(0), 12u);
    EXPECT_EQ(rkmesh::menger_triangles(1), 20u * 12u - 4u * 24u);  // 20 cubes, 24 shared faces
    EXPECT_EQ(rkmesh::icosphere_triangles(3), 1280u);
    EXPECT_FALSE(rkmesh::edges_paired(rkmesh::axis_quad(0, 0.0, {0, 0}, {1, 1})));
    // Transform helper: exact offset in double, then float.
    const auto far = rkmesh::transformed(rkmesh::icosphere(1), 1.0, {1e5, 0.0, 0.0});
    EXPECT_EQ(far.positions[0].x, static_cast<float>(static_cast<double>(rkmesh::icosphere(1).positions[0].x) + 1e5));
}

// ---------------------------------------------------------------------------------------------
// Surface voxels equal the oracle's.

TEST(SvoVoxelize, EveryMeshDepths1To7)
{
    for (const auto& nm : all_meshes())
        for (int d = 1; d <= 7; ++d) expect_surface_matches(nm.mesh, options(d), nm.name + " depth " + std::to_string(d));
}

// The packer finds bricks in parallel over blocks of 2^16 leaves of each span, and a brick may
// straddle a block boundary. A surface fill's spans are its chunks (at most 2^15 leaves), so the
// case needs a solid fill, whose leaves form one span: a tree of many blocks must still hold
// exactly the oracle's voxels.
TEST(SvoVoxelize, TreeOfManyPackBlocksMatchesTheOracle)
{
    const SvoMeshData m = rkmesh::icosphere(3);
    SvoBuildOptions o = options(7, SvoFill::solid);
    o.threads = 2;
    const Built b = build(m, o);
    ASSERT_TRUE(b.ok) << b.st.message;
    const ref_svo::Snapped s = ref_svo::snap_mesh(m, lattice_of(b.tree));
    const auto surface = ref_svo::surface_voxels(s, 7);
    const ref_svo::SolidRef in = ref_svo::inside_voxels(s, 7);
    std::vector<std::uint64_t> want;
    std::set_union(surface.begin(), surface.end(), in.inside.begin(), in.inside.end(), std::back_inserter(want));
    EXPECT_TRUE(same_voxels(b.voxels, want, s, "icosphere(3) solid depth 7"));
    EXPECT_EQ(b.tree.voxel_count, want.size());
    EXPECT_GT(b.tree.voxel_count, 8u << 16) << "fewer leaves than the test needs";
}

TEST(SvoVoxelize, AttributesAndThreadsDoNotChangeTheSet)
{
    const auto m = rkmesh::textured_quad();
    const auto sphere = rkmesh::icosphere(3);
    for (int d : {3, 6}) {
        SvoBuildOptions a = options(d), b = options(d);
        b.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;
        b.threads = 1;
        EXPECT_EQ(build(m, a).voxels, build(m, b).voxels);
        EXPECT_EQ(build(sphere, a).voxels, build(sphere, b).voxels);
    }
}

TEST(SvoVoxelize, QuadOnRootCentrePlaneMarksBothSides)
{
    // Automatic bounds centre the root cube on the flat quad, so it lies exactly on the root's
    // split plane: every voxel on both sides is touched (2 * 4^depth voxels).
    for (int axis = 0; axis < 3; ++axis)
        for (int d = 1; d <= 7; ++d) {
            const auto m = rkmesh::axis_quad(axis, 0.25, {-1.0, -1.0}, {1.0, 1.0});
            Built b;
            expect_surface_matches(m, options(d), "centre quad axis " + std::to_string(axis) + " depth " + std::to_string(d), &b);
            ASSERT_TRUE(b.ok);
            EXPECT_EQ(b.voxels.size(), 2ull << (2 * d));
            const std::uint32_t mid = 1u << (d - 1);
            for (std::uint64_t k : b.voxels) {
                const int c = ref_svo::unkey(k)[axis];
                EXPECT_TRUE(c == static_cast<int>(mid) - 1 || c == static_cast<int>(mid)) << c;
            }
        }
}

TEST(SvoVoxelize, QuadsOnEveryLevelsSplitPlanes)
{
    // Fixed root [0,1]^3: the plane k / 2^l is a lattice plane at every level l <= depth. Quads on
    // them (edges on split planes too), on the root's own faces, and slightly off them.
    for (int d = 1; d <= 7; ++d) {
        SvoMeshData m;
        for (int axis = 0; axis < 3; ++axis) {
            for (int l = 1; l <= d; ++l) {
                const int k = (l * 5 + axis) % (1 << l) | 1;  // an odd numerator: a plane first split at level l
                rkmesh::append(m, rkmesh::axis_quad(axis, std::ldexp(k, -l), {0.25, 0.5}, {0.75, 1.0}));
            }
            rkmesh::append(m, rkmesh::axis_quad(axis, 0.0, {0.0, 0.0}, {0.5, 0.125}));   // root face x = 0
            rkmesh::append(m, rkmesh::axis_quad(axis, 1.0, {0.5, 0.5}, {1.0, 1.0}));     // root face x = 1
            rkmesh::append(m, rkmesh::axis_quad(axis, std::nextafter(0.5f, 1.0f), {0.1, 0.1}, {0.3, 0.2}));
        }
        SvoBuildOptions o = options(d);
        o.fixed_bounds = true;
        o.bounds_min = glm::vec3(0.0f);
        o.bounds_size = 1.0f;
        Built b;
        expect_surface_matches(m, o, "split-plane quads depth " + std::to_string(d), &b);
        // Independent count for one of them: the quad on the root face x = 1 touches only the last
        // column of voxels, over [0.5, 1] x [0.5, 1].
        const auto face = rkmesh::axis_quad(0, 1.0, {0.5, 0.5}, {1.0, 1.0});
        const Built f = build(face, o);
        ASSERT_TRUE(f.ok) << f.st.message;
        const std::size_t half = std::size_t(1) << (d - 1);
        EXPECT_EQ(f.voxels.size(), (half + 1) * (half + 1)) << d;
        for (std::uint64_t k : f.voxels) EXPECT_EQ(ref_svo::unkey(k).x, (1 << d) - 1);
    }
}

TEST(SvoVoxelize, SliversAndDegenerateTriangles)
{
    // Slivers at several depths (needles collapse to points at coarse depths: degenerate).
    const auto sl = rkmesh::slivers(200, 5);
    std::size_t degenerate_seen = 0;
    for (int d : {1, 3, 5, 7}) {
        Built b;
        expect_surface_matches(sl, options(d), "slivers depth " + std::to_string(d), &b);
        degenerate_seen += b.stats.skipped_degenerate;
    }
    EXPECT_GT(degenerate_seen, 0u);

    // Every kind of invalid triangle next to valid ones; the counts are known by construction.
    SvoMeshData m = rkmesh::icosphere(1);
    const auto nv = static_cast<std::uint32_t>(m.positions.size());
    const std::size_t valid = rkmesh::triangle_count(m);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const std::uint32_t p_nan = rkmesh::push_vertex(m, {nan, 0.0f, 0.0f});
    const std::uint32_t p_inf = rkmesh::push_vertex(m, {0.0f, -inf, 0.0f});
    const std::uint32_t c0 = rkmesh::push_vertex(m, {-0.5f, -0.5f, -0.5f});
    const std::uint32_t c1 = rkmesh::push_vertex(m, {0.0f, 0.0f, 0.0f});
    const std::uint32_t c2 = rkmesh::push_vertex(m, {0.25f, 0.25f, 0.25f});
    rkmesh::push_tri(m, 0, 1, p_nan);        // non-finite
    rkmesh::push_tri(m, p_inf, 2, 3);        // non-finite
    rkmesh::push_tri(m, 0, 1, nv + 100);     // bad index
    rkmesh::push_tri(m, 4, 4, 5);            // repeated vertex: degenerate
    rkmesh::push_tri(m, c0, c1, c2);         // collinear (exactly, also after snapping): degenerate
    rkmesh::push_tri(m, 6, 7, 6);            // degenerate
    for (int d : {2, 6}) {
        Built b;
        expect_surface_matches(m, options(d), "invalid triangles depth " + std::to_string(d), &b);
        const Built alone = build(rkmesh::icosphere(1), options(d));
        EXPECT_EQ(b.stats.triangles_in, valid + 6);
        EXPECT_EQ(b.stats.triangles_used, valid);
        EXPECT_EQ(b.stats.skipped_non_finite, 2u);
        EXPECT_EQ(b.stats.skipped_bad_index, 1u);
        EXPECT_EQ(b.stats.skipped_degenerate, 3u);
        // The root comes from the usable triangles only: the same as for the icosphere alone.
        EXPECT_EQ(b.tree.root_size, alone.tree.root_size);
        EXPECT_EQ(b.tree.root_min, alone.tree.root_min);
        EXPECT_EQ(b.voxels, alone.voxels);
    }
}

TEST(SvoVoxelize, FarFromTheOrigin)
{
    const auto sphere = rkmesh::icosphere(3, 1.0);
    const auto torus = rkmesh::torus(32, 12, 1.0, 0.3);
    struct C { const char* name; SvoMeshData m; };
    const C cases[] = {
        {"icosphere +1e5", rkmesh::transformed(sphere, 1.0, {1e5, 1e5, 0.0})},
        {"torus +1e5", rkmesh::transformed(torus, 1.0, {0.0, 1e5, -1e5})},
        {"icosphere r=1000 at -3e6", rkmesh::transformed(sphere, 1000.0, {-3e6, 0.0, 2e6})},
        {"icosphere r=1 at -3e6 (float spacing 0.25)", rkmesh::transformed(sphere, 1.0, {-3e6, -3e6, -3e6})},
        {"box r=3 at -3e6", rkmesh::transformed(rkmesh::box({-1, -1, -1}, {1, 1, 1}, {0.2, 0.4, 0.6}), 3.0, {-3e6, 5.0, 0.0})},
    };
    for (const auto& c : cases)
        for (int d : {1, 3, 5, 7}) expect_surface_matches(c.m, options(d), std::string(c.name) + " depth " + std::to_string(d));
}

TEST(SvoVoxelize, RandomSoup)
{
    for (std::uint64_t seed : {1ull, 2ull, 3ull}) {
        const auto m = rkmesh::random_soup(400, seed, 0.2);
        for (int d : {4, 7}) expect_surface_matches(m, options(d), "soup seed " + std::to_string(seed) + " depth " + std::to_string(d));
    }
}

TEST(SvoVoxelize, FixedBoundsClipTheMesh)
{
    const auto sphere = rkmesh::uv_sphere(32, 16, 1.0);
    for (int d : {1, 2, 4, 7}) {
        SvoBuildOptions o = options(d);
        o.fixed_bounds = true;
        o.bounds_min = glm::vec3(-0.3f, -1.2f, -0.9f);
        o.bounds_size = 1.4f;
        Built b;
        expect_surface_matches(sphere, o, "clipped sphere depth " + std::to_string(d), &b);
        ASSERT_TRUE(b.ok);
        EXPECT_EQ(b.tree.root_min, o.bounds_min);
        EXPECT_EQ(b.tree.root_size, o.bounds_size);
        // Triangles entirely outside the root cube: at least those whose bounding box misses it, at
        // most those that miss it exactly.
        const ref_svo::Snapped s = ref_svo::snap_mesh(sphere, lattice_of(b.tree));
        const i64 top = i64(1) << (d + 16);
        const i64 rlo[3] = {0, 0, 0}, rhi[3] = {top, top, top};
        std::size_t bbox_out = 0, exact_out = 0;
        for (const auto& t : s.tris) {
            bool miss = false;
            for (int a = 0; a < 3; ++a)
                miss = miss || std::min({t.v[0][a], t.v[1][a], t.v[2][a]}) > top || std::max({t.v[0][a], t.v[1][a], t.v[2][a]}) < 0;
            bbox_out += miss;
            exact_out += !ref_svo::tri_box_sat(t.v, rlo, rhi);
        }
        EXPECT_GT(bbox_out, 0u);
        EXPECT_GE(b.stats.skipped_outside, bbox_out);
        EXPECT_LE(b.stats.skipped_outside, exact_out);
    }
}

TEST(SvoVoxelize, TouchingAndCrossingTheRootFromOutside)
{
    // Fixed root [0,1]^3. Triangles outside it that touch it at one corner point or along an edge
    // segment (closed boxes: they mark the voxels they touch), triangles one lattice unit outside
    // (nothing), and a huge triangle whose vertices are 50 root sizes away slicing through it.
    for (int d = 1; d <= 7; ++d) {
        SvoBuildOptions o = options(d);
        o.fixed_bounds = true;
        o.bounds_min = glm::vec3(0.0f);
        o.bounds_size = 1.0f;
        const double unit = std::ldexp(1.0, -(d + 16));
        const int last = (1 << d) - 1;
        auto tri = [](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
            SvoMeshData m;
            for (const auto& p : {a, b, c}) m.indices.push_back(rkmesh::push_vertex(m, rkmesh::to_vec3(p.x, p.y, p.z)));
            return m;
        };
        const SvoMeshData corner = tri({1, 1, 1}, {2, 1.5, 1.2}, {1.5, 2, 1.7});
        const SvoMeshData edge = tri({0.2, 0, 0}, {0.6, 0, 0}, {0.4, -0.5, -0.5});
        const SvoMeshData off_face = tri({-unit, 0.1, 0.1}, {-unit, 0.9, 0.2}, {-unit, 0.5, 0.8});
        const SvoMeshData off_corner = tri({1 + unit, 1 + unit, 1 + unit}, {2, 1.5, 1.2}, {1.5, 2, 1.7});
        const SvoMeshData slice = tri({-50, -50, 101.5}, {101.5, -50, -50}, {-50, 101.5, -50});  // x + y + z = 1.5
        Built b;
        expect_surface_matches(corner, o, "corner touch depth " + std::to_string(d), &b);
        ASSERT_EQ(b.voxels.size(), 1u);
        EXPECT_EQ(b.voxels[0], ref_svo::key(last, last, last));
        expect_surface_matches(edge, o, "edge touch depth " + std::to_string(d), &b);
        ASSERT_FALSE(b.voxels.empty());
        for (std::uint64_t k : b.voxels) EXPECT_EQ(ref_svo::unkey(k).y + ref_svo::unkey(k).z, 0);
        SvoMeshData mixed = slice;
        rkmesh::append(mixed, off_face);
        rkmesh::append(mixed, off_corner);
        expect_surface_matches(mixed, o, "slice + one unit outside, depth " + std::to_string(d), &b);
        EXPECT_EQ(b.stats.skipped_outside, 2u) << d;
        EXPECT_GT(b.voxels.size(), std::size_t(1) << d) << d;
    }
}

TEST(SvoVoxelize, Depth16SmallTriangles)
{
    // Small triangles (a few voxels at depth 16) spread over the root, some straddling or lying on
    // chunk and split planes; the oracle runs over each triangle's own voxel range, which is all
    // of the set.
    SvoMeshData m = rkmesh::random_soup(300, 99, 4.0 / 65536.0);
    rkmesh::append(m, rkmesh::axis_quad(0, 0.5, {0.25, 0.25}, {0.25 + 3.0 / 65536, 0.25 + 2.0 / 65536}));
    rkmesh::append(m, rkmesh::axis_quad(1, 32.0 / 65536, {0.5 - 1.0 / 65536, 0.5}, {0.5 + 1.0 / 65536, 0.5 + 1.0 / 65536}));
    rkmesh::append(m, rkmesh::axis_quad(2, 1.0, {0.75, 0.0}, {0.75 + 2.0 / 65536, 2.0 / 65536}));
    rkmesh::append(m, rkmesh::transformed(rkmesh::icosphere(1), 3.0 / 65536, {1024.0 / 65536, 1.0 / 65536 * 4095, 0.5}));
    SvoBuildOptions o = options(16);
    o.fixed_bounds = true;
    o.bounds_min = glm::vec3(0.0f);
    o.bounds_size = 1.0f;
    Built b;
    expect_surface_matches(m, o, "depth 16", &b);
    EXPECT_GT(b.voxels.size(), 1000u);
    // Automatic bounds on the soup alone (the root is then not a power-of-two cube).
    expect_surface_matches(rkmesh::random_soup(300, 7, 3.0 / 65536.0), options(16), "depth 16 auto bounds");
    // The deepest tree the format allows (lattice coordinates up to 2^36).
    o.depth = 20;
    expect_surface_matches(rkmesh::random_soup(100, 5, 3.0 / 1048576.0), o, "depth 20");
}

// ---------------------------------------------------------------------------------------------
// The public predicate against both exact methods, on adversarial pairs.

TEST(SvoVoxelize, PublicOverlapPredicate)
{
    rkmesh::Rng rng(2024);
    auto ri = [&](i64 lo, i64 hi) { return lo + static_cast<i64>(rng.next() % static_cast<std::uint64_t>(hi - lo + 1)); };
    long total = 0, overlaps = 0, mismatches = 0;
    std::string first;
    auto check = [&](const i64 v[3][3], const i64 bmin[3], i64 size, const char* cls) {
        const i64 bhi[3] = {bmin[0] + size, bmin[1] + size, bmin[2] + size};
        const bool sat = ref_svo::tri_box_sat(v, bmin, bhi), lp = ref_svo::tri_box_lp(v, bmin, bhi);
        const bool got = svo_triangle_box_overlap(v, bmin, size);
        ++total;
        overlaps += sat;
        if (sat != lp || got != sat) {
            if (++mismatches <= 5) {
                std::ostringstream o;
                o << "\n  [" << cls << "] tri {(" << v[0][0] << "," << v[0][1] << "," << v[0][2] << "),(" << v[1][0] << ","
                  << v[1][1] << "," << v[1][2] << "),(" << v[2][0] << "," << v[2][1] << "," << v[2][2] << ")} box min ("
                  << bmin[0] << "," << bmin[1] << "," << bmin[2] << ") size " << size << ": builder " << got << ", sat " << sat
                  << ", lp " << lp;
                first += o.str();
            }
        }
    };
    i64 v[3][3], bmin[3];
    // Small integers around a small box: touching in every way is frequent.
    for (int n = 0; n < 40000; ++n) {
        const i64 size = ri(1, 4);
        for (auto& x : bmin) x = ri(-2, 2);
        for (auto& p : v)
            for (auto& x : p) x = ri(-6, 7);
        check(v, bmin, size, "small");
    }
    // A vertex, or an edge's midpoint, on the box boundary (a face, edge or corner point) or one
    // unit outside it; the rest of the triangle anywhere around.
    for (int n = 0; n < 20000; ++n) {
        const i64 size = 6;
        for (auto& x : bmin) x = ri(-1000, 1000);
        i64 q[3];  // a face point (1 axis on the boundary), an edge point (2) or a corner (3)
        for (int a = 0; a < 3; ++a) q[a] = bmin[a] + ri(0, size);
        const int fixed = static_cast<int>(ri(1, 3)), start = static_cast<int>(ri(0, 2));
        for (int f = 0; f < fixed; ++f) {
            const int a = (start + f) % 3;
            const i64 side = ri(0, 1);
            q[a] = bmin[a] + size * side + (n % 2) * (side ? 1 : -1);  // odd n: one unit outside
        }
        if (n % 4 < 2) {
            for (int a = 0; a < 3; ++a) v[0][a] = q[a];
        } else {
            for (int a = 0; a < 3; ++a) {
                const i64 h = ri(-6, 6);
                v[0][a] = q[a] + h, v[1][a] = q[a] - h;  // the edge v0-v1 runs through q
            }
        }
        for (int k = (n % 4 < 2 ? 1 : 2); k < 3; ++k)
            for (int a = 0; a < 3; ++a) v[k][a] = q[a] + ri(-12, 12);
        check(v, bmin, size, "vertex or edge at the boundary");
    }
    // Coplanar with a face (and with the plane one unit off it).
    for (int n = 0; n < 10000; ++n) {
        const i64 size = ri(1, 8);
        for (auto& x : bmin) x = ri(-50, 50);
        const int a = ri(0, 2) == 0 ? 0 : static_cast<int>(ri(1, 2));
        const i64 plane = bmin[a] + (ri(0, 1) ? size : 0) + ri(-1, 1) * (n % 4 == 0);
        for (auto& p : v) {
            for (int b = 0; b < 3; ++b) p[b] = bmin[b] + ri(-10, size + 10);
            p[a] = plane;
        }
        check(v, bmin, size, "coplanar");
    }
    // The triangle's plane through a box corner, edge lines through box edges.
    for (int n = 0; n < 10000; ++n) {
        const i64 size = ri(2, 10);
        for (auto& x : bmin) x = ri(-100, 100);
        const i64 corner[3] = {bmin[0] + size * ri(0, 1), bmin[1] + size * ri(0, 1), bmin[2] + size * ri(0, 1)};
        i64 u[3], w[3];
        for (int a = 0; a < 3; ++a) u[a] = ri(-5, 5), w[a] = ri(-5, 5);
        const i64 s[3][2] = {{ri(-3, 3), ri(-3, 3)}, {ri(-3, 3), ri(-3, 3)}, {ri(-3, 3), ri(-3, 3)}};
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) v[k][a] = corner[a] + s[k][0] * u[a] + s[k][1] * w[a];
        check(v, bmin, size, "plane through corner");
    }
    // Huge triangles (coordinates up to 2^39) around a voxel-sized box, and tiny ones near a huge box.
    for (int n = 0; n < 10000; ++n) {
        const i64 big = i64(1) << 37;
        const i64 size = i64(1) << 16;
        for (auto& x : bmin) x = ri(-size, size);
        // Centroid P near the box (inside it or up to a box size away): v = P + A, P + B, P - A - B.
        i64 P[3], A[3], B[3];
        for (int a = 0; a < 3; ++a) P[a] = bmin[a] + ri(-size, 2 * size), A[a] = ri(-big, big), B[a] = ri(-big, big);
        for (int a = 0; a < 3; ++a) v[0][a] = P[a] + A[a], v[1][a] = P[a] + B[a], v[2][a] = P[a] - A[a] - B[a];
        check(v, bmin, size, "huge triangle");
        const i64 hsize = i64(1) << 38;
        for (auto& x : bmin) x = -(hsize / 2);
        const i64 corner[3] = {bmin[0] + hsize * ri(0, 1), bmin[1] + hsize * ri(0, 1), bmin[2] + hsize * ri(0, 1)};
        for (auto& p : v)
            for (int a = 0; a < 3; ++a) p[a] = corner[a] + ri(-2, 2);
        check(v, bmin, hsize, "tiny triangle at a huge box's corner");
    }
    // Anywhere within the documented range |coordinate| < 2^40: big triangles, big boxes.
    for (int n = 0; n < 5000; ++n) {
        const i64 lim = (i64(1) << 40) - 1;
        const i64 size = ri(1, i64(1) << 39);
        for (auto& x : bmin) x = ri(-lim, lim - size);
        for (auto& p : v)
            for (auto& x : p) x = ri(-lim, lim);
        check(v, bmin, size, "range limit");
    }
    // Collinear (degenerate) triangles: the segment they are.
    for (int n = 0; n < 10000; ++n) {
        const i64 size = ri(1, 5);
        for (auto& x : bmin) x = ri(-3, 3);
        i64 p0[3], d[3];
        for (int a = 0; a < 3; ++a) p0[a] = ri(-6, 6), d[a] = ri(-3, 3);
        const i64 t[3] = {0, ri(-3, 3), ri(-3, 3)};
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) v[k][a] = p0[a] + t[k] * d[a];
        check(v, bmin, size, "collinear");
    }
    EXPECT_EQ(mismatches, 0) << mismatches << " of " << total << " pairs differ:" << first;
    EXPECT_GE(total, 100000);
    EXPECT_GT(overlaps, total / 10);
    EXPECT_LT(overlaps, total * 9 / 10);
}

// ---------------------------------------------------------------------------------------------
// Watertightness of closed meshes at depths 5..8: no outside path to the inside.

namespace {

struct Shape {
    std::string name;
    SvoMeshData mesh;
    // Whether the ball of radius m around p (object space) lies inside the shape (conservative).
    std::function<bool(glm::dvec3 p, double m)> inside_by;
    double tessellation;  // how far the mesh may be from the analytic surface
};

std::vector<Shape> closed_shapes()
{
    std::vector<Shape> v;
    {
        const double r = 1.0;
        const int level = 4;
        const double edge_angle = 2.0 * std::atan(2.0) / (1 << level);
        v.push_back({"icosphere(4)", rkmesh::icosphere(level, r), [r](glm::dvec3 p, double mm) { return r - glm::length(p) > mm; },
                     r * (1.0 - std::cos(edge_angle))});
    }
    {
        const double r = 0.7;
        const glm::dvec3 c(0.2, 0.1, -0.3);
        v.push_back({"uv_sphere(48,24)", rkmesh::uv_sphere(48, 24, r, c), [r, c](glm::dvec3 p, double mm) { return r - glm::length(p - c) > mm; },
                     2.0 * r * (1.0 - std::cos(rkmesh::kPi / 24))});
    }
    {
        const double R = 1.0, r = 0.4;
        const int M = 48, m = 24;
        v.push_back({"torus(48,24)", rkmesh::torus(M, m, R, r),
                     [R, r](glm::dvec3 p, double mm) { return r - std::hypot(std::hypot(p.x, p.y) - R, p.z) > mm; },
                     2.0 * ((R + r) * (1.0 - std::cos(rkmesh::kPi / M)) + r * (1.0 - std::cos(rkmesh::kPi / m)))});
    }
    {
        const int level = 2;
        v.push_back({"menger(2)", rkmesh::menger_sponge(level),
                     [level](glm::dvec3 p, double mm) {
                         // Every cell that the cube [p - mm, p + mm] overlaps is filled.
                         const int n = 9;
                         int lo[3], hi[3];
                         for (int a = 0; a < 3; ++a) {
                             lo[a] = static_cast<int>(std::floor((p[a] - mm) * n));
                             hi[a] = static_cast<int>(std::floor((p[a] + mm) * n));
                             if (lo[a] < 0 || hi[a] >= n) return false;
                         }
                         for (int z = lo[2]; z <= hi[2]; ++z)
                             for (int y = lo[1]; y <= hi[1]; ++y)
                                 for (int x = lo[0]; x <= hi[0]; ++x)
                                     if (!rkmesh::menger_filled(level, x, y, z)) return false;
                         return true;
                     },
                     0.0});
    }
    return v;
}

}  // namespace

TEST(SvoVoxelize, WatertightFloodFillAndDda)
{
    for (const auto& sh : closed_shapes())
        for (int d = 5; d <= 8; ++d) {
            // Depth 8 for the icosphere and the sponge only (time).
            if (d == 8 && sh.name.rfind("icosphere", 0) != 0 && sh.name.rfind("menger", 0) != 0) continue;
            if (d == 5 && sh.name.rfind("menger", 0) == 0) continue;     // no voxel centre is a diagonal deep
            const std::string what = sh.name + " depth " + std::to_string(d);
            const Built b = build(sh.mesh, options(d));
            ASSERT_TRUE(b.ok) << what << ": " << b.st.message;
            const int n = 1 << d;
            const auto occ = ref_svo::dense(b.voxels, n);
            const auto outside = ref_svo::flood_outside(occ, n);
            const double vs = static_cast<double>(b.tree.root_size) / n;
            const glm::dvec3 rmin(b.tree.root_min);
            const double margin = std::sqrt(3.0) * vs + sh.tessellation;
            auto centre = [&](int i, int j, int k) { return rmin + (glm::dvec3(i, j, k) + 0.5) * vs; };
            // Exact parity of the snapped mesh: reached voxels must all be outside it.
            const ref_svo::Snapped s = ref_svo::snap_mesh(sh.mesh, lattice_of(b.tree));
            const ref_svo::SolidRef solid = ref_svo::inside_voxels(s, d);
            long leaks_analytic = 0, leaks_parity = 0, reached = 0, enclosed = 0;
            std::string example;
            for (int k = 0; k < n; ++k)
                for (int j = 0; j < n; ++j)
                    for (int i = 0; i < n; ++i) {
                        const std::size_t id = static_cast<std::size_t>(i) + static_cast<std::size_t>(n) * (j + static_cast<std::size_t>(n) * k);
                        reached += outside[id];
                        enclosed += !outside[id] && !occ[id];
                        if (outside[id] && sh.inside_by(centre(i, j, k), margin) && ++leaks_analytic == 1)
                            example = "(" + std::to_string(i) + "," + std::to_string(j) + "," + std::to_string(k) + ")";
                    }
            for (std::uint64_t kk : solid.inside) {
                const glm::ivec3 c = ref_svo::unkey(kk);
                leaks_parity += outside[static_cast<std::size_t>(c.x) + static_cast<std::size_t>(n) * (c.y + static_cast<std::size_t>(n) * c.z)];
            }
            EXPECT_EQ(leaks_analytic, 0) << what << ": the outside flood reaches deep-inside voxel " << example;
            EXPECT_EQ(leaks_parity, 0) << what;
            EXPECT_GT(reached, 0) << what;
            EXPECT_GT(enclosed, 0) << what;  // empty voxels the flood cannot reach: the interior
            // DDA rays from deep-inside points to far outside all hit an occupied voxel.
            rkmesh::Rng rng(static_cast<std::uint64_t>(d) * 77 + sh.name.size());
            int rays = 0, misses = 0;
            for (int tries = 0; tries < 20000 && rays < 150; ++tries) {
                const glm::dvec3 p = rmin + glm::dvec3(rng.uniform(), rng.uniform(), rng.uniform()) * static_cast<double>(b.tree.root_size);
                if (!sh.inside_by(p, margin)) continue;
                glm::dvec3 dir(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
                if (glm::length(dir) < 1e-3) continue;
                const glm::dvec3 a = (p - rmin) / vs;
                const glm::dvec3 far = a + glm::normalize(dir) * (4.0 * n);
                ++rays;
                misses += !ref_svo::dda(n, a, far, [&](int i, int j, int k) {
                    return occ[static_cast<std::size_t>(i) + static_cast<std::size_t>(n) * (j + static_cast<std::size_t>(n) * k)] != 0;
                });
            }
            EXPECT_GE(rays, 100) << what;
            EXPECT_EQ(misses, 0) << what;
        }
}

// ---------------------------------------------------------------------------------------------
// Solid fill: surface plus odd-parity centres, exactly; and analytic inside/outside far from the
// surface.

TEST(SvoVoxelize, SolidMatchesOracle)
{
    using glm::dvec3;
    struct C { std::string name; SvoMeshData m; std::function<double(dvec3)> inside; double tess = 0.0; };
    std::vector<C> cases;
    cases.push_back({"icosphere(3)", rkmesh::icosphere(3, 1.0), [](dvec3 p) { return 1.0 - glm::length(p); }, 0.05});
    cases.push_back({"uv_sphere(24,12)", rkmesh::uv_sphere(24, 12, 1.0), [](dvec3 p) { return 1.0 - glm::length(p); }, 0.08});
    cases.push_back({"torus(32,16)", rkmesh::torus(32, 16, 1.0, 0.4),
                     [](dvec3 p) { return 0.4 - std::hypot(std::hypot(p.x, p.y) - 1.0, p.z); }, 0.03});
    // A cube centred in its root: the diagonals of its x faces run through column centres (ties).
    cases.push_back({"cube", rkmesh::box(dvec3(-1.0), dvec3(1.0)),
                     [](dvec3 p) { return 1.0 - std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}); }});
    cases.push_back({"box rotated", rkmesh::box(dvec3(-0.4, -0.3, -0.2), dvec3(0.5, 0.3, 0.25), dvec3(0.3, 0.5, 0.7)), nullptr});
    cases.push_back({"thin_wall x", rkmesh::thin_wall(1.0, 1e-3, 0), nullptr});
    cases.push_back({"menger(2)", rkmesh::menger_sponge(2), nullptr});
    cases.push_back({"torus at +1e5", rkmesh::transformed(rkmesh::torus(32, 16, 1.0, 0.4), 1.0, {1e5, 0.0, -1e5}), nullptr});
    cases.push_back({"icosphere(3) at -3e6 (float spacing 0.25)", rkmesh::transformed(rkmesh::icosphere(3), 1.0, dvec3(-3e6)), nullptr});
    cases.push_back({"random_soup (open)", rkmesh::random_soup(60, 8), nullptr});
    cases.push_back({"axis_quad x (open)", rkmesh::axis_quad(0, 0.0, {-1.0, -1.0}, {1.0, 1.0}), nullptr});
    std::size_t ties = 0;
    for (const auto& c : cases)
        for (int d = 1; d <= 7; ++d) {
            if (d == 7 && c.name != "icosphere(3)" && c.name != "cube" && c.name != "menger(2)") continue;  // time
            const std::string what = c.name + " solid depth " + std::to_string(d);
            const Built b = build(c.m, options(d, SvoFill::solid));
            ASSERT_TRUE(b.ok) << what << ": " << b.st.message;
            const ref_svo::Snapped s = ref_svo::snap_mesh(c.m, lattice_of(b.tree));
            const auto surface = ref_svo::surface_voxels(s, d);
            const ref_svo::SolidRef in = ref_svo::inside_voxels(s, d);
            ties += in.tie_points;
            std::vector<std::uint64_t> want;
            std::set_union(surface.begin(), surface.end(), in.inside.begin(), in.inside.end(), std::back_inserter(want));
            EXPECT_TRUE(same_voxels(b.voxels, want, s, what));
            EXPECT_EQ(b.stats.surface_voxels, surface.size()) << what;
            EXPECT_EQ(b.stats.interior_voxels, want.size() - surface.size()) << what;
            if (c.inside && d >= 3) {
                const int n = 1 << d;
                const double vs = static_cast<double>(b.tree.root_size) / n;
                const double margin = std::sqrt(3.0) * vs + c.tess;
                const auto occ = ref_svo::dense(b.voxels, n);
                long wrong = 0, checked = 0;
                for (int k = 0; k < n; ++k)
                    for (int j = 0; j < n; ++j)
                        for (int i = 0; i < n; ++i) {
                            const dvec3 p = dvec3(b.tree.root_min) + (dvec3(i, j, k) + 0.5) * vs;
                            const double depth_in = c.inside(p);
                            if (std::abs(depth_in) <= margin) continue;
                            ++checked;
                            wrong += (depth_in > 0) != (occ[static_cast<std::size_t>(i) + static_cast<std::size_t>(n) * (j + static_cast<std::size_t>(n) * k)] != 0);
                        }
                EXPECT_EQ(wrong, 0) << what << " (" << checked << " voxels checked)";
            }
        }
    EXPECT_GT(ties, 0u);  // the cube's shared diagonals put centres exactly on projected edges
}

TEST(SvoVoxelize, SolidWithFixedBoundsThatClip)
{
    // Every kept triangle counts in the crossing parity, also one entirely outside the root cube:
    // a +x ray from inside the sphere leaves it beyond the root when the root is the sphere's -x
    // part. (Clipped on the -x side instead, the exits lie inside the root.)
    const auto sphere = rkmesh::icosphere(3, 1.0);
    for (const glm::vec3 bmin : {glm::vec3(0.2f, -0.6f, -0.6f), glm::vec3(-1.4f, -0.6f, -0.6f)})
        for (int d : {2, 3, 5}) {
            SvoBuildOptions o = options(d, SvoFill::solid);
            o.fixed_bounds = true;
            o.bounds_min = bmin;
            o.bounds_size = 1.2f;
            const std::string what = "clipped solid, bounds_min.x " + std::to_string(bmin.x) + ", depth " + std::to_string(d);
            const Built b = build(sphere, o);
            ASSERT_TRUE(b.ok) << what << ": " << b.st.message;
            const ref_svo::Snapped s = ref_svo::snap_mesh(sphere, lattice_of(b.tree));
            const auto surface = ref_svo::surface_voxels(s, d);
            const ref_svo::SolidRef in = ref_svo::inside_voxels(s, d);
            std::vector<std::uint64_t> want;
            std::set_union(surface.begin(), surface.end(), in.inside.begin(), in.inside.end(), std::back_inserter(want));
            EXPECT_TRUE(same_voxels(b.voxels, want, s, what));
        }
}

TEST(SvoVoxelize, SolidTieRuleOnOpenTriangles)
{
    // Open triangles whose projected vertices sit exactly on column centres ((j + 1/2) / 2^d in y
    // and z, fixed root [0,1]^3), so centres fall on unshared edges and vertices: the parity then
    // depends on the documented tie rule (a centre on an edge a->b of the counter-clockwise yz
    // projection counts iff b.z < a.z, or b.z == a.z and b.y > a.y), which the oracle implements
    // as the perturbation (y + e, z + e^2).
    for (int d = 2; d <= 6; ++d) {
        const int n = 1 << d;
        rkmesh::Rng rng(static_cast<std::uint64_t>(d) + 1000);
        auto centre = [&]() { return (static_cast<double>(rng.next() % static_cast<std::uint64_t>(n)) + 0.5) / n; };
        SvoMeshData m;
        for (int t = 0; t < 40; ++t) {
            double y[3], z[3];
            for (int k = 0; k < 3; ++k) y[k] = centre(), z[k] = centre();
            if (t % 4 == 1) z[1] = z[0];  // a horizontal edge through centres
            if (t % 4 == 2) y[2] = y[1];  // a vertical one
            for (int k = 0; k < 3; ++k) m.indices.push_back(rkmesh::push_vertex(m, rkmesh::to_vec3(rng.uniform(0.05, 0.95), y[k], z[k])));
        }
        SvoBuildOptions o = options(d, SvoFill::solid);
        o.fixed_bounds = true;
        o.bounds_min = glm::vec3(0.0f);
        o.bounds_size = 1.0f;
        const Built b = build(m, o);
        ASSERT_TRUE(b.ok) << b.st.message;
        const ref_svo::Snapped s = ref_svo::snap_mesh(m, lattice_of(b.tree));
        const auto surface = ref_svo::surface_voxels(s, d);
        const ref_svo::SolidRef in = ref_svo::inside_voxels(s, d);
        EXPECT_GT(in.tie_points, 20u) << d;
        std::vector<std::uint64_t> want;
        std::set_union(surface.begin(), surface.end(), in.inside.begin(), in.inside.end(), std::back_inserter(want));
        EXPECT_TRUE(same_voxels(b.voxels, want, s, "tie triangles solid depth " + std::to_string(d)));
    }
}

// ---------------------------------------------------------------------------------------------
// Nothing to voxelise.

TEST(SvoVoxelize, EmptyAndAllDegenerateMeshesFail)
{
    auto expect_empty = [](const SvoMeshData& m, const char* what) {
        SvoTree t;
        SvoStatus st;
        EXPECT_FALSE(build_svo(m.view(), options(4), t, st)) << what;
        EXPECT_EQ(st.code, SvoError::empty_mesh) << what;
        EXPECT_FALSE(st.message.empty()) << what;
    };
    expect_empty(SvoMeshData{}, "no triangles");
    SvoMeshData m;
    m.positions = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 1, 0}, {std::nanf(""), 0, 0}};
    m.indices = {0, 1, 2, 0, 0, 3, 3, 3, 3, 0, 3, 4, 0, 3, 7};
    expect_empty(m, "collinear, repeated, NaN, bad index");
    SvoMeshData only_positions;
    only_positions.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    expect_empty(only_positions, "positions without indices");
}

// Compact level of detail (SvoBuildOptions::shared_sub_attributes): the structure is the same, the
// level-(depth-1) nodes have no attribute entries (a lookup or trace stopping there returns the
// brick's), every voxel keeps its exact attributes, the file round-trips and the validator rejects
// an inconsistent flag; on the figure mesh, structure + colour drop to at most a quarter of the
// thesis's format (issue 10's goal) where the full LOD tree takes 0.29 of it.
TEST(SvoVoxelize, SharedSubNodeAttributes)
{
    const SvoMeshData data = rkmesh::figure();
    SvoBuildOptions opt;
    opt.depth = 9;
    opt.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;
    SvoTree full, compact;
    SvoStatus st;
    ASSERT_TRUE(build_svo(data.view(), opt, full, st)) << st.message;
    opt.shared_sub_attributes = true;
    ASSERT_TRUE(build_svo(data.view(), opt, compact, st)) << st.message;
    ASSERT_TRUE(svo_validate(compact, st)) << st.message;
    EXPECT_EQ(compact.attributes, full.attributes | RK_SVO_ATTR_SHARED_SUB);
    EXPECT_EQ(compact.words, full.words);
    EXPECT_EQ(compact.level_nodes, full.level_nodes);
    EXPECT_EQ(compact.attr_count, full.attr_count - full.level_nodes[opt.depth - 1]);
    const std::vector<uint32_t> gf = full.gpu_words(), gc = compact.gpu_words();
    const uint32_t depth = full.depth;
    long voxels = 0, subs = 0;
    // Every voxel (enumerated from the full tree): same colour, normal, material through the
    // compact tree's lookup; at level depth-1 the lookup returns the brick's entry.
    svo_for_each_voxel(full, [&](glm::uvec3 cell, uint64_t fa) {
        const rk_svo_hit b = rk_svo_lookup(gc.data(), compact.desc_words, compact.gpu_brick_base_word(), depth, cell, depth);
        ASSERT_TRUE(b.found);
        ASSERT_EQ(b.level, depth);
        ASSERT_EQ(compact.color[b.attr], full.color[fa]);
        ASSERT_EQ(compact.normal[b.attr], full.normal[fa]);
        ASSERT_EQ(compact.material[b.attr], full.material[fa]);
        ++voxels;
        const rk_svo_hit s = rk_svo_lookup(gc.data(), compact.desc_words, compact.gpu_brick_base_word(), depth, cell, depth - 1);
        ASSERT_TRUE(s.found);
        ASSERT_EQ(s.level, depth - 1);
        ASSERT_EQ(s.attr, s.ordinal);  // the brick's own entry
        ASSERT_EQ(compact.color[s.attr], full.color[s.ordinal]);
        ++subs;
    });
    EXPECT_EQ(voxels, static_cast<long>(full.voxel_count));
    EXPECT_GT(subs, 0);
    // A trace stopped at level depth-1 reads the brick's attributes too.
    const rk_svo_tree tree = svo_trace_tree(compact, depth - 1);
    const rk_svo_trace_hit h = rk_svo_trace(gc.data(), tree, glm::vec3(compact.root_min) + glm::vec3(-1.0f, 0.5f, 0.5f) * compact.root_size,
                                            glm::vec3(1.0f, 0.0f, 0.0f), RK_FLT_MAX, glm::vec2(0.0f));
    ASSERT_TRUE(h.hit);
    EXPECT_EQ(h.level, depth - 1);
    EXPECT_EQ(rk_svo_trace_attr(gc.data(), tree, h), h.node);
    // File round trip; an inconsistent flag is corrupt.
    std::vector<uint8_t> bytes;
    SvoTree back;
    ASSERT_TRUE(svo_save(compact, bytes, st)) << st.message;
    ASSERT_TRUE(svo_load(bytes.data(), bytes.size(), back, st)) << st.message;
    EXPECT_EQ(back.brick_base, compact.brick_base);
    SvoTree bad = compact;
    bad.brick_base[3] &= ~RK_SVO_BRICK_SHARED_SUB;
    EXPECT_FALSE(svo_validate(bad, st));
    EXPECT_NE(st.message.find("brick_base[3]"), std::string::npos) << st.message;
    bad = full;
    bad.attributes |= RK_SVO_ATTR_SHARED_SUB;
    EXPECT_FALSE(svo_validate(bad, st));
    // Bytes against the thesis's format for the same tree (colour only, as the thesis stores).
    opt.attributes = RK_SVO_ATTR_COLOR;
    opt.depth = 10;
    SvoTree c_full, c_compact;
    opt.shared_sub_attributes = false;
    ASSERT_TRUE(build_svo(data.view(), opt, c_full, st)) << st.message;
    opt.shared_sub_attributes = true;
    ASSERT_TRUE(build_svo(data.view(), opt, c_compact, st)) << st.message;
    uint64_t nonleaf = 0;
    for (uint32_t l = 0; l < c_full.depth; ++l) nonleaf += c_full.level_nodes[l];
    const double thesis = 4.0 + 8.0 * (1.0 + 8.0 * static_cast<double>(nonleaf));
    const double r_full = static_cast<double>(c_full.structure_bytes() + c_full.attribute_bytes()) / thesis;
    const double r_compact = static_cast<double>(c_compact.structure_bytes() + c_compact.attribute_bytes()) / thesis;
    std::printf("figure depth 10, colour only: structure + colour = %.3f of the thesis's bytes with full LOD, %.3f with "
                "shared sub-node attributes (%.2f -> %.2f B/voxel)\n", r_full, r_compact,
                static_cast<double>(c_full.structure_bytes() + c_full.attribute_bytes()) / static_cast<double>(c_full.voxel_count),
                static_cast<double>(c_compact.structure_bytes() + c_compact.attribute_bytes()) / static_cast<double>(c_compact.voxel_count));
    EXPECT_GT(r_full, 0.25);
    EXPECT_LE(r_compact, 0.25);
}

// ---------------------------------------------------------------------------------------------
// strip_area: the closed-form area the builder uses for voxels whose column square lies inside
// the triangle's shadow (untextured, no vertex normals), against clipping the unit square to the
// strip in float64.

namespace {
double clipped_strip_area(double a, double b, double c)
{
    std::vector<std::pair<double, double>> poly = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    auto clip = [&](double pa, double pb, double pc) {  // keep pa x + pb y + pc >= 0
        std::vector<std::pair<double, double>> out;
        for (size_t i = 0; i < poly.size(); ++i) {
            const auto p = poly[i], q = poly[(i + 1) % poly.size()];
            const double dp = pa * p.first + pb * p.second + pc, dq = pa * q.first + pb * q.second + pc;
            if (dp >= 0) out.push_back(p);
            if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) {
                const double t = dp / (dp - dq);
                out.push_back({p.first + (q.first - p.first) * t, p.second + (q.second - p.second) * t});
            }
        }
        poly = out;
    };
    clip(a, b, c);
    clip(-a, -b, 1.0 - c);
    double twice = 0;
    for (size_t i = 0; i < poly.size(); ++i) {
        const auto p = poly[i], q = poly[(i + 1) % poly.size()];
        twice += p.first * q.second - q.first * p.second;
    }
    return std::fabs(twice) / 2;
}
}  // namespace

TEST(SvoBuildFilter, StripAreaMatchesClippingInFloat64)
{
    std::vector<float> slopes = {0.0f, -0.0f, 1.0f, -1.0f, 1e-30f, -1e-30f, 1e-7f, 0.5f, -0.5f, 0.999999f, 0.25f, -0.75f};
    std::vector<float> offsets = {0.0f, 1.0f, -1.0f, 0.5f, 2.0f, -2.0f, 1e-7f, -1e-7f, 1.0f - 1e-7f, 0.25f, 1.5f, -0.5f};
    uint64_t rng = 0x9E3779B97F4A7C15ull;
    auto uni = [&]() {
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<float>(static_cast<double>(rng >> 40) * (1.0 / 16777216.0));
    };
    double worst = 0;
    glm::vec3 worst_at(0.0f);
    size_t n = 0;
    auto check = [&](float a, float b, float c) {
        const double want = clipped_strip_area(a, b, c);
        const float got = svo_detail::strip_area(a, b, c);
        ASSERT_TRUE(std::isfinite(got)) << a << " " << b << " " << c;
        ASSERT_GE(got, 0.0f);
        ASSERT_LE(got, 1.0f);
        const double err = std::fabs(static_cast<double>(got) - want);
        if (err > worst) { worst = err; worst_at = {a, b, c}; }
        ++n;
    };
    for (float a : slopes)
        for (float b : slopes)
            for (float c : offsets) check(a, b, c);
    for (int i = 0; i < 200000; ++i) check(2 * uni() - 1, 2 * uni() - 1, 4 * uni() - 2);
    // A float area's rounding: a few ulps of 1.
    EXPECT_LE(worst, 1e-6) << "over " << n << " strips; worst at a = " << worst_at.x << ", b = " << worst_at.y << ", c = " << worst_at.z;
}
