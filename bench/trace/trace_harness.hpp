// raykit — bench/trace/trace_harness.hpp: the timing harness of raykit_bench_trace. A tracer is
// described once (TracerSpec: name, how to prepare it for a scene and depth) and registered with a
// static TracerRegistrar in its own trace_<name>.cpp; main() (trace_main.cpp) then registers one
// Google Benchmark row per scene x tracer x depth x thread count:
//
//   trace/<mesh>/<tracer>/threads:<n>            exact tracers (Embree on the triangles)
//   trace/<mesh>/<tracer>/d<depth>/threads:<n>   voxel tracers (OpenVDB's level set, raykit's octree)
//
// One iteration traces the scene's whole frame (512 x 512 primary rays, 64 x 64 with --smoke), the
// image's rows handed out in chunks to n threads (n - 1 std::threads plus the calling one), each with
// its own per-thread tracer made before timing. Preparing (BVH, level set, octree) happens once per
// (mesh, tracer, depth), on the first row that needs it, outside the timed loop; only the most
// recent preparation is kept (rows of one tracer and depth are adjacent, so nothing is built twice).
//
// Counters: Mrays/s (rays / median frame time: robust to a frame slowed by another process),
// frame_ms (that median), hits (rays that hit: a checksum), build_ms (the preparation, timed by the
// tracer), load_avg_1m (after the row: how busy the machine was), and against the reference
// tracer's hits on the same rays (Embree, when compiled in): hit_diff_pct (hit count difference, %),
// pix_diff_pct (rays hit by one and missed by the other, %) and dt_vox (mean of t - t_ref over rays
// both hit, in voxels of the row's depth; exact rows give dt instead, in world units). A row outside
// options().hit_tol_pct or dt_tol_vox prints a warning line on stderr and counts as a sanity
// failure (--smoke then exits 1).
//
// Adding a tracer (e.g. raykit's octree traversal) is one file with a registrar:
//
//   static rktrace::TracerRegistrar reg({"raykit", "raykit octree, ...", /*order*/ 30, /*voxel*/ true, {},
//       false, [](const rktrace::Scene& s, int depth) {
//           auto tree = std::make_shared<Tree>(build(s.mesh, s.cube, depth));  // timed into build_ms
//           rktrace::Prepared p;
//           p.keep = tree;
//           p.make_thread = [t = tree.get()] {
//               return rktrace::per_ray([t](const rktrace::Ray& r) { return t->trace(r.org, r.dir); });  // t or kMiss
//           };
//           return p;
//       }});
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <benchmark/benchmark.h>

#include "../stats.hpp"
#include "trace_scene.hpp"

namespace rktrace {

/// A per-thread ray caster over a span of rays: t[i] = hit distance of rays[i] (along its unit
/// direction, from its origin), or kMiss. Called from one thread at a time.
using SpanTracer = std::function<void(const Ray* rays, std::size_t n, float* t)>;

/// Wraps a per-ray callable `float(const Ray&)` into a SpanTracer; the per-ray call is inlined into
/// the span loop (one indirect call per chunk of rows, not per ray).
template <class PerRay>
SpanTracer per_ray(PerRay fn)
{
    return [fn](const Ray* rays, std::size_t n, float* t) mutable {
        for (std::size_t i = 0; i < n; ++i) t[i] = fn(rays[i]);
    };
}

/// A tracer prepared for one scene and depth.
struct Prepared {
    double build_ms = 0.0;                   // reported as build_ms
    std::function<SpanTracer()> make_thread;  // one per thread, called before timing
    std::shared_ptr<void> keep;              // owns what the per-thread tracers point into
    std::vector<std::pair<std::string, double>> counters;  // extra counters of the rows
    std::string skip;                        // non-empty: the rows are skipped with this message
};

struct TracerSpec {
    std::string name;   // trace/<mesh>/<name>/...
    std::string label;  // what it is (library version, settings): the rows' label
    int order = 0;      // per mesh, tracers run in ascending order (Embree 10, OpenVDB 20)
    bool voxel = false;  // one row per depth (d<depth>); else depth is -1
    std::vector<int> depths;  // voxel tracers' depths; empty: options().depths (--smoke overrides)
    bool reference = false;   // the tracer other rows' hits are checked against
    /// Builds the tracer for a scene (depth -1 for exact tracers); may throw (the rows are then
    /// skipped with the message).
    std::function<Prepared(const Scene&, int depth)> prepare;
    /// Sanity tolerances of this tracer's rows against the reference; negative: options()'s. (A
    /// conservative surface voxelisation has more hits: its silhouettes are up to a voxel wider.)
    double hit_tol_pct = -1.0;
    double dt_tol_vox = -1.0;
    /// One-sided floor on hit_diff_pct (negative = fewer hits than the reference), when tighter
    /// than -hit_tol: a conservative tracer must not lose hits. Positive: unused.
    double hit_floor_pct = 1.0;
};

struct Options {
    bool smoke = false;  // --smoke: 64 x 64 image, depth 6, 2 iterations per row
    bool full = false;   // RAYKIT_BENCH_TRACE_FULL=1: depths 8..12
    int image = 512;
    std::vector<int> depths{8, 9, 10};
    std::vector<int> threads{1, 2};
    double hit_tol_pct = 3.0;  // |hit_diff_pct| above this: sanity failure
    double dt_tol_vox = 2.0;   // |dt_vox| above this: sanity failure
};

inline Options& options()
{
    static Options o;
    return o;
}

inline std::vector<TracerSpec>& tracers()
{
    static std::vector<TracerSpec> t;
    return t;
}

inline std::vector<Scene>& scenes()
{
    static std::vector<Scene> s;
    return s;
}

/// Registers a tracer at static-initialisation time (one per trace_<name>.cpp).
struct TracerRegistrar {
    explicit TracerRegistrar(TracerSpec spec) { tracers().push_back(std::move(spec)); }
};

/// Rows whose sanity check failed (row names; a row run twice by Google Benchmark counts once).
inline std::set<std::string>& sanity_failures()
{
    static std::set<std::string> f;
    return f;
}

inline double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

using rkbench_stats::median;

/// The 1-minute load average (Linux /proc/loadavg; -1 where unavailable): above the core count,
/// other processes took time from the row (the 2-thread rows first).
inline double load_average()
{
    double l = -1.0;
    if (FILE* f = std::fopen("/proc/loadavg", "r")) {
        if (std::fscanf(f, "%lf", &l) != 1) l = -1.0;
        std::fclose(f);
    }
    return l;
}

/// Traces every ray of a width-wide row-major frame into t, with tracers.size() threads (the
/// calling one included) taking chunks of kRowsPerChunk rows from a shared counter.
inline void trace_frame(const std::vector<Ray>& rays, int width, std::vector<SpanTracer>& tracers, float* t)
{
    constexpr int kRowsPerChunk = 4;
    const int rows = static_cast<int>(rays.size() / static_cast<std::size_t>(width));
    std::atomic<int> next{0};
    auto work = [&](std::size_t tid) {
        SpanTracer& tr = tracers[tid];
        for (;;) {
            const int r0 = next.fetch_add(kRowsPerChunk, std::memory_order_relaxed);
            if (r0 >= rows) break;
            const int r1 = std::min(rows, r0 + kRowsPerChunk);
            const std::size_t b = static_cast<std::size_t>(r0) * static_cast<std::size_t>(width);
            const std::size_t e = static_cast<std::size_t>(r1) * static_cast<std::size_t>(width);
            tr(rays.data() + b, e - b, t + b);
        }
    };
    std::vector<std::thread> workers;
    for (std::size_t i = 1; i < tracers.size(); ++i) workers.emplace_back(work, i);
    work(0);
    for (std::thread& w : workers) w.join();
}

/// The tracer prepared for (scene, tracer, depth): built on first use; the previous one is freed
/// first (level sets at depth 11-12 take gigabytes).
inline std::shared_ptr<const Prepared> prepared_for(const Scene& s, const TracerSpec& spec, int depth)
{
    static std::string key;
    static std::shared_ptr<const Prepared> cached;
    const std::string k = s.key + "/" + spec.name + "/" + std::to_string(depth);
    if (k != key || !cached) {
        cached.reset();
        key.clear();
        cached = std::make_shared<const Prepared>(spec.prepare(s, depth));
        key = k;
    }
    return cached;
}

/// The reference tracer's t for every ray of the scene (one thread), or nullptr without one.
inline const std::vector<float>* reference_t(const Scene& s)
{
    static std::map<std::string, std::vector<float>> cache;
    auto it = cache.find(s.key);
    if (it != cache.end()) return &it->second;
    for (const TracerSpec& spec : tracers()) {
        if (!spec.reference) continue;
        const Prepared p = spec.prepare(s, -1);
        if (!p.skip.empty()) return nullptr;
        std::vector<SpanTracer> one{p.make_thread()};
        std::vector<float> t(s.rays.size(), kMiss);
        trace_frame(s.rays, s.camera.width, one, t.data());
        return &cache.emplace(s.key, std::move(t)).first->second;
    }
    return nullptr;
}

struct Agreement {
    std::uint64_t hits = 0, ref_hits = 0, differ = 0, both = 0;
    double sum_dt = 0.0;
    double hit_diff_pct() const
    {
        if (!ref_hits) return 0.0;
        return 100.0 * (static_cast<double>(hits) - static_cast<double>(ref_hits)) / static_cast<double>(ref_hits);
    }
    double mean_dt() const { return both ? sum_dt / static_cast<double>(both) : 0.0; }
};

inline Agreement agreement(const std::vector<float>& t, const std::vector<float>& ref)
{
    Agreement a;
    for (std::size_t i = 0; i < t.size(); ++i) {
        const bool h = is_hit(t[i]), r = is_hit(ref[i]);
        a.hits += h;
        a.ref_hits += r;
        a.differ += h != r;
        if (h && r) {
            ++a.both;
            a.sum_dt += static_cast<double>(t[i]) - static_cast<double>(ref[i]);
        }
    }
    return a;
}

/// One row: times whole frames of `threads` threads, then reports rate, hits, agreement.
inline void run_row(benchmark::State& st, const std::string& row, const Scene& s, const TracerSpec& spec, int depth, int threads)
{
    std::shared_ptr<const Prepared> p;
    const std::vector<float>* ref = nullptr;
    try {
        ref = reference_t(s);
        p = prepared_for(s, spec, depth);
    } catch (const std::exception& e) {
        st.SkipWithError(e.what());
        return;
    }
    if (!p->skip.empty()) {
        st.SkipWithError(p->skip.c_str());
        return;
    }
    std::vector<SpanTracer> per_thread;
    for (int i = 0; i < threads; ++i) per_thread.push_back(p->make_thread());
    std::vector<float> t(s.rays.size(), kMiss);
    std::vector<double> frame_s;
    for (auto _ : st) {
        const auto t0 = std::chrono::steady_clock::now();
        trace_frame(s.rays, s.camera.width, per_thread, t.data());
        frame_s.push_back(seconds_since(t0));
        benchmark::DoNotOptimize(t.data());
        benchmark::ClobberMemory();
    }
    const double rays = static_cast<double>(s.rays.size());
    const double frame = median(frame_s);
    st.counters["Mrays/s"] = frame > 0.0 ? rays / frame * 1e-6 : 0.0;
    st.counters["frame_ms"] = frame * 1e3;
    st.counters["build_ms"] = p->build_ms;
    for (const auto& c : p->counters) st.counters[c.first] = c.second;
    st.counters["load_avg_1m"] = load_average();
    std::uint64_t hits = 0;
    for (float x : t) hits += is_hit(x);
    st.counters["hits"] = static_cast<double>(hits);
    std::string label = spec.label;
    if (depth >= 0) {
        st.counters["voxel"] = s.cube.voxel(depth);
        label += ", voxel " + std::to_string(s.cube.voxel(depth));
    }
    st.SetLabel(label);
    if (!ref) return;
    const Agreement a = agreement(t, *ref);
    st.counters["hit_diff_pct"] = a.hit_diff_pct();
    st.counters["pix_diff_pct"] = 100.0 * static_cast<double>(a.differ) / rays;
    const double hit_tol = spec.hit_tol_pct >= 0.0 ? spec.hit_tol_pct : options().hit_tol_pct;
    const double dt_tol = spec.dt_tol_vox >= 0.0 ? spec.dt_tol_vox : options().dt_tol_vox;
    bool ok = std::fabs(a.hit_diff_pct()) <= hit_tol && (spec.hit_floor_pct > 0.0 || a.hit_diff_pct() >= spec.hit_floor_pct);
    char msg[256];
    if (depth >= 0) {
        const double dt_vox = a.mean_dt() / s.cube.voxel(depth);
        st.counters["dt_vox"] = dt_vox;
        ok = ok && std::fabs(dt_vox) <= dt_tol;
        std::snprintf(msg, sizeof msg, "hits %llu vs %llu reference (%+.2f%%), mean t - t_ref %+.3f voxels",
                      static_cast<unsigned long long>(a.hits), static_cast<unsigned long long>(a.ref_hits), a.hit_diff_pct(), dt_vox);
    } else {
        st.counters["dt"] = a.mean_dt();
        ok = ok && std::fabs(a.mean_dt()) <= 1e-4 * static_cast<double>(s.cube.size);
        std::snprintf(msg, sizeof msg, "hits %llu vs %llu reference (%+.2f%%), mean t - t_ref %+.3g",
                      static_cast<unsigned long long>(a.hits), static_cast<unsigned long long>(a.ref_hits), a.hit_diff_pct(), a.mean_dt());
    }
    if (!ok && sanity_failures().insert(row).second) {
        std::fprintf(stderr, "raykit_bench_trace: WARNING %s: %s (tolerance %.1f%% hits, %.1f voxels)\n", row.c_str(), msg,
                     hit_tol, dt_tol);
    }
}

/// Registers every scene x tracer x depth x thread-count row, tracers in `order`.
inline void register_rows()
{
    std::vector<TracerSpec>& specs = tracers();
    std::stable_sort(specs.begin(), specs.end(), [](const TracerSpec& a, const TracerSpec& b) {
        return a.order != b.order ? a.order < b.order : a.name < b.name;
    });
    const Options& o = options();
    for (std::size_t si = 0; si < scenes().size(); ++si)
        for (std::size_t ti = 0; ti < specs.size(); ++ti) {
            const TracerSpec& spec = specs[ti];
            std::vector<int> depths{-1};
            if (spec.voxel) depths = (o.smoke || spec.depths.empty()) ? o.depths : spec.depths;
            for (int depth : depths) {
                // Per-mesh caps bound the peers' costly level sets; a tracer listing its own depths runs them all.
                if (!o.smoke && !o.full && spec.depths.empty() && depth > scenes()[si].default_max_depth) continue;
                for (int threads : o.threads) {
                    std::string row = "trace/" + scenes()[si].key + "/" + spec.name;
                    if (depth >= 0) row += "/d" + std::to_string(depth);
                    row += "/threads:" + std::to_string(threads);
                    auto* b = benchmark::RegisterBenchmark(row.c_str(), [=](benchmark::State& st) {
                        run_row(st, row, scenes()[si], tracers()[ti], depth, threads);
                    });
                    // Not UseRealTime() (it would append /real_time to the names): the Time column is
                    // wall-clock anyway, and Mrays/s comes from the harness's own wall-clock frames.
                    b->Unit(benchmark::kMillisecond);
                    if (o.smoke) b->Iterations(2);
                }
            }
        }
}

}  // namespace rktrace
