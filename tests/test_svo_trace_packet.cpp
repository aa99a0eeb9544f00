// svo_trace_packet8 / svo_trace_packet16 / svo_trace_packets (raykit/svo_trace_packet.hpp: 8 or 16
// coherent rays sharing one traversal; 16 on AVX-512 lanes where the CPU has them, else as two 8-ray
// packets, which must give the same bits) against rk_svo_trace per ray, on camera-tile packets, the
// secondary rays of a camera's hits in their pixels' tiles (shadow rays towards a sun, a sun along
// an axis and a point light; mirror reflections), random coherent packets and adversarial packets (every family of svo_trace_rays.hpp:
// axis-parallel, through edges and corners, origins inside and on the lattice, mixed octants, far
// origins, short t_max)
// over random trees and voxelised meshes at depths 3, 6, 10 and 16 (and coarse max_level stops).
// Each ray must give rk_svo_trace's hit flag, level and cell, and t within kTol root sizes (plus
// 8 ULPs of a far origin's distance), and in the same cell the same face normal (the packets compute
// it on their lanes, a twin of rk_svo_trace_entry_normal_); where it does not, the packet's answer
// is checked against the float64 brute-force reference (tests/reference/svo_dda_ref.hpp) with the
// acceptance rule of test_svo_traverse: a hit on an occupied cell the exact ray touches, entered no earlier than the
// first touch and no later than the first solid voxel (within tolerance); a miss only when the exact
// ray passes through no voxel by more than the tolerance. Counts are printed.
// The checks live in svo_trace_packet_check.hpp; parts/test_svo_trace_packet/lod.cpp runs them in a
// RK_SVO_TRAVERSE_LOD=1 build with a footprint cone.
#include "svo_trace_packet_check.hpp"

#if defined(__SSE__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

static_assert(RK_SVO_TRAVERSE_LOD == 0, "the default build");

TEST(SvoTracePacket, RandomTrees)
{
    unsigned tw = 0u, th = 0u;
    svo_trace_packet_best_tile(tw, th);
    std::printf("[packet] default tile %ux%u; 16- and 32-ray packets on %s\n", tw, th,
                tw == 8u ? "AVX-512 lanes" : "AVX2 registers (no AVX-512F here)");
    Tally total;
    for (uint32_t depth : {1u, 2u, 3u, 6u, 10u}) {
        const size_t side3 = size_t(1) << (3 * std::min(depth, 8u));
        const size_t counts[] = {1, std::max<size_t>(1, side3 / 100), side3 / 8 + 1, side3 / 2 + 1};
        for (int k = 0; k < 4; ++k) {
            svotest::PackOptions po;
            po.pointer_bits = (k & 1) ? 4 : 23;
            SvoTree t = svotest::pack_cells(depth, svotest::random_cells(depth, std::min<size_t>(counts[k], 12000), 7 * depth + k), po);
            t.root_min = glm::vec3(-2.0f, 0.5f, 8.0f);
            t.root_size = 4.0f;
            all_sets("random d" + std::to_string(depth) + " k" + std::to_string(k), t, total, 1);
        }
    }
    {
        SvoTree t = svotest::pack_cells(16, svotest::random_cells(16, 2500, 5));
        t.root_min = glm::vec3(-1024.0f);
        t.root_size = 2048.0f;
        all_sets("random d16", t, total, 2);
    }
    {
        // Depth 16 with hits: a cluster of voxels around the centre, seen by narrow cameras.
        std::vector<glm::uvec3> cells;
        for (uint32_t z = 0; z < 24; ++z)
            for (uint32_t y = 0; y < 24; ++y)
                for (uint32_t x = 0; x < 24; ++x)
                    if (svotest::test_hash((uint64_t(z) << 20) | (uint64_t(y) << 10) | x) % 3u == 0u)
                        cells.push_back(glm::uvec3(32756u) + glm::uvec3(x, y, z));
        SvoTree t = svotest::pack_cells(16, cells);
        t.root_min = glm::vec3(-1024.0f);
        t.root_size = 2048.0f;
        compare("clustered d16 camera", t, camera(t, glm::vec3(0.45f, 0.35f, 1.0f), 128, 96, 1.6f, 2.5e-4f), 128, total);
        compare("clustered d16 camera axis-aligned", t, camera(t, glm::vec3(0.0f, 0.0f, 1.0f), 96, 96, 1.6f, 2.5e-4f), 96, total);
        compare("clustered d16 camera close", t, camera(t, glm::vec3(-0.3f, 0.8f, 0.2f), 64, 64, 1e-3f, 0.6f), 64, total);
    }
    expect_totals("random trees", total);
}

TEST(SvoTracePacket, VoxelisedMeshes)
{
    struct Build {
        const char* name;
        SvoMeshData mesh;
        int depth;
        SvoFill fill;
    };
    std::vector<Build> builds;
    builds.push_back({"torus d3 surface", rkmesh::torus(48, 24), 3, SvoFill::surface});
    builds.push_back({"menger d6 solid", rkmesh::menger_sponge(2), 6, SvoFill::solid});
    builds.push_back({"torus_69120 d10 surface", rkmesh::torus(192, 180), 10, SvoFill::surface});
    builds.push_back({"uv_sphere_69632 d10 surface", rkmesh::uv_sphere(256, 137), 10, SvoFill::surface});
    builds.push_back({"figure d10 surface", rkmesh::figure(), 10, SvoFill::surface});
    builds.push_back({"far torus d6", rkmesh::transformed(rkmesh::torus(32, 16), 1.0, glm::dvec3(3e4, -2e4, 1e4)), 6, SvoFill::surface});
    Tally total;
    for (Build& b : builds) {
        SvoTree t;
        std::string why;
        if (!svotrace::build_colour_tree(b.mesh, b.depth, b.fill, t, why)) {
            ADD_FAILURE() << b.name << ": " << why;
            continue;
        }
        all_sets(b.name, t, total, 1);
        for (uint32_t level : {1u, 2u, uint32_t(b.depth) - 1u}) {
            const std::string coarse = std::string(b.name) + " max_level " + std::to_string(level);
            compare((coarse + " camera").c_str(), t, camera(t, glm::vec3(0.45f, 0.35f, 1.0f), 64, 48), 64, total, level);
            compare((coarse + " adversarial").c_str(), t, adversarial(t, 2000, 40 + level, false), 0, total, level);
        }
    }
    expect_totals("meshes", total);
}

TEST(SvoTracePacket, NoNanOnHostileInput)
{
    SvoTree t = svotest::pack_cells(6, svotest::random_cells(6, 3000, 3));
    const std::vector<uint32_t> words = t.gpu_words();
    const rk_svo_tree tree = svo_trace_tree(t);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    const float odd[] = {0.0f, -0.0f, 1e-38f, -1e-45f, 1e30f, -3e38f, 1.0f, 0.5f};
    std::vector<SvoRay> all;
    for (int p = 0; p < 2000; ++p) {
        SvoRay r[8];
        rk_svo_trace_hit h[8];
        for (SvoRay& s : r) {
            s.origin = glm::vec3(U(rng), U(rng), U(rng)) * (p % 3 == 0 ? 1e30f : 2.0f);
            s.dir = glm::vec3(odd[rng() % 8], odd[rng() % 8], odd[rng() % 8]) * ((rng() & 1) ? 1.0f : U(rng));
            s.t_max = (rng() % 4 == 0) ? -1.0f : 3e38f;
        }
        svo_trace_packet8(words.data(), tree, r, h);
        for (const rk_svo_trace_hit& x : h) {
            EXPECT_FALSE(std::isnan(x.t));
            EXPECT_FALSE(std::isnan(x.normal.x) || std::isnan(x.normal.y) || std::isnan(x.normal.z));
        }
        all.insert(all.end(), r, r + 8);
    }
    // The same rays against rk_svo_trace (huge and zero directions, far origins, negative t_max).
    Tally total;
    compare("hostile input", t, all, 0, total);
    EXPECT_EQ(total.bad, 0);
}

// Tiles that do not divide the frame, a partial last row, odd and out-of-range tile sizes (a tile
// whose ray count overflows 32 bits traces 8 rays at a time) and the default tile: every answer is
// rk_svo_trace's (or an accepted tie), whatever the tile.
TEST(SvoTracePacket, PartialAndOddTiles)
{
    SvoTree t = svotest::pack_cells(7, svotest::random_cells(7, 30000, 17));
    t.root_min = glm::vec3(-1.0f, 2.0f, 0.5f);
    t.root_size = 3.0f;
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    const size_t w = 37;
    std::vector<SvoRay> rays = camera(t, glm::vec3(0.45f, 0.35f, 1.0f), int(w), 13);
    rays.resize(rays.size() - 11);  // a partial last row
    std::vector<rk_svo_trace_hit> one(rays.size()), pk(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) one[i] = rk_svo_trace(words.data(), tree, rays[i].origin, rays[i].dir, rays[i].t_max, glm::vec2(0.0f));
    const unsigned tiles[][2] = {{0u, 0u}, {1u, 1u}, {3u, 5u}, {5u, 6u}, {8u, 4u}, {4u, 8u}, {32u, 1u}, {1u, 32u},
                                 {33u, 1u}, {6u, 6u}, {0x10000u, 0x10000u}, {0x80000001u, 2u}};
    Tally total;
    for (const auto& tw : tiles) {
        std::fill(pk.begin(), pk.end(), rk_svo_trace_hit{});
        svo_trace_packets(words.data(), tree, rays.data(), rays.size(), w, pk.data(), tw[0], tw[1]);
        const std::string label = "tile " + std::to_string(tw[0]) + "x" + std::to_string(tw[1]);
        compare_hits(label.c_str(), t, tree, rays, pk, one, total, glm::vec2(0.0f));
    }
    // Ray counts below a packet's width.
    for (unsigned n : {1u, 7u, 9u, 17u, 31u}) {
        std::fill(pk.begin(), pk.end(), rk_svo_trace_hit{});
        svo_trace_packet32(words.data(), tree, rays.data() + 100, pk.data(), n);
        for (unsigned i = 0; i < n; ++i) EXPECT_TRUE(bit_equal(pk[i], one[100 + i])) << "svo_trace_packet32 n=" << n << " ray " << i;
    }
    EXPECT_EQ(total.bad, 0);
    EXPECT_GT(total.hits, total.rays / 4);
}

#if defined(__SSE__) || defined(_M_X64)
// Rays with t_max 0 that start inside solid voxels hit them at t = 0; the packets' closed end of
// the interval must not be a denormal that denormals-are-zero (MXCSR DAZ, which Embree recommends)
// reads as 0.
TEST(SvoTracePacket, ZeroTmaxUnderDenormalsAreZero)
{
    std::vector<glm::uvec3> cells;
    for (uint32_t z = 8; z < 24; ++z)
        for (uint32_t y = 8; y < 24; ++y)
            for (uint32_t x = 8; x < 24; ++x) cells.push_back(glm::uvec3(x, y, z));
    SvoTree t = svotest::pack_cells(5, cells);
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<float> U(0.3f, 0.7f), D(-1.0f, 1.0f);
    std::vector<SvoRay> rays(640);
    for (SvoRay& r : rays) {
        r.origin = t.root_min + t.root_size * glm::vec3(U(rng), U(rng), U(rng));
        r.dir = glm::vec3(D(rng), D(rng), D(rng)) + glm::vec3(1e-3f);
        r.t_max = 0.0f;
    }
    const unsigned csr = _mm_getcsr();
    for (unsigned mode : {0u, 0x8040u}) {  // off; DAZ (bit 6) and FTZ (bit 15)
        _mm_setcsr(csr | mode);
        std::vector<rk_svo_trace_hit> pk(rays.size());
        long one_hits = 0, pk_hits[3] = {0, 0, 0};
        for (size_t i = 0; i < rays.size(); ++i)
            one_hits += rk_svo_trace(words.data(), tree, rays[i].origin, rays[i].dir, rays[i].t_max, glm::vec2(0.0f)).hit ? 1 : 0;
        for (unsigned k = 0; k < 3u; ++k) {
            svo_trace_packets(words.data(), tree, rays.data(), rays.size(), 32, pk.data(), k == 2u ? 8u : 4u, k == 0u ? 2u : 4u);
            for (const rk_svo_trace_hit& h : pk) pk_hits[k] += h.hit ? 1 : 0;
        }
        _mm_setcsr(csr);
        EXPECT_EQ(one_hits, long(rays.size())) << "mode " << mode;
        for (unsigned k = 0; k < 3u; ++k) EXPECT_EQ(pk_hits[k], one_hits) << "mode " << mode << " packet " << k;
    }
}
#endif
