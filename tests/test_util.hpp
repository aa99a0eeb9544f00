// Small numeric helpers shared by raykit's tests: ULP distance and error statistics that remember
// the worst input, so a failing assertion says where it failed.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <sstream>
#include <string>

namespace rktest {

/// Distance in units in the last place between two floats (+0 and -0 are 0 apart; NaN is infinitely far).
inline double ulp_distance(float a, float b)
{
    if (std::isnan(a) || std::isnan(b)) return std::numeric_limits<double>::infinity();
    auto key = [](float f) {
        std::int32_t i;
        std::memcpy(&i, &f, sizeof i);
        return i < 0 ? static_cast<std::int64_t>(std::numeric_limits<std::int32_t>::min()) - i : static_cast<std::int64_t>(i);
    };
    return static_cast<double>(std::llabs(key(a) - key(b)));
}

/// Distance in ULPs of the float nearest `exact`: error of a float result against a float64 value.
inline double ulp_error(float got, double exact)
{
    const float e = static_cast<float>(exact);
    const double ulp = std::abs(static_cast<double>(std::nextafter(e, std::numeric_limits<float>::infinity())) - e);
    return std::abs(static_cast<double>(got) - exact) / (ulp > 0 ? ulp : std::numeric_limits<float>::denorm_min());
}

/// The value of `candidates` nearest to `got` when `got` lies outside their range, else `got`
/// itself: for comparing against an interval of exact values (input rounding, see CTS intervals).
inline double nearest_in(double got, std::initializer_list<double> candidates)
{
    double lo = *candidates.begin(), hi = lo;
    for (double c : candidates) {
        lo = c < lo ? c : lo;
        hi = c > hi ? c : hi;
    }
    return got < lo ? lo : got > hi ? hi : got;
}

struct ErrorStats {
    double max_abs = 0, sum_abs = 0, max_ulp = 0;
    long count = 0;
    std::string worst;      // input that gave max_abs
    std::string worst_ulp;  // input that gave max_ulp

    void add(double got, double exact, const std::string& input, double ulps = -1)
    {
        const double e = std::abs(got - exact);
        sum_abs += e;
        ++count;
        if (e > max_abs || std::isnan(e)) {
            max_abs = std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
            worst = input;
        }
        if (ulps > max_ulp) {
            max_ulp = ulps;
            worst_ulp = input;
        }
    }
    double mean_abs() const { return count ? sum_abs / static_cast<double>(count) : 0.0; }
    std::string str() const
    {
        std::ostringstream s;
        s.precision(3);
        s << "max abs " << max_abs << " (at " << worst << "), mean abs " << mean_abs();
        if (max_ulp > 0) s << ", max ulp " << max_ulp << " (at " << worst_ulp << ")";
        s << ", n = " << count;
        return s.str();
    }
};

template <typename... T>
std::string fmt(const T&... v)
{
    std::ostringstream s;
    s.precision(9);
    ((s << v << ' '), ...);
    return s.str();
}

}  // namespace rktest
