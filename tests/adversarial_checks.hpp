// GoogleTest glue for the adversarial sweeps (tests/adversarial.hpp): the ADV / ADV_N / CHECK
// macros, value formatting, and the checks of the functions whose body depends on option macros
// (rk_tonemap, rk_fresnel_window, rk_window_glass_reflectance, rk_window_glass_shade). Those are
// in an anonymous namespace: every translation unit of test_adversarial (tests/test_adversarial.cpp
// with the default macros, tests/parts/test_adversarial/*.cpp with others) checks its own build.
// Include after defining the option macros.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "adversarial.hpp"
#include "raykit/fresnel.hpp"
#include "raykit/tonemap.hpp"
#include "raykit/window_glass.hpp"

namespace rktest::adv {

/// Rows of every function's sweep (times RK_ADV_SCALE).
inline constexpr long kRows = 100000;

inline std::string S(float x)
{
    char b[64];
    std::snprintf(b, sizeof b, "%.9g", static_cast<double>(x));
    return b;
}
inline std::string S(glm::vec2 v) { return "(" + S(v.x) + ", " + S(v.y) + ")"; }
inline std::string S(glm::vec3 v) { return "(" + S(v.x) + ", " + S(v.y) + ", " + S(v.z) + ")"; }
inline std::string S(glm::vec4 v) { return "(" + S(v.x) + ", " + S(v.y) + ", " + S(v.z) + ", " + S(v.w) + ")"; }

/// Every sweep's name and row count, for the summary the main test prints.
inline std::vector<Tally>& registry()
{
    static std::vector<Tally> r;
    return r;
}

/// Fails the current test with the sweep's first failures; records the sweep. `per_row`: inputs
/// each row feeds at least (pixels of an image, lookups of a map); the sweep must see >= kRows.
inline void report(Tally t, double per_row = 1.0)
{
    t.rows = static_cast<long>(static_cast<double>(t.rows) * per_row);
    EXPECT_EQ(t.fails, 0) << t.summary();
    EXPECT_GE(t.rows, kRows) << t.name << ": too few inputs";
    registry().push_back(t);
}

}  // namespace rktest::adv

/// ADV(name, body): `body` runs kRows times with `G` (the Gen) and `TL` (the Tally) in scope.
#define ADV(NAME, ...)                                                                                   \
    ::rktest::adv::report(::rktest::adv::sweep(NAME, ::rktest::adv::kRows,                               \
                                               [&](::rktest::adv::Gen & G, ::rktest::adv::Tally & TL) { \
                                                   __VA_ARGS__                                           \
                                               }))
/// ADV_N(name, rows, inputs_per_row, body): for rows with many inputs (images, maps); the sweep
/// must still see >= kRows inputs. A body may also add its row's inputs to TL.rows itself.
#define ADV_N(NAME, ROWS, PER_ROW, ...)                                                                    \
    ::rktest::adv::report(::rktest::adv::sweep(NAME, ROWS,                                                 \
                                               [&](::rktest::adv::Gen & G, ::rktest::adv::Tally & TL) {   \
                                                   __VA_ARGS__                                             \
                                               }),                                                         \
                          PER_ROW)
/// CALL(f, args...): f(args...) with the arguments evaluated left to right (a braced list; a call's
/// own arguments are unsequenced), so a failure lists the drawn arguments in parameter order.
#define CALL(F, ...) std::apply([&](auto&&... rk_arg) { return F(rk_arg...); }, std::tuple{__VA_ARGS__})
/// CHECK(condition, what): records a failure of the current row, with `what` (a string, evaluated
/// only on failure) and the row's arguments.
#define CHECK(COND, WHAT)                                                         \
    do {                                                                          \
        if (!(COND)) TL.fail(G, std::string(#COND) + "  got " + std::string(WHAT)); \
    } while (0)

namespace {

/// The functions built from option macros, in this translation unit's configuration `config`.
/// Promises checked (see the table in tests/test_adversarial.cpp): rk_tonemap in [0, 1] for every
/// input, NaN and ±Inf included; rk_fresnel_window and rk_window_glass_reflectance in [0, 1] for
/// every finite input, the latter 1 at grazing incidence where the model has an interface and
/// panes (its comment); rk_window_glass_shade finite and >= 0.
[[maybe_unused]] void check_configured_functions(const std::string& config)
{
    using namespace raykit;
    using rktest::adv::Floats;
    using rktest::adv::Vecs;
    using rktest::adv::S;
    using rktest::adv::within;
    using rktest::adv::finite;
    const Floats all = Floats::all();
    const Floats any = Floats::any();
    const Floats cosine = Floats::any().mark({0.0f, 1.0f, 0.7597469f, 0.5f});
    const Floats eta = Floats::any().mark({1.0f, 1.52f, 1.0f / 1.52f, RK_FRESNEL_ETA_MIN, RK_FRESNEL_ETA_MAX});
    const Floats panes = Floats::any().mark({0.0f, 1.0f, 2.0f, 1e6f});

    ADV("rk_tonemap [" + config + "]", {
        const vec3 r = CALL(rk_tonemap, G.v3(Vecs::all()), G.f(all));
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_fresnel_window [" + config + "]", {
        const float c = G.f(cosine), e = G.f(eta), n = G.f(panes);
        const float r = rk_fresnel_window(c, e, n);
        CHECK(within(r, 0.0f, 1.0f), S(r));
    });
    ADV("rk_window_glass_reflectance [" + config + "]", {
        const float c = G.f(cosine), e = G.f(eta), n = G.f(panes);
        const float r = rk_window_glass_reflectance(c, e, n);
        CHECK(within(r, 0.0f, 1.0f), S(r));
        // Grazing incidence reflects everything where the model has an interface (eta != 1 after
        // its clamping; the fast mode clamps eta to >= 1) and panes (models that read them:
        // panes >= RK_FLT_MIN).
        const float ec = RK_WINDOW_GLASS_FRESNEL == 1 ? clamp(e, 1.0f, RK_FRESNEL_ETA_MAX) : rk_fresnel_clamp_eta(e);
        const bool uses_panes = RK_WINDOW_GLASS_FRESNEL == 1 || RK_FRESNEL_WINDOW_MODE == 3;
        CHECK(!(c <= 0.0f && ec != 1.0f && (!uses_panes || n >= RK_FLT_MIN)) || r >= 1.0f - 1e-6f, S(r));
    });
    ADV("rk_window_glass_shade [" + config + "]", {
        const vec3 r = CALL(rk_window_glass_shade, G.v3(Vecs::any()), G.v3(Vecs::any()), G.v3(Vecs::all()),
                            G.v3(Vecs::all()), G.v3(Vecs::any()), G.f(eta), G.f(panes));
        CHECK(finite(r) && within(r, 0.0f, RK_FLT_MAX), S(r));
    });
}

}  // namespace
