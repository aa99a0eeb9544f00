// raykit — interior_features.hpp: what an interior-mapped scene uses, turned into the minimal set
// of feature macros for shaders/raykit/interior_shading.glsl and samples/common/interior_building.frag
// (C++ only). Pass the result to raykit::inject_shader_defines / load_shader_file
// (raykit/shader_source.hpp) or to raykit_compile_shaders(DEFINES ...).
//
// Every interior macro is emitted with an explicit value (a feature the scene does not use is set
// to its "off" value rather than left to the file's default), so one description always gives the
// same shader, and a feature that is off is compiled out (zero instructions).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "raykit/shader_define.hpp"
#include "raykit/status.hpp"

namespace raykit {

/// How room surfaces are textured (RK_IM_SHADING).
enum class InteriorTextures {
    four_textures = 0,  ///< ceiling, floor, x-wall, z-wall textures (the thesis's variant; a branch
                        ///< over four samplers, the dearest mode on SIMD CPU rasterisers)
    texture_array = 1,  ///< one sampler2DArray, a random layer per room and wall (RECOMMENDED: one
                        ///< fetch, no sampler branch, the cheapest mode measured)
    padded_atlas = 2,   ///< one 2D atlas of padded tiles, a random tile per room and wall
    cube_per_room = 3,  ///< a cube-map array, a random cube per room, rotated by k * 90° and tinted
};

/// How the window glass combines reflection and interior (RK_IM_COMPOSE_MODE).
enum class InteriorGlass {
    fresnel = 0,          ///< R reflection + (1 - R) tint interior (pane with multiple reflections)
    thesis_additive = 1,  ///< reflection + interior (the thesis's appendix; for comparison)
};

/// What an interior-mapped scene uses. Defaults: the recommended room textures (a texture array)
/// and no extras; thesis() is the thesis's material (four textures).
struct InteriorSceneDesc {
    InteriorTextures textures = InteriorTextures::texture_array;
    InteriorGlass glass = InteriorGlass::fresnel;
    bool room_lights = false;    ///< per-room on/off, colour and level (RK_IM_ROOM_LIGHTS)
    int furniture_layers = 0;    ///< furniture / character planes, 0..4 (RK_IM_FURNITURE_LAYERS)
    /// Sprite sheets are flipbooks (a frame per room and time; RK_IM_FURNITURE_FLIPBOOK 1). Set it
    /// to false when every sprite sheet is one image: the per-layer frame lookup (a room hash and
    /// integer arithmetic) is then compiled out. Ignored without furniture.
    bool furniture_flipbook = true;
    bool varying_walls = false;  ///< walls displaced per wall index (RK_IM_VARYING_WALLS, interior_mapping.glsl)
    bool reflections = false;    ///< dual-paraboloid environment in the windows (RK_IM_REFLECTION)
    float fade_distance = 0.0f;  ///< > 0: interiors fade to a flat colour from here on (RK_IM_FADE)
    // Options of samples/common/interior_building.frag only (ignored by interior_shading.glsl):
    bool textured_facade = false;  ///< facade from a texture (alpha = window mask) instead of procedural
    bool tonemap_output = false;   ///< output tone-mapped sRGB (rk_tonemap) instead of linear HDR

    /// The thesis's material: four room textures, no extras.
    static InteriorSceneDesc thesis()
    {
        InteriorSceneDesc d;
        d.textures = InteriorTextures::four_textures;
        return d;
    }
};

/// interior_defines: the macro set of a scene, in a fixed order:
/// RK_IM_SHADING, RK_IM_COMPOSE_MODE, RK_IM_ROOM_LIGHTS, RK_IM_FURNITURE_LAYERS,
/// RK_IM_FURNITURE_FLIPBOOK, RK_IM_VARYING_WALLS, RK_IM_REFLECTION, RK_IM_FADE, RK_IM_BUILDING_FACADE,
/// RK_IM_BUILDING_OUTPUT. RK_IM_FURNITURE_FLIPBOOK is 1 only with furniture and a flipbook.
/// furniture_layers outside 0..4 or a fade distance that is negative or not finite: an empty set,
/// described in *st (status.hpp). Exact (a table); cost: 10 small strings.
inline std::vector<ShaderDefine> interior_defines(const InteriorSceneDesc& d, Status* st = nullptr)
{
    detail::reset(st);
    if (d.furniture_layers < 0 || d.furniture_layers > 4) {
        detail::report(st, "raykit::interior_defines: furniture_layers must be in 0..4");
        return {};
    }
    if (!(d.fade_distance >= 0.0f) || d.fade_distance > 3.4e38f) {
        detail::report(st, "raykit::interior_defines: fade_distance must be finite and >= 0");
        return {};
    }
    auto b = [](bool on) { return std::string(on ? "1" : "0"); };
    return {
        {"RK_IM_SHADING", std::to_string(static_cast<int>(d.textures))},
        {"RK_IM_COMPOSE_MODE", std::to_string(static_cast<int>(d.glass))},
        {"RK_IM_ROOM_LIGHTS", b(d.room_lights)},
        {"RK_IM_FURNITURE_LAYERS", std::to_string(d.furniture_layers)},
        {"RK_IM_FURNITURE_FLIPBOOK", b(d.furniture_layers > 0 && d.furniture_flipbook)},
        {"RK_IM_VARYING_WALLS", b(d.varying_walls)},
        {"RK_IM_REFLECTION", b(d.reflections)},
        {"RK_IM_FADE", b(d.fade_distance > 0.0f)},
        {"RK_IM_BUILDING_FACADE", b(d.textured_facade)},
        {"RK_IM_BUILDING_OUTPUT", b(d.tonemap_output)},
    };
}

/// The padded-atlas layout of RK_IM_SHADING 2 (see interior_shading.glsl, "PADDING RULE"): tiles of
/// `tile` texels surrounded by a gutter of `pad` texels on every side (filled with the tile's own
/// texels wrapped around, as GL_REPEAT would read them), cells of tile + 2 pad texels, `grid` x
/// `grid` cells. Mip levels 0..max_lod never mix two tiles when the cell is a multiple of 2^max_lod
/// (level-L texels are then box-filtered from blocks inside one cell) and pad >= max(1, 2^(max_lod-1))
/// (a bilinear tap at level L reaches 2^(L-1) base texels beyond the tile proper); the shader clamps
/// its LOD to max_lod.
struct InteriorAtlasLayout {
    int tile = 0;     ///< texels of the tile proper
    int pad = 0;      ///< gutter texels on each side
    int grid = 0;     ///< cells per atlas side
    int max_lod = 0;  ///< highest mip level the shader may use
    int cell() const { return tile + 2 * pad; }
    int size() const { return grid * cell(); }  ///< atlas side in texels
};

/// interior_atlas_layout: the smallest valid padding for `tile`-texel tiles sampled down to mip
/// `max_lod` (pad = max(1, 2^(max_lod-1)), so the cell is tile + 2^max_lod texels from level 1 on),
/// in a grid x grid atlas. When tile is not a positive multiple of 2^max_lod, max_lod is outside
/// 0..12, grid < 1, or the atlas would exceed 65536 texels: an all-zero layout (size() 0), described
/// in *st (status.hpp). Exact integer arithmetic; cost O(1). Its result passes
/// interior_atlas_mip_safe at every level 0..max_lod (tests/test_interior_features.cpp).
inline InteriorAtlasLayout interior_atlas_layout(int tile, int grid, int max_lod, Status* st = nullptr)
{
    detail::reset(st);
    if (max_lod < 0 || max_lod > 12 || grid < 1 || tile < 1 || tile % (1 << max_lod) != 0) {
        detail::report(st, "raykit::interior_atlas_layout: tile must be a positive multiple of 2^max_lod, "
                           "max_lod in 0..12, grid >= 1");
        return {};
    }
    const int pad = max_lod == 0 ? 1 : 1 << (max_lod - 1);
    if ((static_cast<long long>(tile) + 2 * pad) * grid > 65536LL) {  // in 64 bits: no int overflow
        detail::report(st, "raykit::interior_atlas_layout: atlas too large (more than 65536 texels a side)");
        return {};
    }
    InteriorAtlasLayout l;
    l.tile = tile;
    l.pad = pad;
    l.grid = grid;
    l.max_lod = max_lod;
    return l;
}

/// interior_atlas_mip_safe: whether mip level `lod` of `layout`, sampled bilinearly anywhere inside a
/// tile proper, reads only texels of that tile's cell (the padding rule: the two bilinear taps
/// around any tile-interior sample position at that level, each a cell-aligned block of 2^lod base
/// texels that the box filter built the level from, stay inside the cell). Exact when the cell
/// is a multiple of 2^lod (always so for interior_atlas_layout); otherwise false, which is
/// conservative: a wide enough gutter can keep the mixed texels out of reach (tests/
/// test_interior_features.cpp emulates the mip chain and GL_LINEAR and finds it never falsely
/// safe). Cost O(1): the taps move monotonically with the sample position, so the two extreme
/// positions of the tile proper decide.
inline bool interior_atlas_mip_safe(const InteriorAtlasLayout& layout, int lod)
{
    const long s = 1L << lod;
    const long cell = layout.cell();
    if (cell % s != 0) return false;  // level-lod texels straddle two cells
    // Base-texel coordinates x in [pad, pad + tile) of the tile proper; at level lod the sample sits at
    // x / s and bilinear reads texels floor(x / s - 0.5) and that + 1, i.e. base texels
    // [floor(x / s - 0.5) s, (floor(x / s - 0.5) + 2) s). Check the extremes of x (monotone).
    const double lo_x = static_cast<double>(layout.pad);
    const double hi_x = static_cast<double>(layout.pad + layout.tile) - 1e-6;
    const double ds = static_cast<double>(s);
    const long first = static_cast<long>(std::floor(lo_x / ds - 0.5)) * s;
    const long last = (static_cast<long>(std::floor(hi_x / ds - 0.5)) + 2) * s;
    return first >= 0 && last <= cell;
}

}  // namespace raykit
