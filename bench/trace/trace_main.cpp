// raykit — bench/trace/trace_main.cpp: main() of raykit_bench_trace, CPU primary-ray throughput of
// ray tracers on the same meshes and cameras (bench/trace/trace_scene.hpp), side by side: Embree on
// the source triangles (trace_embree.cpp), OpenVDB's level-set ray intersector on a narrow-band
// level set of the same mesh (trace_openvdb.cpp), and whatever else registers a TracerSpec
// (trace_harness.hpp). The peers are optional at configure time (bench/trace/CMakeLists.txt);
// scripts/bench_trace.sh installs them, builds and runs this.
//
// Arguments: Google Benchmark's, plus --smoke (64 x 64 image, depth 6, 2 iterations per row, exit 1
// when a row's hits or distances disagree with the reference tracer's: the bench.trace.smoke ctest).
// Environment: RAYKIT_BENCH_TRACE_FULL=1 adds depths 11 and 12 to the default 8..10 and lifts the
// per-mesh caps (Scene::default_max_depth; level sets there take gigabytes and minutes, rows whose
// estimate exceeds the memory limit are skipped).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "trace_harness.hpp"

#ifndef RAYKIT_BENCH_BUILD_TYPE
#define RAYKIT_BENCH_BUILD_TYPE "unknown"
#endif
#ifndef RAYKIT_BENCH_COMPILER
#define RAYKIT_BENCH_COMPILER "unknown"
#endif

namespace {

std::string vec(glm::vec3 v)
{
    char b[96];
    std::snprintf(b, sizeof b, "(%.4f, %.4f, %.4f)", static_cast<double>(v.x), static_cast<double>(v.y), static_cast<double>(v.z));
    return b;
}

std::string join(const std::vector<int>& v)
{
    std::string s;
    for (int x : v) s += (s.empty() ? "" : ",") + std::to_string(x);
    return s;
}

}  // namespace

int main(int argc, char** argv)
{
    rktrace::Options& o = rktrace::options();
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--smoke") == 0) {
            o.smoke = true;
        } else {
            argv[kept++] = argv[i];
        }
    }
    argc = kept;
    const char* full = std::getenv("RAYKIT_BENCH_TRACE_FULL");
    o.full = full && std::strcmp(full, "1") == 0;
    if (o.smoke) {
        o.image = 64;
        o.depths = {6};
    } else if (o.full) {
        o.depths = {8, 9, 10, 11, 12};
    }

    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    rktrace::scenes() = rktrace::make_scenes(o.image);

    benchmark::AddCustomContext("raykit_build_type", RAYKIT_BENCH_BUILD_TYPE);
    benchmark::AddCustomContext("raykit_compiler", RAYKIT_BENCH_COMPILER);
    benchmark::AddCustomContext("raykit_trace_mode", o.smoke ? "smoke" : o.full ? "full" : "default");
    benchmark::AddCustomContext("raykit_trace_image", std::to_string(o.image) + "x" + std::to_string(o.image));
    benchmark::AddCustomContext("raykit_trace_depths", join(o.depths));
    benchmark::AddCustomContext("raykit_trace_hardware_threads", std::to_string(std::thread::hardware_concurrency()));
    for (const rktrace::Scene& s : rktrace::scenes()) {
        benchmark::AddCustomContext("raykit_trace_scene:" + s.key,
                                    s.title + "; triangles " + std::to_string(s.triangles) + "; cube min " + vec(s.cube.min) +
                                        " size " + std::to_string(s.cube.size) + "; eye " + vec(s.camera.eye) + " looking at " +
                                        vec(s.bounds.centre()) + ", 40 degrees vertical field of view");
    }
    std::string names;
    for (const rktrace::TracerSpec& t : rktrace::tracers()) {
        names += (names.empty() ? "" : ",") + t.name;
        benchmark::AddCustomContext("raykit_trace_tracer:" + t.name, t.label);
    }
    benchmark::AddCustomContext("raykit_trace_tracers", names);
    if (rktrace::tracers().empty()) {
        std::fprintf(stderr, "raykit_bench_trace: no tracers compiled in (Embree and OpenVDB were not found at configure time;"
                             " scripts/bench_trace.sh installs them)\n");
    }

    rktrace::register_rows();
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();

    const auto& failed = rktrace::sanity_failures();
    if (!failed.empty()) {
        std::fprintf(stderr, "raykit_bench_trace: %zu row(s) disagree with the reference tracer (see the warnings above)\n", failed.size());
        if (o.smoke) return 1;
    }
    return 0;
}
