// Tests of raykit/interior_features.hpp: the macro set of a scene description and the padded-atlas
// rule (checked against a brute-force simulation of the bilinear taps, and against an emulation of
// box-filtered mip levels sampled with GL_LINEAR).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "raykit/interior_features.hpp"
#include "raykit/shader_source.hpp"

using namespace raykit;

namespace {

std::map<std::string, std::string> as_map(const std::vector<ShaderDefine>& v)
{
    std::map<std::string, std::string> m;
    for (const ShaderDefine& d : v) {
        EXPECT_EQ(m.count(d.name), 0u) << "duplicate " << d.name;
        m[d.name] = d.value;
    }
    return m;
}

}  // namespace

TEST(InteriorFeatures, DefaultSceneIsTheRecommendedMaterial)
{
    // The default follows the docs' recommendation (a texture array); thesis() is four textures.
    EXPECT_EQ(as_map(interior_defines(InteriorSceneDesc{})).at("RK_IM_SHADING"), "1");
    const auto m = as_map(interior_defines(InteriorSceneDesc::thesis()));
    EXPECT_EQ(m.size(), 10u);
    EXPECT_EQ(m.at("RK_IM_SHADING"), "0");
    EXPECT_EQ(m.at("RK_IM_COMPOSE_MODE"), "0");
    EXPECT_EQ(m.at("RK_IM_ROOM_LIGHTS"), "0");
    EXPECT_EQ(m.at("RK_IM_FURNITURE_LAYERS"), "0");  // no furniture -> the feature compiled out
    EXPECT_EQ(m.at("RK_IM_FURNITURE_FLIPBOOK"), "0");  // ... and so is its flipbook
    EXPECT_EQ(m.at("RK_IM_VARYING_WALLS"), "0");
    EXPECT_EQ(m.at("RK_IM_REFLECTION"), "0");
    EXPECT_EQ(m.at("RK_IM_FADE"), "0");
    EXPECT_EQ(m.at("RK_IM_BUILDING_FACADE"), "0");
    EXPECT_EQ(m.at("RK_IM_BUILDING_OUTPUT"), "0");
}

TEST(InteriorFeatures, EachFeatureMapsToItsMacro)
{
    InteriorSceneDesc d;
    d.textures = InteriorTextures::cube_per_room;
    d.glass = InteriorGlass::thesis_additive;
    d.room_lights = true;
    d.furniture_layers = 3;
    d.varying_walls = true;
    d.reflections = true;
    d.fade_distance = 250.0f;
    d.textured_facade = true;
    d.tonemap_output = true;
    const auto m = as_map(interior_defines(d));
    EXPECT_EQ(m.at("RK_IM_SHADING"), "3");
    EXPECT_EQ(m.at("RK_IM_COMPOSE_MODE"), "1");
    EXPECT_EQ(m.at("RK_IM_ROOM_LIGHTS"), "1");
    EXPECT_EQ(m.at("RK_IM_FURNITURE_LAYERS"), "3");
    EXPECT_EQ(m.at("RK_IM_FURNITURE_FLIPBOOK"), "1");  // furniture_flipbook defaults to true
    EXPECT_EQ(m.at("RK_IM_VARYING_WALLS"), "1");
    EXPECT_EQ(m.at("RK_IM_REFLECTION"), "1");
    EXPECT_EQ(m.at("RK_IM_FADE"), "1");
    EXPECT_EQ(m.at("RK_IM_BUILDING_FACADE"), "1");
    EXPECT_EQ(m.at("RK_IM_BUILDING_OUTPUT"), "1");
    d.textures = InteriorTextures::padded_atlas;
    EXPECT_EQ(as_map(interior_defines(d)).at("RK_IM_SHADING"), "2");
    d.textures = InteriorTextures::texture_array;
    EXPECT_EQ(as_map(interior_defines(d)).at("RK_IM_SHADING"), "1");
    d.furniture_flipbook = false;  // single-image sprites: the flipbook lookup compiled out
    EXPECT_EQ(as_map(interior_defines(d)).at("RK_IM_FURNITURE_FLIPBOOK"), "0");
    d.furniture_flipbook = true;
    // The injected text defines each macro once, after #version.
    const std::string src = inject_shader_defines("#version 450 core\nvoid main() {}\n", interior_defines(d));
    EXPECT_NE(src.find("#define RK_IM_FURNITURE_LAYERS 3"), std::string::npos);
    EXPECT_LT(src.find("#version"), src.find("#define RK_IM_SHADING 1"));
}

TEST(InteriorFeatures, InvalidDescriptionsAreReported)
{
    auto expect_bad = [](const InteriorSceneDesc& d, const char* field) {
        Status st;
        EXPECT_TRUE(interior_defines(d, &st).empty());
        EXPECT_EQ(st.code, Error::invalid_argument);
        EXPECT_NE(st.message.find(field), std::string::npos) << st.message;
        EXPECT_TRUE(interior_defines(d).empty());
    };
    InteriorSceneDesc d;
    d.furniture_layers = 5;
    expect_bad(d, "furniture_layers");
    d.furniture_layers = -1;
    expect_bad(d, "furniture_layers");
    d.furniture_layers = 0;
    d.fade_distance = -1.0f;
    expect_bad(d, "fade_distance");
    d.fade_distance = std::numeric_limits<float>::infinity();
    expect_bad(d, "fade_distance");
    d.fade_distance = std::numeric_limits<float>::quiet_NaN();
    expect_bad(d, "fade_distance");
    d.fade_distance = 10.0f;
    Status st;
    EXPECT_EQ(interior_defines(d, &st).size(), 10u);
    EXPECT_TRUE(st.ok());
}

TEST(InteriorFeatures, AtlasPaddingRuleVsBruteForce)
{
    // Brute force: for every tile-interior sample position on a fine sub-texel lattice, at every
    // level, the base-texel span of the two bilinear taps (each a cell-aligned 2^lod block) must lie
    // inside the cell. Compare with interior_atlas_mip_safe for several paddings.
    auto brute = [](int tile, int pad, int lod) {
        const int cell = tile + 2 * pad;
        const int s = 1 << lod;
        if (cell % s != 0) return false;
        for (int i = 0; i < tile * 16; ++i) {
            const double x = pad + (i + 0.5) / 16.0;  // base-texel coordinate in the tile proper
            const double xl = x / s - 0.5;
            const long t0 = static_cast<long>(std::floor(xl));
            if (t0 * s < 0 || (t0 + 2) * s > cell) return false;
        }
        return true;
    };
    int safe = 0, unsafe = 0;
    for (int lod = 0; lod <= 4; ++lod) {
        for (int pad = 0; pad <= 20; ++pad) {
            for (int tile : {16, 32, 48, 64}) {
                InteriorAtlasLayout l;
                l.tile = tile;
                l.pad = pad;
                l.grid = 4;
                l.max_lod = lod;
                const bool b = brute(tile, pad, lod);
                EXPECT_EQ(interior_atlas_mip_safe(l, lod), b) << tile << " " << pad << " " << lod;
                (b ? safe : unsafe) += 1;
            }
        }
    }
    EXPECT_GT(safe, 20);
    EXPECT_GT(unsafe, 20);
    // The layout helper's padding is valid at every level up to max_lod, and the minimal one.
    for (int lod = 0; lod <= 5; ++lod) {
        const InteriorAtlasLayout l = interior_atlas_layout(64, 4, lod);
        EXPECT_EQ(l.pad, lod == 0 ? 1 : 1 << (lod - 1));
        for (int k = 0; k <= lod; ++k) EXPECT_TRUE(interior_atlas_mip_safe(l, k)) << lod << " " << k;
        {
            InteriorAtlasLayout smaller = l;
            smaller.pad = l.pad - 1;
            EXPECT_FALSE(brute(smaller.tile, smaller.pad, lod)) << lod;
            EXPECT_FALSE(interior_atlas_mip_safe(smaller, lod)) << lod;
        }
        EXPECT_EQ(l.size(), 4 * (64 + 2 * l.pad));
    }
    Status st;
    EXPECT_EQ(interior_atlas_layout(60, 4, 3, &st).size(), 0);  // 60 not a multiple of 8
    EXPECT_EQ(st.code, Error::invalid_argument);
    EXPECT_EQ(interior_atlas_layout(64, 0, 2, &st).size(), 0);
    EXPECT_EQ(interior_atlas_layout(64, 1, 13, &st).size(), 0);
    // Too large, including sizes whose int product would overflow.
    EXPECT_EQ(interior_atlas_layout(4096, 17, 0, &st).size(), 0);
    EXPECT_NE(st.message.find("too large"), std::string::npos) << st.message;
    EXPECT_EQ(interior_atlas_layout(1 << 30, 1 << 20, 0, &st).size(), 0);
    EXPECT_EQ(interior_atlas_layout(4094, 16, 0, &st).size(), 65536);  // (4094 + 2) * 16: the limit itself
    EXPECT_TRUE(st.ok());
}

TEST(InteriorFeatures, AtlasPaddingRuleVsEmulatedMipFiltering)
{
    // Independent of the tap arithmetic above: an atlas whose texels hold their cell's id (1-D per
    // axis: the rule is separable), the mip chain built by 2:1 box filtering as glGenerateMipmap
    // does for power-of-two sizes (a texel mixing two cells gets a value that is no cell's id),
    // and GL_LINEAR sampling (texel centres at i + 1/2, clamp to edge) at level L of every
    // sub-texel position inside every tile proper. The layout is mip-safe at L iff no tap with a
    // non-zero weight reads a value other than the sampled tile's id.
    auto emulate = [](int tile, int pad, int grid, int lod) {
        const int cell = tile + 2 * pad, size = grid * cell;
        std::vector<std::vector<double>> levels(1, std::vector<double>(static_cast<size_t>(size)));
        for (int x = 0; x < size; ++x) levels[0][static_cast<size_t>(x)] = 1.0 + x / cell;  // cell id
        for (int l = 1; l <= lod; ++l) {
            const std::vector<double>& prev = levels.back();
            if (prev.size() % 2 != 0) return false;  // odd size: GL's rounding would mix texels
            std::vector<double> next(prev.size() / 2);
            for (size_t i = 0; i < next.size(); ++i) next[i] = 0.5 * (prev[2 * i] + prev[2 * i + 1]);
            levels.push_back(next);
        }
        const std::vector<double>& lv = levels[static_cast<size_t>(lod)];
        const double scale = static_cast<double>(lv.size()) / size;
        for (int c = 0; c < grid; ++c) {
            const double id = 1.0 + c;
            for (int i = 0; i < tile * 8; ++i) {
                const double base = c * cell + pad + (i + 0.5) / 8.0;  // base-texel coordinate, tile proper
                const double xl = base * scale - 0.5;
                const long t0 = static_cast<long>(std::floor(xl));
                const double w1 = xl - static_cast<double>(t0);
                for (int k = 0; k < 2; ++k) {
                    const double w = k ? w1 : 1.0 - w1;
                    const long t = std::clamp(t0 + k, 0L, static_cast<long>(lv.size()) - 1);
                    if (w > 0.0 && lv[static_cast<size_t>(t)] != id) return false;
                }
            }
        }
        return true;
    };
    // interior_atlas_mip_safe must never call an unsafe layout safe; it is exact when the cell is a
    // multiple of 2^lod (level texels aligned with cells, as interior_atlas_layout makes them) and
    // conservative otherwise (it rejects unaligned cells even where a wide gutter keeps the mixed
    // texels out of reach).
    int safe = 0, unsafe = 0, conservative = 0;
    for (int lod = 0; lod <= 4; ++lod)
        for (int pad = 0; pad <= 12; ++pad)
            for (int tile : {16, 32, 48}) {
                InteriorAtlasLayout l;
                l.tile = tile;
                l.pad = pad;
                l.grid = 4;
                l.max_lod = lod;
                const bool e = emulate(tile, pad, 4, lod);
                const bool lib = interior_atlas_mip_safe(l, lod);
                const bool aligned = l.cell() % (1 << lod) == 0;
                (e ? safe : unsafe) += 1;
                if (lib && !e) ADD_FAILURE() << "falsely safe: tile " << tile << " pad " << pad << " lod " << lod;
                if (aligned && lib != e) ADD_FAILURE() << "aligned cell, disagrees: tile " << tile << " pad " << pad << " lod " << lod;
                conservative += (!lib && e) ? 1 : 0;
            }
    std::printf("[features] atlas padding vs emulated box-filtered mips + bilinear: %d safe, %d unsafe layouts; rejected although "
                "safe (unaligned cells): %d\n",
                safe, unsafe, conservative);
    EXPECT_GT(safe, 20);
    EXPECT_GT(unsafe, 20);
    // And the minimal layouts interior_atlas_layout returns pass the emulation at every level.
    for (int lod = 0; lod <= 4; ++lod) {
        const InteriorAtlasLayout l = interior_atlas_layout(64, 4, lod);
        for (int k = 0; k <= lod; ++k) EXPECT_TRUE(emulate(l.tile, l.pad, l.grid, k)) << lod << " " << k;
    }
}
