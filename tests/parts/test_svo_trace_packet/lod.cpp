// test_svo_trace_packet's second build: level of detail on, so that the packets' footprint stops
// (each lane's test on the children it enters, answered when the walk reaches that child) are
// compared with rk_svo_trace's, ray by ray, on random trees and voxelised meshes, with footprints
// that stop rays at several levels (growing with distance, constant, steep) and one that stops every
// ray at the root.
#define RK_SVO_TRAVERSE_LOD 1
#include "../../svo_trace_packet_check.hpp"

TEST(SvoTracePacket, LodBuildSameAnswers)
{
    // A footprint of 0.003 + 0.008 * distance (world units; the roots are 2-4 units wide).
    const glm::vec2 cone(0.003f, 0.008f);
    Tally total;
    for (uint32_t depth : {3u, 6u, 10u}) {
        const size_t side3 = size_t(1) << (3 * std::min(depth, 8u));
        for (int k = 0; k < 2; ++k) {
            SvoTree t = svotest::pack_cells(depth, svotest::random_cells(depth, std::min<size_t>(k ? side3 / 2 + 1 : side3 / 8 + 1, 12000),
                                                                          11 * depth + uint64_t(k)));
            t.root_min = glm::vec3(-2.0f, 0.5f, 8.0f);
            t.root_size = 4.0f;
            all_sets("LOD random d" + std::to_string(depth) + " k" + std::to_string(k), t, total, 1, cone);
        }
    }
    struct Build {
        const char* name;
        SvoMeshData mesh;
        int depth;
    };
    std::vector<Build> builds;
    builds.push_back({"LOD torus_69120 d10", rkmesh::torus(192, 180), 10});
    builds.push_back({"LOD figure d12", rkmesh::figure(), 12});
    for (Build& b : builds) {
        SvoTree t;
        std::string why;
        if (!svotrace::build_colour_tree(b.mesh, b.depth, SvoFill::surface, t, why)) {
            ADD_FAILURE() << b.name << ": " << why;
            continue;
        }
        all_sets(b.name, t, total, 1, cone);
        compare((std::string(b.name) + " max_level 7 camera").c_str(), t, camera(t, glm::vec3(0.45f, 0.35f, 1.0f), 64, 48), 64, total,
                7u, cone);
    }
    // Footprints of other shapes on a depth-8 tree 4 units wide: constant (bias only, 0.1 units: every
    // ray stops at level 6, 1/16 unit, wherever it is, so a node's rays are answered among its
    // children at once) and steep (rays stop a few levels below the root, deeper near the camera).
    SvoTree r8 = svotest::pack_cells(8, svotest::random_cells(8, 12000, 5));
    r8.root_min = glm::vec3(-2.0f, 0.5f, 8.0f);
    r8.root_size = 4.0f;
    Tally flat, steep;
    // (Without the secondary sets: they trace without a footprint, and their leaf hits would not be
    // the footprint's.)
    all_sets("LOD random d8, constant footprint", r8, flat, 1, glm::vec2(0.1f, 0.0f), false);
    all_sets("LOD random d8, steep footprint", r8, steep, 1, glm::vec2(0.0f, 0.05f), false);
    EXPECT_EQ(flat.coarse, flat.hits) << "a constant footprint of 1.6 level-6 nodes stops every hit above the leaves";
    EXPECT_GT(steep.coarse, steep.hits / 2);
    expect_totals("LOD constant footprint", flat);
    expect_totals("LOD steep footprint", steep);
    expect_totals("LOD build", total);
    std::printf("[packet] LOD build: %ld of %ld hits stop above the tree's max_level\n", total.coarse, total.hits);
    EXPECT_GT(total.coarse, total.hits / 5) << "the footprint must stop rays at coarse levels for the test to mean anything";

    // A footprint wider than the root: every entering ray stops there (rk_svo_trace_begin_'s answer).
    Tally root;
    SvoTree t = svotest::pack_cells(6, svotest::random_cells(6, 3000, 3));
    compare("LOD root stop", t, camera(t, glm::vec3(0.45f, 0.35f, 1.0f), 32, 32), 32, root, ~0u, glm::vec2(10.0f, 0.0f));
    EXPECT_EQ(root.bad, 0);
    EXPECT_EQ(root.exact, root.rays);
    EXPECT_EQ(root.coarse, root.hits);
    EXPECT_GT(root.hits, 100);
}
