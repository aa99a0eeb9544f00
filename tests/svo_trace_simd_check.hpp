// The comparison behind test_svo_trace_simd: svo_trace_rays (raykit/svo_trace_simd.hpp, the SIMD
// twin of rk_svo_trace's loop) against rk_svo_trace called per ray, field by field and bit for bit,
// over the traversal tests' ray families, voxelised meshes and camera frames. Included by each
// translation unit of the test with its own RK_SVO_TRAVERSE_* macros; everything here has internal
// linkage, so each TU compares its own build.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "raykit/svo_build.hpp"
#include "raykit/svo_trace_simd.hpp"
#include "reference/svo_meshes.hpp"
#include "svo_test_pack.hpp"
#include "svo_trace_rays.hpp"

namespace {

struct SimdTally {
    long rays = 0, hits = 0, differ = 0, bound = 0;
    unsigned long long iterations = 0;
};

uint32_t fbits(float f)
{
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

bool same_hit(const raykit::rk_svo_trace_hit& a, const raykit::rk_svo_trace_hit& b)
{
    return a.hit == b.hit && fbits(a.t) == fbits(b.t) && a.level == b.level && a.cell == b.cell &&
           fbits(a.normal.x) == fbits(b.normal.x) && fbits(a.normal.y) == fbits(b.normal.y) &&
           fbits(a.normal.z) == fbits(b.normal.z) && a.node == b.node && a.brick_bit == b.brick_bit &&
           a.brick_mask == b.brick_mask && a.iterations == b.iterations;
}

/// Traces `rays` both ways and counts the rays whose answers differ in any bit (printing the first).
void compare_rays(const char* what, const raykit::SvoTree& t, const std::vector<raykit::SvoRay>& rays, glm::vec2 cone,
                  SimdTally& tally, uint32_t max_level = ~0u)
{
    const raykit::rk_svo_tree tree = raykit::svo_trace_tree(t, max_level);
    const std::vector<uint32_t> words = t.gpu_words();
    std::vector<raykit::rk_svo_trace_hit> simd(rays.size()), one(rays.size());
    raykit::svo_trace_rays(words.data(), tree, rays.data(), rays.size(), simd.data(), cone, raykit::SvoTraceMode::best);
    for (size_t i = 0; i < rays.size(); ++i)
        one[i] = raykit::rk_svo_trace(words.data(), tree, rays[i].origin, rays[i].dir, rays[i].t_max, cone);
    long differ = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        tally.iterations += one[i].iterations;
        tally.hits += one[i].hit ? 1 : 0;
        tally.bound += one[i].iterations >= raykit::rk_svo_trace_iteration_bound(tree) ? 1 : 0;
        if (same_hit(simd[i], one[i])) continue;
        if (differ++ == 0)
            ADD_FAILURE() << what << ": ray " << i << " (" << rays[i].origin.x << ", " << rays[i].origin.y << ", "
                          << rays[i].origin.z << ") dir (" << rays[i].dir.x << ", " << rays[i].dir.y << ", " << rays[i].dir.z
                          << "): simd hit " << simd[i].hit << " t " << simd[i].t << " level " << simd[i].level << " iter "
                          << simd[i].iterations << "; per ray hit " << one[i].hit << " t " << one[i].t << " level "
                          << one[i].level << " iter " << one[i].iterations;
    }
    tally.rays += long(rays.size());
    tally.differ += differ;
    EXPECT_EQ(differ, 0) << what;
}

std::vector<raykit::SvoRay> family_rays(const raykit::SvoTree& t, size_t n, uint64_t seed)
{
    std::vector<raykit::SvoRay> out;
    for (const svotrace::Ray& r : svotrace::make_rays(n, t.root_min, t.root_size, t.depth, seed)) {
        raykit::SvoRay s;
        s.origin = r.origin;
        s.dir = r.dir;
        s.t_max = r.t_max;
        out.push_back(s);
    }
    return out;
}

/// A w x h pinhole frame looking at the root's centre from `from` (a direction), as a camera sees it.
std::vector<raykit::SvoRay> camera_rays(const raykit::SvoTree& t, glm::vec3 from, int w, int h)
{
    const glm::vec3 centre = t.root_min + glm::vec3(0.5f * t.root_size);
    const glm::vec3 eye = centre + glm::normalize(from) * (1.6f * t.root_size);
    const glm::vec3 f = glm::normalize(centre - eye);
    const glm::vec3 r = glm::normalize(glm::cross(f, glm::vec3(0.0f, 1.0f, 0.0f)));
    const glm::vec3 u = glm::cross(r, f);
    std::vector<raykit::SvoRay> out;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float sx = (2.0f * (float(x) + 0.5f) / float(w) - 1.0f) * 0.45f;
            const float sy = (2.0f * (float(y) + 0.5f) / float(h) - 1.0f) * 0.45f;
            raykit::SvoRay s;
            s.origin = eye;
            s.dir = glm::normalize(f + sx * r + sy * u);
            out.push_back(s);
        }
    return out;
}

/// Every family on random trees (depths 1..8, near and far pointers), voxelised meshes, coarse
/// max_level stops, a depth-16 tree and camera frames; `cone` is passed to both (a LOD build uses it).
SimdTally compare_everything(glm::vec2 cone)
{
    SimdTally tally;
    for (uint32_t depth = 1; depth <= 8; ++depth)
        for (int k = 0; k < 4; ++k) {
            const size_t side3 = size_t(1) << (3 * depth);
            const size_t counts[] = {1, std::max<size_t>(1, side3 / 100), side3 / 8 + 1, side3 / 2 + 1};
            svotest::PackOptions po;
            po.pointer_bits = (k & 1) ? 4 : 23;
            raykit::SvoTree t = svotest::pack_cells(depth, svotest::random_cells(depth, std::min<size_t>(counts[k], 12000), 7 * depth + k), po);
            t.root_min = glm::vec3(-2.0f, 0.5f, 8.0f);
            t.root_size = 4.0f;
            char what[64];
            std::snprintf(what, sizeof what, "random d%u k%d pb%u", depth, k, po.pointer_bits);
            compare_rays(what, t, family_rays(t, 6000, 100 * depth + uint64_t(k)), cone, tally);
        }
    {
        raykit::SvoTree t = svotest::pack_cells(16, svotest::random_cells(16, 2500, 5));
        t.root_min = glm::vec3(-1024.0f);
        t.root_size = 2048.0f;
        compare_rays("random d16", t, family_rays(t, 20000, 16), cone, tally);
    }
    struct Build {
        const char* name;
        raykit::SvoMeshData mesh;
        int depth;
        raykit::SvoFill fill;
    };
    std::vector<Build> builds;
    builds.push_back({"torus d8 surface", rkmesh::torus(48, 24), 8, raykit::SvoFill::surface});
    builds.push_back({"menger d7 solid", rkmesh::menger_sponge(2), 7, raykit::SvoFill::solid});
    builds.push_back({"figure d10 surface", rkmesh::figure(), 10, raykit::SvoFill::surface});
    builds.push_back({"far torus d8", rkmesh::transformed(rkmesh::torus(32, 16), 1.0, glm::dvec3(3e4, -2e4, 1e4)), 8,
                      raykit::SvoFill::surface});
    for (Build& b : builds) {
        raykit::SvoTree t;
        std::string why;
        if (!svotrace::build_colour_tree(b.mesh, b.depth, b.fill, t, why)) {
            ADD_FAILURE() << b.name << ": " << why;
            continue;
        }
        compare_rays(b.name, t, family_rays(t, 30000, 17), cone, tally);
        std::string cam = std::string(b.name) + " camera";
        compare_rays(cam.c_str(), t, camera_rays(t, glm::vec3(0.45f, 0.35f, 1.0f), 160, 120), cone, tally);
        std::string cam2 = std::string(b.name) + " camera, axis-aligned";
        compare_rays(cam2.c_str(), t, camera_rays(t, glm::vec3(0.0f, 0.0f, 1.0f), 96, 96), cone, tally);
        for (uint32_t level : {0u, 1u, 4u, uint32_t(b.depth) - 1u}) {
            std::string coarse = std::string(b.name) + " max_level " + std::to_string(level);
            compare_rays(coarse.c_str(), t, family_rays(t, 4000, 40 + level), cone, tally, level);
        }
    }
    return tally;
}

}  // namespace
