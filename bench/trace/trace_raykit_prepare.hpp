// raykit — bench/trace/trace_raykit_prepare.hpp: how raykit_bench_trace runs raykit's tracers over
// a scene (the tree, its words and uniforms, one SpanTracer per thread), shared by trace_raykit.cpp
// (full detail) and trace_raykit_lod.cpp (a RK_SVO_TRAVERSE_LOD=1 unit). Included once per unit,
// after its RK_SVO_* macros; everything is unit-local.
#pragma once

#include <cmath>
#include <memory>

#include "raykit/svo_build.hpp"
#include "raykit/svo_trace_packet.hpp"
#include "raykit/svo_trace_simd.hpp"
#include "raykit/svo_traverse.hpp"
#include "trace_harness.hpp"

namespace rktrace {
namespace {


struct Tree {
    raykit::SvoTree tree;
    std::vector<uint32_t> words;
    raykit::rk_svo_tree uniforms;
};

/// raykit's tracer of mode 0 (rk_svo_trace per ray), 1 (svo_trace_rays) or 2 (svo_trace_packets)
/// at `depth`; in a RK_SVO_TRAVERSE_LOD=1 unit, packets stop where a node is no wider than
/// `lod_pixels` pixels of the scene's camera (rk_svo_pixel_cone).
Prepared prepare(const Scene& s, int depth, int mode, float lod_pixels = 0.0f)
{
    Prepared p;
    auto t = std::make_shared<Tree>();
    const raykit::SvoBuildOptions opt = svo_options(s, depth);
    raykit::SvoStatus st;
    const auto t0 = std::chrono::steady_clock::now();
    if (!raykit::build_svo(s.mesh.view(), opt, t->tree, st)) {
        p.skip = "raykit build_svo failed: " + st.message;
        return p;
    }
    p.build_ms = 1000.0 * seconds_since(t0);
    t->words = t->tree.gpu_words();
    t->uniforms = raykit::svo_trace_tree(t->tree);
    p.counters.push_back({"bytes_per_voxel", double(t->tree.structure_bytes()) / double(t->tree.voxel_count)});
    p.keep = t;
    const Tree* tp = t.get();
    if (mode == 0) {
        p.make_thread = [tp] {
            return per_ray([tp](const Ray& r) {
                const raykit::rk_svo_trace_hit h =
                    raykit::rk_svo_trace(tp->words.data(), tp->uniforms, r.org, r.dir, RK_FLT_MAX, glm::vec2(0.0f));
                return h.hit ? h.t : kMiss;
            });
        };
        return p;
    }
    if (!raykit::svo_trace_simd_available()) {
        p.skip = "this CPU has no AVX2: svo_trace_rays would be the per-ray rows again";
        return p;
    }
    if (mode == 2) {
        // svo_trace_packets over each chunk of 4 rows, its default tiles: 8 x 4 (32 rays per traversal
        // on AVX-512 lanes) where the CPU has AVX-512, else 4 x 4 (16 rays on two AVX2 registers per
        // value).
        const std::size_t width = static_cast<std::size_t>(s.camera.width);
        const glm::vec2 cone = lod_pixels > 0.0f ? raykit::rk_svo_pixel_cone(2.0f * std::atan(s.camera.tan_half_fov_y),
                                                                             static_cast<float>(s.camera.height), lod_pixels)
                                                 : glm::vec2(0.0f);
        p.make_thread = [tp, width, cone]() -> SpanTracer {
            auto in = std::make_shared<std::vector<raykit::SvoRay>>();
            auto out = std::make_shared<std::vector<raykit::rk_svo_trace_hit>>();
            return [tp, in, out, width, cone](const Ray* rays, std::size_t n, float* t_out) {
                in->resize(n);
                out->resize(n);
                for (std::size_t i = 0; i < n; ++i) {
                    (*in)[i].origin = rays[i].org;
                    (*in)[i].dir = rays[i].dir;
                }
                raykit::svo_trace_packets(tp->words.data(), tp->uniforms, in->data(), n, width, out->data(), 0u, 0u, cone);
                for (std::size_t i = 0; i < n; ++i) t_out[i] = (*out)[i].hit ? (*out)[i].t : kMiss;
            };
        };
        return p;
    }
    // svo_trace_rays over each chunk of rows: the rays copied into its input and the hits out of its
    // output inside the timed loop (what a caller with its own ray layout pays).
    p.make_thread = [tp]() -> SpanTracer {
        auto in = std::make_shared<std::vector<raykit::SvoRay>>();
        auto out = std::make_shared<std::vector<raykit::rk_svo_trace_hit>>();
        return [tp, in, out](const Ray* rays, std::size_t n, float* t_out) {
            in->resize(n);
            out->resize(n);
            for (std::size_t i = 0; i < n; ++i) {
                (*in)[i].origin = rays[i].org;
                (*in)[i].dir = rays[i].dir;
            }
            raykit::svo_trace_rays(tp->words.data(), tp->uniforms, in->data(), n, out->data());
            for (std::size_t i = 0; i < n; ++i) t_out[i] = (*out)[i].hit ? (*out)[i].t : kMiss;
        };
    };
    return p;
}

}  // namespace
}  // namespace rktrace
