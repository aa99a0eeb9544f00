// raykit's rows of raykit_bench_trace: the C++ build of svo_traverse.glsl (rk_svo_trace, the same
// text the shaders run) over a tree that raykit::build_svo voxelises from the scene's triangles in
// the shared root cube (so depth D means the same voxels as OpenVDB's rows), geometry only (no
// attribute stream is read, as in a depth or shadow pass). Rows: trace/<mesh>/raykit/d<D>/threads:<n>.
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

Prepared prepare(const Scene& s, int depth, int mode)
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
        // svo_trace_packets over each chunk of 4 rows, its default tiles: 4 x 4 (16 rays per traversal
        // on AVX-512 lanes) where the CPU has AVX-512, else 4 x 2 (8 rays on AVX2 lanes).
        const std::size_t width = static_cast<std::size_t>(s.camera.width);
        p.make_thread = [tp, width]() -> SpanTracer {
            auto in = std::make_shared<std::vector<raykit::SvoRay>>();
            auto out = std::make_shared<std::vector<raykit::rk_svo_trace_hit>>();
            return [tp, in, out, width](const Ray* rays, std::size_t n, float* t_out) {
                in->resize(n);
                out->resize(n);
                for (std::size_t i = 0; i < n; ++i) {
                    (*in)[i].origin = rays[i].org;
                    (*in)[i].dir = rays[i].dir;
                }
                raykit::svo_trace_packets(tp->words.data(), tp->uniforms, in->data(), n, width, out->data());
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

// Tolerances: a surface voxelisation marks every voxel the surface touches, so its shell reaches up
// to a voxel outside the surface: silhouettes widen by up to a voxel (more hits: +14% on the torus
// and +37% on the thin-limbed figure at depth 6 in the 64 x 64 smoke frame, a few % at depth 10 in
// 512 x 512) and hits come up to sqrt(3) voxels early (about -1.0 to -1.5 measured). It never loses
// hits, though: fewer than the reference's minus 3% fails the row, so a traversal that misses
// surfaces cannot pass the smoke test.
const TracerRegistrar reg(TracerSpec{"raykit", "raykit rk_svo_trace (C++ build of svo_traverse.glsl), geometry only", 30, true,
                                     {8, 9, 10, 11, 12}, false,
                                     [](const Scene& s, int depth) { return prepare(s, depth, 0); }, 50.0, 2.0, -3.0});
// The same rays through svo_trace_rays (raykit/svo_trace_simd.hpp): the loop on 8 AVX2 lanes, the
// answers bit for bit rk_svo_trace's (test_svo_trace_simd).
const TracerRegistrar reg_simd(TracerSpec{"raykit_simd", "raykit svo_trace_rays (rk_svo_trace's loop on 8 AVX2 lanes), geometry only",
                                          31, true, {8, 9, 10, 11, 12}, false,
                                          [](const Scene& s, int depth) { return prepare(s, depth, 1); }, 50.0, 2.0, -3.0});

// Coherent rays (4 x 4 pixel tiles on AVX-512, else 4 x 2) sharing one traversal (raykit/svo_trace_packet.hpp):
// the answers are rk_svo_trace's (test_svo_trace_packet).
const TracerRegistrar reg_packet(TracerSpec{"raykit_packet", "raykit svo_trace_packets (4x4 ray packets on AVX-512 lanes, else 4x2 on AVX2), geometry only",
                                            32, true, {8, 9, 10, 11, 12}, false,
                                            [](const Scene& s, int depth) { return prepare(s, depth, 2); }, 50.0, 2.0, -3.0});

}  // namespace
}  // namespace rktrace
