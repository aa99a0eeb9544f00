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
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "raykit/common.hpp"
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

/// Registers BM_<suite>/<variant>/<params>: times `fn(input)` over `inputs` and attaches `acc`.
template <class In, class Fn>
void add_bench(const Info& info, const Accuracy& acc, std::vector<In> inputs, Fn fn)
{
    const std::string name = "BM_" + current_suite().info.name + "/" + info.variant + "/" + info.params;
    std::string label = info.family + "|" + info.function + "|" + info.against;
    if (!info.flags.empty()) label += "|" + info.flags;
    benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& st) {
        const In* in = inputs.data();
        const std::size_t n = inputs.size();
        for (auto _ : st) {
            for (std::size_t i = 0; i < n; ++i) {
                auto r = fn(in[i]);
                benchmark::DoNotOptimize(r);
            }
        }
        st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(n));
        // n calls per iteration as a rate, inverted: seconds per call (the console shows "ns").
        st.counters["time_per_call"] = benchmark::Counter(static_cast<double>(n),
                                                        benchmark::Counter::kIsIterationInvariantRate |
                                                            benchmark::Counter::kInvert);
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
    });
}

}  // namespace rkbench
