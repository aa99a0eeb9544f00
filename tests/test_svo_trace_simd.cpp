// svo_trace_rays (raykit/svo_trace_simd.hpp) against rk_svo_trace per ray: the same answer in every
// bit for every ray (tests/svo_trace_simd_check.hpp), in the default build here and in a
// level-of-detail build with a small iteration bound in parts/test_svo_trace_simd/lod.cpp.
#include "svo_trace_simd_check.hpp"

static_assert(RK_SVO_TRAVERSE_LOD == 0 && RK_SVO_TRAVERSE_MAX_ITER == 0, "the default build");

TEST(SvoTraceSimd, SameAnswersAsPerRayTrace)
{
    if (!raykit::svo_trace_simd_available()) GTEST_SKIP() << "this CPU or build has no AVX2 lanes: svo_trace_rays is rk_svo_trace per ray here";
    const SimdTally t = compare_everything(glm::vec2(0.0f));
    std::printf("[simd] default build: %ld rays (%ld hits, %llu loop iterations), %ld differ\n", t.rays, t.hits,
                t.iterations, t.differ);
    EXPECT_GE(t.rays, 500000);
    EXPECT_GT(t.hits, t.rays / 10);
}

TEST(SvoTraceSimd, EmptyAndShortBatches)
{
    raykit::SvoTree t = svotest::pack_cells(3, svotest::random_cells(3, 100, 9));
    const raykit::rk_svo_tree tree = raykit::svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    raykit::svo_trace_rays(words.data(), tree, nullptr, 0, nullptr);  // nothing to do, nothing touched
    // Fewer rays than lanes, and rays the set-up answers alone (misses, zero directions).
    std::vector<raykit::SvoRay> rays(3);
    rays[0].origin = glm::vec3(0.5f, 0.5f, -1.0f);
    rays[1].dir = glm::vec3(0.0f);
    rays[2].origin = glm::vec3(5.0f);
    std::vector<raykit::rk_svo_trace_hit> hits(3);
    raykit::svo_trace_rays(words.data(), tree, rays.data(), 3, hits.data());
    for (int i = 0; i < 3; ++i) {
        const raykit::rk_svo_trace_hit h = raykit::rk_svo_trace(words.data(), tree, rays[size_t(i)].origin, rays[size_t(i)].dir,
                                                                rays[size_t(i)].t_max, glm::vec2(0.0f));
        EXPECT_TRUE(same_hit(h, hits[size_t(i)])) << i;
    }
    EXPECT_FALSE(hits[1].hit);
    EXPECT_FALSE(hits[2].hit);
}
