// raykit — bench_main.cpp: main() of raykit_bench. Every bench_<tech>.cpp registers a suite through
// a static rkbench::SuiteRegistrar (bench_common.hpp); this file only runs them, in ascending
// order, and records in the JSON context what scripts/bench_report.py needs to write
// docs/benchmarks.md:
//   raykit_build_type, raykit_compiler       how raykit was compiled
//   raykit_inputs_per_iteration, raykit_sweep_points
//   raykit_suites                            the suites' names, in report order
//   raykit_suite:<s>:<field>                 title, source, unit, baseline, families (in order),
//                                            plot_families, about, gpu, goals, plot_error (see rkbench::SuiteInfo)
//   raykit_family:<family>                   a family's title
//   raykit_baseline, raykit_plot_families    the first suite's baseline and the union of every
//                                            suite's plot families (read by older reports)
#include <algorithm>
#include <string>
#include <vector>

#include "bench_common.hpp"

#ifndef RAYKIT_BENCH_BUILD_TYPE
#define RAYKIT_BENCH_BUILD_TYPE "unknown"
#endif
#ifndef RAYKIT_BENCH_COMPILER
#define RAYKIT_BENCH_COMPILER "unknown"
#endif

namespace {

std::string join(const std::vector<std::string>& v)
{
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ",") + x;
    return s;
}

}  // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

    auto& suites = rkbench::suites();
    std::stable_sort(suites.begin(), suites.end(), [](const rkbench::Suite& a, const rkbench::Suite& b) {
        return a.info.order != b.info.order ? a.info.order < b.info.order : a.info.name < b.info.name;
    });
    for (std::size_t i = 0; i < suites.size(); ++i) {
        rkbench::current_suite_index() = i;
        suites[i].register_benchmarks();
    }

    benchmark::AddCustomContext("raykit_build_type", RAYKIT_BENCH_BUILD_TYPE);
    benchmark::AddCustomContext("raykit_compiler", RAYKIT_BENCH_COMPILER);
    benchmark::AddCustomContext("raykit_inputs_per_iteration", std::to_string(rkbench::kInputs));
    benchmark::AddCustomContext("raykit_sweep_points", std::to_string(rkbench::kSweep));

    std::vector<std::string> names, plot_union;
    for (const rkbench::Suite& s : suites) {
        const rkbench::SuiteInfo& in = s.info;
        const std::string key = "raykit_suite:" + in.name + ":";
        names.push_back(in.name);
        std::vector<std::string> fams;
        for (const auto& f : s.families) {
            fams.push_back(f.first);
            benchmark::AddCustomContext("raykit_family:" + f.first, f.second);
        }
        for (const std::string& f : in.plot_families) {
            if (std::find(plot_union.begin(), plot_union.end(), f) == plot_union.end()) plot_union.push_back(f);
        }
        benchmark::AddCustomContext(key + "title", in.title);
        benchmark::AddCustomContext(key + "source", in.source);
        benchmark::AddCustomContext(key + "unit", in.unit);
        benchmark::AddCustomContext(key + "baseline", in.baseline);
        benchmark::AddCustomContext(key + "families", join(fams));
        benchmark::AddCustomContext(key + "plot_families", join(in.plot_families));
        benchmark::AddCustomContext(key + "about", in.about);
        benchmark::AddCustomContext(key + "gpu", in.gpu);
        benchmark::AddCustomContext(key + "goals", in.goals);
        benchmark::AddCustomContext(key + "plot_error", in.plot_error);
    }
    benchmark::AddCustomContext("raykit_suites", join(names));
    if (!suites.empty()) benchmark::AddCustomContext("raykit_baseline", suites.front().info.baseline);
    benchmark::AddCustomContext("raykit_plot_families", join(plot_union));

    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
