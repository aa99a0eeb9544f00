// rk_svo_gl.hpp — a sample integration of raykit's octree ray casting into an OpenGL 4.5 frame
// (copy and adapt): SvoGlObject uploads a packed tree (geometry words and attribute streams as
// SSBOs) and draws it with a full-screen pass that casts one ray per pixel through
// svo_traverse.glsl, shades the hit and writes a depth value compatible with the rasterised
// geometry around it (svo_hybrid.glsl), so voxels and triangles occlude each other both ways with
// the ordinary depth test. MeshGl draws a triangle mesh with the same lighting, for the hybrid demo
// and tests.
//
// Frame recipe (what samples/svo_demo and tests/gpu/parity_svo_hybrid.cpp do):
//   1. draw the rasterised geometry (depth test on, depth writes on);
//   2. optionally copy the depth buffer to a texture (glCopyImageSubData / glBlitFramebuffer) and
//      pass it to draw(): each ray then stops at the depth already there (rk_svo_depth_to_t);
//   3. draw the voxel objects (depth test on, same compare function as the geometry).
#pragma once

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "raykit/shader_source.hpp"
#include "raykit/svo_features.hpp"
#include "raykit/svo_format.hpp"
#include "raykit/svo_hybrid.hpp"
#include "raykit/svo_secondary.hpp"
#include "raykit/svo_traverse.hpp"
#include "rk_gl.hpp"

namespace rkgl {

/// What a voxel pass computes per pixel (fragment shader uniforms, besides the matrices).
struct SvoDrawParams {
    glm::vec3 light_dir_world{0.4f, 0.8f, 0.45f};  ///< towards the light
    glm::vec3 ambient{0.18f};
    float lod_pixels = 0.0f;       ///< > 0: stop at nodes this many pixels wide (needs lod build)
    float fov_y = 1.0f;            ///< camera field of view, for the LOD cone
    uint32_t max_level = ~0u;      ///< deepest level to descend to
    GLuint depth_texture = 0;      ///< copy of the depth buffer for early termination (0: none)
    bool show_iterations = false;  ///< colour = iterations / 64 (a cost heat map; misses included)
    bool secondary = false;        ///< materials: shadows, mirror reflection, refraction (needs a tree with materials)
};

/// The fragment shader of the voxel pass. Its feature macros are set per program, from
/// raykit::svo_defines (svo_features.hpp): RK_SVO_TRAVERSE_LOD, and three passes through
/// svo_secondary.glsl, each compiled out when 0 (the default): RK_SVO_PASS_SHADOWS (shadow rays
/// towards the light), RK_SVO_PASS_REFLECTION (a material with reflectance > 0 is a mirror) and
/// RK_SVO_PASS_REFRACTION (a material with base_color.a < 1 refracts with its ior and absorption).
inline std::string svo_fragment_source()
{
    return R"(#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "raykit/svo_traverse.glsl"
#include "raykit/svo_hybrid.glsl"
layout(std430, binding = 1) readonly buffer RkColors { uint rk_colors[]; };
layout(std430, binding = 2) readonly buffer RkNormals { uint rk_normals[]; };
layout(location = 0) uniform mat4 u_obj_to_clip;
layout(location = 1) uniform mat4 u_clip_to_obj;
layout(location = 2) uniform vec4 u_depth;      // z_near_ndc, depth_range.x, depth_range.y, use depth texture
layout(location = 3) uniform uvec4 u_tree;      // depth, max_level, desc_words, brick_base_word
layout(location = 4) uniform vec4 u_root;       // root_min, root_size
layout(location = 5) uniform vec2 u_cone;
layout(location = 6) uniform vec3 u_light_obj;  // towards the light, object space, unit
layout(location = 7) uniform vec4 u_viewport;   // x, y, width, height
layout(location = 8) uniform uvec2 u_streams;   // has colours, has normals
layout(location = 9) uniform vec4 u_ambient;    // rgb, show iterations
layout(binding = 0) uniform sampler2D u_depth_tex;
layout(location = 0) out vec4 frag;
#ifndef RK_SVO_PASS_SHADOWS
#define RK_SVO_PASS_SHADOWS 0
#endif
#ifndef RK_SVO_PASS_REFLECTION
#define RK_SVO_PASS_REFLECTION 0
#endif
#ifndef RK_SVO_PASS_REFRACTION
#define RK_SVO_PASS_REFRACTION 0
#endif
#define RK_SVO_PASS_BOUNCE (RK_SVO_PASS_REFLECTION || RK_SVO_PASS_REFRACTION)
#if RK_SVO_PASS_SHADOWS || RK_SVO_PASS_BOUNCE
// Refract at the stored smooth normals (a voxelised sphere then bends light like a ball, not like a
// staircase of cube faces); the face where no normal is stored.
#define RK_SVO_INTERFACE_NORMAL(media, attr, face_n) (u_streams.y != 0u ? rk_svo_unpack_normal(rk_normals[attr]) : (face_n))
#include "raykit/svo_secondary.glsl"
#endif

// Local shading of a hit: stored colour and normal, one directional light (shadowed by the octree
// itself with secondary rays on).
// The stored smooth normal of attribute `a` (the face where none is stored), facing the ray.
vec3 rk_pass_normal(uint a, rk_svo_trace_hit h, vec3 d)
{
    vec3 n = u_streams.y != 0u ? rk_svo_unpack_normal(rk_normals[a]) : h.normal;
    return dot(n, d) > 0.0 ? -n : n;
}

// `a` is the hit's attribute index (rk_svo_trace_attr), fetched once by the caller.
vec3 rk_pass_local(rk_svo_tree tree, vec3 p, vec3 d, rk_svo_trace_hit h, uint a, bool shadows)
{
    vec3 albedo = u_streams.x != 0u ? rk_svo_unpack_color(rk_colors[a]).rgb : vec3(0.8);
    vec3 n = rk_pass_normal(a, h, d);
    float diff = max(dot(n, u_light_obj), 0.0);
#if RK_SVO_PASS_SHADOWS
    // Shadow ray from one voxel along the smooth normal: on a curved voxel surface the cube faces
    // of the neighbouring voxels would otherwise shadow each other (Wilks's self-shadowing
    // artefacts); the face-offset rk_svo_shadowed is exact for flat voxel geometry.
    if (shadows && diff > 0.0) {
        vec3 so = rk_svo_secondary_origin(p, h.normal, u_light_obj, tree, h.level) + n * rk_svo_voxel_size(tree, h.level);
        if (rk_svo_trace(0u, tree, so, u_light_obj, 3.0e38, vec2(0.0)).hit) diff = 0.0;
    }
#endif
    return albedo * (u_ambient.rgb + (1.0 - u_ambient.rgb) * diff);
}

#if RK_SVO_PASS_BOUNCE
// Per material: x = mirror reflectance, y = opacity (alpha; < 1 refracts).
layout(std430, binding = 8) readonly buffer RkSurface { vec4 rk_surface[]; };

vec3 rk_pass_sky(vec3 d)
{
    return mix(vec3(0.62, 0.70, 0.80), vec3(0.22, 0.36, 0.66), clamp(d.y, 0.0, 1.0));
}

// One more bounce: what a secondary ray sees (locally shaded, no further bounces).
vec3 rk_pass_radiance(rk_svo_tree tree, vec3 o, vec3 d)
{
    rk_svo_trace_hit h = rk_svo_trace(0u, tree, o, d, 3.0e38, vec2(0.0));
    if (!h.hit) return rk_pass_sky(d);
    return rk_pass_local(tree, o + d * h.t, d, h, rk_svo_trace_attr(0u, tree, h), true);
}

vec3 rk_pass_secondary(rk_svo_tree tree, vec3 o, vec3 dir, rk_svo_trace_hit h)
{
    vec3 p = rk_svo_hit_point(tree, o, dir, h);  // on the entered face exactly
    vec3 d = normalize(dir);
    uint a = rk_svo_trace_attr(0u, tree, h);
    vec3 local = rk_pass_local(tree, p, d, h, a, true);
    uint mat = rk_svo_material_ids[a];
    vec4 surf = rk_surface[mat];
    vec3 col = local;
#if RK_SVO_PASS_REFRACTION
    if (surf.y < 1.0) {
        // Refractive: Fresnel reflection plus what leaves the object(s), absorbed on the way.
        rk_svo_refraction r = rk_svo_refract_through(0u, tree, 0u, o, d, 1.0, 6u);
        vec3 refl = rk_pass_radiance(tree, r.reflect_origin, r.reflect_dir);
        vec3 through = rk_pass_radiance(tree, r.origin, r.dir);  // (an incomplete path goes on from where it stopped)
        col = r.reflectance * refl + (1.0 - r.reflectance) * surf.y * local + (1.0 - surf.y) * r.transmittance * through;
        return col;
    }
#endif
#if RK_SVO_PASS_REFLECTION
    if (surf.x > 0.0) {
        // Mirror about the stored smooth normal (the cube faces of a tilted voxel plane would
        // reflect in stripes).
        vec3 rd = reflect(d, rk_pass_normal(a, h, d));
        vec3 refl = rk_pass_radiance(tree, rk_svo_secondary_origin(p, h.normal, rd, tree, h.level), rd);
        col = mix(local, refl, surf.x);
    }
#endif
    return col;
}
#endif

void main()
{
    vec2 ndc = (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0;
    vec3 o, d;
    rk_svo_pixel_ray(u_clip_to_obj, ndc, u_depth.x, o, d);
    float t_max = 3.402823e38;
    if (u_depth.w > 0.5)
        t_max = rk_svo_depth_to_t(u_clip_to_obj, ndc, texelFetch(u_depth_tex, ivec2(gl_FragCoord.xy), 0).x,
                                  vec2(u_depth.y, u_depth.z), o, d);
    rk_svo_tree tree;
    tree.depth = u_tree.x; tree.max_level = u_tree.y; tree.desc_words = u_tree.z; tree.brick_base_word = u_tree.w;
    tree.root_min = u_root.xyz; tree.root_size = u_root.w;
    rk_svo_trace_hit h = rk_svo_trace(0u, tree, o, d, t_max, u_cone);
    if (u_ambient.w > 0.5) {
        frag = vec4(vec3(float(h.iterations) / 64.0), 1.0);
        gl_FragDepth = h.hit ? rk_svo_window_depth(u_obj_to_clip, o + d * h.t, vec2(u_depth.y, u_depth.z)) : gl_FragCoord.z;
        return;
    }
    if (!h.hit) discard;
    gl_FragDepth = rk_svo_window_depth(u_obj_to_clip, o + d * h.t, vec2(u_depth.y, u_depth.z));
#if RK_SVO_PASS_BOUNCE
    frag = vec4(rk_pass_secondary(tree, o, d, h), 1.0);
#else
    frag = vec4(rk_pass_local(tree, o + d * h.t, d, h, rk_svo_trace_attr(0u, tree, h), RK_SVO_PASS_SHADOWS != 0), 1.0);
#endif
}
)";
}

/// A full-screen triangle (no vertex buffer).
inline const char* fullscreen_vertex_source()
{
    return R"(#version 450 core
void main()
{
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
)";
}

/// The render target of a hybrid frame: RGBA8 colour and 32-bit float depth, plus a second depth
/// texture that copy_depth() fills, for the voxel pass's early termination (SvoDrawParams::
/// depth_texture) while the depth buffer itself stays bound. Bound for drawing on construction and
/// by bind(); the default framebuffer is bound again on destruction.
class DepthTarget {
public:
    DepthTarget(int width, int height) : w_(width), h_(height)
    {
        glCreateTextures(GL_TEXTURE_2D, 1, &color_);
        glTextureStorage2D(color_, 1, GL_RGBA8, width, height);
        glCreateTextures(GL_TEXTURE_2D, 1, &depth_);
        glTextureStorage2D(depth_, 1, GL_DEPTH_COMPONENT32F, width, height);
        glCreateTextures(GL_TEXTURE_2D, 1, &depth_copy_);
        glTextureStorage2D(depth_copy_, 1, GL_DEPTH_COMPONENT32F, width, height);
        glTextureParameteri(depth_copy_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(depth_copy_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glCreateFramebuffers(1, &fbo_);
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, color_, 0);
        glNamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
        bind();
    }
    ~DepthTarget()
    {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteFramebuffers(1, &fbo_);
        GLuint t[3] = {color_, depth_, depth_copy_};
        glDeleteTextures(3, t);
    }
    DepthTarget(const DepthTarget&) = delete;
    DepthTarget& operator=(const DepthTarget&) = delete;

    void bind() const
    {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glViewport(0, 0, w_, h_);
    }
    /// Copies the depth buffer into the copy texture and returns that texture.
    GLuint copy_depth() const
    {
        glCopyImageSubData(depth_, GL_TEXTURE_2D, 0, 0, 0, 0, depth_copy_, GL_TEXTURE_2D, 0, 0, 0, 0, w_, h_, 1);
        return depth_copy_;
    }
    GLuint fbo() const { return fbo_; }
    /// The colour pixels, bottom row first (GL order) or top row first (PNG order). Binds the target.
    std::vector<unsigned char> read_rgba8(bool top_row_first) const
    {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        std::vector<unsigned char> px(size_t(w_) * size_t(h_) * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, w_, h_, GL_RGBA, GL_UNSIGNED_BYTE, px.data());
        if (!top_row_first) return px;
        std::vector<unsigned char> out(px.size());
        const size_t row = size_t(w_) * 4;
        for (int y = 0; y < h_; ++y) std::memcpy(&out[size_t(y) * row], &px[size_t(h_ - 1 - y) * row], row);
        return out;
    }
    /// The depth buffer, bottom row first. Binds the target.
    std::vector<float> read_depth() const
    {
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        std::vector<float> d(size_t(w_) * size_t(h_));
        glReadPixels(0, 0, w_, h_, GL_DEPTH_COMPONENT, GL_FLOAT, d.data());
        return d;
    }

private:
    int w_, h_;
    GLuint fbo_ = 0, color_ = 0, depth_ = 0, depth_copy_ = 0;
};

/// An octree's geometry words (SvoTree::gpu_words()) where svo_format.glsl reads them, bound while
/// alive: an SSBO at `binding` (RK_SVO_BUFFER_TEXTURE=0), or an R32UI 2D texture on texture unit
/// `binding`, RK_SVO_TEXTURE_WIDTH texels per row, zero-padded (RK_SVO_BUFFER_TEXTURE=1, for
/// GLSL ES 3.0 / WebGL 2).
class SvoWordsGl {
public:
    SvoWordsGl(const std::vector<uint32_t>& words, bool texture, GLuint binding = 0)
    {
        if (texture) {
            const glm::uvec2 ext = raykit::svo_texture_extent(words.size());
            std::vector<uint32_t> padded(static_cast<size_t>(ext.x) * ext.y, 0u);
            std::copy(words.begin(), words.end(), padded.begin());
            glCreateTextures(GL_TEXTURE_2D, 1, &tex_);
            glTextureStorage2D(tex_, 1, GL_R32UI, static_cast<GLsizei>(ext.x), static_cast<GLsizei>(ext.y));
            // Integer textures are incomplete (texelFetch returns 0) with the default mipmap filter.
            glTextureParameteri(tex_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(tex_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTextureSubImage2D(tex_, 0, 0, 0, static_cast<GLsizei>(ext.x), static_cast<GLsizei>(ext.y), GL_RED_INTEGER,
                                GL_UNSIGNED_INT, padded.data());
            glBindTextureUnit(binding, tex_);
        } else {
            buffer_ = make_buffer(words.size() * 4, words.data());
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer_);
        }
    }
    ~SvoWordsGl()
    {
        if (buffer_) glDeleteBuffers(1, &buffer_);
        if (tex_) glDeleteTextures(1, &tex_);
    }
    SvoWordsGl(const SvoWordsGl&) = delete;
    SvoWordsGl& operator=(const SvoWordsGl&) = delete;

private:
    GLuint buffer_ = 0, tex_ = 0;
};

/// A packed octree on the GPU and its draw call.
class SvoGlObject {
public:
    SvoGlObject(const raykit::SvoTree& tree, const std::string& shader_dir)
    {
        tree_.depth = tree.depth;
        tree_.desc_words = tree.desc_words;
        tree_.brick_base_word = tree.gpu_brick_base_word();
        tree_.root_min = tree.root_min;
        tree_.root_size = tree.root_size;
        tree_.colors = !tree.color.empty();
        tree_.normals = !tree.normal.empty();
        const std::vector<uint32_t> words = tree.gpu_words();
        words_ = make_buffer(words.size() * 4, words.data());
        const uint32_t zero = 0;
        colors_ = tree.color.empty() ? make_buffer(4, &zero) : make_buffer(tree.color.size() * 4, tree.color.data());
        normals_ = tree.normal.empty() ? make_buffer(4, &zero) : make_buffer(tree.normal.size() * 4, tree.normal.data());
        // Programs: 0 plain, 1 LOD, 2 secondary rays (only for trees with materials: shadows, and
        // reflection and refraction where the materials have them).
        for (int k = 0; k < 3; ++k) {
            if (k == 2 && tree.material.empty()) break;
            raykit::SvoSceneDesc scene;
            scene.lod = k == 1;
            scene.shadows = k == 2;
            const std::vector<raykit::SvoMaterial> none;
            const std::string fs = resolved_shader(svo_fragment_source(), "svo_pass.frag", shader_dir, {shader_dir},
                                                   raykit::svo_defines(scene, k == 2 ? tree.materials : none));
            prog_[k] = build_program({{GL_VERTEX_SHADER, fullscreen_vertex_source()}, {GL_FRAGMENT_SHADER, fs}});
        }
        if (!tree.material.empty()) {
            material_ids_ = make_buffer(tree.material.size() * 4, tree.material.data());
            const std::vector<glm::vec4> media = raykit::svo_media_table(tree);
            media_ = make_buffer(media.size() * sizeof(glm::vec4), media.data());
            std::vector<glm::vec4> surf;
            for (const raykit::SvoMaterial& m : tree.materials) surf.push_back(glm::vec4(m.reflectance, m.base_color.a, 0.0f, 0.0f));
            if (surf.empty()) surf.push_back(glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
            surface_ = make_buffer(surf.size() * sizeof(glm::vec4), surf.data());
        }
        glCreateVertexArrays(1, &vao_);
    }
    ~SvoGlObject()
    {
        GLuint b[6] = {words_, colors_, normals_, material_ids_, media_, surface_};
        glDeleteBuffers(6, b);
        for (GLuint p : prog_)
            if (p) glDeleteProgram(p);
        glDeleteVertexArrays(1, &vao_);
    }
    SvoGlObject(const SvoGlObject&) = delete;
    SvoGlObject& operator=(const SvoGlObject&) = delete;

    /// Draws the object placed by `model` into the bound framebuffer's viewport (depth test and
    /// function as set by the caller).
    void draw(const glm::mat4& model, const glm::mat4& view, const glm::mat4& proj, raykit::SvoDepthConvention conv,
              const SvoDrawParams& p) const
    {
        const raykit::SvoHybridView hv = raykit::svo_hybrid_view(model, view, proj, conv);
        GLint vp[4];
        glGetIntegerv(GL_VIEWPORT, vp);
        const bool lod = p.lod_pixels > 0.0f;
        const bool secondary = p.secondary && prog_[2] != 0;
        const GLuint prog = prog_[secondary ? 2 : (lod ? 1 : 0)];
        glUseProgram(prog);
        glUniformMatrix4fv(0, 1, GL_FALSE, &hv.obj_to_clip[0][0]);
        glUniformMatrix4fv(1, 1, GL_FALSE, &hv.clip_to_obj[0][0]);
        glUniform4f(2, hv.z_near_ndc, hv.depth_range.x, hv.depth_range.y, p.depth_texture ? 1.0f : 0.0f);
        const uint32_t ml = p.max_level < tree_.depth ? p.max_level : tree_.depth;
        glUniform4ui(3, tree_.depth, ml, tree_.desc_words, tree_.brick_base_word);
        glUniform4f(4, tree_.root_min.x, tree_.root_min.y, tree_.root_min.z, tree_.root_size);
        // The cone's slope is an angle, the same in object and world units (a uniform model scale
        // scales node sizes and distances alike), so it needs no conversion.
        const glm::vec2 cone = lod ? raykit::rk_svo_pixel_cone(p.fov_y, float(vp[3]), p.lod_pixels) : glm::vec2(0.0f);
        glUniform2f(5, cone.x, cone.y);
        const glm::vec3 l = glm::normalize(glm::vec3(glm::inverse(model) * glm::vec4(p.light_dir_world, 0.0f)));
        glUniform3f(6, l.x, l.y, l.z);
        glUniform4f(7, float(vp[0]), float(vp[1]), float(vp[2]), float(vp[3]));
        glUniform2ui(8, tree_.colors ? 1u : 0u, tree_.normals ? 1u : 0u);
        glUniform4f(9, p.ambient.x, p.ambient.y, p.ambient.z, p.show_iterations ? 1.0f : 0.0f);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, words_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, colors_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, normals_);
        if (secondary) {
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, material_ids_);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, media_);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, surface_);
        }
        if (p.depth_texture) glBindTextureUnit(0, p.depth_texture);
        glBindVertexArray(vao_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }


    /// The buffers draw() binds: the octree words (gpu_words(), binding 0) and the colour stream
    /// (binding 1), for passes of your own over the same tree (e.g. a compute pass).
    GLuint words_buffer() const { return words_; }
    GLuint colors_buffer() const { return colors_; }

private:
    /// What draw() needs of the tree (kept by value: the caller's SvoTree may go away).
    struct TreeInfo {
        uint32_t depth = 0, desc_words = 0, brick_base_word = 0;
        glm::vec3 root_min{0.0f};
        float root_size = 0.0f;
        bool colors = false, normals = false;
    };
    TreeInfo tree_;
    GLuint words_ = 0, colors_ = 0, normals_ = 0, vao_ = 0, material_ids_ = 0, media_ = 0, surface_ = 0;
    GLuint prog_[3] = {0, 0, 0};
};

/// A lit triangle mesh (positions + normals, flat colour) for the rasterised side of the frame.
class MeshGl {
public:
    MeshGl(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals, const std::vector<uint32_t>& indices)
        : count_(GLsizei(indices.size()))
    {
        std::vector<float> v;
        v.reserve(positions.size() * 6);
        for (size_t i = 0; i < positions.size(); ++i) {
            const glm::vec3 n = i < normals.size() ? normals[i] : glm::vec3(0.0f, 0.0f, 1.0f);
            v.insert(v.end(), {positions[i].x, positions[i].y, positions[i].z, n.x, n.y, n.z});
        }
        vbo_ = make_buffer(v.size() * 4, v.data());
        ibo_ = make_buffer(indices.size() * 4, indices.data());
        glCreateVertexArrays(1, &vao_);
        glVertexArrayVertexBuffer(vao_, 0, vbo_, 0, 24);
        glVertexArrayElementBuffer(vao_, ibo_);
        glEnableVertexArrayAttrib(vao_, 0);
        glEnableVertexArrayAttrib(vao_, 1);
        glVertexArrayAttribFormat(vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribFormat(vao_, 1, 3, GL_FLOAT, GL_FALSE, 12);
        glVertexArrayAttribBinding(vao_, 0, 0);
        glVertexArrayAttribBinding(vao_, 1, 0);
        prog_ = build_program({{GL_VERTEX_SHADER, R"(#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_nrm;
layout(location = 0) uniform mat4 u_mvp;
layout(location = 1) uniform mat4 u_model;
out vec3 v_nrm;
void main() { gl_Position = u_mvp * vec4(a_pos, 1.0); v_nrm = mat3(u_model) * a_nrm; }
)"},
                               {GL_FRAGMENT_SHADER, R"(#version 450 core
in vec3 v_nrm;
layout(location = 2) uniform vec3 u_color;
layout(location = 3) uniform vec3 u_light;
layout(location = 0) out vec4 frag;
void main() { vec3 n = normalize(v_nrm); frag = vec4(u_color * (0.18 + 0.82 * abs(dot(n, u_light))), 1.0); }
)"}});
    }
    ~MeshGl()
    {
        GLuint b[2] = {vbo_, ibo_};
        glDeleteBuffers(2, b);
        glDeleteVertexArrays(1, &vao_);
        glDeleteProgram(prog_);
    }
    MeshGl(const MeshGl&) = delete;
    MeshGl& operator=(const MeshGl&) = delete;

    /// Draws with mvp = proj * view * model computed in double (as svo_hybrid_view does, so both
    /// sides of the frame project with the same float matrix).
    void draw(const glm::mat4& model, const glm::mat4& view, const glm::mat4& proj, glm::vec3 color, glm::vec3 light_world) const
    {
        const glm::mat4 mvp = glm::mat4(glm::dmat4(proj) * glm::dmat4(view) * glm::dmat4(model));
        glUseProgram(prog_);
        glUniformMatrix4fv(0, 1, GL_FALSE, &mvp[0][0]);
        glUniformMatrix4fv(1, 1, GL_FALSE, &model[0][0]);
        glUniform3f(2, color.x, color.y, color.z);
        const glm::vec3 l = glm::normalize(light_world);
        glUniform3f(3, l.x, l.y, l.z);
        glBindVertexArray(vao_);
        glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
    }

private:
    GLsizei count_;
    GLuint vbo_ = 0, ibo_ = 0, vao_ = 0, prog_ = 0;
};

}  // namespace rkgl
