// raykit_svo_simd_ab: svo_trace_rays (8 AVX2 lanes) against rk_svo_trace per ray, paired in one
// process: the same tree and the same 512 x 512 primary rays of raykit_bench_trace's scenes (figure,
// uv_sphere_5856, torus_69120), both modes run in turn 7 times in chunks of 2,048 rays, each timed
// in thread CPU time, the best of the 7 kept (the least disturbed by other processes). Prints
// Mrays/s of each and their ratio, with the loop iterations per ray that enters the root.
// Usage: raykit_svo_simd_ab [depth (default 10)]
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "raykit/svo_build.hpp"
#include "raykit/svo_trace_simd.hpp"
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
    if (!raykit::svo_trace_simd_available()) std::printf("note: no AVX2 here, both modes are the per-ray loop\n");
    for (rktrace::Scene& s : rktrace::make_scenes(512)) {
        if (s.key != "figure" && s.key != "uv_sphere_5856" && s.key != "torus_69120") continue;
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
        std::vector<raykit::rk_svo_trace_hit> hits(rays.size());
        double best[2] = {1e30, 1e30};
        for (int rep = 0; rep < 7; ++rep)
            for (int m = 0; m < 2; ++m) {
                const double t0 = cpu_seconds();
                for (size_t c = 0; c < rays.size(); c += 2048)
                    raykit::svo_trace_rays(words.data(), tree, rays.data() + c, std::min<size_t>(2048, rays.size() - c),
                                           hits.data() + c, glm::vec2(0.0f),
                                           m ? raykit::SvoTraceMode::best : raykit::SvoTraceMode::scalar);
                best[m] = std::min(best[m], cpu_seconds() - t0);
            }
        unsigned long long iterations = 0;
        long entered = 0;
        for (const raykit::rk_svo_trace_hit& h : hits) {
            iterations += h.iterations;
            entered += h.iterations > 0 ? 1 : 0;
        }
        const double n = double(rays.size());
        std::printf("%-16s d%d: %ld of %zu rays enter the root, %.1f iterations each; per ray %.2f Mrays/s, "
                    "lanes %.2f Mrays/s, ratio %.2f\n",
                    s.key.c_str(), depth, entered, rays.size(), double(iterations) / double(std::max(entered, 1L)),
                    n / best[0] / 1e6, n / best[1] / 1e6, best[0] / best[1]);
    }
    return 0;
}
