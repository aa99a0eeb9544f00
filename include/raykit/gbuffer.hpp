// raykit — gbuffer.hpp: the CPU build of shaders/raykit/gbuffer.glsl (unit-vector encodings,
// position from depth, two halves in one word), the double-precision helpers that compute its
// uniforms, and a G-buffer layout descriptor with validation and presets.
//
// Every rk_* function below is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_gbuffer.cpp checks that both builds agree on a real driver. Measured errors,
// costs and the presets' sizes: docs/deferred.md.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "raykit/common.hpp"
#include "raykit/status.hpp"

namespace raykit {
#include "raykit/gbuffer.glsl"

/// gbuffer_depth_params: rk_gb_depth_params computed in double (then rounded once to float): the k
/// of rk_gb_linear_depth for near plane `n`, far plane `f` (+infinity or f <= n: an infinite far
/// plane) and the usual (near at 0; OpenGL [-1, 1] and Vulkan [0, 1] alike) or reversed (near at 1)
/// depth. Domain: n > 0 finite; anything else gives (0, 0, z), for which rk_gb_linear_depth
/// returns RK_FLT_MAX everywhere.
inline vec3 gbuffer_depth_params(double n, double f, bool reversed)
{
    const float z = reversed ? 0.0f : 1.0f;
    if (!(n > 0.0) || !std::isfinite(n)) return vec3(0.0f, 0.0f, z);
    const bool inf = !(f > n) || !std::isfinite(f);
    // A denormal near (or far) plane: 1 / n beyond float's range is held at RK_FLT_MAX.
    const double lim = static_cast<double>(RK_FLT_MAX);
    return vec3(static_cast<float>(std::min(1.0 / n, lim)), inf ? 0.0f : static_cast<float>(std::min(1.0 / f, lim)), z);
}

/// gbuffer_view_ray: the `ray` uniform of rk_gb_view_pos for the column-major perspective
/// projection P (any depth convention, off-centre frusta, Vulkan's negative P[1][1]):
/// (1 / P[0][0], 1 / P[1][1], P[2][0] / P[0][0], P[2][1] / P[1][1]), in double. A P with a zero
/// diagonal entry (not a projection) gives 0 for that axis; entries beyond float's range are held
/// at +-RK_FLT_MAX (rk_gb_view_pos then stays finite).
inline vec4 gbuffer_view_ray(const mat4& P)
{
    const double a = P[0][0], b = P[1][1], lim = static_cast<double>(RK_FLT_MAX);
    const double ia = a != 0.0 ? 1.0 / a : 0.0, ib = b != 0.0 ? 1.0 / b : 0.0;
    // A tiny diagonal would overflow float: every entry is held at +-RK_FLT_MAX.
    auto f = [lim](double x) { return static_cast<float>(std::min(std::max(x, -lim), lim)); };
    return vec4(f(ia), f(ib), f(P[2][0] * ia), f(P[2][1] * ib));
}

// ---------------------------------------------------------------------------------------------
// Layout descriptor

/// Render-target formats a G-buffer is made of (the core formats of OpenGL 4.5 and Vulkan that
/// support colour attachment).
enum class GbFormat {
    r8, rg8, rgba8, rgb10a2, r11g11b10f, rg8_snorm, rgba8_snorm, r16, rg16, rgba16, rg16_snorm, rgba16_snorm,
    r16f, rg16f, rgba16f, r32f, rg32f, rgba32f, r32ui, rg32ui, rgba32ui,
};

/// gb_format_bits: bits per texel of a format. gb_format_channels: its channel count.
/// gb_format_name: its name ("rgba16f").
inline int gb_format_bits(GbFormat f)
{
    switch (f) {
    case GbFormat::r8: return 8;
    case GbFormat::rg8: case GbFormat::rg8_snorm: case GbFormat::r16: case GbFormat::r16f: return 16;
    case GbFormat::rgba8: case GbFormat::rgb10a2: case GbFormat::r11g11b10f: case GbFormat::rgba8_snorm:
    case GbFormat::rg16: case GbFormat::rg16_snorm: case GbFormat::rg16f: case GbFormat::r32f: case GbFormat::r32ui: return 32;
    case GbFormat::rgba16: case GbFormat::rgba16_snorm: case GbFormat::rgba16f: case GbFormat::rg32f: case GbFormat::rg32ui: return 64;
    case GbFormat::rgba32f: case GbFormat::rgba32ui: return 128;
    }
    return 0;
}
inline int gb_format_channels(GbFormat f)
{
    switch (f) {
    case GbFormat::r8: case GbFormat::r16: case GbFormat::r16f: case GbFormat::r32f: case GbFormat::r32ui: return 1;
    case GbFormat::rg8: case GbFormat::rg8_snorm: case GbFormat::rg16: case GbFormat::rg16_snorm: case GbFormat::rg16f:
    case GbFormat::rg32f: case GbFormat::rg32ui: return 2;
    case GbFormat::r11g11b10f: return 3;
    default: return 4;
    }
}
inline const char* gb_format_name(GbFormat f)
{
    switch (f) {
    case GbFormat::r8: return "r8";
    case GbFormat::rg8: return "rg8";
    case GbFormat::rgba8: return "rgba8";
    case GbFormat::rgb10a2: return "rgb10a2";
    case GbFormat::r11g11b10f: return "r11g11b10f";
    case GbFormat::rg8_snorm: return "rg8_snorm";
    case GbFormat::rgba8_snorm: return "rgba8_snorm";
    case GbFormat::r16: return "r16";
    case GbFormat::rg16: return "rg16";
    case GbFormat::rgba16: return "rgba16";
    case GbFormat::rg16_snorm: return "rg16_snorm";
    case GbFormat::rgba16_snorm: return "rgba16_snorm";
    case GbFormat::r16f: return "r16f";
    case GbFormat::rg16f: return "rg16f";
    case GbFormat::rgba16f: return "rgba16f";
    case GbFormat::r32f: return "r32f";
    case GbFormat::rg32f: return "rg32f";
    case GbFormat::rgba32f: return "rgba32f";
    case GbFormat::r32ui: return "r32ui";
    case GbFormat::rg32ui: return "rg32ui";
    case GbFormat::rgba32ui: return "rgba32ui";
    }
    return "?";
}

/// One render target: its format and what each channel holds (empty: unused).
struct GbTarget {
    std::string name;
    GbFormat format = GbFormat::rgba8;
    std::vector<std::string> channels;
};

/// A G-buffer: its colour targets, and the depth buffer's bits (0: position is stored in a
/// target instead, as in the thesis).
struct GbLayout {
    std::string name;
    std::vector<GbTarget> targets;
    int depth_bits = 32;
};

/// What validate_gbuffer_layout enforces. max_targets: the API's colour attachment limit (8 on
/// current desktop GPUs; the thesis's 2005 hardware had 4). equal_bits: every target the same
/// number of bits (the rule of NVIDIA's 2005 drivers the thesis worked under). warn_targets: a
/// target count from which validate_gbuffer_layout adds a warning (the thesis: GeForce 6 lost
/// speed going from 3 to 4 targets); 0: none.
struct GbLayoutRules {
    int max_targets = 8;
    bool equal_bits = false;
    int warn_targets = 0;
};

/// gbuffer_bits_per_pixel: the layout's colour bits plus its depth bits.
inline int gbuffer_bits_per_pixel(const GbLayout& l)
{
    int bits = l.depth_bits;
    for (const GbTarget& t : l.targets) bits += gb_format_bits(t.format);
    return bits;
}

/// validate_gbuffer_layout: checks `l` against `rules`: 1..max_targets targets, no more channel
/// names than the format has, no channel named twice, depth_bits one of 0, 16, 24, 32, and (if
/// asked) equal bits per target. Returns false with the first violation in `st`; a warning (the
/// rules' warn_targets) goes into `warning` without failing.
inline bool validate_gbuffer_layout(const GbLayout& l, const GbLayoutRules& rules, Status& st, std::string* warning = nullptr)
{
    st = Status{};
    if (warning) warning->clear();
    if (l.targets.empty()) return st.fail(Error::invalid_argument, "G-buffer layout '" + l.name + "' has no target");
    if (static_cast<int>(l.targets.size()) > rules.max_targets)
        return st.fail(Error::invalid_argument, "G-buffer layout '" + l.name + "' has " + std::to_string(l.targets.size()) +
                                                    " targets, more than the limit of " + std::to_string(rules.max_targets));
    if (l.depth_bits != 0 && l.depth_bits != 16 && l.depth_bits != 24 && l.depth_bits != 32)
        return st.fail(Error::invalid_argument, "G-buffer layout '" + l.name + "': depth_bits must be 0, 16, 24 or 32");
    std::vector<std::string> seen;
    for (const GbTarget& t : l.targets) {
        if (static_cast<int>(t.channels.size()) > gb_format_channels(t.format))
            return st.fail(Error::invalid_argument, "target '" + t.name + "' names " + std::to_string(t.channels.size()) +
                                                        " channels but " + gb_format_name(t.format) + " has " +
                                                        std::to_string(gb_format_channels(t.format)));
        for (const std::string& c : t.channels) {
            if (c.empty()) continue;
            for (const std::string& s : seen)
                if (s == c) return st.fail(Error::invalid_argument, "channel '" + c + "' is stored twice");
            seen.push_back(c);
        }
        if (rules.equal_bits && gb_format_bits(t.format) != gb_format_bits(l.targets[0].format))
            return st.fail(Error::invalid_argument, "target '" + t.name + "' has " + std::to_string(gb_format_bits(t.format)) +
                                                        " bits, '" + l.targets[0].name + "' has " +
                                                        std::to_string(gb_format_bits(l.targets[0].format)) + " (equal_bits rule)");
    }
    if (warning && rules.warn_targets > 0 && static_cast<int>(l.targets.size()) >= rules.warn_targets)
        *warning = "G-buffer layout '" + l.name + "' uses " + std::to_string(l.targets.size()) + " targets (warning from " +
                   std::to_string(rules.warn_targets) + ")";
    return true;
}

/// gbuffer_layout_thesis: the thesis's Table 2.1: four RGBA16F targets (the formats are not stated
/// in the thesis; equal bits were required, and position needs floats): eye-space position and
/// material id; normal; diffuse colour and the normal map's x; tangent x, y, w and the normal map's
/// y (z of both rebuilt by hemisphere remapping). No depth buffer read: position is stored.
/// 256 bits per pixel of targets, plus the depth buffer the rasteriser needs (24 bits counted).
inline GbLayout gbuffer_layout_thesis()
{
    GbLayout l;
    l.name = "thesis";
    l.depth_bits = 24;
    l.targets = {
        {"rt0", GbFormat::rgba16f, {"position.x", "position.y", "position.z", "material_id"}},
        {"rt1", GbFormat::rgba16f, {"normal.x", "normal.y", "normal.z", ""}},
        {"rt2", GbFormat::rgba16f, {"diffuse.r", "diffuse.g", "diffuse.b", "nmap_normal.x"}},
        {"rt3", GbFormat::rgba16f, {"tangent.x", "tangent.y", "tangent.w", "nmap_normal.y"}},
    };
    return l;
}

/// gbuffer_layout_compact: a compact modern layout: position from the 32-bit float depth buffer
/// (rk_gb_linear_depth, rk_gb_view_pos; reversed-Z recommended), the shading normal (normal maps
/// applied) octahedral in RG16 SNORM, albedo and ambient occlusion in RGBA8 (sRGB), and specular,
/// emission as two halves in R32UI (rk_gb_pack_half2) next to roughness, metalness and material in
/// RGBA8. 160 bits per pixel with depth, against the thesis's 280.
inline GbLayout gbuffer_layout_compact()
{
    GbLayout l;
    l.name = "compact";
    l.depth_bits = 32;
    l.targets = {
        {"albedo", GbFormat::rgba8, {"albedo.r", "albedo.g", "albedo.b", "occlusion"}},
        {"normal", GbFormat::rg16_snorm, {"normal.oct.x", "normal.oct.y"}},
        {"material", GbFormat::rgba8, {"roughness", "metalness", "material_id", "flags"}},
        {"emission", GbFormat::r32ui, {"specular|emission (half2)"}},
    };
    return l;
}

}  // namespace raykit
