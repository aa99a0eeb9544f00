// raykit — bench_svo.cpp: build time, size and memory of the sparse voxel octree builder
// (raykit::build_svo, include/raykit/svo_build.hpp) against the anchors of Gritzner's thesis, for
// the "Octree build" section of docs/benchmarks.md (scripts/bench_report.py).
//
// Suite "svo", one family "svo_build": BM_svo/<mesh>/depth:<d>/threads:<t>, surface fill, colour +
// normal + material streams, for the test meshes (tests/reference/svo_meshes.hpp): icosphere(3)
// (1,280 triangles, filling its cube), figure() (1,024 triangles, a stand-in for the thesis's character;
// also with the colour stream only, with shared sub-node attributes, and with smooth vertex
// normals), menger_sponge(2) (2,112 triangles, many holes
// and axis-aligned faces) and uv_sphere(256, 137) (69,632 triangles, the ~70k case).
//   - threads:1 times the single-threaded build. threads:2 times the 2-thread build and, in the same
//     iterations, a 1-thread build with the timer paused, alternating which goes first (paired,
//     interleaved): speedup_paired is the median of the per-pair ratios t1 / t2, so load from other
//     processes that drifts over the run cancels out of the ratio. Rows deeper than kPairedMaxDepth
//     have threads:2 only, unpaired.
//   - Counters (of the last build; the tree does not depend on the thread count): voxels,
//     triangles (used), nonleaf_nodes (sum of level_nodes[0..depth-1]), bytes_struct
//     (SvoTree::structure_bytes), bytes_color (colour stream + brick bases: what a colour-only tree
//     would store), bytes_attr (SvoTree::attribute_bytes: colour + normal + material), bytes_total,
//     their per-voxel values, bytes_thesis = 4 + 8 (1 + 8 nonleaf_nodes) (Gritzner's file size for
//     the same tree), thesis_ratio = (bytes_struct + bytes_color) / bytes_thesis, est_peak_bytes
//     (estimate_svo_memory), peak_bytes (SvoBuildStats::peak_bytes, the builder's own accounting),
//     rss_peak_bytes (Linux: rise of the process's peak resident set over the build, VmHWM after a
//     clear_refs reset, the largest over the iterations; 0 where unavailable), voxels_per_second,
//     seconds_median (median over the iterations of the timed build, less sensitive than Google
//     Benchmark's mean to one build slowed by another job), s_voxelize / s_pack (stage times of the
//     last build), load_avg_1m (the 1-minute load average after the row: how busy the machine was).
//     Timed: build_svo alone (freeing the previous tree and resetting the RSS peak run paused).
//   - Rows whose memory estimate exceeds the limit (min(RAYKIT_BENCH_SVO_MAX_BYTES or 8 GiB, half
//     of MemAvailable)) are skipped with an error saying so; the report lists them.
//
// Environment: RAYKIT_BENCH_SVO_FULL=1 (set by scripts/bench.sh and scripts/bench_svo.sh) registers
// depths 6..11 for every mesh and 12..13 for the 1k mesh, with a minimum time per row; otherwise
// (the bench.smoke ctest) only depths 6..7, one iteration each. RAYKIT_BENCH_SVO_MAX_DEPTH=<d> caps
// the depth either way. RAYKIT_BENCH_SVO_SKIP=1 registers no octree row (scripts/bench.sh sets it
// for its extra processes, which repeat only the per-call suites).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "bench_common.hpp"
#include "proc_memory.hpp"
#include "raykit/svo_build.hpp"
#include "reference/svo_meshes.hpp"

namespace rkbench {
namespace {

const char* const kFam = "svo_build";
constexpr int kMinDepth = 6;
constexpr int kSmokeMaxDepth = 7;
constexpr int kPairedMaxDepth = 11;       // deeper rows: threads:2 only, unpaired
constexpr double kFullMinTime = 0.2;      // seconds of timed builds per row in the full run (longer builds run once)
constexpr double kPairedMinTime = 2.0;    // the same for paired rows (their timed part is the 2-thread builds):
                                          // the ~0.5 s depth-11 builds of the 1k mesh get 4 pairs, not 1
constexpr uint32_t kAttributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;

struct MeshCase {
    std::string key;    // BM_svo/<key>/...
    std::string title;  // for the report
    int full_max_depth = 11;
    std::shared_ptr<const raykit::SvoMeshData> mesh;
    uint32_t attributes = kAttributes;  // streams stored
};

std::string env(const char* name)
{
    const char* v = std::getenv(name);
    return v ? std::string(v) : std::string();
}

// ---------------------------------------------------------------------------------------------
// Process memory (Linux): the peak resident set can be reset (clear_refs 5) and read (VmHWM), so the
// rise of the peak over one build is measured independently of the builder's own accounting.

uint64_t status_kb(const char* key) { return rkbench_mem::proc_kb("/proc/self/status", key); }
using rkbench_mem::mem_available_bytes;

/// Frees what the allocator caches and resets the peak resident set; returns the current resident
/// set in bytes (0 when the peak cannot be reset, then no RSS figure is reported).
uint64_t reset_rss_peak()
{
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
#if defined(__linux__)
    FILE* f = std::fopen("/proc/self/clear_refs", "w");
    if (!f) return 0;
    const bool ok = std::fputs("5", f) >= 0;
    if (std::fclose(f) != 0 || !ok) return 0;
    return status_kb("VmRSS") * 1024u;
#else
    return 0;
#endif
}

uint64_t rss_peak_bytes() { return status_kb("VmHWM") * 1024u; }

/// The 1-minute load average (Linux /proc/loadavg; -1 where unavailable): how busy the machine was.
double load_average()
{
#if defined(__linux__)
    FILE* f = std::fopen("/proc/loadavg", "r");
    if (!f) return -1.0;
    double l = -1.0;
    if (std::fscanf(f, "%lf", &l) != 1) l = -1.0;
    std::fclose(f);
    return l;
#else
    return -1.0;
#endif
}

// ---------------------------------------------------------------------------------------------
// One build.

struct Build {
    raykit::SvoTree tree;
    raykit::SvoBuildStats stats;
    double seconds = 0.0;
    uint64_t rss_rise = 0;  // 0: not measured
};

raykit::SvoBuildOptions options(int depth, int threads, uint32_t attributes)
{
    raykit::SvoBuildOptions o;
    o.depth = depth;
    o.threads = threads;
    // RK_SVO_ATTR_SHARED_SUB in a case's attributes selects the compact level of detail.
    o.attributes = attributes & (RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL);
    o.shared_sub_attributes = (attributes & RK_SVO_ATTR_SHARED_SUB) != 0;
    return o;
}

/// Frees b's previous tree and resets the peak resident set (call with the timer paused); returns
/// the resident set to measure the rise from (0: not measurable).
uint64_t prepare(Build& b)
{
    b.tree = raykit::SvoTree{};
    return reset_rss_peak();
}

/// Builds into b, prepared by prepare() (rss0 = its result); b.seconds times build_svo alone; false
/// with `err`.
bool build(const raykit::SvoMeshData& mesh, uint32_t attributes, int depth, int threads, Build& b, uint64_t rss0, std::string& err)
{
    raykit::SvoStatus st;
    const auto t0 = std::chrono::steady_clock::now();
    const bool ok = raykit::build_svo(mesh.view(), options(depth, threads, attributes), b.tree, st, &b.stats);
    b.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const uint64_t hwm = rss0 ? rss_peak_bytes() : 0;
    b.rss_rise = hwm > rss0 ? hwm - rss0 : 0;
    if (!ok) err = st.message;
    return ok;
}

/// The size and memory counters of a finished build (see the top of this file).
void size_counters(benchmark::State& s, const Build& b, uint64_t est, uint64_t rss_rise)
{
    const raykit::SvoTree& t = b.tree;
    uint64_t nonleaf = 0;
    for (size_t l = 0; l < t.depth && l < t.level_nodes.size(); ++l) nonleaf += t.level_nodes[l];
    const double vox = static_cast<double>(t.voxel_count);
    const double per = vox > 0 ? 1.0 / vox : 0.0;
    const double b_struct = static_cast<double>(t.structure_bytes());
    const double b_color = 4.0 * static_cast<double>(t.color.size() + t.brick_base.size());
    const double b_attr = static_cast<double>(t.attribute_bytes());
    const double b_thesis = 4.0 + 8.0 * (1.0 + 8.0 * static_cast<double>(nonleaf));
    using C = benchmark::Counter;
    auto bytes = [](double v) { return C(v, C::kDefaults, C::OneK::kIs1024); };
    s.counters["voxels"] = vox;
    s.counters["triangles"] = static_cast<double>(b.stats.triangles_used);
    s.counters["nonleaf_nodes"] = static_cast<double>(nonleaf);
    s.counters["bytes_struct"] = bytes(b_struct);
    s.counters["bytes_color"] = bytes(b_color);
    s.counters["bytes_attr"] = bytes(b_attr);
    s.counters["bytes_total"] = bytes(b_struct + b_attr);
    s.counters["B_struct_per_voxel"] = b_struct * per;
    s.counters["B_color_per_voxel"] = b_color * per;
    s.counters["B_attr_per_voxel"] = b_attr * per;
    s.counters["bytes_thesis"] = bytes(b_thesis);
    s.counters["thesis_ratio"] = (b_struct + b_color) / b_thesis;
    s.counters["est_peak_bytes"] = bytes(static_cast<double>(est));
    s.counters["peak_bytes"] = bytes(static_cast<double>(b.stats.peak_bytes));
    s.counters["rss_peak_bytes"] = bytes(static_cast<double>(rss_rise));
    s.counters["s_voxelize"] = b.stats.seconds_voxelize;
    s.counters["s_pack"] = b.stats.seconds_pack;
    s.counters["voxels_per_second"] = C(vox, C::kIsIterationInvariantRate);
}

/// Skips the row (true) when the build's memory estimate is over the limit or invalid.
bool skip_for_memory(benchmark::State& s, const raykit::SvoMeshData& mesh, uint32_t attributes, int depth, int threads, uint64_t& est)
{
    raykit::SvoStatus st;
    est = raykit::estimate_svo_memory(mesh.view(), options(depth, threads, attributes), st);
    if (est == 0) {
        s.SkipWithError(("estimate_svo_memory failed: " + st.message).c_str());
        return true;
    }
    uint64_t limit = 8ull << 30;
    const std::string cap = env("RAYKIT_BENCH_SVO_MAX_BYTES");
    if (!cap.empty()) limit = std::strtoull(cap.c_str(), nullptr, 10);
    const uint64_t avail = mem_available_bytes();
    if (avail) limit = std::min(limit, avail / 2);
    if (est > limit) {
        char msg[200];
        std::snprintf(msg, sizeof msg, "skipped: estimated peak %.2f GiB > limit %.2f GiB (RAYKIT_BENCH_SVO_MAX_BYTES, half of MemAvailable)",
                      static_cast<double>(est) / 1073741824.0, static_cast<double>(limit) / 1073741824.0);
        s.SkipWithError(msg);
        return true;
    }
    return false;
}

void register_row(const MeshCase& mc, int depth, int threads, bool paired, bool full)
{
    const std::string name = "BM_svo/" + mc.key + "/depth:" + std::to_string(depth) + "/threads:" + std::to_string(threads);
    const std::string label = std::string(kFam) + "|build_svo(" + mc.key + ", depth " + std::to_string(depth) + ", " +
                              std::to_string(threads) + (threads == 1 ? " thread" : " threads") +
                              (paired ? ", paired with 1 thread" : "") + ")|";
    const std::shared_ptr<const raykit::SvoMeshData> mesh = mc.mesh;
    const uint32_t attrs = mc.attributes;
    auto* b = benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& s) {
        uint64_t est = 0;
        if (skip_for_memory(s, *mesh, attrs, depth, threads, est)) return;
        Build main_b, other;
        std::string err;
        std::vector<double> t1, t2, ratio, times;
        uint64_t rss = 0;
        long iter = 0;
        for (auto _ : s) {
            s.PauseTiming();
            const bool single_first = paired && (iter & 1) == 1;
            bool ok = !single_first || build(*mesh, attrs, depth, 1, other, prepare(other), err);
            other.tree = raykit::SvoTree{};
            if (ok) {
                const uint64_t rss0 = prepare(main_b);
                s.ResumeTiming();
                ok = build(*mesh, attrs, depth, threads, main_b, rss0, err);
                s.PauseTiming();
            }
            if (ok && paired && !single_first) ok = build(*mesh, attrs, depth, 1, other, prepare(other), err);
            other.tree = raykit::SvoTree{};  // only its time is kept: do not hold two trees at once
            if (!ok) {
                s.SkipWithError(("build_svo failed: " + err).c_str());
                break;
            }
            rss = std::max(rss, main_b.rss_rise);
            times.push_back(main_b.seconds);
            if (paired) {
                t1.push_back(other.seconds);
                t2.push_back(main_b.seconds);
                ratio.push_back(other.seconds / main_b.seconds);
            }
            ++iter;
            s.ResumeTiming();
        }
        if (!err.empty()) return;
        size_counters(s, main_b, est, rss);
        s.counters["load_avg_1m"] = load_average();
        s.counters["seconds_median"] = median(times);
        if (paired) {
            s.counters["t1_paired_s"] = median(t1);
            s.counters["t2_paired_s"] = median(t2);
            s.counters["speedup_paired"] = median(ratio);
            s.counters["pairs"] = static_cast<double>(ratio.size());
        }
        s.SetLabel(label);
    });
    b->UseRealTime()->Unit(benchmark::kMillisecond)->Repetitions(1);
    if (full) {
        b->MinTime(paired ? kPairedMinTime : kFullMinTime);
    } else {
        b->Iterations(1);
    }
}

/// m with smooth vertex normals (area-weighted face normals summed per shared vertex), so that the
/// builder takes its general path (a normal interpolated at each clipped piece's centroid).
raykit::SvoMeshData with_smooth_normals(raykit::SvoMeshData m)
{
    std::vector<glm::dvec3> sum(m.positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
        const glm::dvec3 a(m.positions[m.indices[t]]), b(m.positions[m.indices[t + 1]]), c(m.positions[m.indices[t + 2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        for (size_t k = 0; k < 3; ++k) sum[m.indices[t + k]] += n;
    }
    m.normals.resize(m.positions.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        const double l = glm::length(sum[i]);
        m.normals[i] = l > 0.0 ? glm::vec3(sum[i] / l) : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    return m;
}

void register_svo()
{
    if (env("RAYKIT_BENCH_SVO_SKIP") == "1") return;
    const bool full = env("RAYKIT_BENCH_SVO_FULL") == "1";
    int cap = 99;
    const std::string cap_s = env("RAYKIT_BENCH_SVO_MAX_DEPTH");
    if (!cap_s.empty()) cap = std::atoi(cap_s.c_str());

    std::vector<MeshCase> meshes;
    meshes.push_back({"icosphere3", "icosphere(3): unit sphere, 1,280 triangles (the thesis's ~1k-triangle case)", 13,
                      std::make_shared<const raykit::SvoMeshData>(rkmesh::icosphere(3))});
    meshes.push_back({"figure", "figure(): a 1.8-unit standing figure, 1,024 triangles (a stand-in for the thesis's 1,027-triangle character)", 13,
                      std::make_shared<const raykit::SvoMeshData>(rkmesh::figure())});
    meshes.push_back({"figure_smooth", "figure() with smooth vertex normals (the builder's general path: clipped pieces and their centroids)", 11,
                      std::make_shared<const raykit::SvoMeshData>(with_smooth_normals(rkmesh::figure()))});
    meshes.push_back({"figure_colour", "figure() with the colour stream only (what the thesis's format stores)", 11,
                      std::make_shared<const raykit::SvoMeshData>(rkmesh::figure()), RK_SVO_ATTR_COLOR});
    meshes.push_back({"figure_colour_shared",
                      "figure() with the colour stream only and shared sub-node attributes (the compact level of detail: a "
                      "stop at level depth-1 reads its brick's colour)", 11,
                      std::make_shared<const raykit::SvoMeshData>(rkmesh::figure()), RK_SVO_ATTR_COLOR | RK_SVO_ATTR_SHARED_SUB});
    meshes.push_back({"menger2", "menger_sponge(2): unit cube, 2,112 triangles, 400 square holes, axis-aligned faces", 11,
                      std::make_shared<const raykit::SvoMeshData>(rkmesh::menger_sponge(2))});
    meshes.push_back({"uvsphere256", "uv_sphere(256, 137): unit sphere, 69,632 triangles (the ~70k case)", 11,
                      std::make_shared<const raykit::SvoMeshData>(rkmesh::uv_sphere(256, 137))});

    add_family(kFam, "Octree build: build_svo on the test meshes, depths 6 and up, 1 and 2 threads");
    std::string keys;
    for (const MeshCase& mc : meshes) {
        const int max_depth = std::min(cap, full ? mc.full_max_depth : kSmokeMaxDepth);
        for (int depth = kMinDepth; depth <= max_depth; ++depth) {
            if (depth <= kPairedMaxDepth) {
                register_row(mc, depth, 1, false, full);
                register_row(mc, depth, 2, true, full);
            } else {
                register_row(mc, depth, 2, false, full);
            }
        }
        benchmark::AddCustomContext("raykit_svo:mesh:" + mc.key, mc.title);
        keys += (keys.empty() ? "" : ",") + mc.key;
    }
    benchmark::AddCustomContext("raykit_svo:meshes", keys);
    benchmark::AddCustomContext("raykit_svo:full", full ? "1" : "0");
    benchmark::AddCustomContext("raykit_svo:attributes", "color,normal,material");
}

const SuiteRegistrar registrar(
    {"svo", 40, "Octree build: include/raykit/svo_build.hpp", "bench/bench_svo.cpp", "build", "", {},
     "- **time**: wall-clock time of one `build_svo` call (surface fill, colour + normal + material streams, "
     "median over the row's iterations: builds repeat until 0.2 s, 2 s for the paired 2-thread rows, so a build "
     "longer than that runs once; one repetition, whatever scripts/bench.sh asks of the other suites); 2T = 2 "
     "worker threads. **speed-up**: median over interleaved pairs of a 1-thread and a 2-thread build run back to "
     "back (alternating which goes first), so machine load that drifts during the run cancels out of the ratio; "
     "the number of pairs is shown.\n"
     "- **B/voxel**: bytes per leaf voxel. *structure* = the geometry words a traversal reads "
     "(`SvoTree::structure_bytes`); *colour* = the colour stream plus the brick bases, i.e. what a "
     "colour-only tree (as the thesis's) stores; *all attr.* = colour + normal + material "
     "(`SvoTree::attribute_bytes`). Attributes cover the inner nodes as well (level of detail).\n"
     "- **vs thesis**: (structure + colour) / the thesis's file size for the same tree, "
     "4 + 8 (1 + 8 N) bytes with N = the non-empty non-leaf nodes (levels 0..depth-1).\n"
     "- **peak memory**: *est.* = `estimate_svo_memory` (an upper estimate, what a memory budget is checked "
     "against), *builder* = `SvoBuildStats::peak_bytes` (the builder's own accounting of its large "
     "allocations), *RSS* = rise of the process's peak resident set over the build (Linux VmHWM).",
     ""},
    &register_svo);

}  // namespace
}  // namespace rkbench
