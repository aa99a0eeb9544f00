#version 450 core
// raykit sample deferred_city — dc_gbuffer.frag: writes the compact G-buffer
// (raykit::gbuffer_layout_compact(): 160 bits a pixel with the depth buffer):
//   0 SRGB8_ALPHA8: albedo, occlusion (1 here);
//   1 R32UI: the shading normal, octahedral in two 16-bit SNORM fields (rk_gb_oct_pack_snorm; the
//     same grid as an RG16_SNORM target, packed by raykit so every driver rounds alike);
//   2 RGBA8: gloss, metalness (0), material (0 ground, 1 facade), flags (0);
//   3 R32UI: specular weight and emission as two halves (rk_gb_pack_half2);
//   depth: D32F, reversed-Z (position is rebuilt from it by rk_gb_linear_depth + rk_gb_view_pos).
#extension GL_GOOGLE_include_directive : require
#include "dc_common.glsl"
#include "dc_material.glsl"
layout(location = 0) out vec4 o_albedo;
layout(location = 1) out uint o_normal;
layout(location = 2) out vec4 o_material;
layout(location = 3) out uint o_extra;
void main()
{
    DcSurface s = dc_material();
    o_albedo = vec4(s.albedo, 1.0);
    o_normal = rk_gb_oct_pack_snorm(s.n, 16u);
    o_material = vec4(s.gloss, 0.0, v_mat.x < 0.5 ? 0.0 : 1.0, 0.0);
    o_extra = rk_gb_pack_half2(s.spec, s.emission);
}
