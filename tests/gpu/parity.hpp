// raykit GPU parity harness: runs a shared function in an OpenGL 4.5 compute shader on a real
// driver (Mesa llvmpipe in CI, a GPU when present) over thousands of ordinary and adversarial
// inputs and compares every output with the C++ build of the very same .glsl text.
//
// Adding a case is one RK_PARITY entry: the body is written once and used twice — stringised
// into the compute shader and compiled as the C++ lambda — so the GPU and CPU run identical code:
//
//   RK_PARITY("rk_fresnel_schlick", "raykit/fresnel.glsl", (dom::cosine(), dom::unit()), 1,
//             o[0] = rk_fresnel_schlick(a[0], a[1]);)
//
// `a` holds the inputs (float[n_in]), `o` the outputs (float[n_out]); both languages index them
// the same way. Outputs are compared with |gpu - cpu| <= abs_tol + rel_tol * |cpu|, and every
// GPU output must be finite.
//
// GLSL lets a driver flush denormals to zero (GLSL 4.50 §4.7.1); NVIDIA's does, llvmpipe's does not.
// On a flushing driver (probed once, driver_flushes_denormals) a denormal input is seen as a signed
// zero by the shader, so the rows are given to both builds with their denormal inputs flushed:
// the comparison stays like with like, and the denormal classes are exercised where the driver keeps
// them (llvmpipe, CI). Cases whose inputs are bit patterns (floatBitsToUint) keep them as they are.
// Likewise a CPU output that is denormal is compared as the signed zero such a driver stores.
//
// A flushing driver also flushes *intermediate* results, which flushing the inputs does not model.
// RAYKIT_PARITY_EMULATE=ftz (x86-64 only; ctest gpu.parity_ftz) stands a CPU model of such a driver
// in for the GL one in run() and run_adversarial(): the "gpu" column is the C++ build run with the
// SSE control register's flush-to-zero and denormals-are-zero bits set, so every denormal operand
// and result of the case's arithmetic becomes a signed zero, as on NVIDIA's driver. The comparison,
// tolerances and tie rules are those of the real driver; divisions stay correctly rounded (a
// hardware driver's 2.5-ulp division and its reassociation are not modelled).
#pragma once

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "adversarial.hpp"
#include "rk_gl.hpp"
#include "test_util.hpp"

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#define RK_PARITY_CAN_EMULATE_FTZ 1
#else
#define RK_PARITY_CAN_EMULATE_FTZ 0
#endif

namespace parity {

/// An input's domain: a random range plus special values that are always included.
struct Domain {
    float lo = 0.0f, hi = 1.0f;
    bool log_scale = false;        // draw log-uniformly in [lo, hi] (lo > 0)
    std::vector<float> specials;   // domain-specific edge values (critical angles, ...)
};

/// Edge values every input also receives: zeros of both signs, denormals, the smallest normal,
/// 1 and its neighbours, huge values. "Any finite input" is the contract of every rk_ function.
inline const std::vector<float>& adversarial()
{
    static const std::vector<float> v = {0.0f, -0.0f, 1e-45f, -1e-45f, 1e-40f, -1e-40f, 1.17549435e-38f,
                                         -1.17549435e-38f, 1.0f, std::nextafter(1.0f, 0.0f), std::nextafter(1.0f, 2.0f),
                                         -1.0f, 0.5f, 2.0f, 1e-20f, -1e-20f, 1e20f, -1e20f, 1e30f, -1e30f,
                                         3.4028235e38f, -3.4028235e38f};
    return v;
}

namespace dom {
inline Domain cosine() { return {0.0f, 1.0f, false, {0.7597469f, 0.9682458f, 0.5547002f, 0.0871557f}}; }
inline Domain unit() { return {0.0f, 1.0f, false, {0.04f, 0.0425800f}}; }
inline Domain eta() { return {0.25f, 4.0f, true, {1.52f, 1.0f / 1.52f, 1.33f, 1.0f / 1.33f, 1.0000001f}}; }
inline Domain signed_unit() { return {-1.0f, 1.0f, false, {}}; }
inline Domain range(float lo, float hi) { return {lo, hi, false, {}}; }
}  // namespace dom

struct Case {
    std::string name;
    std::string include;                     // e.g. "raykit/fresnel.glsl"
    std::vector<Domain> inputs;
    int n_out;
    std::string glsl_body;
    std::function<void(const float*, float*)> cpu;
    double abs_tol = 2e-6, rel_tol = 2e-5;
    std::vector<raykit::ShaderDefine> defines;
    bool flush_denormal_inputs = true;  // false: the inputs are bit patterns, passed on unchanged
    /// Optional: whether a row whose outputs differ is an equivalent answer (in, gpu row, cpu row),
    /// e.g. two encodings of one direction on a seam; such rows count as ties, not mismatches.
    std::function<bool(const float*, const float*, const float*)> tie;
    /// On a hardware driver (hardware_allowances()), a mismatching finite row is accepted when every
    /// GPU output lies within what moving each input by up to this many ulps moves the C++ output
    /// (within_conditioning()); 0 turns that off. Bit-pattern cases never get it.
    int hw_ulps = 4;
};

#define RK_PARITY_LIST(...) __VA_ARGS__
#define RK_PARITY(NAME, INCLUDE, DOMAINS, NOUT, ...)                                                   \
    parity::Case { NAME, INCLUDE, std::vector<parity::Domain>{RK_PARITY_LIST DOMAINS}, NOUT, #__VA_ARGS__, \
                   [](const float* a, float* o) { (void)a; (void)o; __VA_ARGS__ }, 2e-6, 2e-5, {}, true, {} }

/// Builds the input table: `random_rows` rows drawn from the domains, then for every input and
/// every special (domain-specific and adversarial) a row with that input set and the others random.
inline std::vector<float> make_inputs(const Case& c, int random_rows, unsigned seed)
{
    std::mt19937 rng(seed);
    const size_t n_in = c.inputs.size();
    auto draw = [&](const Domain& d) {
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        if (d.log_scale) return d.lo * std::pow(d.hi / d.lo, u(rng));
        return d.lo + (d.hi - d.lo) * u(rng);
    };
    std::vector<float> rows;
    auto add_row = [&](size_t fixed, float value) {
        for (size_t k = 0; k < n_in; ++k) rows.push_back(k == fixed ? value : draw(c.inputs[k]));
    };
    for (int r = 0; r < random_rows; ++r) add_row(n_in, 0.0f);
    for (size_t k = 0; k < n_in; ++k) {
        std::vector<float> specials = c.inputs[k].specials;
        specials.insert(specials.end(), adversarial().begin(), adversarial().end());
        for (float s : specials) {
            for (int rep = 0; rep < 8; ++rep) add_row(k, s);
        }
    }
    // All inputs adversarial at once.
    for (int r = 0; r < 512; ++r) {
        for (size_t k = 0; k < n_in; ++k) rows.push_back(adversarial()[static_cast<size_t>(rng()) % adversarial().size()]);
    }
    return rows;
}

inline std::string compute_source(const Case& c)
{
    const size_t n_in = c.inputs.size();
    std::string s = "#version 450 core\n";
    s += "#extension GL_GOOGLE_include_directive : require\n";
    s += "layout(local_size_x = 64) in;\n";
    s += "layout(std430, binding = 0) readonly buffer Inputs { float rk_in[]; };\n";
    s += "layout(std430, binding = 1) writeonly buffer Outputs { float rk_out[]; };\n";
    s += "layout(location = 0) uniform uint rk_rows;\n";
    s += "#include \"" + c.include + "\"\n";
    s += "void main() {\n  uint i = gl_GlobalInvocationID.x;\n  if (i >= rk_rows) return;\n";
    s += "  float a[" + std::to_string(n_in) + "];\n";
    s += "  for (uint k = 0u; k < " + std::to_string(n_in) + "u; ++k) a[k] = rk_in[i * " + std::to_string(n_in) + "u + k];\n";
    s += "  float o[" + std::to_string(c.n_out) + "];\n";
    s += "  for (uint k = 0u; k < " + std::to_string(c.n_out) + "u; ++k) o[k] = 0.0;\n";
    s += "  { " + c.glsl_body + " }\n";
    s += "  for (uint k = 0u; k < " + std::to_string(c.n_out) + "u; ++k) rk_out[i * " + std::to_string(c.n_out) + "u + k] = o[k];\n";
    s += "}\n";
    return s;
}

struct Result {
    bool ok = true;
    long rows = 0, mismatches = 0, non_finite = 0, ties = 0, conditioned = 0;
    double max_abs = 0, max_ulp = 0;
    std::string worst;
};

/// The folder holding raykit/*.glsl (compile definition of the test target).
inline std::string shader_dir() { return RAYKIT_SHADER_DIR; }

/// RAYKIT_PARITY_REPLAY=DIR replays a hardware driver's answers on any machine: the rows found in
/// DIR (a RAYKIT_PARITY_DUMP of that driver, matched by case name and exact input bits) take the
/// dumped GPU outputs, every other row the current driver's; the run then behaves as on that
/// driver (denormals flushed, hardware allowances on). Rows of functions changed since the dump
/// replay the old answers.
inline const char* replay_dir()
{
    const char* d = std::getenv("RAYKIT_PARITY_REPLAY");
    return d && *d ? d : nullptr;
}

/// Whether RAYKIT_PARITY_EMULATE=ftz asks for the CPU model of a flushing driver (top of this file).
/// Asking for it where it cannot run (not x86-64) aborts the process instead of testing nothing.
inline bool emulate_ftz()
{
    static const bool on = [] {
        const char* v = std::getenv("RAYKIT_PARITY_EMULATE");
        const bool want = v != nullptr && std::string(v) == "ftz";
        if (want && !RK_PARITY_CAN_EMULATE_FTZ) {
            std::fprintf(stderr, "[parity] RAYKIT_PARITY_EMULATE=ftz needs x86-64 (the SSE FTZ/DAZ bits)\n");
            std::abort();
        }
        if (want) std::printf("[parity] emulating a flushing driver: the C++ build with FTZ and DAZ set\n");
        return want;
    }();
    return on;
}

/// x as a driver that flushes denormals holds it: a denormal becomes the zero of its sign.
inline float flushed(float x) { return std::fpclassify(x) == FP_SUBNORMAL ? std::copysign(0.0f, x) : x; }

/// The case's C++ build over `in` with flush-to-zero and denormals-are-zero set (the control
/// register is restored afterwards): the "gpu" column of RAYKIT_PARITY_EMULATE=ftz.
inline std::vector<float> run_cpu_ftz(const Case& c, const std::vector<float>& in)
{
    const size_t n_in = c.inputs.size(), n_out = static_cast<size_t>(c.n_out);
    const size_t rows = in.size() / n_in;
    std::vector<float> out(rows * n_out, 0.0f);
#if RK_PARITY_CAN_EMULATE_FTZ
    const unsigned int saved = _mm_getcsr();
    _mm_setcsr(saved | 0x8040u);  // FTZ (bit 15) | DAZ (bit 6)
    for (size_t i = 0; i < rows; ++i) c.cpu(&in[i * n_in], &out[i * n_out]);
    _mm_setcsr(saved);
    // GLM's min/max/clamp are compare-and-select, which passes a denormal operand through unchanged
    // (the compare sees it as zero), where a driver's min/max instruction flushes its result: the
    // model's outputs are flushed as such a driver stores them.
    for (float& v : out) v = flushed(v);
#else
    (void)c;
#endif
    return out;
}

/// Runs the case's body on the current GL context over `in` (rows of c.inputs.size() floats) and
/// returns the outputs (rows of c.n_out floats). Under RAYKIT_PARITY_EMULATE=ftz: run_cpu_ftz.
inline std::vector<float> run_gpu(const Case& c, const std::string& shader_dir, const std::vector<float>& in)
{
    if (emulate_ftz()) return run_cpu_ftz(c, in);
    const size_t rows = in.size() / c.inputs.size();
    const size_t n_out = static_cast<size_t>(c.n_out);
    const std::string src = rkgl::resolved_shader(compute_source(c), c.name + ".comp", shader_dir, {shader_dir}, c.defines);
    GLuint prog = rkgl::build_program({{GL_COMPUTE_SHADER, src}});
    GLuint bin = rkgl::make_buffer(in.size() * sizeof(float), in.data());
    GLuint bout = rkgl::make_buffer(rows * n_out * sizeof(float), nullptr);
    glUseProgram(prog);
    glUniform1ui(0, static_cast<GLuint>(rows));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bin);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bout);
    glDispatchCompute(static_cast<GLuint>((rows + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<float> gpu = rkgl::read_floats(bout, rows * n_out);
    glDeleteBuffers(1, &bin);
    glDeleteBuffers(1, &bout);
    glDeleteProgram(prog);
    return gpu;
}

/// Whether the current GL context is a software rasteriser (Mesa llvmpipe or softpipe, which CI
/// runs): there bounds measured on its exact IEEE arithmetic and filtering apply; a hardware
/// driver gets the allowances GL gives it.
inline bool software_renderer()
{
    const GLubyte* r = glGetString(GL_RENDERER);
    const std::string rend = r ? reinterpret_cast<const char*>(r) : "";
    return rend.find("llvmpipe") != std::string::npos || rend.find("softpipe") != std::string::npos;
}

/// Whether the current GL context's shaders flush denormal floats to zero (GLSL allows it): a
/// compute shader multiplies runtime values whose product, or whose factor, is denormal. Probed
/// once per process (the parity tests share one context).
inline bool driver_flushes_denormals()
{
    if (emulate_ftz() || replay_dir()) return true;
    static const int flushes = [] {
        const char* src = "#version 450 core\nlayout(local_size_x = 1) in;\n"
                          "layout(std430, binding = 0) readonly buffer I { float v[]; };\n"
                          "layout(std430, binding = 1) writeonly buffer O { float r[]; };\n"
                          "void main() { r[0] = v[0] * v[1]; r[1] = v[2] * v[3]; }\n";
        const float in[4] = {1e-40f, 1.0f, 1.17549435e-38f, 0.25f};
        GLuint prog = rkgl::build_program({{GL_COMPUTE_SHADER, src}});
        GLuint bin = rkgl::make_buffer(sizeof in, in);
        GLuint bout = rkgl::make_buffer(2 * sizeof(float), nullptr);
        glUseProgram(prog);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bin);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bout);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        const std::vector<float> r = rkgl::read_floats(bout, 2);
        glDeleteBuffers(1, &bin);
        glDeleteBuffers(1, &bout);
        glDeleteProgram(prog);
        const bool f = r[0] == 0.0f || r[1] == 0.0f;
        std::printf("[parity] the driver %s denormals (1e-40 * 1 = %g, FLT_MIN / 4 = %g)\n", f ? "flushes" : "keeps",
                    double(r[0]), double(r[1]));
        return f ? 1 : 0;
    }();
    return flushes != 0;
}

/// The rows as the shader sees them: denormal inputs flushed to signed zeros where the driver
/// flushes them (see the top of this file) and the case takes values, not bit patterns.
inline std::vector<float> as_driver_sees(const Case& c, std::vector<float> in)
{
    if (!c.flush_denormal_inputs || !driver_flushes_denormals()) return in;
    for (float& x : in) x = flushed(x);
    return in;
}

inline std::string dump_file_name(const std::string& name)
{
    std::string file = name;
    for (char& ch : file)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
    return file + ".tsv";
}

/// RAYKIT_PARITY_DUMP=DIR: every mismatching row of run() and every out-of-range row of
/// run_adversarial() is appended to DIR/<case>.tsv as hexadecimal floats (exact), one row per line:
/// "in<TAB>...<TAB>|<TAB>gpu ...<TAB>|<TAB>cpu ...". For studying a hardware driver's rows offline.
inline void dump_row(const std::string& name, const float* in, size_t n_in, const float* gpu, size_t n_out,
                     const float* cpu)
{
    const char* dir = std::getenv("RAYKIT_PARITY_DUMP");
    if (!dir || !*dir) return;
    FILE* f = std::fopen((std::string(dir) + "/" + dump_file_name(name)).c_str(), "a");
    if (!f) return;
    auto put = [f](const float* v, size_t n) {
        for (size_t j = 0; j < n; ++j) std::fprintf(f, "%a\t", static_cast<double>(v[j]));
    };
    put(in, n_in);
    std::fprintf(f, "|\t");
    put(gpu, n_out);
    if (cpu) {
        std::fprintf(f, "|\t");
        put(cpu, n_out);
    }
    std::fprintf(f, "\n");
    std::fclose(f);
}


/// Overlays the dumped GPU rows of case `name` (see replay_dir) on `gpu`; returns how many matched.
inline long replay_overlay(const std::string& name, const std::vector<float>& in, size_t n_in, std::vector<float>& gpu,
                           size_t n_out)
{
    const char* dir = replay_dir();
    if (!dir) return 0;
    FILE* f = std::fopen((std::string(dir) + "/" + dump_file_name(name)).c_str(), "r");
    if (!f) return 0;
    long matched = 0;
    char line[1 << 14];
    while (std::fgets(line, sizeof line, f)) {
        std::vector<float> row_in, row_gpu;
        int part = 0;
        for (char* tok = std::strtok(line, "\t\n"); tok; tok = std::strtok(nullptr, "\t\n")) {
            if (tok[0] == '|') { ++part; continue; }
            const float v = static_cast<float>(std::strtod(tok, nullptr));
            if (part == 0) row_in.push_back(v);
            else if (part == 1) row_gpu.push_back(v);
        }
        if (row_in.size() != n_in || row_gpu.size() != n_out) continue;
        for (size_t i = 0; i * n_in < in.size(); ++i) {
            if (std::memcmp(&in[i * n_in], row_in.data(), n_in * sizeof(float)) != 0) continue;
            std::copy(row_gpu.begin(), row_gpu.end(), gpu.begin() + long(i * n_out));
            ++matched;
        }
    }
    std::fclose(f);
    std::printf("[parity] replaying %ld dumped rows of %s\n", matched, name.c_str());
    return matched;
}

/// Whether the comparison grants a hardware driver what GLSL allows it (GLSL 4.50 §4.7.1: 2.5-ulp
/// division and nothing for divisors beyond 2^±126, fused multiply-adds, transcendentals of
/// driver-defined accuracy): on a hardware driver and in a replay of one, not on llvmpipe (exact
/// IEEE arithmetic, CI) nor in the flushing-driver model, where the strict comparison stays.
inline bool hardware_allowances()
{
    if (replay_dir()) return true;
    return !emulate_ftz() && !software_renderer();
}

/// x moved by `steps` ulps (negative: downwards), staying finite; on a flushing driver the
/// neighbours of zero are ±FLT_MIN, as the driver sees no denormals.
inline float ulp_step(float x, int steps, bool flush)
{
    const float dir = steps < 0 ? -std::numeric_limits<float>::infinity() : std::numeric_limits<float>::infinity();
    for (int s = 0; s < std::abs(steps); ++s) {
        float y = std::nextafter(x, dir);
        if (flush && std::fpclassify(y) == FP_SUBNORMAL)  // ±FLT_MIN steps to zero, zero to ±FLT_MIN
            y = std::abs(x) >= std::numeric_limits<float>::min() ? std::copysign(0.0f, x)
                                                                  : std::copysign(std::numeric_limits<float>::min(), dir);
        if (!std::isfinite(y)) break;
        x = y;
    }
    return x;
}

/// A tie rule for hardware drivers only (hardware_allowances(); llvmpipe keeps the strict check):
/// every GPU output within rel times the row's largest |C++ output|. For functions that cancel terms
/// of the scale of their largest output (a coordinate 1e20 away): a driver's contraction or
/// reciprocal division rounds those terms differently, which no input move of a few ulps
/// reproduces (each input alone may not even reach the cancelling terms).
/// Outputs listed in `exact` (indices, flags) must still be equal.
inline std::function<bool(const float*, const float*, const float*)> hw_row_scale_tie(int n_out, double rel,
                                                                                      std::vector<int> exact = {})
{
    return [n_out, rel, exact](const float*, const float* g, const float* h) {
        if (!hardware_allowances()) return false;
        double scale = 0.0;
        for (int k = 0; k < n_out; ++k) scale = std::max(scale, std::abs(static_cast<double>(h[k])));
        for (int k = 0; k < n_out; ++k) {
            const bool ex = std::find(exact.begin(), exact.end(), k) != exact.end();
            if (ex ? g[k] != h[k] : !(std::abs(static_cast<double>(g[k]) - h[k]) <= rel * scale)) return false;
        }
        return true;
    };
}

/// The conditioning allowance of a hardware driver: whether every output of `gpu` lies within the
/// range the C++ build's output takes when each input moves by up to c.hw_ulps ulps (each input
/// alone to both ends, then 64 random joint moves; the range widened by the case's tolerance).
/// An answer that close inputs give is the driver's rounding (reciprocal division, contraction,
/// approximate built-ins) meeting the function's own conditioning: a jump at a decision boundary,
/// cancellation of large terms. Outputs that no nearby input gives (a flipped result, a value off
/// the documented range, anything non-finite) still fail.
inline bool within_conditioning(const Case& c, const float* in, const float* gpu, bool flush)
{
    if (c.hw_ulps <= 0 || !c.flush_denormal_inputs) return false;
    const size_t n_in = c.inputs.size(), n_out = static_cast<size_t>(c.n_out);
    std::vector<double> lo(n_out, std::numeric_limits<double>::infinity()), hi(n_out, -std::numeric_limits<double>::infinity());
    std::vector<float> x(in, in + n_in), out(n_out);
    auto eval = [&] {
        std::fill(out.begin(), out.end(), 0.0f);
        c.cpu(x.data(), out.data());
        for (size_t k = 0; k < n_out; ++k) {
            const float v = flush ? flushed(out[k]) : out[k];
            if (!std::isfinite(v)) continue;
            lo[k] = std::min(lo[k], static_cast<double>(v));
            hi[k] = std::max(hi[k], static_cast<double>(v));
        }
    };
    eval();
    for (size_t j = 0; j < n_in; ++j) {
        for (int sgn : {-1, 1}) {
            x.assign(in, in + n_in);
            x[j] = ulp_step(in[j], sgn * c.hw_ulps, flush);
            eval();
        }
    }
    uint32_t seed = 2166136261u;
    for (size_t j = 0; j < n_in; ++j) {
        uint32_t b;
        std::memcpy(&b, &in[j], 4);
        seed = (seed ^ b) * 16777619u;
    }
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> step(-c.hw_ulps, c.hw_ulps);
    for (int t = 0; t < 64; ++t) {
        for (size_t j = 0; j < n_in; ++j) x[j] = ulp_step(in[j], step(rng), flush);
        eval();
    }
    // RAYKIT_PARITY_DEBUG_COND=1 prints each judged row's GPU output and the range reached.
    if (std::getenv("RAYKIT_PARITY_DEBUG_COND"))
        for (size_t k = 0; k < n_out; ++k) std::printf("  cond %s out %zu: gpu %.9g range [%.9g, %.9g]\n", c.name.c_str(), k, gpu[k], lo[k], hi[k]);
    for (size_t k = 0; k < n_out; ++k) {
        const double g = gpu[k];
        if (!std::isfinite(g) || !(lo[k] <= hi[k])) return false;
        const double slack_lo = c.abs_tol + c.rel_tol * std::abs(lo[k]), slack_hi = c.abs_tol + c.rel_tol * std::abs(hi[k]);
        if (g < lo[k] - slack_lo || g > hi[k] + slack_hi) return false;
    }
    return true;
}

/// Runs one case on the current GL context and on the CPU; prints a one-line report.
/// `exact_outputs` (optional) lists output indices compared bit-exactly instead of with the
/// case's tolerance (integer results such as indices and hash halves).
inline Result run(const Case& c, const std::string& shader_dir, int random_rows = 4096,
                  const std::vector<int>& exact_outputs = {})
{
    const size_t n_in = c.inputs.size();
    const size_t n_out = static_cast<size_t>(c.n_out);
    const std::vector<float> in = as_driver_sees(c, make_inputs(c, random_rows, 20261122u));
    const size_t rows = in.size() / n_in;
    std::vector<float> gpu = run_gpu(c, shader_dir, in);
    replay_overlay(c.name, in, n_in, gpu, n_out);
    const bool hw = hardware_allowances();

    Result r;
    r.rows = static_cast<long>(rows);
    std::vector<float> cpu(n_out);
    int shown = 0;
    std::string mismatch_rows;  // the first three mismatching rows, whole
    // A flushing driver also stores a denormal result as a signed zero: so is the CPU's (value cases).
    const bool flush_outputs = c.flush_denormal_inputs && driver_flushes_denormals();
    for (size_t i = 0; i < rows; ++i) {
        std::fill(cpu.begin(), cpu.end(), 0.0f);
        c.cpu(&in[i * n_in], cpu.data());
        if (flush_outputs)
            for (float& h : cpu) h = flushed(h);
        const long mismatches_before = r.mismatches;
        for (size_t k = 0; k < n_out; ++k) {
            const float g = gpu[i * n_out + k], h = cpu[k];
            const double err = std::abs(static_cast<double>(g) - h);
            const bool finite = std::isfinite(g);
            const bool exact = std::find(exact_outputs.begin(), exact_outputs.end(), static_cast<int>(k)) != exact_outputs.end();
            const bool bad = !finite || !std::isfinite(h) || (exact ? g != h : err > c.abs_tol + c.rel_tol * std::abs(h));
            r.non_finite += finite ? 0 : 1;
            r.mismatches += bad ? 1 : 0;
            const double ulp = rktest::ulp_distance(g, h);
            if (err > r.max_abs || (!finite && r.max_abs != std::numeric_limits<double>::infinity())) {
                r.max_abs = finite ? err : std::numeric_limits<double>::infinity();
                std::string w = "in (";
                for (size_t j = 0; j < n_in; ++j) w += rktest::fmt(in[i * n_in + j]);
                w += ") out[" + std::to_string(k) + "] gpu " + rktest::fmt(g) + "cpu " + rktest::fmt(h);
                r.worst = w;
            }
            r.max_ulp = std::max(r.max_ulp, ulp);
        }
        const bool row_finite = std::all_of(gpu.begin() + long(i * n_out), gpu.begin() + long((i + 1) * n_out),
                                            [](float g) { return std::isfinite(g); });
        if (r.mismatches > mismatches_before && row_finite && c.tie && c.tie(&in[i * n_in], &gpu[i * n_out], cpu.data())) {
            r.mismatches = mismatches_before;
            ++r.ties;
        } else if (r.mismatches > mismatches_before && row_finite && hw &&
                   within_conditioning(c, &in[i * n_in], &gpu[i * n_out], flush_outputs)) {
            r.mismatches = mismatches_before;
            ++r.conditioned;
        } else if (r.mismatches > mismatches_before && (dump_row(c.name, &in[i * n_in], n_in, &gpu[i * n_out], n_out, cpu.data()),
                                                        ++shown <= 3)) {
            std::string m = "in (";
            for (size_t j = 0; j < n_in; ++j) m += rktest::fmt(in[i * n_in + j]);
            m += ") gpu (";
            for (size_t k = 0; k < n_out; ++k) m += rktest::fmt(gpu[i * n_out + k]);
            m += ") cpu (";
            for (size_t k = 0; k < n_out; ++k) m += rktest::fmt(cpu[k]);
            mismatch_rows += "\n         mismatch: " + m + ")";
        }
    }
    r.ok = r.mismatches == 0;
    std::printf("[parity] %-44s rows %6ld  max abs %.3g  max ulp %.3g  mismatches %ld  non-finite %ld%s%s%s%s%s\n",
                c.name.c_str(), r.rows, r.max_abs, r.max_ulp, r.mismatches, r.non_finite,
                c.tie ? ("  equivalent (ties) " + std::to_string(r.ties)).c_str() : "",
                hw ? ("  within conditioning " + std::to_string(r.conditioned)).c_str() : "",
                r.worst.empty() ? "" : "\n         worst: ", r.worst.c_str(), mismatch_rows.c_str());
    return r;
}

/// An adversarial sample on the driver: `rows` rows drawn by `draw` from tests/adversarial.hpp's
/// stream (seeded by the case's name) through the case's body on the GPU; every output must be
/// finite and pass `ok(output index, value)` (the documented range). The CPU sweeps with the same
/// generator are tests/test_adversarial.cpp. Returns the failing outputs; prints a report.
inline long run_adversarial(const Case& c, const std::string& shader_dir, long rows,
                            const std::function<void(rktest::adv::Gen&, float*)>& draw,
                            const std::function<bool(int, float)>& ok)
{
    const size_t n_in = c.inputs.size(), n_out = static_cast<size_t>(c.n_out);
    rktest::adv::Gen g(rktest::adv::seed_for(c.name));
    std::vector<float> in(static_cast<size_t>(rows) * n_in);
    for (long r = 0; r < rows; ++r) draw(g, &in[static_cast<size_t>(r) * n_in]);
    std::vector<float> gpu = run_gpu(c, shader_dir, in);
    replay_overlay(c.name + " adversarial", in, n_in, gpu, n_out);
    long bad = 0;
    std::string first;
    for (size_t r = 0; r < static_cast<size_t>(rows); ++r) {
        bool row_bad = false;
        for (size_t k = 0; k < n_out; ++k) {
            const float v = gpu[r * n_out + k];
            if (std::isfinite(v) && ok(static_cast<int>(k), v)) continue;
            row_bad = true;
            if (bad++ == 0) {
                first = "in (";
                for (size_t j = 0; j < n_in; ++j) first += rktest::fmt(in[r * n_in + j]);
                first += ") out[" + std::to_string(k) + "] " + rktest::fmt(v);
            }
        }
        if (row_bad) dump_row(c.name + " adversarial", &in[r * n_in], n_in, &gpu[r * n_out], n_out, nullptr);
    }
    std::printf("[parity] %-44s adversarial rows %6ld  out of range %ld%s%s\n", c.name.c_str(), rows, bad,
                first.empty() ? "" : "\n         first: ", first.c_str());
    return bad;
}

}  // namespace parity
