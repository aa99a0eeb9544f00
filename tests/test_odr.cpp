// Feature macros must not break the one-definition rule: this test links translation units that
// include the same headers with different RK_* macros, built at -O0 where the linker keeps one copy
// of a shared inline definition for all of them:
//   this file                               the defaults;
//   tests/parts/test_odr/other_config.cpp   the first macro of every configured namespace changed;
//   tests/parts/test_odr/second_macros.cpp  the second macro of each namespace that has two or more;
//   tests/parts/test_odr/third_macros.cpp   the third (RK_FRESNEL_WINDOW_MODE of rk_im_window).
// Each TU runs the checks of tests/odr_probe.hpp: every configured function must give what that
// TU's macros say (computed independently), and any two TUs whose macros differ for a check must
// get different results, so that one shared copy would fail. The configured functions live in
// inline namespaces named after the macro values (RK_CONFIGURED_BEGIN, docs/dialect.md), so each
// TU keeps its own. Changing one macro per namespace per TU is what catches a namespace name that
// forgets a macro: the TUs that differ in that macro alone would share the function.
// Odr.EveryOptionMacroIsProbed keeps the list complete: every option macro of shaders/raykit/*.glsl
// is either changed alone by some pair of TUs for some check, or is read by GLSL only (checked).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>

#include "glsl_scan.hpp"
#include "odr_probe.hpp"  // this TU: the defaults

OdrProbe odr_probe_other_config();
OdrProbe odr_probe_second_macros();
OdrProbe odr_probe_third_macros();

static OdrProbe odr_probe_defaults() { RK_ODR_PROBE_BODY }

namespace {
struct Config {
    const char* name;
    OdrProbe probe;
};
std::vector<Config> configs()
{
    return {{"defaults", odr_probe_defaults()},
            {"other_config", odr_probe_other_config()},
            {"second_macros", odr_probe_second_macros()},
            {"third_macros", odr_probe_third_macros()}};
}

float max_abs_diff(const std::vector<float>& a, const std::vector<float>& b)
{
    float d = a.size() == b.size() ? 0.0f : INFINITY;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i) {
        const float e = std::isnan(a[i]) || std::isnan(b[i]) ? INFINITY : std::fabs(a[i] - b[i]);
        d = std::max(d, e);
    }
    return d;
}

std::string show(const std::vector<float>& v)
{
    std::string s;
    for (float x : v) s += (s.empty() ? "" : ", ") + std::to_string(x);
    return "(" + s + ")";
}

/// The macros of check i that differ between probes a and b.
std::set<std::string> differing(const OdrCheck& a, const OdrCheck& b)
{
    std::set<std::string> d;
    for (size_t k = 0; k < a.macros.size() && k < b.macros.size(); ++k) {
        if (a.macros[k].second != b.macros[k].second) d.insert(a.macros[k].first);
    }
    return d;
}
}  // namespace

TEST(Odr, EachTranslationUnitKeepsItsMacros)
{
    const std::vector<Config> c = configs();
    for (size_t i = 0; i < c[0].probe.size(); ++i) {
        std::printf("[odr] %s:", c[0].probe[i].name.c_str());
        for (const Config& x : c) std::printf(" %s %s", x.name, i < x.probe.size() ? show(x.probe[i].got).c_str() : "-");
        std::printf("\n");
    }
    for (const Config& x : c) {
        ASSERT_EQ(x.probe.size(), c[0].probe.size()) << x.name;
        for (size_t i = 0; i < x.probe.size(); ++i) {
            const OdrCheck& k = x.probe[i];
            ASSERT_EQ(k.name, c[0].probe[i].name);
            ASSERT_EQ(k.got.size(), k.want.size()) << k.name;
            EXPECT_LE(max_abs_diff(k.got, k.want), k.tol)
                << x.name << ": " << k.name << " gives " << show(k.got) << ", its macros say " << show(k.want);
        }
    }
    // Any two TUs whose macros differ for a check get different results (else it could not fail).
    int pairs = 0;
    for (size_t a = 0; a < c.size(); ++a) {
        for (size_t b = a + 1; b < c.size(); ++b) {
            for (size_t i = 0; i < c[a].probe.size(); ++i) {
                const OdrCheck &ka = c[a].probe[i], &kb = c[b].probe[i];
                if (differing(ka, kb).empty()) continue;
                ++pairs;
                EXPECT_GT(max_abs_diff(ka.got, kb.got), 10.0f * std::max(ka.tol, kb.tol))
                    << ka.name << ": " << c[a].name << " and " << c[b].name << " differ in their macros but not in "
                    << show(ka.got);
            }
        }
    }
    EXPECT_GE(pairs, 20);
}

// Every option macro of shaders/raykit/*.glsl is covered: some check's macros differ in it alone
// between two TUs (so a namespace name that forgot it would make those two share a definition), or
// it is read by GLSL only: no C++ code mentions it beyond its own default and range check.
TEST(Odr, EveryOptionMacroIsProbed)
{
    // Read only by GLSL (C++ never sees a use): the interior shading pass and the luminance
    // reduction (files C++ does not compile), and resource selection and bindings.
    const std::set<std::string> glsl_only = {
        "RK_IM_SHADING", "RK_IM_ROOM_LIGHTS", "RK_IM_FADE", "RK_IM_FURNITURE_LAYERS", "RK_IM_FURNITURE_FLIPBOOK",
        "RK_LUMINANCE_REDUCE_SOURCE", "RK_LUMINANCE_REDUCE_GROUP", "RK_LUMINANCE_REDUCE_THREAD_TILE",
        "RK_LUMINANCE_HISTOGRAM_BINS", "RK_LUMINANCE_REDUCE_BINDING_IMAGE", "RK_LUMINANCE_REDUCE_BINDING_SCRATCH",
        "RK_LUMINANCE_REDUCE_BINDING_HISTOGRAM", "RK_LUMINANCE_REDUCE_BINDING_RESULT", "RK_SVO_BUFFER_TEXTURE",
        "RK_SVO_WORDS_BINDING", "RK_SVO_MATERIAL_IDS_BINDING", "RK_SVO_MEDIA_BINDING"};
    const std::string inc = std::string(RAYKIT_SAMPLES_DIR) + "/../include/raykit";
    const auto glsl = rktest::read_dir(std::string(RAYKIT_SHADER_DIR) + "/raykit", ".glsl");
    const auto headers = rktest::read_dir(inc, ".hpp");
    ASSERT_GE(glsl.size(), 30u);
    ASSERT_GE(headers.size(), 30u);
    const std::map<std::string, std::string> options = rktest::option_macros(glsl);
    ASSERT_GE(options.size(), 30u);

    // Isolated: macros that some pair of TUs changes alone for some check.
    std::set<std::string> isolated;
    const std::vector<Config> c = configs();
    for (size_t a = 0; a < c.size(); ++a) {
        for (size_t b = a + 1; b < c.size(); ++b) {
            for (size_t i = 0; i < c[a].probe.size(); ++i) {
                const std::set<std::string> d = differing(c[a].probe[i], c[b].probe[i]);
                if (d.size() == 1) isolated.insert(*d.begin());
            }
        }
    }
    for (const auto& kv : options) {
        // RK_IM_NUDGE_TAG names RK_IM_NUDGE's value: the two change together.
        std::string m = kv.first;
        if (m == "RK_IM_NUDGE_TAG") m = "RK_IM_NUDGE";
        EXPECT_TRUE(isolated.count(m) || glsl_only.count(m))
            << kv.first << " (" << kv.second << ") is not probed by tests/test_odr.cpp: add a check to tests/odr_probe.hpp "
            << "and change it alone in one of tests/parts/test_odr/*.cpp (or, if C++ never reads it, list it as GLSL-only)";
        EXPECT_FALSE(isolated.count(m) && glsl_only.count(m)) << m;
    }
    for (const std::string& m : glsl_only) EXPECT_TRUE(options.count(m)) << m << " is no longer an option macro";

    // The GLSL-only ones really are: not in the C++ view of any file C++ compiles (comments and
    // the macro's own #ifndef / #define / range check / RK_OPTION_CHECK lines aside), nor in any
    // header's code (comments and string literals aside).
    const std::set<std::string> cpp = rktest::cpp_compiled(headers, glsl);
    ASSERT_TRUE(cpp.count("svo_format.glsl") && cpp.count("interior_compose.glsl") && !cpp.count("interior_shading.glsl"));
    for (const std::string& m : glsl_only) {
        for (const std::string& f : cpp) {
            const auto g = glsl.find(f);
            ASSERT_NE(g, glsl.end()) << f;
            std::istringstream in(rktest::cpp_view(rktest::strip_comments(g->second, false)));
            std::string line;
            for (int n = 1; std::getline(in, line); ++n) {
                const size_t i = line.find_first_not_of(" \t");
                const std::string t = i == std::string::npos ? std::string() : line.substr(i);
                if (t.rfind("#ifndef " + m, 0) == 0 || t.rfind("#define " + m, 0) == 0 || t.rfind("#if " + m + " <", 0) == 0 ||
                    t.rfind("#error", 0) == 0 || t.rfind("RK_OPTION_CHECK(", 0) == 0)
                    continue;
                EXPECT_FALSE(rktest::mentions(t, m)) << m << " is listed as GLSL-only but C++ reads it: " << f << ":" << n << ": " << t;
            }
        }
        for (const auto& h : headers) {
            const std::string code = rktest::strip_comments(h.second, true);
            EXPECT_FALSE(rktest::mentions(code, m)) << m << " is listed as GLSL-only but " << h.first << " uses it";
        }
    }
}
