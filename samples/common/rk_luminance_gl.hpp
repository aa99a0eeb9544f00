// raykit samples — rk_luminance_gl.hpp: the OpenGL 4.5 host of shaders/raykit/luminance_reduce.glsl.
// Runs the compute chain on a GL texture (any float format, read with texelFetch) or a float SSBO
// (1, 3 or 4 floats per pixel) and returns the log-average luminance, the optional histogram and
// what the finish pass derives from it (percentile-trimmed average, robust min/max, Reinhard 2002
// key/white, adapted luminance, EV100, exposure). The results also stay on the GPU in
// result_buffer() (RK_LUM_RESULT_* floats), so a tone-mapping pass can read them with no stall.
//
//   rkgl::LuminanceReducer reducer(RAYKIT_SHADER_DIR);      // compiles 4 programs
//   rkgl::LuminanceReduceOptions opt;  opt.dt = frame_seconds;
//   rkgl::LuminanceReduceResult r = reducer.reduce_texture(hdr_tex, w, h, 4, opt);
//
// The CPU references are raykit::log_average_luminance / luminance_histogram / histogram_stats
// (raykit/exposure.hpp); tests/gpu/parity_exposure.cpp checks them against this host.
// Needs a current GL 4.5 context (rk_gl.hpp's HeadlessContext or an application's).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "raykit/exposure.hpp"
#include "raykit/shader_source.hpp"
#include "rk_gl.hpp"

namespace rkgl {

/// Parameters of one reduction. Percentiles are fractions of the pixels in [0, 1].
struct LuminanceReduceOptions {
    float delta = RK_LOG_LUM_DELTA;  ///< Eq. 3.14's delta
    bool histogram = true;           ///< bin the terms (needed for the trimmed average, robust min/max, key/white)
    float hist_min_log2 = -24.0f;    ///< histogram range in log2 luminance: 64 stops, 4 bins per stop
    float hist_max_log2 = 40.0f;     ///< (values outside land in the end bins)
    float window_low = 0.05f;        ///< percentile window of the trimmed average (Unreal: 0.80 / 0.983)
    float window_high = 0.95f;
    float robust_low = 0.01f;        ///< robust min/max percentiles for Reinhard 2002 (as raykit::LogAverageOptions)
    float robust_high = 0.99f;
    bool adapt_to_histogram = false; ///< adaptation target: the trimmed average instead of the log-average
    float dt = 0.0f;                 ///< seconds since the previous reduction (0: the state does not move)
    float tau_up = 0.4f;             ///< time constant towards a brighter scene (light adaptation, fast), s
    float tau_down = 2.5f;           ///< towards a darker scene (dark adaptation, slower), s
    float ev_compensation = 0.0f;    ///< stops added to the automatic exposure
    bool reset_adaptation = false;   ///< jump to the target (camera cut); also happens on the first run
};

/// What the finish pass wrote (RK_LUM_RESULT_* of exposure.glsl) plus the histogram.
struct LuminanceReduceResult {
    float log_average = 0.0f, mean_log2 = 0.0f, histogram_average = 0.0f;
    float robust_min = 0.0f, robust_max = 0.0f, key = 0.0f, white = 0.0f;
    float adapted = 0.0f, ev100 = 0.0f, exposure = 0.0f;
    std::vector<std::uint32_t> histogram;  ///< empty when the option is off
};

class LuminanceReducer {
public:
    /// Workgroup layout compiled into the programs (luminance_reduce.glsl's macros).
    static constexpr int kGroup = 16, kThreadTile = 4, kTile = kGroup * kThreadTile, kBins = 256;

    /// Compiles the programs from `shader_dir` (the folder holding raykit/*.glsl). Throws
    /// std::runtime_error with the driver's log on failure.
    explicit LuminanceReducer(const std::string& shader_dir)
    {
        image_tex_ = build(shader_dir, image_main(), 0, "luminance_reduce_image_tex.comp");
        image_buf_ = build(shader_dir, image_main(), 1, "luminance_reduce_image_buf.comp");
        partials_ = build(shader_dir, partials_main(), 0, "luminance_reduce_partials.comp");
        finish_ = build(shader_dir, finish_main(), 0, "luminance_reduce_finish.comp");
        glCreateSamplers(1, &sampler_);
        glSamplerParameteri(sampler_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glSamplerParameteri(sampler_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        histogram_ = make_buffer(sizeof(std::uint32_t) * kBins, nullptr);
        const std::vector<float> zeros(RK_LUM_RESULT_COUNT, 0.0f);
        result_ = make_buffer(sizeof(float) * zeros.size(), zeros.data());
    }
    ~LuminanceReducer()
    {
        for (GLuint p : {image_tex_, image_buf_, partials_, finish_}) glDeleteProgram(p);
        glDeleteSamplers(1, &sampler_);
        for (GLuint b : {scratch_, histogram_, result_}) {
            if (b) glDeleteBuffers(1, &b);
        }
    }
    LuminanceReducer(const LuminanceReducer&) = delete;
    LuminanceReducer& operator=(const LuminanceReducer&) = delete;

    /// Reduces a width x height texture (level 0). channels: 1 reads .r as luminance, 3 or 4 read
    /// linear Rec.709 RGB. Any float/normalised format; filtering state is overridden (a NEAREST
    /// sampler is bound), so a texture without mipmaps works. Blocks until the result is read back.
    LuminanceReduceResult reduce_texture(GLuint texture, int width, int height, int channels,
                                         const LuminanceReduceOptions& options = {})
    {
        dispatch(texture, false, width, height, channels, options);
        return read_result(options.histogram);
    }

    /// Reduces a float SSBO of width * height pixels of `channels` (1, 3 or 4) floats, row-major.
    LuminanceReduceResult reduce_buffer(GLuint buffer, int width, int height, int channels,
                                        const LuminanceReduceOptions& options = {})
    {
        dispatch(buffer, true, width, height, channels, options);
        return read_result(options.histogram);
    }

    /// Records the chain without reading back (results in result_buffer(); a later pass that reads
    /// it needs glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT), which dispatch issues at its end).
    void dispatch(GLuint source, bool source_is_buffer, int width, int height, int channels,
                  const LuminanceReduceOptions& o)
    {
        if (channels != 1 && channels != 3 && channels != 4) {
            throw std::invalid_argument("rkgl::LuminanceReducer: channels must be 1, 3 or 4");
        }
        raykit::Status st;
        const std::vector<raykit::ReductionPass> chain = raykit::reduction_chain(width, height, kTile, &st);
        if (!st) throw std::invalid_argument("rkgl::LuminanceReducer: " + st.message);
        std::vector<GLuint> offsets(1, 0u);
        for (const raykit::ReductionPass& p : chain) {
            offsets.push_back(offsets.back() + static_cast<GLuint>(p.out_width * p.out_height));
        }
        ensure_scratch(offsets.back());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, scratch_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, histogram_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, result_);
        if (o.histogram) {
            const GLuint zero = 0;
            glClearNamedBufferData(histogram_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }

        // Pass 1: image -> per-tile sums (+ histogram).
        const GLuint image_program = source_is_buffer ? image_buf_ : image_tex_;
        glUseProgram(image_program);
        if (source_is_buffer) {
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, source);
        } else {
            glBindTextureUnit(0, source);
            glBindSampler(0, sampler_);
        }
        glUniform2i(0, width, height);
        glUniform1i(1, channels);
        glUniform1f(2, o.delta);
        glUniform1i(3, o.histogram ? 1 : 0);
        glUniform2f(4, o.hist_min_log2, o.hist_max_log2);
        glUniform1ui(5, offsets[0]);
        glDispatchCompute(static_cast<GLuint>(chain[0].out_width), static_cast<GLuint>(chain[0].out_height), 1);
        if (!source_is_buffer) glBindSampler(0, 0);

        // Passes 2..n: sums -> sums.
        glUseProgram(partials_);
        for (size_t k = 1; k < chain.size(); ++k) {
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
            glUniform2i(0, chain[k].in_width, chain[k].in_height);
            glUniform1ui(1, offsets[k - 1]);
            glUniform1ui(2, offsets[k]);
            glDispatchCompute(static_cast<GLuint>(chain[k].out_width), static_cast<GLuint>(chain[k].out_height), 1);
        }

        // Finish: one invocation.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUseProgram(finish_);
        glUniform1ui(0, offsets[chain.size() - 1]);
        glUniform1f(1, static_cast<float>(static_cast<double>(width) * static_cast<double>(height)));
        glUniform1i(2, o.histogram ? 1 : 0);
        glUniform2f(3, o.hist_min_log2, o.hist_max_log2);
        glUniform2f(4, o.window_low, o.window_high);
        glUniform2f(5, o.robust_low, o.robust_high);
        glUniform1i(6, o.adapt_to_histogram ? 1 : 0);
        glUniform1f(7, o.dt);
        glUniform2f(8, o.tau_up, o.tau_down);
        glUniform1f(9, o.ev_compensation);
        glUniform1i(10, o.reset_adaptation ? 1 : 0);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
        glUseProgram(0);
    }

    /// Reads the result buffer (and the histogram when `with_histogram`).
    LuminanceReduceResult read_result(bool with_histogram) const
    {
        const std::vector<float> v = read_floats(result_, RK_LUM_RESULT_COUNT);
        LuminanceReduceResult r;
        r.log_average = v[RK_LUM_RESULT_LOG_AVERAGE];
        r.mean_log2 = v[RK_LUM_RESULT_MEAN_LOG2];
        r.histogram_average = v[RK_LUM_RESULT_HIST_AVERAGE];
        r.robust_min = v[RK_LUM_RESULT_ROBUST_MIN];
        r.robust_max = v[RK_LUM_RESULT_ROBUST_MAX];
        r.key = v[RK_LUM_RESULT_KEY];
        r.white = v[RK_LUM_RESULT_WHITE];
        r.adapted = v[RK_LUM_RESULT_ADAPTED];
        r.ev100 = v[RK_LUM_RESULT_EV100];
        r.exposure = v[RK_LUM_RESULT_EXPOSURE];
        if (with_histogram) {
            r.histogram.resize(kBins);
            glGetNamedBufferSubData(histogram_, 0, static_cast<GLsizeiptr>(sizeof(std::uint32_t) * kBins), r.histogram.data());
        }
        return r;
    }

    /// RK_LUM_RESULT_COUNT floats (binding 3 in the reduction); the adaptation state lives here.
    GLuint result_buffer() const { return result_; }
    /// kBins uint counts of the last reduction with the histogram option.
    GLuint histogram_buffer() const { return histogram_; }

private:
    static std::string common_head()
    {
        return "#version 450 core\n#extension GL_GOOGLE_include_directive : require\n"
               "#include \"raykit/luminance_reduce.glsl\"\n";
    }
    static std::string image_main()
    {
        return common_head() +
               "layout(local_size_x = RK_LUMINANCE_REDUCE_GROUP, local_size_y = RK_LUMINANCE_REDUCE_GROUP) in;\n"
               "layout(location = 0) uniform ivec2 u_size;\n"
               "layout(location = 1) uniform int u_channels;\n"
               "layout(location = 2) uniform float u_delta;\n"
               "layout(location = 3) uniform int u_histogram;\n"
               "layout(location = 4) uniform vec2 u_hist_range;\n"
               "layout(location = 5) uniform uint u_out_offset;\n"
               "void main() {\n"
               "  rk_luminance_reduce_image(u_size, u_channels, u_delta, u_histogram != 0, u_hist_range.x, u_hist_range.y,\n"
               "                            u_out_offset);\n"
               "}\n";
    }
    static std::string partials_main()
    {
        return common_head() +
               "layout(local_size_x = RK_LUMINANCE_REDUCE_GROUP, local_size_y = RK_LUMINANCE_REDUCE_GROUP) in;\n"
               "layout(location = 0) uniform ivec2 u_in_size;\n"
               "layout(location = 1) uniform uint u_in_offset;\n"
               "layout(location = 2) uniform uint u_out_offset;\n"
               "void main() { rk_luminance_reduce_partials(u_in_size, u_in_offset, u_out_offset); }\n";
    }
    static std::string finish_main()
    {
        return common_head() +
               "layout(local_size_x = 1) in;\n"
               "layout(location = 0) uniform uint u_in_offset;\n"
               "layout(location = 1) uniform float u_count;\n"
               "layout(location = 2) uniform int u_histogram;\n"
               "layout(location = 3) uniform vec2 u_hist_range;\n"
               "layout(location = 4) uniform vec2 u_window;\n"
               "layout(location = 5) uniform vec2 u_robust;\n"
               "layout(location = 6) uniform int u_adapt_to_histogram;\n"
               "layout(location = 7) uniform float u_dt;\n"
               "layout(location = 8) uniform vec2 u_tau;\n"
               "layout(location = 9) uniform float u_ev_compensation;\n"
               "layout(location = 10) uniform int u_reset;\n"
               "void main() {\n"
               "  rk_luminance_reduce_finish(u_in_offset, u_count, u_histogram != 0, u_hist_range.x, u_hist_range.y,\n"
               "                             u_window, u_robust, u_adapt_to_histogram != 0, u_dt, u_tau.x, u_tau.y,\n"
               "                             u_ev_compensation, u_reset != 0);\n"
               "}\n";
    }
    static GLuint build(const std::string& shader_dir, const std::string& main_src, int source_kind, const std::string& name)
    {
        const std::string src =
            resolved_shader(main_src, name, shader_dir, {shader_dir},
                            {{"RK_LUMINANCE_REDUCE_SOURCE", std::to_string(source_kind)},
                             {"RK_LUMINANCE_REDUCE_GROUP", std::to_string(kGroup)},
                             {"RK_LUMINANCE_REDUCE_THREAD_TILE", std::to_string(kThreadTile)},
                             {"RK_LUMINANCE_HISTOGRAM_BINS", std::to_string(kBins)}});
        return build_program({{GL_COMPUTE_SHADER, src}});
    }
    void ensure_scratch(GLuint floats)
    {
        if (floats <= scratch_floats_) return;
        if (scratch_) glDeleteBuffers(1, &scratch_);
        scratch_ = make_buffer(sizeof(float) * floats, nullptr);
        scratch_floats_ = floats;
    }

    GLuint image_tex_ = 0, image_buf_ = 0, partials_ = 0, finish_ = 0, sampler_ = 0;
    GLuint scratch_ = 0, histogram_ = 0, result_ = 0;
    GLuint scratch_floats_ = 0;
};

}  // namespace rkgl
