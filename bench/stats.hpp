// raykit — bench/stats.hpp: the statistics shared by raykit_bench (bench_common.hpp, bench_svo.cpp)
// and raykit_bench_trace (trace/trace_harness.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace rkbench_stats {

/// The median of v (the mean of the two middle values for an even count); 0 for an empty v.
inline double median(std::vector<double> v)
{
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace rkbench_stats
