// GPU parity for shaders/raykit/svo_traverse.glsl (RK_SVO_TRAVERSE_LOD=0; the LOD build is in
// parity_svo_trace_lod.cpp): rk_svo_trace and rk_svo_trace_attr on the driver against the C++ build,
// over random trees (depths 1..16, forced far pointers) and voxelised meshes, every adversarial ray
// family of svo_trace_rays.hpp and rays aimed at voxels, words from an SSBO and from the R32UI texture layout. Same node for
// every ray except ties (svotrace_gpu::compare).
#include <random>

#include "raykit/svo_build.hpp"
#include "reference/svo_meshes.hpp"
#include "svo_test_pack.hpp"
#include "svo_trace_gpu.hpp"

using namespace raykit;

TEST(GpuParity, SvoTraceRandomTrees)
{
    struct Spec { uint32_t depth; size_t cells; uint32_t pointer_bits; uint32_t max_level; };
    const Spec specs[] = {{1, 3, 23, 99}, {2, 20, 23, 99}, {3, 100, 23, 99}, {5, 3000, 4, 99},
                          {7, 4000, 23, 5}, {8, 6000, 23, 99}, {16, 3000, 23, 99}};
    for (const Spec& s : specs) {
        svotest::PackOptions po;
        po.pointer_bits = s.pointer_bits;
        SvoTree t = svotest::pack_cells(s.depth, svotest::random_cells(s.depth, s.cells, 1000 + s.depth), po);
        t.root_min = glm::vec3(-2.0f, 0.5f, 8.0f);
        t.root_size = 4.0f;
        const rk_svo_tree tree = svo_trace_tree(t, s.max_level);
        // The adversarial families, and rays aimed at voxels: random rays through a sparse deep
        // tree (depth 16: 3,000 voxels in 2^48 cells) almost never hit.
        std::vector<svotrace::Ray> rays = svotrace::make_rays(20000, t.root_min, t.root_size, s.depth, 7 + s.depth);
        std::vector<glm::ivec3> cells;
        svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t) { cells.push_back(glm::ivec3(c)); });
        const std::vector<svotrace::Ray> aimed = svotrace::aimed_rays(cells, t.root_min, t.root_size, s.depth, 5000, 3 + s.depth);
        rays.insert(rays.end(), aimed.begin(), aimed.end());
        const auto cpu = svotrace_gpu::cpu_trace(t.gpu_words(), tree, rays, glm::vec2(0.0f));
        for (bool texture : {false, true}) {
            const auto gpu = svotrace_gpu::gpu_trace(t, tree, rays, false, glm::vec2(0.0f), texture);
            char what[96];
            std::snprintf(what, sizeof what, "random d%u L%u pb%u %s", s.depth, tree.max_level, s.pointer_bits,
                          texture ? "texture" : "ssbo");
            // At least half the aimed rays hit (a max_level stop hits the voxel's ancestor).
            svotrace_gpu::compare(what, rays, gpu, cpu, t.root_min, t.root_size, 2e-6, 2500);
        }
    }
}

TEST(GpuParity, SvoTraceVoxelisedMeshes)
{
    struct Build { const char* name; SvoMeshData mesh; int depth; SvoFill fill; };
    std::vector<Build> builds;
    builds.push_back({"torus d8", rkmesh::torus(48, 24), 8, SvoFill::surface});
    builds.push_back({"menger d7 solid", rkmesh::menger_sponge(2), 7, SvoFill::solid});
    builds.push_back({"figure d10", rkmesh::figure(), 10, SvoFill::surface});
    for (Build& b : builds) {
        SvoTree t;
        std::string why;
        ASSERT_TRUE(svotrace::build_colour_tree(b.mesh, b.depth, b.fill, t, why)) << b.name << ": " << why;
        const rk_svo_tree tree = svo_trace_tree(t);
        const std::vector<svotrace::Ray> rays = svotrace::make_rays(30000, t.root_min, t.root_size, t.depth, 99);
        const auto cpu = svotrace_gpu::cpu_trace(t.gpu_words(), tree, rays, glm::vec2(0.0f));
        const auto gpu = svotrace_gpu::gpu_trace(t, tree, rays, false, glm::vec2(0.0f), false);
        svotrace_gpu::compare(b.name, rays, gpu, cpu, t.root_min, t.root_size, 2e-6, 2500);
    }
}
