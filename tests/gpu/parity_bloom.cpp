// GPU parity cases for shaders/raykit/bloom.glsl (see parity.hpp), plus the whole GPU bloom chain of
// samples/common/rk_bloom_gl.hpp (the passes of shaders/raykit/bloom_passes.glsl: bright pass,
// downsamples, merged-tap Gaussian, upsample) against raykit::bloom_reference, and the skip.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/bloom.hpp"
#include "rk_bloom_gl.hpp"

using namespace raykit;
using parity::Domain;
namespace dom = parity::dom;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

/// A colour channel: HDR range plus the non-finite values the functions must sanitise.
Domain hdr() { return {0.0f, 8.0f, false, {kNaN, kInf, -kInf, -1.0f, 1.5f, 1e18f, 2e18f}}; }
/// A threshold / knee / strength.
Domain param(float hi) { return {0.0f, hi, false, {kNaN, kInf, -kInf, -0.5f, 1.5f, 0.5f}}; }
/// Filter weights.
Domain weight() { return {0.0f, 1.0f, false, {kNaN, kInf, -kInf, -0.25f, 0.0f, 1.0f}}; }

std::vector<parity::Case> bloom_cases()
{
    const char* B = "raykit/bloom.glsl";
    // Outputs of the RGB functions go to o[0..2]; mode loops write 3 (or 1) outputs per mode.
    std::vector<parity::Case> cases = {
        RK_PARITY("rk_bloom_sanitize(float)", B, (hdr()), 1, o[0] = rk_bloom_sanitize(a[0]);),
        RK_PARITY("rk_bloom_sanitize(vec3)", B, (hdr(), hdr(), hdr()), 3,
                  vec3 r = rk_bloom_sanitize(vec3(a[0], a[1], a[2])); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_luminance", B, (hdr(), hdr(), hdr()), 1, o[0] = rk_bloom_luminance(vec3(a[0], a[1], a[2]));),
        RK_PARITY("rk_bloom_knee", B, (param(3.0f), param(1.0f)), 1, o[0] = rk_bloom_knee(a[0], a[1]);),
        RK_PARITY("rk_bloom_cutoff", B, (param(3.0f), param(1.0f)), 3,
                  for (int m = 0; m < 3; ++m) { o[m] = rk_bloom_cutoff(a[0], a[1], m); }),
        RK_PARITY("rk_bloom_weight_hard", B, (hdr(), param(3.0f)), 1, o[0] = rk_bloom_weight_hard(a[0], a[1]);),
        RK_PARITY("rk_bloom_weight_soft_knee", B, (hdr(), param(3.0f), param(1.0f)), 1,
                  o[0] = rk_bloom_weight_soft_knee(a[0], a[1], a[2]);),
        RK_PARITY("rk_bloom_weight_subtract", B, (hdr(), param(3.0f), param(1.0f)), 1,
                  o[0] = rk_bloom_weight_subtract(a[0], a[1], a[2]);),
        RK_PARITY("rk_bloom_weight", B, (hdr(), param(3.0f), param(1.0f)), 4,
                  for (int m = 0; m < 4; ++m) { o[m] = rk_bloom_weight(a[0], a[1], a[2], m); }),
        RK_PARITY("rk_bloom_bright_pass_hard", B, (hdr(), hdr(), hdr(), param(3.0f)), 3,
                  vec3 r = rk_bloom_bright_pass_hard(vec3(a[0], a[1], a[2]), a[3]); o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_bright_pass_soft_knee", B, (hdr(), hdr(), hdr(), param(3.0f), param(1.0f)), 3,
                  vec3 r = rk_bloom_bright_pass_soft_knee(vec3(a[0], a[1], a[2]), a[3], a[4]);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_bright_pass_subtract", B, (hdr(), hdr(), hdr(), param(3.0f), param(1.0f)), 3,
                  vec3 r = rk_bloom_bright_pass_subtract(vec3(a[0], a[1], a[2]), a[3], a[4]);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_bright_pass", B, (hdr(), hdr(), hdr(), param(3.0f), param(1.0f)), 9,
                  for (int m = 0; m < 3; ++m) {
                      vec3 r = rk_bloom_bright_pass(vec3(a[0], a[1], a[2]), a[3], a[4], m);
                      o[3 * m] = r.x; o[3 * m + 1] = r.y; o[3 * m + 2] = r.z;
                  }),
        RK_PARITY("rk_bloom_karis_weight", B, (hdr(), hdr(), hdr()), 1, o[0] = rk_bloom_karis_weight(vec3(a[0], a[1], a[2]));),
        RK_PARITY("rk_bloom_weighted_average", B, (hdr(), hdr(), hdr(), hdr(), weight(), weight(), weight(), weight()), 3,
                  vec3 r = rk_bloom_weighted_average(vec3(a[0], a[1], a[2]), vec3(a[3], a[0], 1.0f), vec3(a[1], a[3], a[2]),
                                                     vec3(0.0f), vec4(a[4], a[5], a[6], a[7]));
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_karis_average", B, (hdr(), hdr(), hdr(), hdr(), weight(), weight(), weight(), weight()), 3,
                  vec3 r = rk_bloom_karis_average(vec3(a[0], a[1], a[2]), vec3(a[3], a[0], 1.0f), vec3(a[1], a[3], a[2]),
                                                  vec3(0.0f), vec4(a[4], a[5], a[6], a[7]));
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_source_texel", B, (dom::range(0.0f, 512.0f), dom::range(1.0f, 512.0f), dom::range(1.0f, 1024.0f)), 1,
                  o[0] = rk_bloom_source_texel(a[0], a[1], a[2]);),
        RK_PARITY("rk_bloom_bilinear_weights", B, (dom::range(-2.0f, 600.0f), dom::range(-2.0f, 600.0f)), 4,
                  vec4 r = rk_bloom_bilinear_weights(vec2(a[0], a[1])); o[0] = r.x; o[1] = r.y; o[2] = r.z; o[3] = r.w;),
        RK_PARITY("rk_bloom_sum_levels", B, (hdr(), hdr(), hdr(), hdr(), param(2.0f), param(2.0f), param(2.0f), param(2.0f)), 3,
                  vec3 r = rk_bloom_sum_levels(vec3(a[0], a[1], a[2]), vec3(a[3], a[0], 1.0f), vec3(a[1], a[3], a[2]),
                                               vec3(a[2]), vec4(a[4], a[5], a[6], a[7]));
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_composite_add", B, (hdr(), hdr(), hdr(), hdr(), param(2.0f)), 3,
                  vec3 r = rk_bloom_composite_add(vec3(a[0], a[1], a[2]), vec3(a[3], a[2], a[0]), a[4]);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_composite_mix", B, (hdr(), hdr(), hdr(), hdr(), param(1.0f)), 3,
                  vec3 r = rk_bloom_composite_mix(vec3(a[0], a[1], a[2]), vec3(a[3], a[2], a[0]), a[4]);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_composite_conserve", B, (hdr(), hdr(), hdr(), hdr(), param(1.0f)), 3,
                  vec3 h = vec3(a[0], a[1], a[2]);
                  vec3 r = rk_bloom_composite_conserve(h, rk_bloom_bright_pass_hard(h, 1.0f), vec3(a[3], a[2], a[0]), a[4]);
                  o[0] = r.x; o[1] = r.y; o[2] = r.z;),
        RK_PARITY("rk_bloom_composite", B, (hdr(), hdr(), hdr(), hdr(), param(1.0f)), 9,
                  for (int m = 0; m < 3; ++m) {
                      vec3 h = vec3(a[0], a[1], a[2]);
                      vec3 r = rk_bloom_composite(h, vec3(a[3]), vec3(a[3], a[2], a[0]), a[4], m);
                      o[3 * m] = r.x; o[3 * m + 1] = r.y; o[3 * m + 2] = r.z;
                  }),
    };
    return cases;
}

// ---- helpers for the chain tests ----------------------------------------------------------------

GLuint upload(const BloomImage& img)
{
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA32F, img.width, img.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureSubImage2D(tex, 0, 0, 0, img.width, img.height, GL_RGB, GL_FLOAT, img.pixels.data());
    return tex;
}

BloomImage download(GLuint tex, int w, int h)
{
    BloomImage img(w, h);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(tex, 0, GL_RGB, GL_FLOAT, static_cast<GLsizei>(img.pixels.size() * sizeof(vec3)), img.pixels.data());
    return img;
}

/// A small HDR frame: a dim random background (luminance < 1.2), a few bright blobs up to
/// luminance ~60 (one touching the border), and one NaN, one -Inf and one negative pixel.
BloomImage hdr_test_image(int w, int h)
{
    BloomImage img(w, h);
    std::mt19937 rng(2024);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (vec3& c : img.pixels) c = vec3(1.2f * u(rng), 1.2f * u(rng), 1.2f * u(rng));
    struct Blob {
        float x, y, r;
        vec3 c;
    };
    const Blob blobs[] = {{40.0f, 30.0f, 3.0f, vec3(60.0f, 40.0f, 20.0f)}, {100.0f, 70.0f, 6.0f, vec3(3.0f, 2.5f, 4.0f)},
                          {2.0f, 90.0f, 4.0f, vec3(10.0f, 10.0f, 30.0f)}, {130.0f, 20.0f, 1.0f, vec3(25.0f)}};
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            for (const Blob& b : blobs) {
                const float d = std::hypot(static_cast<float>(x) - b.x, static_cast<float>(y) - b.y);
                if (d < b.r) img.at(x, y) += b.c * (1.0f - 0.5f * d / b.r);
            }
        }
    }
    img.at(10, 10) = vec3(kNaN, 1.0f, 1.0f);
    img.at(11, 10) = vec3(-kInf);
    img.at(12, 10) = vec3(-3.0f, 2.0f, -1.0f);
    return img;
}

struct Compare {
    double max_rel = 0;  // max |gpu - cpu| / max(1, |cpu|)
    double max_abs = 0;
    long non_finite = 0;
    std::string worst;
};

Compare compare(const BloomImage& gpu, const BloomImage& cpu)
{
    Compare c;
    for (int y = 0; y < cpu.height; ++y) {
        for (int x = 0; x < cpu.width; ++x) {
            for (int ch = 0; ch < 3; ++ch) {
                const double g = gpu.at(x, y)[ch], h = cpu.at(x, y)[ch];
                if (!std::isfinite(g)) ++c.non_finite;
                const double e = std::abs(g - h);
                c.max_abs = std::max(c.max_abs, e);
                const double rel = e / std::max(1.0, std::abs(h));
                if (rel > c.max_rel || !std::isfinite(g)) {
                    c.max_rel = std::isfinite(g) ? rel : std::numeric_limits<double>::infinity();
                    c.worst = rktest::fmt("pixel", x, y, "ch", ch, "gpu", g, "cpu", h);
                }
            }
        }
    }
    return c;
}

}  // namespace

TEST(GpuParity, Bloom)
{
    long rows = 0;
    for (const parity::Case& c : bloom_cases()) {
        const parity::Result r = parity::run(c, parity::shader_dir(), 2048);
        rows += r.rows;
        EXPECT_TRUE(r.ok) << c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << c.name;
    }
    std::printf("[parity] bloom: %ld input rows in total\n", rows);
}

// The whole GPU chain (reduction, prefilter, 5 downsamples, 8 merged-tap blurs, composite) against
// the CPU reference, which blurs with the full 19-tap discrete kernel in float64: this also checks
// the linear-sampling merge on real texture hardware. Tolerance: |gpu - cpu| <= tol * max(1, |cpu|):
// on llvmpipe (float filter weights) tol 2e-6 for RGBA32F intermediates (measured 3.0e-7 output,
// 1.2e-6 levels) and 3e-3 for RGBA16F (fp16 rounding, 4.9e-4 relative per pass over ~8 passes;
// measured 1.5e-3). Hardware samplers quantise the bilinear fraction (typically to 1/256), which
// moves every merged tap by up to 1/512 texel: there the RGBA32F tolerance is 1e-2 (not measured
// here: no hardware GPU in this test's CI).
TEST(GpuBloom, ChainMatchesCpuReference)
{
    const bool software = parity::software_renderer();
    const double tol32 = software ? 2e-6 : 1e-2;
    const double tol16 = software ? 3e-3 : 1.5e-2;
    const int w = 160, h = 120;
    const BloomImage img = hdr_test_image(w, h);
    const GLuint tex = upload(img);
    struct Setting {
        const char* name;
        BloomParams p;
        GLenum format;
        double tol;
    };
    std::vector<Setting> settings;
    settings.push_back({"thesis (hard 1.5, add), RGBA32F", BloomParams::thesis(), GL_RGBA32F, tol32});
    settings.push_back({"recommended (soft knee, Karis), RGBA32F", BloomParams::recommended(), GL_RGBA32F, tol32});
    BloomParams cons = BloomParams::recommended();
    cons.mode = RK_BLOOM_MODE_SUBTRACT;
    cons.composite = RK_BLOOM_COMPOSITE_CONSERVE;
    cons.strength = 0.6f;
    cons.level_weights = vec4(4.0f, 3.0f, 2.0f, 1.0f);
    settings.push_back({"subtract knee, conserve, RGBA32F", cons, GL_RGBA32F, tol32});
    BloomParams mix = BloomParams::thesis();
    mix.composite = RK_BLOOM_COMPOSITE_MIX;
    mix.strength = 0.3f;
    mix.first_div = 4;
    mix.levels = 3;
    mix.sigma = 2.0f;
    mix.radius = 6;
    settings.push_back({"mix, 1/4, 3 levels, sigma 2, RGBA32F", mix, GL_RGBA32F, tol32});
    settings.push_back({"thesis, RGBA16F", BloomParams::thesis(), GL_RGBA16F, tol16});

    rkgl::BloomGl bloom(parity::shader_dir());  // one set of programs for every setting
    for (const Setting& s : settings) {
        bloom.set_format(s.format);
        bloom.set_params(s.p);
        bloom.apply(tex, w, h);  // first frame: the driver compiles its shader variants
        glFinish();
        bloom.reset_stats();
        const auto t0 = std::chrono::steady_clock::now();
        const rkgl::BloomGlFrame frame = bloom.apply(tex, w, h);
        glFinish();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        const BloomResult ref = bloom_reference(img, s.p);
        ASSERT_TRUE(frame.chain_run && ref.chain_run) << s.name;
        EXPECT_EQ(frame.reduction.count_above, ref.reduction.count_above) << s.name;
        // The GPU's dot may fuse multiply-adds: luminance within 2 ulp.
        EXPECT_NEAR(frame.reduction.max_luminance, ref.reduction.max_luminance, 2.5e-7 * ref.reduction.max_luminance) << s.name;
        const Compare out = compare(download(frame.texture, w, h), ref.output);
        Compare lv;
        for (int l = 0; l < s.p.levels; ++l) {
            const BloomImage& r = ref.levels[static_cast<size_t>(l)];
            const Compare c = compare(download(bloom.level_texture(l), r.width, r.height), r);
            if (c.max_rel > lv.max_rel) lv = c;
        }
        std::printf("[bloom] %-42s %ld draws, %.1f ms | output max rel err %.3g (max abs %.3g) | levels %.3g\n"
                    "        worst: %s\n",
                    s.name, bloom.stats().draws, ms, out.max_rel, out.max_abs, lv.max_rel, out.worst.c_str());
        EXPECT_EQ(out.non_finite, 0) << s.name;
        EXPECT_LE(out.max_rel, s.tol) << s.name << ": " << out.worst;
        EXPECT_LE(lv.max_rel, s.tol) << s.name << ": " << lv.worst;
        EXPECT_EQ(bloom.stats().dispatches, 1);
        EXPECT_EQ(bloom.stats().draws, static_cast<long>(bloom.chain().downsamples.size() + 2 * bloom.chain().levels.size() + 1));
    }
    glDeleteTextures(1, &tex);
}

// "Bloom is skipped entirely when the reduction shows no pixel above threshold": count the draws
// (BloomGl's counter and, independently, a GL_PRIMITIVES_GENERATED query) for a frame with nothing
// above the threshold and one with a single bright pixel.
TEST(GpuBloom, SkippedWhenNothingExceedsTheThreshold)
{
    const int w = 96, h = 64;
    BloomImage dark(w, h);
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(0.0f, 1.4f);
    for (vec3& c : dark.pixels) c = vec3(u(rng));  // luminance < 1.5 everywhere
    dark.at(5, 5) = vec3(kNaN);                     // NaN and +-Inf never count as bright ...
    dark.at(6, 5) = vec3(-kInf);
    BloomImage bright = dark;
    bright.at(50, 30) = vec3(1.6f);                 // ... one pixel just above does

    rkgl::BloomGl bloom(parity::shader_dir(), GL_RGBA16F);
    GLuint query = 0;
    glCreateQueries(GL_PRIMITIVES_GENERATED, 1, &query);
    auto run = [&](const BloomImage& img, rkgl::BloomGlFrame& frame) {
        const GLuint tex = upload(img);
        bloom.reset_stats();
        glBeginQuery(GL_PRIMITIVES_GENERATED, query);
        frame = bloom.apply(tex, w, h);
        glEndQuery(GL_PRIMITIVES_GENERATED);
        GLuint prims = 0;
        glGetQueryObjectuiv(query, GL_QUERY_RESULT, &prims);
        const bool returned_input = frame.texture == tex;
        glDeleteTextures(1, &tex);
        return std::make_pair(prims, returned_input);
    };
    rkgl::BloomGlFrame f;
    const auto skipped = run(dark, f);
    std::printf("[bloom] dark frame: max luminance %.4f, %u above 1.5 -> %ld draws, %ld dispatches, %u primitives\n",
                static_cast<double>(f.reduction.max_luminance), f.reduction.count_above, bloom.stats().draws,
                bloom.stats().dispatches, skipped.first);
    EXPECT_FALSE(f.chain_run);
    EXPECT_FALSE(f.composited);
    EXPECT_TRUE(skipped.second);  // the input texture is handed back untouched
    EXPECT_EQ(f.reduction.count_above, 0u);
    EXPECT_NEAR(f.reduction.max_luminance, bloom_reduce(dark, 1.5f).max_luminance, 2e-7);
    EXPECT_EQ(bloom.stats().draws, 0);
    EXPECT_EQ(bloom.stats().dispatches, 1);  // the reduction only
    EXPECT_EQ(bloom.stats().skipped, 1);
    EXPECT_EQ(skipped.first, 0u);

    const auto ran = run(bright, f);
    std::printf("[bloom] one pixel at 1.6: %u above -> %ld draws, %u primitives\n", f.reduction.count_above,
                bloom.stats().draws, ran.first);
    EXPECT_TRUE(f.chain_run);
    EXPECT_EQ(f.reduction.count_above, 1u);
    EXPECT_EQ(bloom.stats().draws, 15);  // 1 prefilter + 5 downsamples + 8 blurs + 1 composite
    EXPECT_EQ(ran.first, 15u);

    // The soft knee lowers the cutoff to T - K: the dark frame now blooms.
    bloom.set_params(BloomParams::recommended());
    run(dark, f);
    EXPECT_TRUE(f.chain_run);
    EXPECT_GT(f.reduction.count_above, 0u);
    glDeleteQueries(1, &query);
}
