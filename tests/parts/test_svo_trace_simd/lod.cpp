// test_svo_trace_simd's second build: level of detail on and an iteration bound of 96, so that the
// lanes' LOD stop and their bound are compared with rk_svo_trace's too (grazing rays and deep trees
// reach 96 iterations).
#define RK_SVO_TRAVERSE_LOD 1
#define RK_SVO_TRAVERSE_MAX_ITER 96
#include "../../svo_trace_simd_check.hpp"

TEST(SvoTraceSimd, SameAnswersWithLodAndASmallBound)
{
    if (!raykit::svo_trace_simd_available()) GTEST_SKIP() << "this CPU or build has no AVX2 lanes";
    // A footprint of 0.002 + 0.004 * distance (world units): stops at several levels.
    const SimdTally t = compare_everything(glm::vec2(0.002f, 0.004f));
    std::printf("[simd] LOD build, bound 96: %ld rays (%ld hits, %ld at the bound), %ld differ\n", t.rays, t.hits, t.bound,
                t.differ);
    EXPECT_GE(t.rays, 500000);
    EXPECT_GT(t.bound, 100);  // the bound path is exercised
}
