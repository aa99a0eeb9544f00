// Level-of-detail traversal (RK_SVO_TRAVERSE_LOD=1), in a translation unit of its own inside
// test_svo_traverse, whose main file uses the default build (RK_SVO_TRAVERSE_LOD=0). Checks that the
// two builds coexist (each keeps its behaviour: raykit::rk_svo_trace here stops early, the other
// never does) and the LOD contract against the float64 dense-grid oracle:
//   - a hit node is non-empty, and no larger than the footprint at its distance unless it is a voxel;
//   - its parent was not small enough to stop at (the footprint grows along the ray, so the
//     parent, entered no later, had a footprint no larger);
//   - it is entered no later than the first voxel the exact ray passes through (a coarse node
//     contains its voxels), and where the exact ray enters it (hit point on its surface within
//     2e-6 root sizes, plus 8 ULPs of a far origin's distance).
#define RK_SVO_TRAVERSE_LOD 1
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "raykit/svo_build.hpp"
#include "raykit/svo_traverse.hpp"
#include "reference/svo_dda_ref.hpp"
#include "reference/svo_meshes.hpp"
#include "svo_trace_rays.hpp"

using namespace raykit;

// In ../../test_svo_traverse.cpp, built with the default RK_SVO_TRAVERSE_LOD=0.
bool svo_trace_default_build(const SvoTree& t, glm::vec3 origin, glm::vec3 dir, float t_max, glm::vec2 cone, uint32_t* level);

TEST(SvoTraceLod, StopsAtTheFootprintAndAgreesWithTheOracle)
{
    static_assert(RK_SVO_TRAVERSE_LOD == 1, "this translation unit tests the LOD build");
    SvoTree t;
    std::string why;
    ASSERT_TRUE(svotrace::build_colour_tree(rkmesh::figure(), 9, SvoFill::surface, t, why)) << why;
    const rk_svo_tree tree = svo_trace_tree(t);
    const std::vector<uint32_t> words = t.gpu_words();
    // Occupancy at every level (a node exists iff some voxel below it does).
    std::vector<rkref::DdaGrid> grid;
    for (int l = 0; l <= 9; ++l) grid.emplace_back(l);
    svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t) {
        for (int l = 0; l <= 9; ++l) grid[size_t(l)].set(int(c.x >> (9 - l)), int(c.y >> (9 - l)), int(c.z >> (9 - l)));
    });
    const rkref::DdaGrid& fine = grid[9];
    const double rs = double(t.root_size);
    const auto rays = svotrace::make_rays(40000, t.root_min, t.root_size, t.depth, 23);
    for (float px : {0.5f, 4.0f, 32.0f}) {
        const glm::vec2 cone = rk_svo_pixel_cone(1.0471976f, 512.0f, px);
        long coarse = 0, bad = 0, other_coarse = 0;
        double worst_off = 0.0;
        for (const svotrace::Ray& r : rays) {
            const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, r.origin, r.dir, r.t_max, cone);
            uint32_t level0 = 0;
            const bool hit0 = svo_trace_default_build(t, r.origin, r.dir, r.t_max, cone, &level0);
            other_coarse += hit0 && level0 < t.depth;
            if (!h.hit) {
                // Missing here means the full-detail build misses too (the same descent, stopped later).
                if (hit0) ++bad;
                continue;
            }
            coarse += h.level < t.depth;
            const double cs = rs / double(1u << h.level);
            const glm::dvec3 d(r.dir);
            const double dist = double(h.t) * glm::length(d);  // object units travelled
            const double foot = double(cone.x) + double(cone.y) * dist;
            const bool occupied = grid[h.level].get(int(h.cell.x), int(h.cell.y), int(h.cell.z));
            const rkref::DdaHit ref = rkref::dda_first_hit(fine, glm::dvec3(t.root_min), rs,
                                                           rkref::DdaRay{glm::dvec3(r.origin), d, double(r.t_max)},
                                                           8e-6 * rs, 2e-6 * rs);
            const double tunit = rs / glm::length(d);
            const double far_tol = 8.0 * 0x1p-24 * glm::length(glm::dvec3(r.origin) - glm::dvec3(t.root_min)) / rs;
            // The parent was entered no later than this node, with a footprint no larger: it
            // must have been too big to stop at then.
            bool parent_too_big = true;
            if (h.level > 0) {
                double tp = 0.0;
                const glm::ivec3 pc(int(h.cell.x >> 1), int(h.cell.y >> 1), int(h.cell.z >> 1));
                if (rkref::ray_touches_cell(glm::dvec3(t.root_min), rs, int(h.level) - 1, pc, rkref::DdaRay{glm::dvec3(r.origin), d, double(r.t_max)}, 0.0, &tp))
                    parent_too_big = 2.0 * cs > (double(cone.x) + double(cone.y) * tp * glm::length(d)) * (1.0 - 1e-4) - 1e-6 * rs;
            }
            bool ok = occupied && (h.level == t.depth || cs <= foot * (1.0 + 1e-4) + 1e-6 * rs) && parent_too_big;
            // Entered where the exact ray enters it: the hit point on the node's surface (anywhere
            // inside it for an origin inside, t = 0).
            const glm::dvec3 lo = glm::dvec3(t.root_min) + cs * glm::dvec3(h.cell);
            const glm::dvec3 p = glm::dvec3(r.origin) + double(h.t) * d;
            const double off = svotrace::surface_distance(p, lo, cs, h.t == 0.0f) / rs;
            if (far_tol < 8.0 * 0x1p-24 * 10.0) worst_off = std::max(worst_off, off);  // (origins within 10 root sizes)
            ok = ok && off <= 2e-6 + far_tol;
            // No later than the first voxel the exact ray passes through, unless that voxel is
            // inside the node hit (then the node's own entry is what counts, checked by parity).
            const int sh = int(t.depth - h.level);
            if (ok && ref.solid && glm::ivec3(ref.cell_solid.x >> sh, ref.cell_solid.y >> sh, ref.cell_solid.z >> sh) != glm::ivec3(h.cell)) {
                double dmin = 1.0;
                for (int a = 0; a < 3; ++a)
                    if (d[a] != 0.0) dmin = std::min(dmin, std::abs(d[a]) / glm::length(d));
                ok = double(h.t) <= ref.t_solid + (2e-6 + far_tol) * tunit / dmin + 1e-6 * ref.t_solid;
            }
            if (!ok) {
                if (bad < 5)
                    ADD_FAILURE() << px << " px [" << svotrace::family_names[r.family] << "] L" << h.level << " t " << h.t
                                  << " size " << cs << " footprint " << foot << " occupied " << occupied << " ref solid "
                                  << ref.solid << " t " << ref.t_solid;
                ++bad;
            }
        }
        std::printf("[trace] LOD %4.1f px cone: %zu rays, %ld stopped above the voxels, %ld failures, worst hit-point "
                    "offset %.2e root (origins within 10 root sizes)\n", px, rays.size(), coarse, bad, worst_off);
        EXPECT_EQ(bad, 0);
        EXPECT_GT(coarse, 1000);
        EXPECT_EQ(other_coarse, 0) << "the RK_SVO_TRAVERSE_LOD=0 build ignores the cone";
    }
}
