// raykit/gpu_layout.hpp against glslang: every shared struct a user may upload as a block is
// declared inside a std140 uniform block and a std430 buffer block, compiled with glslangValidator
// and its reflection (-q --reflect-all-block-variables) parsed; each member's offset, the member
// set and the block size must equal gpu_members / gpu_size. gpu_pack is then checked to write each
// field's value at that offset, and the padding as zeros.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <algorithm>
#include <regex>
#include <sstream>
#include <string>

#include "raykit/gpu_layout.hpp"
#include "raykit/interior_compose.hpp"
#include "raykit/interior_params.hpp"
#include "raykit/svo_traverse.hpp"

using namespace raykit;

namespace {

struct Reflection {
    std::map<std::string, size_t> offsets;  // member path below the block's `v.` -> offset
    long long block_size = -1;
};

// Compiles `T v;` in a block of `layout` with glslang and returns its reflection.
Reflection reflect(const std::string& type, const std::string& include, GpuLayout layout)
{
    const bool is140 = layout == GpuLayout::std140;
    const std::string path = std::string(::testing::TempDir()) + "rk_layout_" + type + (is140 ? "_140" : "_430") + ".comp";
    {
        std::ofstream f(path);
        f << "#version 450\n#extension GL_GOOGLE_include_directive : require\n#include \"" << include << "\"\n"
          << "layout(local_size_x = 1) in;\n"
          << (is140 ? "layout(std140, binding = 0) uniform Blk { " : "layout(std430, binding = 0) buffer Blk { ") << type
          << " v; } blk;\nvoid main() { " << type << " t = blk.v; }\n";
    }
    const std::string cmd = std::string(RAYKIT_GLSLANG) + " -G -q --reflect-all-block-variables -I" + RAYKIT_SHADER_DIR +
                            " " + path + " 2>&1";
    Reflection r;
    FILE* p = popen(cmd.c_str(), "r");
    if (!p) return r;
    char buf[4096];
    std::string all;
    while (std::fgets(buf, sizeof buf, p)) all += buf;
    pclose(p);
    const std::regex member(R"(^Blk\.v\.([A-Za-z0-9_.]+): offset (\d+))");
    const std::regex block(R"(^Blk: offset -1, type [0-9a-f]+, size (\d+))");
    std::istringstream in(all);
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        if (std::regex_search(line, m, member)) r.offsets[m.str(1)] = std::stoul(m.str(2));
        if (std::regex_search(line, m, block)) r.block_size = std::stoll(m.str(1));
    }
    if (r.offsets.empty()) ADD_FAILURE() << "no reflection from: " << cmd << "\n" << all;
    return r;
}

template <class T>
void expect_layout_matches_glslang(const std::string& type, const std::string& include)
{
    for (const GpuLayout layout : {GpuLayout::std140, GpuLayout::std430}) {
        const char* lname = layout == GpuLayout::std140 ? "std140" : "std430";
        const Reflection r = reflect(type, include, layout);
        std::map<std::string, size_t> ours;
        for (const GpuMember& m : gpu_members<T>(layout)) ours[m.name] = m.offset;
        EXPECT_EQ(ours, r.offsets) << type << " " << lname;
        EXPECT_EQ(static_cast<long long>(gpu_size<T>(layout)), r.block_size) << type << " " << lname;
    }
}

float float_at(const std::vector<uint8_t>& b, size_t off)
{
    float f;
    std::memcpy(&f, b.data() + off, 4);
    return f;
}

}  // namespace

TEST(GpuLayout, OffsetsAndSizesMatchGlslangReflection)
{
    expect_layout_matches_glslang<rk_im_grid>("rk_im_grid", "raykit/interior_mapping.glsl");
    expect_layout_matches_glslang<rk_im_window_params>("rk_im_window_params", "raykit/interior_params.glsl");
    expect_layout_matches_glslang<rk_svo_tree>("rk_svo_tree", "raykit/svo_traverse.glsl");
    expect_layout_matches_glslang<rk_im_building_frame>("rk_im_building_frame", "raykit/interior_params.glsl");
    expect_layout_matches_glslang<rk_im_building_vertex>("rk_im_building_vertex", "raykit/interior_params.glsl");
}

TEST(GpuLayout, TheIssueCaseByHand)
{
    // rk_im_grid: C++ puts origin at byte 12; both block layouts at 16 (a vec3 is 16-aligned).
    EXPECT_EQ(offsetof(rk_im_grid, origin), 12u);
    for (const GpuLayout l : {GpuLayout::std140, GpuLayout::std430}) {
        const std::vector<GpuMember> m = gpu_members<rk_im_grid>(l);
        ASSERT_EQ(m.size(), 2u);
        EXPECT_EQ(m[1].name, "origin");
        EXPECT_EQ(m[1].offset, 16u);
        EXPECT_EQ(gpu_size<rk_im_grid>(l), 32u);
    }
}

TEST(GpuLayout, PackWritesEachFieldAtItsOffset)
{
    rk_im_window_params p = rk_im_window_params_default();
    p.grid.origin = vec3(-5.0f, 6.0f, 7.5f);
    p.seed = 0xdeadbeefu;
    p.flipbook = ivec4(3, -2, 9, 0);
    for (const GpuLayout l : {GpuLayout::std140, GpuLayout::std430}) {
        const std::vector<uint8_t> b = gpu_pack(p, l);
        std::map<std::string, size_t> off;
        std::vector<bool> used(b.size(), false);
        for (const GpuMember& m : gpu_members<rk_im_window_params>(l)) off[m.name] = m.offset;
        EXPECT_EQ(float_at(b, off["grid.origin"] + 8), 7.5f);
        EXPECT_EQ(float_at(b, off["glass_eta"]), 1.52f);
        EXPECT_EQ(float_at(b, off["average_colour"] + 4), 0.4f);
        uint32_t seed;
        std::memcpy(&seed, b.data() + off["seed"], 4);
        EXPECT_EQ(seed, 0xdeadbeefu);
        int32_t fb1;
        std::memcpy(&fb1, b.data() + off["flipbook"] + 4, 4);
        EXPECT_EQ(fb1, -2);
        // Bytes no member covers are zero.
        const std::map<std::string, size_t> sizes = {{"variants", 4}, {"tint_amount", 4}, {"lit_probability", 4},
                                                     {"unlit", 4}, {"glass_eta", 4}, {"glass_panes", 4},
                                                     {"flipbook_fps", 4}, {"time", 4}, {"alpha_threshold", 4},
                                                     {"seed", 4}, {"light_level", 8}, {"fade_range", 8},
                                                     {"atlas", 16}, {"furniture_depth", 16}, {"flipbook", 16}};
        for (const auto& kv : off) {
            const auto s = sizes.find(kv.first);
            const size_t n = s == sizes.end() ? 12 : s->second;  // the rest are vec3
            for (size_t i = 0; i < n; ++i) used[kv.second + i] = true;
        }
        for (size_t i = 0; i < b.size(); ++i) {
            if (!used[i]) {
                EXPECT_EQ(b[i], 0u) << "padding byte " << i;
            }
        }
    }
}

TEST(GpuLayout, MatricesPackColumnMajor)
{
    rk_im_building_vertex v = rk_im_building_vertex_default();
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) v.clip_from_world[c][r] = static_cast<float>(10 * c + r);
    }
    for (const GpuLayout l : {GpuLayout::std140, GpuLayout::std430}) {
        const std::vector<uint8_t> b = gpu_pack(v, l);
        size_t off = 0;
        for (const GpuMember& m : gpu_members<rk_im_building_vertex>(l)) {
            if (m.name == "clip_from_world") off = m.offset;
        }
        ASSERT_EQ(off, 64u);
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) EXPECT_EQ(float_at(b, off + 16 * c + 4 * r), static_cast<float>(10 * c + r));
        }
        EXPECT_EQ(float_at(b, 0), 1.0f);   // world_from_object: identity
        EXPECT_EQ(float_at(b, 4), 0.0f);
    }
}

TEST(GpuLayout, DefaultsAreTheSampleMaterials)
{
    // rk_im_window_params_default() documents the sample material's uniform defaults
    // (samples/common/interior_building.frag): parse them and compare, so neither drifts alone.
    std::ifstream f(std::string(RAYKIT_SAMPLES_DIR) + "/common/interior_building.frag");
    ASSERT_TRUE(f.good());
    std::map<std::string, std::vector<float>> uniforms;
    const std::regex decl(R"(^uniform\s+\w+\s+(u_\w+)\s*=\s*([^;]+);)");
    const std::regex number(R"([-+]?\d+(\.\d*)?([eE][-+]?\d+)?)");
    std::string line;
    while (std::getline(f, line)) {
        std::smatch m;
        if (!std::regex_search(line, m, decl)) continue;
        const std::string init = m.str(2);
        std::vector<float> v;
        const std::string body = init.find('(') != std::string::npos ? init.substr(init.find('(')) : init;
        for (std::sregex_iterator it(body.begin(), body.end(), number), end; it != end; ++it) v.push_back(std::stof(it->str()));
        uniforms[m.str(1)] = v;
    }
    const rk_im_window_params p = rk_im_window_params_default();
    auto expect = [&](const char* u, std::vector<float> want) {
        ASSERT_TRUE(uniforms.count(u)) << u;
        std::vector<float> got = uniforms[u];
        if (got.size() == 1 && want.size() > 1) got.assign(want.size(), got[0]);  // vec3(0.0)
        got.resize(std::min(got.size(), want.size()));
        EXPECT_EQ(got, want) << u;
    };
    expect("u_room_size", {p.grid.room_size.x, p.grid.room_size.y, p.grid.room_size.z});
    expect("u_grid_origin", {p.grid.origin.x, p.grid.origin.y, p.grid.origin.z});
    expect("u_seed", {float(p.seed)});
    expect("u_wall_jitter", {p.jitter.x, p.jitter.y, p.jitter.z});
    expect("u_glass_tint", {p.glass_tint.x, p.glass_tint.y, p.glass_tint.z});
    expect("u_glass_eta", {p.glass_eta});
    expect("u_glass_panes", {p.glass_panes});
    expect("u_lit_probability", {p.lit_probability});
    expect("u_light_warm", {p.light_warm.x, p.light_warm.y, p.light_warm.z});
    expect("u_light_cool", {p.light_cool.x, p.light_cool.y, p.light_cool.z});
    expect("u_light_level", {p.light_level.x, p.light_level.y});
    expect("u_unlit", {p.unlit});
    expect("u_furniture_depth", {p.furniture_depth.x, p.furniture_depth.y, p.furniture_depth.z, p.furniture_depth.w});
    expect("u_flipbook", {float(p.flipbook.x), float(p.flipbook.y), float(p.flipbook.z)});
    expect("u_flipbook_fps", {p.flipbook_fps});
    expect("u_time", {p.time});
    expect("u_alpha_threshold", {p.alpha_threshold});
    expect("u_fade_range", {p.fade_range.x, p.fade_range.y});
    expect("u_room_average", {p.average_colour.x, p.average_colour.y, p.average_colour.z});
    expect("u_variants", {p.variants});
    expect("u_atlas", {p.atlas.x, p.atlas.y, p.atlas.z, p.atlas.w});
    expect("u_tint_amount", {p.tint_amount});
    EXPECT_EQ(p.unlit, RK_IM_UNLIT_DEFAULT);
    const rk_im_building_frame fr = rk_im_building_frame_default();
    expect("u_facade_color", {fr.facade_color.x, fr.facade_color.y, fr.facade_color.z});
    expect("u_frame_color", {fr.frame_color.x, fr.frame_color.y, fr.frame_color.z});
    expect("u_window_size", {fr.window_size.x, fr.window_size.y});
    expect("u_sky_color", {fr.sky_color.x, fr.sky_color.y, fr.sky_color.z});
    expect("u_env_guard_scale", {fr.env_guard_scale});
    expect("u_env_lod_bias", {fr.env_lod_bias});
    expect("u_exposure", {fr.exposure});
    expect("u_reinhard_white", {fr.reinhard_white});
}
