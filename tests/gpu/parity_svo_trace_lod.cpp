// GPU parity for shaders/raykit/svo_traverse.glsl built with RK_SVO_TRAVERSE_LOD=1 (level-of-detail
// stops), in a translation unit of its own: parity_svo_trace.cpp links the RK_SVO_TRAVERSE_LOD=0 C++
// build into the same executable, and both must keep their own behaviour (checked below: this
// build stops early where the other cannot).
#define RK_SVO_TRAVERSE_LOD 1
#include <random>

#include "raykit/svo_build.hpp"
#include "reference/svo_meshes.hpp"
#include "svo_trace_gpu.hpp"

using namespace raykit;

TEST(GpuParity, SvoTraceLevelOfDetail)
{
    static_assert(RK_SVO_TRAVERSE_LOD == 1, "this translation unit tests the LOD build");
    SvoTree t;
    std::string why;
    ASSERT_TRUE(svotrace::build_colour_tree(rkmesh::figure(), 10, SvoFill::surface, t, why)) << why;
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    const std::vector<svotrace::Ray> rays = svotrace::make_rays(30000, t.root_min, t.root_size, t.depth, 5);
    for (float px : {1.0f, 8.0f, 64.0f}) {
        // A pixel cone of a 60 degree camera, `px` pixels wide, on a 512-pixel image.
        const glm::vec2 cone = rk_svo_pixel_cone(1.0471976f, 512.0f, px);
        const std::vector<svotrace_gpu::Out> cpu = svotrace_gpu::cpu_trace(words, tree, rays, cone);
        long coarse = 0;
        for (const svotrace_gpu::Out& o : cpu) coarse += o.hit != 0u && o.level < t.depth;
        // The LOD build really stops early (the LOD-off build in the other translation unit never does).
        EXPECT_GT(coarse, 100) << "cone " << px << " px";
        const auto gpu = svotrace_gpu::gpu_trace(t, tree, rays, true, cone, false);
        char what[64];
        std::snprintf(what, sizeof what, "LOD figure d10, %g px cone (%ld coarse)", px, coarse);
        svotrace_gpu::compare(what, rays, gpu, cpu, t.root_min, t.root_size, 2e-6, 3000);
    }
}
