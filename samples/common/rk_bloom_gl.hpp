// raykit samples — rk_bloom_gl.hpp: an OpenGL 4.5 host for the bloom of shaders/raykit/bloom.glsl
// and bloom_passes.glsl (Fahlén 2005, "Illumination for Real-Time Rendering of Large Architectural
// Environments", §3.4: bright pass -> 2x2 downsamples -> separable Gaussian on 4 levels from 1/8 ->
// magnify and add), with the skip: a small GPU max/count reduction runs first and
// when no pixel's luminance exceeds the bright pass's cutoff, no draw is issued at all.
//
// Per frame (defaults: 1/8, 4 levels, sigma 3, radius 9), for a W x H HDR texture:
//   1 compute dispatch  max luminance + count above rk_bloom_cutoff (16x16 groups, shared-memory
//                       tree, one atomicMax/atomicAdd per group), then a 8-byte read back (a sync
//                       point, as the thesis's glReadPixels of its 1x1 luminance; an engine that
//                       cannot stall can read the previous frame's result instead).
//   if nothing is above:  nothing more (ADD, CONSERVE: apply() returns the input texture), or only
//                       the composite with zero bloom (MIX, whose result is (1 - s) hdr).
//   else 1 prefilter    W/2 x H/2: bright pass of 4 texels (+ Karis) [rk_bloom_prefilter]
//        5 downsamples  1/4 .. 1/64, one bilinear fetch each [rk_bloom_downsample]
//        8 blurs        H and V on 1/8 .. 1/64, merged taps as uniforms, 11 fetches [rk_bloom_blur]
//        1 composite    W x H: 4 bilinear magnifications + composite [rk_bloom_gather_levels,
//                       rk_bloom_composite_pixel]
// = 15 full-screen triangles. Samplers: downsample and magnification CLAMP_TO_EDGE; the blur
// CLAMP_TO_BORDER with a black border (no wrap-around, the image is zero outside: the thesis's
// setting). Intermediate format GL_RGBA16F by default (the thesis's fp16; 4.9e-4 relative rounding
// per pass) or GL_RGBA32F. raykit::bloom_reference() is the CPU mirror of the whole chain.
//
// State: apply() disables blending, depth, stencil and scissor tests and leaves program 0,
// framebuffer 0, vertex array 0 and no samplers on units 0-4 bound; the viewport is changed.
// Needs a current OpenGL 4.5 context (rk_gl.hpp's HeadlessContext, or a window's).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "raykit/bloom.hpp"
#include "raykit/shader_source.hpp"
#include "rk_gl.hpp"

namespace rkgl {

namespace bloom_detail {

inline const char* vertex_source()
{
    return R"(#version 450 core
// A triangle covering the viewport, from gl_VertexID alone (no vertex buffer).
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";
}

inline const char* prefilter_source()
{
    return R"(#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "raykit/bloom_passes.glsl"
layout(binding = 0) uniform sampler2D u_src;   // full-size HDR, nearest sampler (texelFetch)
layout(location = 0) uniform vec2 u_dst_size;
layout(location = 1) uniform float u_threshold;
layout(location = 2) uniform float u_knee;
layout(location = 3) uniform int u_mode;
layout(location = 4) uniform int u_karis;
layout(location = 0) out vec4 o_color;
void main()
{
    o_color = vec4(rk_bloom_prefilter(u_src, gl_FragCoord.xy, u_dst_size, u_threshold, u_knee, u_mode, u_karis != 0), 1.0);
}
)";
}

inline const char* downsample_source()
{
    return R"(#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "raykit/bloom_passes.glsl"
layout(binding = 0) uniform sampler2D u_src;   // linear, clamp to edge
layout(location = 0) uniform vec2 u_dst_size;
layout(location = 0) out vec4 o_color;
void main()
{
    o_color = vec4(rk_bloom_downsample(u_src, gl_FragCoord.xy / u_dst_size), 1.0);
}
)";
}

inline const char* blur_source()
{
    return R"(#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "raykit/bloom_passes.glsl"
layout(binding = 0) uniform sampler2D u_src;   // linear, clamp to border (black)
layout(location = 0) uniform vec2 u_size;      // source = target size
layout(location = 1) uniform vec2 u_dir;       // (1, 0) or (0, 1)
layout(location = 2) uniform int u_count;      // one-sided taps, centre included
layout(location = 8) uniform vec2 u_taps[RK_BLOOM_MAX_TAPS];  // (offset, weight)
layout(location = 0) out vec4 o_color;
void main()
{
    o_color = vec4(rk_bloom_blur(u_src, gl_FragCoord.xy / u_size, u_dir / u_size, u_taps, u_count), 1.0);
}
)";
}

inline const char* composite_source()
{
    return R"(#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "raykit/bloom_passes.glsl"
layout(binding = 0) uniform sampler2D u_hdr;   // nearest (texelFetch)
layout(binding = 1) uniform sampler2D u_l0;    // blurred levels, linear, clamp to edge
layout(binding = 2) uniform sampler2D u_l1;
layout(binding = 3) uniform sampler2D u_l2;
layout(binding = 4) uniform sampler2D u_l3;
layout(location = 0) uniform vec2 u_size;
layout(location = 1) uniform vec4 u_level_weights;
layout(location = 2) uniform float u_threshold;
layout(location = 3) uniform float u_knee;
layout(location = 4) uniform int u_mode;
layout(location = 5) uniform float u_strength;
layout(location = 6) uniform int u_composite;
layout(location = 0) out vec4 o_color;
void main()
{
    vec3 bloom = rk_bloom_gather_levels(u_l0, u_l1, u_l2, u_l3, gl_FragCoord.xy / u_size, u_level_weights);
    o_color = vec4(rk_bloom_composite_pixel(u_hdr, ivec2(gl_FragCoord.xy), bloom, u_threshold, u_knee, u_mode,
                                            u_strength, u_composite), 1.0);
}
)";
}

inline const char* reduce_source()
{
    return R"(#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "raykit/bloom.glsl"
// Max of rk_bloom_luminance and count of pixels with luminance > u_cutoff over the whole texture.
// Luminances are >= +0, so their bit patterns order like the floats: atomicMax on uint is exact.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0) uniform sampler2D u_hdr;   // nearest (texelFetch)
layout(location = 0) uniform float u_cutoff;
layout(std430, binding = 0) buffer Result { uint r_max_bits; uint r_count; };
shared float s_max[256];
shared uint s_count[256];
void main()
{
    ivec2 size = textureSize(u_hdr, 0);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    float y = 0.0;
    uint c = 0u;
    if (p.x < size.x && p.y < size.y) {
        y = rk_bloom_luminance(texelFetch(u_hdr, p, 0).rgb);
        c = y > u_cutoff ? 1u : 0u;
    }
    uint i = gl_LocalInvocationIndex;
    s_max[i] = y;
    s_count[i] = c;
    barrier();
    for (uint s = 128u; s > 0u; s >>= 1u) {
        if (i < s) {
            s_max[i] = max(s_max[i], s_max[i + s]);
            s_count[i] += s_count[i + s];
        }
        barrier();
    }
    if (i == 0u) {
        atomicMax(r_max_bits, floatBitsToUint(s_max[0]));
        atomicAdd(r_count, s_count[0]);
    }
}
)";
}

}  // namespace bloom_detail

/// Counters of the GL work BloomGl issued (for tests and profiling overlays).
struct BloomGlStats {
    long draws = 0;       ///< glDrawArrays calls (one full-screen triangle each)
    long dispatches = 0;  ///< glDispatchCompute calls (the reduction)
    long readbacks = 0;   ///< buffer read backs (the reduction result)
    long skipped = 0;     ///< apply() calls that issued no draw at all
};

/// What BloomGl::apply() produced.
struct BloomGlFrame {
    GLuint texture = 0;        ///< the composite (owned by BloomGl), or the input texture when !composited
    bool chain_run = false;    ///< the downsample/blur chain ran (something exceeded the cutoff)
    bool composited = false;   ///< the composite pass ran
    raykit::BloomReduction reduction;
};

/// BloomGl: owns the programs, samplers, the chain's textures (reallocated when the input size
/// changes) and the reduction buffer. Not copyable. Throws std::runtime_error if a program fails to
/// build, std::invalid_argument for bad parameters.
class BloomGl {
public:
    /// `shader_dir` is the folder holding raykit/*.glsl; `format` the intermediate and output
    /// format (GL_RGBA16F, GL_RGBA32F or GL_R11F_G11F_B10F).
    explicit BloomGl(const std::string& shader_dir, GLenum format = GL_RGBA16F) : format_(format)
    {
        auto build = [&](const char* name, std::vector<std::pair<GLenum, std::string>> stages) {
            for (auto& st : stages) st.second = resolved_shader(st.second, name, shader_dir, {shader_dir});
            return build_program(stages);
        };
        const std::string vs = bloom_detail::vertex_source();
        prefilter_ = build("bloom_prefilter.frag", {{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, bloom_detail::prefilter_source()}});
        downsample_ = build("bloom_downsample.frag", {{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, bloom_detail::downsample_source()}});
        blur_ = build("bloom_blur.frag", {{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, bloom_detail::blur_source()}});
        composite_ = build("bloom_composite.frag", {{GL_VERTEX_SHADER, vs}, {GL_FRAGMENT_SHADER, bloom_detail::composite_source()}});
        reduce_ = build("bloom_reduce.comp", {{GL_COMPUTE_SHADER, bloom_detail::reduce_source()}});

        glCreateSamplers(1, &nearest_);
        glSamplerParameteri(nearest_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(nearest_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glCreateSamplers(1, &edge_);
        glCreateSamplers(1, &border_);
        for (GLuint s : {nearest_, edge_, border_}) {
            const GLint wrap = s == border_ ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE;
            glSamplerParameteri(s, GL_TEXTURE_WRAP_S, wrap);
            glSamplerParameteri(s, GL_TEXTURE_WRAP_T, wrap);
            if (s != nearest_) {
                glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
                glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
            }
        }
        const GLfloat black[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glSamplerParameterfv(border_, GL_TEXTURE_BORDER_COLOR, black);
        glCreateVertexArrays(1, &vao_);
        result_ = make_buffer(2 * sizeof(std::uint32_t), nullptr);
        set_params(raykit::BloomParams{});
    }

    ~BloomGl()
    {
        release_targets();
        glDeleteProgram(prefilter_);
        glDeleteProgram(downsample_);
        glDeleteProgram(blur_);
        glDeleteProgram(composite_);
        glDeleteProgram(reduce_);
        GLuint samplers[3] = {nearest_, edge_, border_};
        glDeleteSamplers(3, samplers);
        glDeleteVertexArrays(1, &vao_);
        glDeleteBuffers(1, &result_);
    }
    BloomGl(const BloomGl&) = delete;
    BloomGl& operator=(const BloomGl&) = delete;

    /// Sets the parameters (raykit::validate_bloom_params) and recomputes the merged taps.
    void set_params(const raykit::BloomParams& p)
    {
        raykit::Status st;
        if (!raykit::validate_bloom_params(p, &st)) throw std::invalid_argument(st.message);
        params_ = p;
        taps_ = raykit::linear_sampled_taps(raykit::gaussian_weights(p.sigma, p.radius));
        if (taps_.size() > RK_BLOOM_MAX_TAPS) throw std::invalid_argument("rkgl::BloomGl: too many taps");
        if (width_ > 0) allocate(width_, height_, true);  // levels / first_div may have changed
    }
    const raykit::BloomParams& params() const { return params_; }
    /// Changes the intermediate/output format (reallocates the textures on the next apply()).
    void set_format(GLenum format)
    {
        if (format == format_) return;
        format_ = format;
        release_targets();
        width_ = height_ = 0;
    }
    GLenum format() const { return format_; }
    /// The merged taps the blur passes use (one-sided, centre first).
    const std::vector<raykit::BloomTap>& taps() const { return taps_; }

    /// The max/count reduction alone: 1 dispatch + 1 read back. `hdr` is any 2-D texture whose
    /// level 0 is width x height.
    raykit::BloomReduction reduce(GLuint hdr, int width, int height, float cutoff)
    {
        const std::uint32_t zero[2] = {0u, 0u};
        glNamedBufferSubData(result_, 0, sizeof zero, zero);
        glUseProgram(reduce_);
        glUniform1f(0, cutoff);
        glBindTextureUnit(0, hdr);
        glBindSampler(0, nearest_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, result_);
        glDispatchCompute(static_cast<GLuint>((width + 15) / 16), static_cast<GLuint>((height + 15) / 16), 1);
        ++stats_.dispatches;
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::uint32_t r[2] = {0u, 0u};
        glGetNamedBufferSubData(result_, 0, sizeof r, r);
        ++stats_.readbacks;
        glBindSampler(0, 0);
        glUseProgram(0);
        raykit::BloomReduction red;
        std::memcpy(&red.max_luminance, &r[0], sizeof red.max_luminance);
        red.count_above = r[1];
        return red;
    }

    /// Runs the bloom on `hdr` (width x height, any float format, sampled with texelFetch and
    /// bilinear fetches of BloomGl's own textures). See the header for the passes and the skip.
    BloomGlFrame apply(GLuint hdr, int width, int height)
    {
        if (width < 1 || height < 1) throw std::invalid_argument("rkgl::BloomGl::apply: empty image");
        allocate(width, height, false);
        const raykit::BloomParams& p = params_;
        BloomGlFrame frame;
        frame.reduction = reduce(hdr, width, height, raykit::rk_bloom_cutoff(p.threshold, p.knee, p.mode));
        frame.chain_run = frame.reduction.count_above > 0;
        if (!frame.chain_run && p.composite != RK_BLOOM_COMPOSITE_MIX) {
            ++stats_.skipped;
            frame.texture = hdr;
            return frame;
        }
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_STENCIL_TEST);
        glDisable(GL_SCISSOR_TEST);
        glBindVertexArray(vao_);
        const size_t n_down = chain_.downsamples.size();
        const size_t first_level = n_down - chain_.levels.size();
        if (frame.chain_run) {
            // Prefilter (bright pass + first downsample).
            glUseProgram(prefilter_);
            const raykit::ivec2 d0 = chain_.downsamples[0];
            glUniform2f(0, static_cast<float>(d0.x), static_cast<float>(d0.y));
            glUniform1f(1, p.threshold);
            glUniform1f(2, p.knee);
            glUniform1i(3, p.mode);
            glUniform1i(4, p.karis ? 1 : 0);
            bind(0, hdr, nearest_);
            draw(down_[0]);
            // Downsamples.
            glUseProgram(downsample_);
            for (size_t i = 1; i < n_down; ++i) {
                const raykit::ivec2 d = chain_.downsamples[i];
                glUniform2f(0, static_cast<float>(d.x), static_cast<float>(d.y));
                bind(0, down_[i - 1].tex, edge_);
                draw(down_[i]);
            }
            // Separable blur of every level: down -> tmp (horizontal), tmp -> down (vertical).
            glUseProgram(blur_);
            std::vector<float> taps(2 * RK_BLOOM_MAX_TAPS, 0.0f);
            for (size_t k = 0; k < taps_.size(); ++k) {
                taps[2 * k] = taps_[k].offset;
                taps[2 * k + 1] = taps_[k].weight;
            }
            glUniform2fv(8, RK_BLOOM_MAX_TAPS, taps.data());
            glUniform1i(2, static_cast<GLint>(taps_.size()));
            for (size_t i = first_level; i < n_down; ++i) {
                const raykit::ivec2 d = chain_.downsamples[i];
                glUniform2f(0, static_cast<float>(d.x), static_cast<float>(d.y));
                glUniform2f(1, 1.0f, 0.0f);
                bind(0, down_[i].tex, border_);
                draw(tmp_[i - first_level]);
                glUniform2f(1, 0.0f, 1.0f);
                bind(0, tmp_[i - first_level].tex, border_);
                draw(down_[i]);
            }
        }
        // Composite. With no chain (MIX only) the level weights are 0 and the (unwritten) level
        // textures' contents are sanitised away by rk_bloom_sum_levels.
        glUseProgram(composite_);
        const raykit::vec4 lw = frame.chain_run ? raykit::bloom_level_weights(p) : raykit::vec4(0.0f);
        glUniform2f(0, static_cast<float>(width), static_cast<float>(height));
        glUniform4f(1, lw.x, lw.y, lw.z, lw.w);
        glUniform1f(2, p.threshold);
        glUniform1f(3, p.knee);
        glUniform1i(4, p.mode);
        glUniform1f(5, p.strength);
        glUniform1i(6, p.composite);
        bind(0, hdr, nearest_);
        for (int l = 0; l < 4; ++l) {
            const size_t i = first_level + static_cast<size_t>(std::min(l, static_cast<int>(chain_.levels.size()) - 1));
            bind(static_cast<GLuint>(1 + l), down_[i].tex, edge_);
        }
        draw(out_);
        frame.composited = true;
        frame.texture = out_.tex;
        for (GLuint u = 0; u < 5; ++u) glBindSampler(u, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindVertexArray(0);
        glUseProgram(0);
        return frame;
    }

    /// The texture of blurred level i (0 = largest) after apply() ran the chain.
    GLuint level_texture(int i) const
    {
        return down_.at(down_.size() - chain_.levels.size() + static_cast<size_t>(i)).tex;
    }
    const raykit::BloomChain& chain() const { return chain_; }
    const BloomGlStats& stats() const { return stats_; }
    void reset_stats() { stats_ = BloomGlStats{}; }

private:
    struct Target {
        GLuint tex = 0, fbo = 0;
        int w = 0, h = 0;
    };

    Target make_target(int w, int h) const
    {
        Target t;
        t.w = w;
        t.h = h;
        glCreateTextures(GL_TEXTURE_2D, 1, &t.tex);
        glTextureStorage2D(t.tex, 1, format_, w, h);
        glCreateFramebuffers(1, &t.fbo);
        glNamedFramebufferTexture(t.fbo, GL_COLOR_ATTACHMENT0, t.tex, 0);
        if (glCheckNamedFramebufferStatus(t.fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            throw std::runtime_error("rkgl::BloomGl: incomplete framebuffer (format not renderable?)");
        }
        return t;
    }

    void release_targets()
    {
        auto release = [](Target& t) {
            if (t.fbo) glDeleteFramebuffers(1, &t.fbo);
            if (t.tex) glDeleteTextures(1, &t.tex);
            t = Target{};
        };
        for (Target& t : down_) release(t);
        for (Target& t : tmp_) release(t);
        release(out_);
        down_.clear();
        tmp_.clear();
    }

    void allocate(int w, int h, bool force)
    {
        if (!force && w == width_ && h == height_) return;
        release_targets();
        width_ = w;
        height_ = h;
        chain_ = raykit::bloom_chain(w, h, params_.first_div, params_.levels);
        for (const raykit::ivec2& d : chain_.downsamples) down_.push_back(make_target(d.x, d.y));
        for (const raykit::ivec2& d : chain_.levels) tmp_.push_back(make_target(d.x, d.y));
        out_ = make_target(w, h);
    }

    static void bind(GLuint unit, GLuint tex, GLuint sampler)
    {
        glBindTextureUnit(unit, tex);
        glBindSampler(unit, sampler);
    }

    void draw(const Target& t)
    {
        glBindFramebuffer(GL_FRAMEBUFFER, t.fbo);
        glViewport(0, 0, t.w, t.h);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        ++stats_.draws;
    }

    GLenum format_;
    raykit::BloomParams params_;
    std::vector<raykit::BloomTap> taps_;
    raykit::BloomChain chain_;
    GLuint prefilter_ = 0, downsample_ = 0, blur_ = 0, composite_ = 0, reduce_ = 0;
    GLuint nearest_ = 0, edge_ = 0, border_ = 0, vao_ = 0, result_ = 0;
    std::vector<Target> down_, tmp_;
    Target out_;
    int width_ = 0, height_ = 0;
    BloomGlStats stats_;
};

}  // namespace rkgl
