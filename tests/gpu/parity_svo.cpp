// GPU parity for shaders/raykit/svo_format.glsl (see parity.hpp): the codecs and brick helpers on
// thousands of ordinary and adversarial inputs (integer results bit-exact), and rk_svo_lookup over
// real packed octrees on the driver, from an SSBO and from the 2D-texture layout, against the C++
// build and against the builder's own voxel list.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/svo_build.hpp"
#include "reference/svo_meshes.hpp"
#include "rk_svo_gl.hpp"

using namespace raykit;
using parity::Domain;
namespace dom = parity::dom;

// A 32-bit word from two inputs in [0, 1] (16 bits each), exact in both languages.
#define RK_WORD(i, j) (uint(clamp(a[i], 0.0f, 1.0f) * 65535.0f) | (uint(clamp(a[j], 0.0f, 1.0f) * 65535.0f) << 16u))
// A uint output as two exactly representable floats.
#define RK_EMIT_U(k, v) o[k] = float((v) & 65535u); o[k + 1] = float((v) >> 16u);
#define RK_PARITY_X(...) RK_PARITY(__VA_ARGS__)

namespace {

parity::Case svo_case(parity::Case c)
{
    // Keep svo_format.glsl's own word buffer off the harness's bindings 0 and 1.
    c.defines.push_back({"RK_SVO_WORDS_BINDING", "5"});
    return c;
}

}  // namespace

TEST(GpuParity, SvoCodecs)
{
    const Domain any = dom::range(-2.0f, 2.0f);
    const Domain u = dom::unit();
    std::vector<parity::Case> cases;
    std::vector<std::vector<int>> exact;
    cases.push_back(svo_case(RK_PARITY_X("rk_svo_pack_color", "raykit/svo_format.glsl", (any, any, any, any), 2,
                                         uint w = rk_svo_pack_color(vec4(a[0], a[1], a[2], a[3])); RK_EMIT_U(0, w))));
    exact.push_back({0, 1});
    cases.push_back(svo_case(RK_PARITY_X("rk_svo_unpack_color", "raykit/svo_format.glsl", (u, u), 4,
                                         vec4 c = rk_svo_unpack_color(RK_WORD(0, 1)); o[0] = c.x; o[1] = c.y; o[2] = c.z; o[3] = c.w;)));
    // Alpha is code / 255: one correctly rounded division in C++, but GLSL allows 2.5 ulp for a
    // division (NVIDIA multiplies by a reciprocal: 1 ulp off for half the codes), so no column is
    // bit-exact here; the tolerance below (2e-7 + 2e-6 |x|) is ~30 ulp at 1.
    exact.push_back({});
    cases.push_back(svo_case(RK_PARITY_X("rk_svo_pack_normal", "raykit/svo_format.glsl", (any, any, any), 2,
                                         uint w = rk_svo_pack_normal(vec3(a[0], a[1], a[2])); RK_EMIT_U(0, w))));
    // A component that underflows on a flushing driver (FLT_MIN / 1.27 -> -0) flips the sign the
    // octahedral fold picks for it: on the fold's edge both words decode to the same direction. Such
    // rows are ties when the two words decode within one quantisation step (1.3e-4 rad) of each
    // other; every other row must give the same word.
    cases.back().tie = [](const float*, const float* g, const float* h) {
        const glm::vec3 a = rk_svo_unpack_normal(uint32_t(g[0]) | (uint32_t(g[1]) << 16));
        const glm::vec3 b = rk_svo_unpack_normal(uint32_t(h[0]) | (uint32_t(h[1]) << 16));
        return glm::length(glm::dvec3(a) - glm::dvec3(b)) <= 1.3e-4;
    };
    exact.push_back({0, 1});
    cases.push_back(svo_case(RK_PARITY_X("rk_svo_unpack_normal", "raykit/svo_format.glsl", (u, u), 3,
                                         vec3 n = rk_svo_unpack_normal(RK_WORD(0, 1)); o[0] = n.x; o[1] = n.y; o[2] = n.z;)));
    exact.push_back({});
    cases.push_back(svo_case(RK_PARITY_X("rk_svo_brick helpers", "raykit/svo_format.glsl", (u, u, u, u, u, u), 16,
                                         uvec2 m = uvec2(RK_WORD(0, 1), RK_WORD(2, 3)); uint bit = uint(clamp(a[4], 0.0f, 1.0f) * 63.0f);
                                         uint sub = bit >> 3u; uint base = RK_WORD(5, 5) >> 4u;
                                         o[0] = rk_svo_brick_has(m, bit) ? 1.0f : 0.0f; o[1] = float(rk_svo_brick_rank(m, bit));
                                         o[2] = float(rk_svo_brick_submask(m)); o[3] = float(rk_svo_brick_voxel_count(m));
                                         RK_EMIT_U(4, rk_svo_brick_voxel_attr(base, m, bit, 2u)); RK_EMIT_U(6, rk_svo_brick_sub_attr(base, m, sub, 7u));
                                         uint sbase = base | RK_SVO_BRICK_SHARED_SUB;
                                         RK_EMIT_U(12, rk_svo_brick_voxel_attr(sbase, m, bit, 2u)); RK_EMIT_U(14, rk_svo_brick_sub_attr(sbase, m, sub, 7u));
                                         uvec3 cell = uvec3(RK_WORD(0, 0) & 1023u, RK_WORD(1, 1) & 1023u, RK_WORD(2, 2) & 1023u);
                                         o[8] = float(rk_svo_brick_bit(cell, 2u)); o[9] = float(rk_svo_brick_bit(cell, 1u));
                                         o[10] = float(rk_svo_child_index(cell, bit % 10u, 10u));
                                         o[11] = float(rk_svo_child_rank(RK_WORD(3, 3) & 255u, bit & 7u));)));
    exact.push_back({0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15});
    cases.push_back(svo_case(RK_PARITY_X("rk_svo_descriptor fields", "raykit/svo_format.glsl", (u, u, u, u), 8,
                                         uint d = RK_WORD(0, 1); uint ord = RK_WORD(2, 3) >> 2u; uint fw = RK_WORD(1, 2) >> 3u;
                                         o[0] = float(rk_svo_child_mask(d)); o[1] = rk_svo_is_far(d) ? 1.0f : 0.0f;
                                         RK_EMIT_U(2, rk_svo_rel_ptr(d)); RK_EMIT_U(4, rk_svo_first_child(ord, d, fw));
                                         RK_EMIT_U(6, rk_svo_word_of(ord, RK_WORD(3, 0) >> 2u));)));
    exact.push_back({0, 1, 2, 3, 4, 5, 6, 7});
    cases.push_back(svo_case(RK_PARITY_X("rk_svo scalar codecs", "raykit/svo_format.glsl", (any, any, u, u), 6,
                                         o[0] = float(rk_svo_pack_unorm8(a[0])); o[1] = float(rk_svo_pack_snorm16(a[1]));
                                         uint w = RK_WORD(2, 3); o[2] = rk_svo_unpack_snorm16(w); o[3] = rk_svo_unpack_snorm16(w >> 16u);
                                         o[4] = float(rk_svo_material_id(w)); o[5] = float(rk_svo_brick_levels(w % 21u));)));
    exact.push_back({0, 1, 4, 5});
    for (size_t i = 0; i < cases.size(); ++i) {
        cases[i].abs_tol = 2e-7;
        cases[i].rel_tol = 2e-6;
        const parity::Result r = parity::run(cases[i], parity::shader_dir(), 8192, exact[i]);
        EXPECT_TRUE(r.ok) << cases[i].name << ": " << r.worst;
    }
}

namespace {

// rk_svo_lookup of `cells` at `max_level` on the driver; the words come from an SSBO (texture
// false) or an R32UI 2D texture (texture true). Returns found, level, attr per cell.
std::vector<uint32_t> gpu_lookup(const SvoTree& t, const std::vector<glm::uvec4>& cells, bool texture)
{
    const std::vector<uint32_t> words = t.gpu_words();
    std::string src = "#version 450 core\n#extension GL_GOOGLE_include_directive : require\n";
    src += "layout(local_size_x = 64) in;\n";
    src += "layout(std430, binding = 1) readonly buffer Cells { uvec4 rk_cells[]; };\n";
    src += "layout(std430, binding = 2) writeonly buffer Out { uint rk_out[]; };\n";
    src += "layout(location = 0) uniform uint rk_n;\nlayout(location = 1) uniform uvec3 rk_tree;\n";
    src += "#include \"raykit/svo_format.glsl\"\n";
    src += "void main() {\n  uint i = gl_GlobalInvocationID.x;\n  if (i >= rk_n) return;\n";
    src += "  uvec4 c = rk_cells[i];\n";
    src += "  rk_svo_hit h = rk_svo_lookup(0u, rk_tree.x, rk_tree.y, rk_tree.z, uvec3(c.x, c.y, c.z), c.w);\n";
    src += "  rk_out[3u * i] = h.found ? 1u : 0u; rk_out[3u * i + 1u] = h.level; rk_out[3u * i + 2u] = h.attr;\n}\n";
    std::vector<ShaderDefine> defs = {{"RK_SVO_WORDS_BINDING", "0"}, {"RK_SVO_BUFFER_TEXTURE", texture ? "1" : "0"}};
    src = rkgl::resolved_shader(src, "svo_lookup.comp", parity::shader_dir(), {parity::shader_dir()}, defs);
    GLuint prog = rkgl::build_program({{GL_COMPUTE_SHADER, src}});
    const rkgl::SvoWordsGl bound_words(words, texture);
    GLuint bcells = rkgl::make_buffer(cells.size() * sizeof(glm::uvec4), cells.data());
    GLuint bout = rkgl::make_buffer(cells.size() * 12, nullptr);
    glUseProgram(prog);
    glUniform1ui(0, static_cast<GLuint>(cells.size()));
    glUniform3ui(1, t.desc_words, t.gpu_brick_base_word(), t.depth);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bcells);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, bout);
    glDispatchCompute(static_cast<GLuint>((cells.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<uint32_t> out(cells.size() * 3);
    glGetNamedBufferSubData(bout, 0, static_cast<GLsizeiptr>(out.size() * 4), out.data());
    GLuint bufs[2] = {bcells, bout};
    glDeleteBuffers(2, bufs);
    glDeleteProgram(prog);
    return out;
}

}  // namespace

TEST(GpuParity, SvoLookupOnPackedTrees)
{
    struct Build { const char* name; SvoMeshData mesh; int depth; uint32_t pointer_bits; SvoFill fill; float root = 0.0f; };
    std::vector<Build> builds;
    builds.push_back({"icosphere d1", rkmesh::icosphere(2), 1, 23, SvoFill::surface});
    builds.push_back({"icosphere d2", rkmesh::icosphere(2), 2, 23, SvoFill::surface});
    builds.push_back({"torus d7 far", rkmesh::torus(48, 24), 7, 4, SvoFill::surface});
    builds.push_back({"menger d6 solid", rkmesh::menger_sponge(2), 6, 23, SvoFill::solid});
    // Depth 16: a unit sphere in a root of 4096 (voxels of 1/16: ~5k voxels, every level descended).
    builds.push_back({"icosphere d16", rkmesh::icosphere(1), 16, 23, SvoFill::surface, 4096.0f});
    std::mt19937 rng(77);
    for (Build& b : builds) {
        SvoBuildOptions opt;
        opt.depth = b.depth;
        opt.pointer_bits = b.pointer_bits;
        opt.fill = b.fill;
        opt.attributes = RK_SVO_ATTR_COLOR;
        if (b.root > 0.0f) {
            opt.fixed_bounds = true;
            opt.bounds_min = glm::vec3(-0.5f * b.root + 0.37f);
            opt.bounds_size = b.root;
        }
        SvoTree t;
        SvoStatus st;
        ASSERT_TRUE(build_svo(b.mesh.view(), opt, t, st)) << b.name << ": " << st.message;
        // Every voxel at full depth (up to 20k), then random cells at random levels, and cells
        // outside the grid.
        std::vector<glm::uvec4> cells;
        std::vector<uint64_t> attrs;
        svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t a) {
            if (cells.size() < 20000) { cells.push_back(glm::uvec4(c, t.depth)); attrs.push_back(a); }
        });
        const size_t nvox = cells.size();
        const uint32_t side = 1u << t.depth;
        for (int i = 0; i < 20000; ++i) {
            std::uniform_int_distribution<uint32_t> cd(0, side - 1), ld(0, t.depth);
            cells.push_back(glm::uvec4(cd(rng), cd(rng), cd(rng), ld(rng)));
        }
        cells.push_back(glm::uvec4(side, 0, 0, t.depth));
        cells.push_back(glm::uvec4(0xFFFFFFFFu, 0xFFFFFFFFu, 0xFFFFFFFFu, t.depth));
        const std::vector<uint32_t> words = t.gpu_words();
        for (bool texture : {false, true}) {
            const std::vector<uint32_t> g = gpu_lookup(t, cells, texture);
            long bad = 0;
            for (size_t i = 0; i < cells.size(); ++i) {
                const rk_svo_hit h = rk_svo_lookup(words.data(), t.desc_words, t.gpu_brick_base_word(), t.depth,
                                                   glm::uvec3(cells[i]), cells[i].w);
                const bool ok = g[3 * i] == (h.found ? 1u : 0u) && g[3 * i + 1] == h.level && g[3 * i + 2] == h.attr;
                // The builder's voxels: found at full depth with the attribute index it reported.
                const bool ok_ref = i >= nvox || (h.found && h.level == t.depth && h.attr == attrs[i]);
                if (!ok || !ok_ref) {
                    if (bad < 3)
                        ADD_FAILURE() << b.name << (texture ? " [texture]" : " [ssbo]") << " cell " << cells[i].x << "," << cells[i].y << ","
                                      << cells[i].z << " level " << cells[i].w << ": gpu " << g[3 * i] << "/" << g[3 * i + 1] << "/"
                                      << g[3 * i + 2] << " cpu " << h.found << "/" << h.level << "/" << h.attr;
                    ++bad;
                }
            }
            std::printf("[parity] rk_svo_lookup %-16s %-9s %zu cells (%zu voxels), %ld mismatches\n", b.name,
                        texture ? "texture" : "ssbo", cells.size(), nvox, bad);
            EXPECT_EQ(bad, 0);
        }
    }
}

// The portable bitCount / findMSB that replace the built-ins under GLSL ES 3.00 (common.glsl):
// on the driver, against the driver's own built-ins, over the bit patterns of random and
// adversarial floats (every sign, exponent and denormal pattern class), and both builds agree.
TEST(GpuParity, PortableBitCountAndFindMsb)
{
    const parity::Domain any{-1e30f, 1e30f, false, {0.0f, -0.0f, 1.0f, -1.0f, 1e-45f, -1e-45f, 3.4028235e38f}};
    // findMSB's -1 is compared as an int: NVIDIA 580.159 converts findMSB(0u) to float as
    // 4294967295 (as if the int were a uint), although the int itself is -1.
    parity::Case c = RK_PARITY("rk_bit_count_portable / rk_find_msb_portable", "raykit/common.glsl", (any), 5,
                               o[0] = float(rk_bit_count_portable(floatBitsToUint(a[0])));
                               o[1] = float(bitCount(floatBitsToUint(a[0])));
                               int mp = rk_find_msb_portable(floatBitsToUint(a[0]));
                               int mb = findMSB(floatBitsToUint(a[0]));
                               o[2] = mp == -1 ? -1.0f : float(mp);
                               o[3] = mb == -1 ? -1.0f : float(mb);
                               o[4] = mp < 0 ? 1.0f : 0.0f;);
    c.flush_denormal_inputs = false;  // bit patterns: every denormal class reaches the functions
    const parity::Result r = parity::run(c, parity::shader_dir(), 8192, {0, 1, 2, 3, 4});
    EXPECT_TRUE(r.ok) << r.mismatches << " mismatches, worst " << r.worst;
    EXPECT_EQ(r.non_finite, 0);
}

// The harness itself: a case whose two builds differ on purpose (RK_PARITY_SIDE is 1 in the shader,
// 0 in C++) must report every row as a mismatch, and a tie rule must turn exactly the rows it
// accepts into ties. This is the path the octahedral-seam rule of SvoCodecs takes on drivers that
// flush denormals (NVIDIA), which llvmpipe never reaches.
#define RK_PARITY_SIDE 0
TEST(GpuParityHarness, MismatchesAndTiesAreCounted)
{
    parity::Case c = RK_PARITY("harness: builds that differ", "raykit/common.glsl", (dom::unit()), 2,
                               o[0] = a[0]; o[1] = float(RK_PARITY_SIDE););
    c.defines.push_back({"RK_PARITY_SIDE", "1"});
    const parity::Result all = parity::run(c, parity::shader_dir(), 256);
    EXPECT_FALSE(all.ok);
    EXPECT_EQ(all.mismatches, all.rows);
    EXPECT_EQ(all.ties, 0);
    c.tie = [](const float* in, const float*, const float*) { return in[0] < 0.5f; };
    const parity::Result tied = parity::run(c, parity::shader_dir(), 256);
    EXPECT_GT(tied.ties, 0);
    EXPECT_GT(tied.mismatches, 0);
    EXPECT_EQ(tied.ties + tied.mismatches, tied.rows);
}
#undef RK_PARITY_SIDE

// The conditioning allowance of hardware drivers (parity::within_conditioning), on the CPU alone:
// a GPU answer that an input a few ulps away gives is accepted (a decision boundary, cancellation),
// one that no nearby input gives is not, nor anything non-finite; bit-pattern cases never get it.
TEST(GpuParityHarness, ConditioningAllowance)
{
    parity::Case step_case;
    step_case.name = "harness: floor";
    step_case.inputs = {dom::unit()};
    step_case.n_out = 1;
    step_case.cpu = [](const float* a, float* o) { o[0] = std::floor(a[0]); };
    const float below_one = std::nextafter(1.0f, 0.0f);
    const float one_gpu[1] = {1.0f}, two_gpu[1] = {2.0f}, nan_gpu[1] = {std::nanf("")};
    EXPECT_TRUE(parity::within_conditioning(step_case, &below_one, one_gpu, false));
    EXPECT_FALSE(parity::within_conditioning(step_case, &below_one, two_gpu, false));
    EXPECT_FALSE(parity::within_conditioning(step_case, &below_one, nan_gpu, false));
    const float half = 0.5f;
    EXPECT_FALSE(parity::within_conditioning(step_case, &half, one_gpu, false));
    step_case.hw_ulps = 0;
    EXPECT_FALSE(parity::within_conditioning(step_case, &below_one, one_gpu, false));
    step_case.hw_ulps = 4;
    step_case.flush_denormal_inputs = false;
    EXPECT_FALSE(parity::within_conditioning(step_case, &below_one, one_gpu, false));

    // Cancellation: 1e20 - 1e20 is 0 in C++; a fused or differently rounded 5e10 is within what a
    // 4-ulp move of either operand gives (ulp(1e20) = 2^43, about 8.8e12), 1e15 is not.
    parity::Case diff_case;
    diff_case.name = "harness: difference";
    diff_case.inputs = {dom::unit(), dom::unit()};
    diff_case.n_out = 1;
    diff_case.cpu = [](const float* a, float* o) { o[0] = a[0] - a[1]; };
    const float big[2] = {1e20f, 1e20f};
    const float near_gpu[1] = {5e10f}, far_gpu[1] = {1e15f};
    EXPECT_TRUE(parity::within_conditioning(diff_case, big, near_gpu, false));
    EXPECT_FALSE(parity::within_conditioning(diff_case, big, far_gpu, false));

    // Steps stay finite and, on a flushing driver, skip the denormals.
    const float fmin = std::numeric_limits<float>::min(), fmax = std::numeric_limits<float>::max();
    EXPECT_EQ(parity::ulp_step(0.0f, 1, true), fmin);
    EXPECT_EQ(parity::ulp_step(0.0f, -1, true), -fmin);
    EXPECT_EQ(parity::ulp_step(fmin, -1, true), 0.0f);
    EXPECT_EQ(parity::ulp_step(0.0f, 1, false), std::numeric_limits<float>::denorm_min());
    EXPECT_EQ(parity::ulp_step(fmax, 3, false), fmax);
    EXPECT_EQ(parity::ulp_step(1.0f, 2, false), std::nextafter(std::nextafter(1.0f, 2.0f), 2.0f));
}
