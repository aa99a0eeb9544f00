// cmake/RaykitDefines.cmake against the C++ helpers it stands in for: raykit_interior_defines and
// raykit_tonemap_defines must give exactly interior_defines() / tonemap_defines() (names, values,
// order) for every tone operator and look and for 600 scene descriptions (all corners of the
// boolean options plus random ones), and reject bad arguments with a message naming the valid ones.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "raykit/interior_features.hpp"
#include "raykit/tonemap.hpp"

using namespace raykit;

namespace {

std::string joined(const std::vector<ShaderDefine>& d)
{
    std::string s;
    for (const ShaderDefine& x : d) s += (s.empty() ? "" : ";") + x.name + "=" + x.value;
    return s;
}

// Runs a CMake script that includes RaykitDefines.cmake; returns its output (stdout + stderr) and
// exit status.
int run_cmake(const std::string& body, std::string& out)
{
    const std::string path = std::string(::testing::TempDir()) + "rk_defines_test.cmake";
    std::ofstream(path) << "include(\"" << RAYKIT_CMAKE_DIR << "/RaykitDefines.cmake\")\n" << body;
    FILE* p = popen((std::string(RAYKIT_CMAKE) + " -P " + path + " 2>&1").c_str(), "r");
    if (!p) return -1;
    char buf[4096];
    out.clear();
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    return pclose(p);
}

const char* const kTextures[] = {"four_textures", "texture_array", "padded_atlas", "cube_per_room"};
const char* const kOperators[] = {"clamp", "reinhard", "aces_narkowicz", "aces_hill", "agx",
                                  "pbr_neutral", "hable", "lottes", "uchimura"};

}  // namespace

TEST(CmakeDefines, TonemapMatchesTheCppHelper)
{
    std::string script, want;
    for (int op = 0; op < 9; ++op) {
        for (int look = 0; look < 3; ++look) {
            script += std::string("raykit_tonemap_defines(d OPERATOR ") + kOperators[op] + " AGX_LOOK " + std::to_string(look) +
                      ")\nmessage(\"case: ${d}\")\n";
            want += "case: " + joined(tonemap_defines(static_cast<ToneOperator>(op), look)) + "\n";
        }
    }
    script += "raykit_tonemap_defines(d OPERATOR agx AGX_LOOK punchy)\nmessage(\"case: ${d}\")\n";
    want += "case: " + joined(tonemap_defines(ToneOperator::agx, 2)) + "\n";
    std::string out;
    ASSERT_EQ(run_cmake(script, out), 0) << out;
    EXPECT_EQ(out, want);
}

TEST(CmakeDefines, InteriorMatchesTheCppHelper)
{
    std::mt19937 rng(7);
    std::string script, want;
    for (int i = 0; i < 600; ++i) {
        InteriorSceneDesc d;
        std::string args;
        const bool corner = i < 128;  // the 2^7 combinations of the booleans, random rest
        auto flag = [&](int bit) { return corner ? ((i >> bit) & 1) != 0 : (rng() & 1u) != 0; };
        const int tex = static_cast<int>(rng() % 5u);  // 4: left to the default
        if (tex < 4) {
            d.textures = static_cast<InteriorTextures>(tex);
            args += std::string(" TEXTURES ") + kTextures[tex];
        }
        if (rng() % 3u == 0u) {
            d.glass = InteriorGlass::thesis_additive;
            args += " GLASS thesis_additive";
        } else if (rng() % 2u == 0u) {
            args += " GLASS fresnel";
        }
        d.furniture_layers = static_cast<int>(rng() % 5u);
        if (d.furniture_layers > 0 || rng() % 2u == 0u) args += " FURNITURE_LAYERS " + std::to_string(d.furniture_layers);
        if ((d.room_lights = flag(0))) args += " ROOM_LIGHTS";
        if ((d.furniture_flipbook = !flag(1)) == false) args += " NO_FURNITURE_FLIPBOOK";
        if ((d.varying_walls = flag(2))) args += " VARYING_WALLS";
        if ((d.reflections = flag(3))) args += " REFLECTIONS";
        if (flag(4)) {
            d.fade_distance = 100.0f;
            args += " FADE";
        }
        if ((d.textured_facade = flag(5))) args += " TEXTURED_FACADE";
        if ((d.tonemap_output = flag(6))) args += " TONEMAP_OUTPUT";
        script += "raykit_interior_defines(d" + args + ")\nmessage(\"case: ${d}\")\n";
        want += "case: " + joined(interior_defines(d)) + "\n";
    }
    std::string out;
    ASSERT_EQ(run_cmake(script, out), 0) << out;
    EXPECT_EQ(out, want);
}

TEST(CmakeDefines, BadArgumentsAreErrorsNamingTheValidOnes)
{
    struct Bad {
        const char* call;
        const char* message;
    };
    for (const Bad& b : {Bad{"raykit_tonemap_defines(d OPERATOR aces)", "OPERATOR must be one of clamp;reinhard"},
                         Bad{"raykit_tonemap_defines(d OPERATOR agx AGX_LOOK 3)", "AGX_LOOK must be"},
                         Bad{"raykit_tonemap_defines(d OPERATOR agx LOOK 1)", "unexpected arguments"},
                         Bad{"raykit_interior_defines(d TEXTURES array)", "TEXTURES must be one of four_textures"},
                         Bad{"raykit_interior_defines(d FURNITURE_LAYERS 5)", "FURNITURE_LAYERS must be 0..4"},
                         Bad{"raykit_interior_defines(d GLASS additive)", "GLASS must be fresnel or thesis_additive"},
                         Bad{"raykit_interior_defines(d ROOMLIGHTS)", "unexpected arguments 'ROOMLIGHTS'"}}) {
        std::string out;
        EXPECT_NE(run_cmake(std::string(b.call) + "\n", out), 0) << b.call;
        std::string flat;  // CMake wraps long messages: compare with runs of white space as one
        for (char c : out) {
            const bool ws = c == ' ' || c == '\n';
            if (!ws || (!flat.empty() && flat.back() != ' ')) flat += ws ? ' ' : c;
        }
        EXPECT_NE(flat.find(b.message), std::string::npos) << b.call << "\n" << out;
    }
}
