// raykit — bench_common.hpp: the parts of raykit_bench that every bench_<tech>.cpp shares: accuracy
// bookkeeping, input generation, benchmark registration and the per-file ("suite") context that
// scripts/bench_report.py turns into docs/benchmarks.md.
//
// A bench file registers itself, without editing bench_main.cpp, with one static registrar:
//
//   void register_all() { rkbench::add_family("fam", "Title: details"); rkbench::add_bench(...); }
//   const rkbench::SuiteRegistrar registrar({"tech", 20, "Title", "bench/bench_tech.cpp", ...}, &register_all);
//
// main() runs the registered suites in ascending `order` (then name), so the benchmark order, and
// with it the report's, does not depend on the link order of the files.
//
// Every benchmark is named BM_<suite>/<variant>/<parameters> and reports:
//   items_per_second, time_per_call  speed over a pre-generated array of kInputs inputs (each
//                                    call's arguments, per-material constants included, are loaded
//                                    from that array so nothing per-material is hoisted out of the
//                                    loop, as it cannot be on a GPU either);
//   max_abs_err, mean_abs_err        error against a float64 reference, computed once at start-up,
//                                    outside any timing;
//   max_ulp                          only where meaningful (exact functions whose result does not
//                                    cross zero);
//   worst_at                         the swept input where max_abs_err occurs, or, for RGB inputs,
//   worst_at_r, worst_at_g, worst_at_b  the three channels of that input.
// The label is "<family>|<function>|<what the error is measured against>[|<flags>]"; flags is a
// comma list, "cross" marking an error measured against a different formula (another fit) rather
// than the function's own. Family titles and the suites' metadata are in the JSON context.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <type_traits>
#include <string>
#include <utility>
#include <vector>

#include "raykit/common.hpp"
#include "stats.hpp"
#include "test_util.hpp"

namespace rkbench {

constexpr std::size_t kInputs = 4096;  // calls per benchmark iteration
constexpr int kSweep = 20001;          // accuracy sweep points (per swept range)

// ---------------------------------------------------------------------------------------------
// Accuracy bookkeeping.

struct Accuracy {
    double max_abs = 0.0, sum_abs = 0.0, max_ulp = 0.0, worst_at = 0.0;
    std::array<double, 3> worst_rgb{};  // with has_rgb: the RGB input where max_abs occurs
    long count = 0;
    bool has_ulp = false;
    bool has_rgb = false;

    /// Adds one result with its float64 reference; `at` is the (scalar) input it came from.
    void add(double got, double exact, double at)
    {
        if (record(got, exact)) worst_at = at;
    }
    /// As add(), for an RGB input (reported as worst_at_r/g/b).
    void add(double got, double exact, const raykit::vec3& at)
    {
        has_rgb = true;
        if (record(got, exact)) {
            worst_rgb = {static_cast<double>(at.x), static_cast<double>(at.y), static_cast<double>(at.z)};
        }
    }
    void add_ulp(float got, double exact, double at)
    {
        add(static_cast<double>(got), exact, at);
        note_ulp(got, exact);
    }
    /// Tracks the ulp error of `got` without adding to the absolute error (for callers that add a
    /// scaled error themselves).
    void note_ulp(float got, double exact)
    {
        has_ulp = true;
        max_ulp = std::max(max_ulp, rktest::ulp_error(got, exact));
    }
    double mean_abs() const { return count > 0 ? sum_abs / static_cast<double>(count) : 0.0; }

private:
    /// Adds |got - exact| (NaN counts as infinite); true when it is the new maximum.
    bool record(double got, double exact)
    {
        double e = std::abs(got - exact);
        if (std::isnan(e)) e = std::numeric_limits<double>::infinity();
        sum_abs += e;
        ++count;
        if (e > max_abs || count == 1) {
            max_abs = e;
            return true;
        }
        return false;
    }
};

/// The i-th of kSweep points spread evenly over [lo, hi], rounded to float (the function's input).
inline float sweep_point(int i, double lo, double hi)
{
    return static_cast<float>(lo + (hi - lo) * static_cast<double>(i) / static_cast<double>(kSweep - 1));
}

/// The i-th of kSweep points spread evenly in log scale over [lo, hi] (lo > 0), rounded to float.
inline float log_sweep_point(int i, double lo, double hi)
{
    const double t = static_cast<double>(i) / static_cast<double>(kSweep - 1);
    return static_cast<float>(lo * std::pow(hi / lo, t));
}

/// Accuracy over the sweep of [lo, hi]: `visit(x, acc)` evaluates the function at float x and adds
/// the result(s) with their float64 reference.
template <class Visit>
Accuracy sweep(double lo, double hi, Visit visit)
{
    Accuracy acc;
    for (int i = 0; i < kSweep; ++i) {
        visit(sweep_point(i, lo, hi), acc);
    }
    return acc;
}

inline double d(float x) { return static_cast<double>(x); }

// ---------------------------------------------------------------------------------------------
// Inputs: uniform random numbers from a fixed seed, generated before any timing.

class Rng {
public:
    explicit Rng(std::uint32_t seed = 20240601u) : gen_(seed) {}

    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(gen_); }
    /// An integer in [0, n).
    int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(gen_); }
    raykit::vec3 unit_vector()
    {
        for (;;) {
            raykit::vec3 v(uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f), uniform(-1.0f, 1.0f));
            float l2 = glm::dot(v, v);
            if (l2 > 1e-4f && l2 <= 1.0f) return v / std::sqrt(l2);
        }
    }

private:
    std::mt19937 gen_;
};

/// kInputs values of `make(rng, i)`, from the same seed for every benchmark (so rows that time the
/// same kind of input time the same inputs).
template <class In, class Make>
std::vector<In> make_inputs(Make make)
{
    Rng rng;
    std::vector<In> v;
    v.reserve(kInputs);
    for (std::size_t i = 0; i < kInputs; ++i) v.push_back(make(rng, i));
    return v;
}

// ---------------------------------------------------------------------------------------------
// Suites (one per bench_<tech>.cpp) and their families.

/// What a bench file says about itself; main() writes it into the JSON context as
/// raykit_suite:<name>:<field> (see bench_main.cpp), so the report needs no knowledge of its own.
struct SuiteInfo {
    std::string name;      // BM_<name>/...; also names the plot, img/bench_<name>_speed_error.png
    int order = 0;         // suites run (and are reported) in ascending order
    std::string title;     // section heading, "<short>: <details>"
    std::string source;    // the bench file, e.g. "bench/bench_fresnel.cpp"
    std::string unit;      // what one call processes: "call", "RGB pixel"
    std::string baseline;  // benchmark whose time is the suite's relative cost 1.0
    std::vector<std::string> plot_families;  // families drawn on the speed-vs-error plot
    std::string about;     // Markdown: what the rows measure, how errors are taken, etc.
    std::string gpu;       // Markdown: how the CPU figures relate to a GPU
    // Goals the report checks, ';'-separated "<row>|<max abs err>|<max relative cost>|<what>", e.g.
    // "BM_fresnel/poly/eta:1.52|0.005|1.3|glass"; the report says met or missed with both numbers.
    std::string goals = {};
    // The error the speed-vs-error plot's x axis shows: "max" (default) or "mean" (where every row's
    // maximum sits at the same few hard points, e.g. shadow edges, and the mean tells them apart).
    std::string plot_error = "max";
};

struct Suite {
    SuiteInfo info;
    void (*register_benchmarks)() = nullptr;
    std::vector<std::pair<std::string, std::string>> families;  // (key, title), registration order
};

inline std::vector<Suite>& suites()
{
    static std::vector<Suite> s;
    return s;
}

/// Index in suites() of the suite whose benchmarks are being registered.
inline std::size_t& current_suite_index()
{
    static std::size_t i = 0;
    return i;
}

inline Suite& current_suite() { return suites().at(current_suite_index()); }

/// Registers a bench file's suite at static-initialisation time.
class SuiteRegistrar {
public:
    SuiteRegistrar(SuiteInfo info, void (*register_benchmarks)())
    {
        Suite s;
        s.info = std::move(info);
        s.register_benchmarks = register_benchmarks;
        suites().push_back(std::move(s));
    }
};

/// Declares a family of the suite being registered: `title` is "<heading>: <details>".
inline void add_family(const std::string& key, const std::string& title)
{
    current_suite().families.emplace_back(key, title);
}

struct Info {
    std::string variant;   // BM_<suite>/<variant>/...
    std::string params;    // .../<params>, e.g. "eta:1.52"
    std::string family;    // key of a raykit_family:<key> context entry
    std::string function;  // the call, as a reader would write it
    std::string against;   // what the error is measured against
    std::string flags = {};  // optional comma list, e.g. "cross"
};

// ---------------------------------------------------------------------------------------------
// Paired timing.
//
// A "pass" runs one function over its kInputs pre-generated inputs, keeping each result alive with
// sink(); a row's *harness* pass is the same loop sinking each input unchanged (the loads and the
// loop every call pays). Every benchmark registered by add_bench times, in each of
// its iterations, four passes back to back: its own function, its harness, the suite's baseline
// function (SuiteInfo::baseline) and the baseline's harness, in an order that rotates so that no
// pass always runs first or after the same other pass. Each iteration gives one paired sample; the
// counters are medians over the iterations:
//   time_per_call              own pass (the manual time Google Benchmark reports), seconds per call
//   harness_per_call           own harness pass, seconds per call
//   baseline_per_call          baseline pass, seconds per call
//   baseline_harness_per_call  baseline's harness pass, seconds per call
//   rel_cost                   (own - own harness) / (baseline - baseline harness) per iteration
//   rel_cost_gross             own / baseline, harnesses included
// A machine that slows down for a while slows the three passes of an iteration alike, so the
// ratios survive what absolute times do not; --benchmark_repetitions then gives the run-to-run
// spread of each ratio (scripts/bench_report.py shows the median and the range of repetitions).

/// Keeps a pass's result alive without a memory round trip: floats and integers stay in a register
/// (an empty asm that takes them as a register operand), GLM vectors component by component; other
/// types fall back to benchmark::DoNotOptimize, which stores to memory and clobbers it. (With
/// DoNotOptimize alone every call paid a store, a reload and a compiler barrier, a fixed cost of
/// several cycles that compressed every ratio.)
template <class T>
inline void sink(const T& v)
{
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    if constexpr (std::is_same<T, float>::value || std::is_same<T, double>::value) {
        asm volatile("" : : "x"(v));
    } else if constexpr (std::is_integral<T>::value || std::is_enum<T>::value) {
        asm volatile("" : : "r"(v));
    } else if constexpr (std::is_same<T, raykit::vec2>::value || std::is_same<T, raykit::vec3>::value ||
                         std::is_same<T, raykit::vec4>::value) {
        for (int i = 0; i < T::length(); ++i) sink(v[i]);
    } else {
        benchmark::DoNotOptimize(v);
    }
#else
    benchmark::DoNotOptimize(v);
#endif
}

using PassFn = std::function<void()>;

struct Passes {
    PassFn own, harness;
};

/// Every add_bench row's passes by benchmark name (filled at registration, before anything runs).
inline std::map<std::string, Passes>& pass_registry()
{
    static std::map<std::string, Passes> m;
    return m;
}

using rkbench_stats::median;

/// Runs the own pass, the baseline's pass and both harnesses once each per iteration in rotating
/// order (see above); sets the iteration's manual time to the own pass and the paired counters.
/// `n` = calls per pass.
inline void run_paired(benchmark::State& st, const Passes& own, const Passes& base, std::size_t n)
{
    using clock = std::chrono::steady_clock;
    // The four cyclic rotations and their reversals: each pass runs first, last, and before and
    // after each other pass equally often.
    static const int kOrders[8][4] = {{0, 1, 2, 3}, {1, 2, 3, 0}, {2, 3, 0, 1}, {3, 0, 1, 2},
                                      {3, 2, 1, 0}, {0, 3, 2, 1}, {1, 0, 3, 2}, {2, 1, 0, 3}};
    const PassFn* pass[4] = {&own.own, &own.harness, &base.own, &base.harness};
    std::vector<double> t_own, t_h, t_base, t_bh, rel, rel_gross;
    std::size_t k = 0;
    for (auto _ : st) {
        double t[4] = {0.0, 0.0, 0.0, 0.0};
        for (int j = 0; j < 4; ++j) {
            const int w = kOrders[k % 8][j];
            const auto t0 = clock::now();
            (*pass[w])();
            const auto t1 = clock::now();
            t[w] = std::chrono::duration<double>(t1 - t0).count();
        }
        ++k;
        st.SetIterationTime(t[0]);
        t_own.push_back(t[0]);
        t_h.push_back(t[1]);
        t_base.push_back(t[2]);
        t_bh.push_back(t[3]);
        rel_gross.push_back(t[2] > 0.0 ? t[0] / t[2] : 0.0);
        if (t[2] - t[3] > 0.0) rel.push_back((t[0] - t[1]) / (t[2] - t[3]));
    }
    const double per = 1.0 / static_cast<double>(n);
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(n));
    st.counters["time_per_call"] = median(t_own) * per;
    st.counters["harness_per_call"] = median(t_h) * per;
    st.counters["baseline_per_call"] = median(t_base) * per;
    st.counters["baseline_harness_per_call"] = median(t_bh) * per;
    st.counters["rel_cost"] = median(rel);
    st.counters["rel_cost_gross"] = median(rel_gross);
}

/// Registers BM_<suite>/<variant>/<params>: times `fn(input)` over `inputs`, paired with the suite's
/// baseline and the harness (run_paired), and attaches `acc`.
template <class In, class Fn>
void add_bench(const Info& info, const Accuracy& acc, std::vector<In> inputs, Fn fn)
{
    const std::string name = "BM_" + current_suite().info.name + "/" + info.variant + "/" + info.params;
    const std::string baseline = current_suite().info.baseline;
    std::string label = info.family + "|" + info.function + "|" + info.against;
    if (!info.flags.empty()) label += "|" + info.flags;
    const auto in = std::make_shared<const std::vector<In>>(std::move(inputs));
    Passes p;
    p.own = [in, fn]() {
        for (const In& x : *in) sink(fn(x));
    };
    p.harness = [in]() {
        for (const In& x : *in) sink(x);
    };
    pass_registry()[name] = p;
    const std::size_t n = in->size();
    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) {
        const auto& reg = pass_registry();
        const auto b = reg.find(baseline);
        // Without a registered baseline (another suite's style), the row is paired with itself.
        run_paired(st, p, b != reg.end() ? b->second : p, n);
        st.counters["max_abs_err"] = acc.max_abs;
        st.counters["mean_abs_err"] = acc.mean_abs();
        if (acc.has_ulp) st.counters["max_ulp"] = acc.max_ulp;
        if (acc.has_rgb) {
            st.counters["worst_at_r"] = acc.worst_rgb[0];
            st.counters["worst_at_g"] = acc.worst_rgb[1];
            st.counters["worst_at_b"] = acc.worst_rgb[2];
        } else {
            st.counters["worst_at"] = acc.worst_at;
        }
        st.SetLabel(label);
    })->UseManualTime();
}

}  // namespace rkbench
