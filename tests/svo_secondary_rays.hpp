// Secondary rays of a camera frame for the octree packet tests and raykit_svo_packet_ab: shadow
// rays and mirror reflections from each primary hit, each ray in its pixel's place in the frame (so
// a pixel tile's secondary rays are its pixels'). Only raykit and GLM; no test framework. TU-local
// (an unnamed namespace): rk_svo_trace differs between translation units built with different
// RK_SVO_TRAVERSE_* macros, so one shared inline definition would break the one-definition rule.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "raykit/svo_secondary.hpp"
#include "raykit/svo_trace_simd.hpp"

namespace svotrace {
namespace {

enum class Secondary { sun, point, mirror };

/// From each hit of `frame` (rk_svo_trace's at full detail; the point from rk_svo_hit_point, the
/// start from rk_svo_secondary_origin, as svo_secondary.glsl does): shadow rays towards a directional
/// light of unit direction `light` (sun) or towards the point `light` (point; t_max its distance),
/// or the mirror reflection about the hit's face normal (mirror; rk_svo_interface_at's reflected
/// direction). A missed pixel's ray starts beyond the root's far corner and leaves along (1, 1, 1):
/// it misses at once, as it would in a renderer that traces every pixel.
inline std::vector<raykit::SvoRay> secondary_rays(const uint32_t* words, const raykit::rk_svo_tree& tree,
                                                  const std::vector<raykit::SvoRay>& frame, Secondary kind,
                                                  glm::vec3 light = glm::vec3(0.0f))
{
    std::vector<raykit::SvoRay> out(frame.size());
    for (std::size_t i = 0; i < frame.size(); ++i) {
        const raykit::SvoRay& r = frame[i];
        const raykit::rk_svo_trace_hit h = raykit::rk_svo_trace(words, tree, r.origin, r.dir, r.t_max, glm::vec2(0.0f));
        raykit::SvoRay& s = out[i];
        if (!h.hit) {
            s.origin = tree.root_min + glm::vec3(2.0f * tree.root_size);
            s.dir = glm::normalize(glm::vec3(1.0f));
            continue;
        }
        const glm::vec3 p = raykit::rk_svo_hit_point(tree, r.origin, r.dir, h);
        s.dir = kind == Secondary::sun     ? light
                : kind == Secondary::point ? glm::normalize(light - p)
                                           : raykit::rk_svo_interface_at(r.dir, h.normal, 1.0f, 1.5f).reflected;
        s.origin = raykit::rk_svo_secondary_origin(p, h.normal, s.dir, tree, h.level);
        if (kind == Secondary::point) s.t_max = glm::length(light - s.origin);
    }
    return out;
}

}  // namespace
}  // namespace svotrace
