// raykit — interior_params.hpp: the CPU build of shaders/raykit/interior_params.glsl:
// rk_im_window_params (what rk_im_shade_window reads besides its samplers) and
// rk_im_window_params_default(), plus its field list for raykit::gpu_pack (raykit/gpu_layout.hpp),
// so an engine can fill the struct in C++ and upload it as a std140 uniform block or a std430
// buffer with the offsets glslang gives it (tests/test_gpu_layout.cpp).
#pragma once

#include "raykit/interior_mapping.hpp"

namespace raykit {
#include "raykit/interior_params.glsl"

/// The fields of rk_im_window_params for gpu_pack, in declaration order.
template <class V>
void rk_gpu_fields(V& v, const rk_im_window_params& s)
{
    v("grid", s.grid);
    v("normal", s.normal);
    v("tangent", s.tangent);
    v("bitangent", s.bitangent);
    v("seed", s.seed);
    v("jitter", s.jitter);
    v("variants", s.variants);
    v("atlas", s.atlas);
    v("tint_amount", s.tint_amount);
    v("lit_probability", s.lit_probability);
    v("light_warm", s.light_warm);
    v("light_cool", s.light_cool);
    v("light_level", s.light_level);
    v("unlit", s.unlit);
    v("glass_tint", s.glass_tint);
    v("glass_eta", s.glass_eta);
    v("glass_panes", s.glass_panes);
    v("furniture_depth", s.furniture_depth);
    v("flipbook", s.flipbook);
    v("flipbook_fps", s.flipbook_fps);
    v("time", s.time);
    v("alpha_threshold", s.alpha_threshold);
    v("fade_range", s.fade_range);
    v("average_colour", s.average_colour);
}

/// The fields of rk_im_building_frame for gpu_pack.
template <class V>
void rk_gpu_fields(V& v, const rk_im_building_frame& s)
{
    v("camera_world", s.camera_world);
    v("env_guard_scale", s.env_guard_scale);
    v("facade_color", s.facade_color);
    v("env_lod_bias", s.env_lod_bias);
    v("frame_color", s.frame_color);
    v("exposure", s.exposure);
    v("sky_color", s.sky_color);
    v("reinhard_white", s.reinhard_white);
    v("window_size", s.window_size);
}

/// The fields of rk_im_building_vertex for gpu_pack.
template <class V>
void rk_gpu_fields(V& v, const rk_im_building_vertex& s)
{
    v("world_from_object", s.world_from_object);
    v("clip_from_world", s.clip_from_world);
    v("camera_world", s.camera_world);
    v("sun_dir", s.sun_dir);
    v("sun_color", s.sun_color);
    v("ambient", s.ambient);
    v("uv_scale", s.uv_scale);
}

}  // namespace raykit
