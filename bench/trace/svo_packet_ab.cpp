// raykit_svo_packet_ab: svo_trace_packets (raykit/svo_trace_packet.hpp; pixel tiles of coherent
// rays sharing one traversal: 8 x 4 on AVX-512 lanes where the CPU has them, else 4 x 4 on AVX2) against rk_svo_trace per ray and
// svo_trace_rays (8 AVX2 lanes, one ray per lane), paired in one process: the same tree and the
// same 512 x 512 primary rays of raykit_bench_trace's scenes, the three tracers run in turn
// (rotating which goes first) in chunks of 4 rows (as raykit_bench_trace hands them out), each pass
// timed in thread CPU time. Per round the ratios of the times in that round are recorded; printed
// are each tracer's best Mrays/s and the median (min - max) of its per-round speed-up over
// rk_svo_trace and over svo_trace_rays, the rays whose answer (hit flag or cell) differs from
// rk_svo_trace's, rk_svo_trace's loop iterations per entering ray and the packet's node expansions
// per packet.
// Usage: raykit_svo_packet_ab [depth (default 10)] [rounds (default 11)] [mesh key or "all" (default: all)]
//        [tile width] [tile height] (default: svo_trace_packet_best_tile)
// RAYKIT_AB_RAYS=shadow or =reflection traces the secondary rays of the frame's hits instead, each in
// its pixel's place (tests/svo_secondary_rays.hpp, as test_svo_trace_packet does): shadow rays
// towards a directional light of direction normalize(0.4, 0.8, 0.45), or mirror reflections about
// the hit's face normal. A tile whose rays lie in several direction octants is traced as one packet
// per octant; its node expansions are their sum.
// RAYKIT_AB_WARM=1 also times the packets with each 4-row chunk traced twice in a row (median of
// the rounds): the second pass finds the chunk's nodes in cache, so cold / warm bounds what any
// node layout could win back from memory.
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "raykit/svo_build.hpp"
#include "raykit/svo_trace_packet.hpp"
#include "raykit/svo_trace_simd.hpp"
#include "svo_secondary_rays.hpp"
#include "trace_scene.hpp"

static double cpu_seconds()
{
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

int main(int argc, char** argv)
{
    const int depth = argc > 1 ? std::atoi(argv[1]) : 10;
    const int reps = argc > 2 ? std::max(1, std::atoi(argv[2])) : 11;
    const char* only = argc > 3 && std::strcmp(argv[3], "all") != 0 ? argv[3] : nullptr;
    unsigned tw = 0u, th = 0u;
    raykit::svo_trace_packet_best_tile(tw, th);
    if (argc > 5) {
        tw = unsigned(std::atoi(argv[4]));
        th = unsigned(std::atoi(argv[5]));
    }
    if (!raykit::svo_trace_simd_available()) std::printf("note: no AVX2 here, every mode is the per-ray loop\n");
    const char* names[3] = {"rk_svo_trace", "svo_trace_rays", "packet"};
    for (rktrace::Scene& s : rktrace::make_scenes(512)) {
        if (only && s.key != only) continue;
        const raykit::SvoBuildOptions opt = rktrace::svo_options(s, depth);
        raykit::SvoTree t;
        raykit::SvoStatus st;
        if (!raykit::build_svo(s.mesh.view(), opt, t, st)) {
            std::printf("%s: build_svo failed: %s\n", s.key.c_str(), st.message.c_str());
            return 1;
        }
        const std::vector<uint32_t> words = t.gpu_words();
        const raykit::rk_svo_tree tree = raykit::svo_trace_tree(t);
        std::vector<raykit::SvoRay> rays(s.rays.size());
        for (size_t i = 0; i < rays.size(); ++i) {
            rays[i].origin = s.rays[i].org;
            rays[i].dir = s.rays[i].dir;
        }
        const size_t n = rays.size();
        const size_t width = size_t(s.camera.width);
        const char* kind_env = std::getenv("RAYKIT_AB_RAYS");
        const std::string kind = kind_env != nullptr ? kind_env : "";
        if (kind == "shadow" || kind == "reflection")
            rays = svotrace::secondary_rays(words.data(), tree, rays, kind == "shadow" ? svotrace::Secondary::sun : svotrace::Secondary::mirror,
                                            glm::normalize(glm::vec3(0.4f, 0.8f, 0.45f)));
        else if (!kind.empty()) {
            std::printf("RAYKIT_AB_RAYS=%s: expected shadow or reflection\n", kind.c_str());
            return 1;
        }
        const size_t chunk = 4 * width;
        std::vector<raykit::rk_svo_trace_hit> hits[3];
        for (auto& h : hits) h.resize(n);
        auto run = [&](int m) {
            raykit::rk_svo_trace_hit* out = hits[m].data();
            for (size_t c = 0; c < n; c += chunk) {
                const size_t e = std::min(n, c + chunk);
                if (m == 0) {
                    for (size_t i = c; i < e; ++i)
                        out[i] = raykit::rk_svo_trace(words.data(), tree, rays[i].origin, rays[i].dir, rays[i].t_max, glm::vec2(0.0f));
                } else if (m == 1) {
                    raykit::svo_trace_rays(words.data(), tree, rays.data() + c, e - c, out + c);
                } else {
                    raykit::svo_trace_packets(words.data(), tree, rays.data() + c, e - c, width, out + c, tw, th);
                }
            }
        };
        std::vector<double> vs_rk[3], vs_rays[3];
        double best[3] = {1e30, 1e30, 1e30};
        for (int rep = 0; rep < reps; ++rep) {
            double sec[3];
            for (int j = 0; j < 3; ++j) {
                const int m = (j + rep) % 3;
                const double t0 = cpu_seconds();
                run(m);
                sec[m] = cpu_seconds() - t0;
                best[m] = std::min(best[m], sec[m]);
            }
            for (int m = 0; m < 3; ++m) {
                vs_rk[m].push_back(sec[0] / sec[m]);
                vs_rays[m].push_back(sec[1] / sec[m]);
            }
        }
        unsigned long long it = 0;
        long entered = 0, hit_count = 0, differ[3] = {0, 0, 0};
        for (size_t i = 0; i < n; ++i) {
            it += hits[0][i].iterations;
            entered += hits[0][i].iterations > 0 ? 1 : 0;
            hit_count += hits[0][i].hit ? 1 : 0;
            for (int m = 0; m < 3; ++m)
                differ[m] += (hits[m][i].hit != hits[0][i].hit || (hits[0][i].hit && hits[m][i].cell != hits[0][i].cell)) ? 1 : 0;
        }
        // Node expansions per tile: the largest `iterations` of the rays of each direction octant's
        // packet (the rays of one octant share a packet), summed over the octants.
        unsigned long long expansions = 0;
        long packets = 0;
        for (size_t y0 = 0; y0 < n / width; y0 += th)
            for (size_t x0 = 0; x0 < width; x0 += tw) {
                uint32_t mx[8] = {0, 0, 0, 0, 0, 0, 0, 0};
                for (size_t y = y0; y < std::min(n / width, size_t(y0 + th)); ++y)
                    for (size_t x = x0; x < std::min(width, size_t(x0 + tw)); ++x) {
                        const glm::vec3 d = rays[y * width + x].dir;
                        const int oct = (std::signbit(d.x) ? 0 : 1) | (std::signbit(d.y) ? 0 : 2) | (std::signbit(d.z) ? 0 : 4);  // as the set-up's flip
                        mx[oct] = std::max(mx[oct], hits[2][y * width + x].iterations);
                    }
                uint32_t sum = 0;
                for (uint32_t m : mx) sum += m;
                expansions += sum;
                packets += sum > 0 ? 1 : 0;
            }
        std::printf("%s%-16s d%d: %zu rays, %ld hit, %ld enter the root (%.1f rk iterations each); packets %ux%u: %ld entering, "
                    "%.1f node expansions each\n",
                    kind.empty() ? "" : (kind + " rays, ").c_str(), s.key.c_str(), depth, n, hit_count, entered, double(it) / double(std::max(entered, 1L)), tw, th, packets,
                    double(expansions) / double(std::max(packets, 1L)));
        for (int m = 0; m < 3; ++m) {
            std::vector<double> a = vs_rk[m], b = vs_rays[m];
            std::sort(a.begin(), a.end());
            std::sort(b.begin(), b.end());
            std::printf("  %-15s %6.2f Mrays/s (best of %d); vs rk_svo_trace x%.3f (%.3f-%.3f); vs svo_trace_rays x%.3f (%.3f-%.3f); "
                        "%ld rays differ\n",
                        names[m], double(n) / best[m] / 1e6, reps, a[a.size() / 2], a.front(), a.back(), b[b.size() / 2], b.front(),
                        b.back(), differ[m]);
        }
        const char* warm_env = std::getenv("RAYKIT_AB_WARM");
        if (warm_env != nullptr && std::strcmp(warm_env, "1") == 0) {
            // Per round: the frame once (each chunk once), then each chunk twice in a row; the
            // second pass's time is the difference.
            std::vector<double> once, twice;
            raykit::rk_svo_trace_hit* out = hits[2].data();
            for (int rep = 0; rep < reps; ++rep)
                for (int k = 1; k <= 2; ++k) {
                    const double t0 = cpu_seconds();
                    for (size_t c = 0; c < n; c += chunk) {
                        const size_t e = std::min(n, c + chunk);
                        for (int pass = 0; pass < k; ++pass)
                            raykit::svo_trace_packets(words.data(), tree, rays.data() + c, e - c, width, out + c, tw, th);
                    }
                    (k == 1 ? once : twice).push_back(cpu_seconds() - t0);
                }
            std::sort(once.begin(), once.end());
            std::sort(twice.begin(), twice.end());
            const double cold = once[once.size() / 2], warm = twice[twice.size() / 2] - cold;
            std::printf("  packets, each chunk twice in a row: %.1f MB of geometry, first pass %.1f ms, second %.1f ms: cold / "
                        "warm x%.2f\n",
                        double(words.size()) * 4e-6, cold * 1e3, warm * 1e3, cold / std::max(warm, 1e-9));
        }
        std::fflush(stdout);
    }
    return 0;
}
