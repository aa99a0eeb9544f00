// Hybrid rendering on the driver (svo_hybrid.glsl through samples/common/rk_svo_gl.hpp): for the
// OpenGL [-1, 1], zero-to-one (Vulkan's) and reversed-Z conventions,
//   - a voxel face writes the float64 reference depth of its plane at the pixel centre (within a
//     few 2^-24), and a rasterised quad in the same plane writes the same depth within the
//     rasteriser's own error against that reference (a few 2^-24 on llvmpipe; NVIDIA's depth
//     interpolation was measured 34 x 2^-24 off it), pixel for pixel;
//   - occlusion is right both ways: a rasterised plane cutting through a voxel block, drawn before
//     or after it, shows in exactly the pixels where the float64 reference (exact pixel ray against
//     the plane, CPU traversal for the voxels) says it is nearer, and both draw orders give the
//     same image;
//   - early termination against a copy of the depth buffer (rk_svo_depth_to_t as t_max) changes
//     no pixel, and saves work: pixels behind the plane walk fewer iterations, none over 2 more;
//   - the voxel pass builds under every feature set raykit::svo_defines gives, and declares the
//     buffers of its secondary rays only where a feature casts them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <cstdio>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "parity.hpp"
#include "raykit/svo_features.hpp"
#include "raykit/svo_traverse.hpp"
#include "rk_svo_gl.hpp"
#include "svo_test_pack.hpp"

using namespace raykit;

namespace {

constexpr int W = 160, H = 120;

/// Clears colour to transparent black and depth to the far value of the convention.
void clear_target(bool reversed)
{
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClearDepth(reversed ? 0.0 : 1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

/// The colour pixels as RGBA8 words, bottom row first.
std::vector<uint32_t> read_color(const rkgl::DepthTarget& t)
{
    const std::vector<unsigned char> px = t.read_rgba8(false);
    std::vector<uint32_t> c(px.size() / 4);
    std::memcpy(c.data(), px.data(), px.size());
    return c;
}

struct Convention {
    SvoDepthConvention conv;
    const char* name;
};

void set_convention(SvoDepthConvention c)
{
    const bool zo = c != SvoDepthConvention::gl_minus_one_to_one;
    glClipControl(GL_LOWER_LEFT, zo ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(c == SvoDepthConvention::reversed_zero_to_one ? GL_GREATER : GL_LESS);
    glDepthMask(GL_TRUE);
}

/// A solid block of voxels [lo, hi) at depth 4 in the root [-1, 1]^3, with colour hashes.
SvoTree make_block(int lo, int hi)
{
    std::vector<glm::uvec3> cells;
    for (int z = lo; z < hi; ++z)
        for (int y = lo; y < hi; ++y)
            for (int x = lo; x < hi; ++x) cells.push_back(glm::uvec3(uint32_t(x), uint32_t(y), uint32_t(z)));
    svotest::PackOptions po;
    po.attributes = RK_SVO_ATTR_COLOR;
    po.root_min = glm::vec3(-1.0f);
    po.root_size = 2.0f;
    return svotest::pack_cells(4, cells, po);
}

}  // namespace

TEST(GpuHybrid, VoxelFaceAndTriangleShareDepthAndOccludeBothWays)
{
    const SvoTree tree = make_block(4, 12);  // the block [-0.5, 0.5]^3
    rkgl::SvoGlObject obj(tree, parity::shader_dir());
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, -0.2f, 0.1f)) *
                            glm::rotate(glm::mat4(1.0f), 0.5f, glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f))) *
                            glm::scale(glm::mat4(1.0f), glm::vec3(1.7f));
    const glm::mat4 view = glm::lookAt(glm::vec3(-2.2f, 1.4f, 3.1f), glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    // The block's face x = -0.5 as a quad (object space), and a plane slicing the block.
    const std::vector<glm::vec3> face = {{-0.5f, -0.5f, -0.5f}, {-0.5f, 0.5f, -0.5f}, {-0.5f, 0.5f, 0.5f}, {-0.5f, -0.5f, 0.5f}};
    const std::vector<glm::vec3> face_n(4, glm::vec3(-1.0f, 0.0f, 0.0f));
    const glm::vec3 pn = glm::normalize(glm::vec3(0.6f, -0.3f, 1.0f));  // slicing plane through the centre
    const glm::vec3 pu = glm::normalize(glm::cross(pn, glm::vec3(0.0f, 1.0f, 0.0f))), pv = glm::cross(pn, pu);
    const std::vector<glm::vec3> slice = {-2.0f * pu - 2.0f * pv, 2.0f * pu - 2.0f * pv, 2.0f * pu + 2.0f * pv, -2.0f * pu + 2.0f * pv};
    const std::vector<glm::vec3> slice_n(4, pn);
    const std::vector<uint32_t> quad = {0, 1, 2, 0, 2, 3};
    rkgl::MeshGl face_mesh(face, face_n, quad), slice_mesh(slice, slice_n, quad);
    const std::vector<uint32_t> words = tree.gpu_words();
    const rk_svo_tree tr = svo_trace_tree(tree);

    const Convention conventions[] = {{SvoDepthConvention::gl_minus_one_to_one, "OpenGL [-1,1]"},
                            {SvoDepthConvention::zero_to_one, "zero-to-one"},
                            {SvoDepthConvention::reversed_zero_to_one, "reversed-Z"}};
    for (const Convention& s : conventions) {
        const bool rev = s.conv == SvoDepthConvention::reversed_zero_to_one;
        const glm::mat4 proj = svo_perspective(0.9f, float(W) / float(H), 0.5f, rev ? INFINITY : 30.0f, s.conv);
        rkgl::DepthTarget target(W, H);
        set_convention(s.conv);
        rkgl::SvoDrawParams params;

        // 1. Same depth for the voxel face and the coplanar quad.
        clear_target(rev);
        obj.draw(model, view, proj, s.conv, params);
        const std::vector<float> dv = target.read_depth();
        clear_target(rev);
        face_mesh.draw(model, view, proj, glm::vec3(1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
        const std::vector<float> dr = target.read_depth();
        const float cleared = rev ? 0.0f : 1.0f;
        // float64 reference: the window depth of the face's plane at each pixel centre. NDC depth is
        // an affine function of NDC x, y over a plane; fitted through three projected corners.
        const glm::dmat4 mvp = glm::dmat4(proj) * glm::dmat4(view) * glm::dmat4(model);
        glm::dvec3 q[3];
        for (int k = 0; k < 3; ++k) {
            const glm::dvec4 c = mvp * glm::dvec4(glm::dvec3(face[size_t(k)]), 1.0);
            q[k] = glm::dvec3(c) / c.w;
        }
        const glm::dvec3 fn = glm::cross(q[1] - q[0], q[2] - q[0]);  // z = q0.z - (fn.x (x - q0.x) + fn.y (y - q0.y)) / fn.z
        const bool zero_to_one = s.conv != SvoDepthConvention::gl_minus_one_to_one;
        auto exact_depth = [&](int x, int y) {
            const double nx = (x + 0.5) / W * 2.0 - 1.0, ny = (y + 0.5) / H * 2.0 - 1.0;
            const double z = q[0].z - (fn.x * (nx - q[0].x) + fn.y * (ny - q[0].y)) / fn.z;
            return zero_to_one ? z : 0.5 * z + 0.5;
        };
        long compared = 0;
        double worst = 0.0, worst_voxel = 0.0, worst_raster = 0.0;
        for (int y = 1; y < H - 1; ++y)
            for (int x = 1; x < W - 1; ++x) {
                bool inner = true;  // the quad covers the 3x3 neighbourhood: not an edge pixel
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) inner = inner && dr[size_t((y + dy) * W + x + dx)] != cleared;
                if (!inner) continue;
                const size_t i = size_t(y * W + x);
                ASSERT_NE(dv[i], cleared) << s.name << ": the voxel block is missing at " << x << "," << y;
                const double ref = exact_depth(x, y);
                worst = std::max(worst, double(std::abs(dv[i] - dr[i])) / 0x1p-24);
                worst_voxel = std::max(worst_voxel, std::abs(double(dv[i]) - ref) / 0x1p-24);
                worst_raster = std::max(worst_raster, std::abs(double(dr[i]) - ref) / 0x1p-24);
                ++compared;
            }
        std::printf("[hybrid] %-14s voxel face vs coplanar triangle: %ld pixels, depth differs by at most %.1f x 2^-24 "
                    "(voxels vs float64 %.1f, rasteriser vs float64 %.1f)\n",
                    s.name, compared, worst, worst_voxel, worst_raster);
        EXPECT_GT(compared, 500);
        // Ours: the voxel pass writes the exact plane depth to a few 2^-24 (measured <= 4 on llvmpipe).
        EXPECT_LE(worst_voxel, 6.0) << s.name;
        // The rasteriser's side: llvmpipe, which CI runs, keeps the two within 6 x 2^-24 of each other
        // (measured <= 4); GL lets a hardware rasteriser interpolate depth more coarsely, so there
        // its own error against the reference is bounded instead (NVIDIA H100: 33.9 measured).
        if (parity::software_renderer()) EXPECT_LE(worst, 6.0) << s.name;
        else EXPECT_LE(worst_raster, 64.0) << s.name;

        // 2. Occlusion both ways, in both draw orders, against the float64 reference.
        const SvoHybridView hv = svo_hybrid_view(model, view, proj, s.conv);
        const glm::dmat4 M = glm::dmat4(proj) * glm::dmat4(view) * glm::dmat4(model);
        std::vector<uint32_t> images[3];
        for (int order = 0; order < 3; ++order) {
            clear_target(rev);
            const glm::vec3 red(1.0f, 0.0f, 0.0f);
            if (order == 0) {
                slice_mesh.draw(model, view, proj, red, pn);
                obj.draw(model, view, proj, s.conv, params);
            } else if (order == 1) {
                obj.draw(model, view, proj, s.conv, params);
                slice_mesh.draw(model, view, proj, red, pn);
            } else {
                // Raster first, then voxels stopping at the copied depth (early termination).
                slice_mesh.draw(model, view, proj, red, pn);
                rkgl::SvoDrawParams early = params;
                early.depth_texture = target.copy_depth();
                obj.draw(model, view, proj, s.conv, early);
            }
            images[order] = read_color(target);
        }
        long checked = 0, wrong = 0, differ_order = 0, differ_early = 0, plane_wins = 0, voxels_win = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t i = size_t(y * W + x);
                differ_order += images[0][i] != images[1][i];
                differ_early += images[0][i] != images[2][i];
                // Reference: the exact pixel ray (pixel centre) against the plane and the voxels.
                const glm::vec2 ndc((float(x) + 0.5f) / W * 2.0f - 1.0f, (float(y) + 0.5f) / H * 2.0f - 1.0f);
                glm::vec3 o, d;
                rk_svo_pixel_ray(hv.clip_to_obj, ndc, hv.z_near_ndc, o, d);
                const rk_svo_trace_hit h = rk_svo_trace(words.data(), tr, o, d, 3.0e38f, glm::vec2(0.0f));
                const double denom = glm::dot(glm::dvec3(pn), glm::dvec3(d));
                const double tp = std::abs(denom) > 1e-12 ? -glm::dot(glm::dvec3(pn), glm::dvec3(o)) / denom : -1.0;
                const glm::dvec3 pp = glm::dvec3(o) + tp * glm::dvec3(d);
                const bool plane_hit = tp > 0.0 && std::abs(glm::dot(pp, glm::dvec3(pu))) < 2.0 && std::abs(glm::dot(pp, glm::dvec3(pv))) < 2.0;
                auto depth_of = [&](glm::dvec3 p) {
                    const glm::dvec4 c = M * glm::dvec4(p, 1.0);
                    return c.z / c.w;
                };
                double dvox = 0.0, dpl = 0.0;
                if (h.hit) dvox = depth_of(glm::dvec3(o) + double(h.t) * glm::dvec3(d));
                if (plane_hit) dpl = depth_of(pp);
                if (h.hit && plane_hit && std::abs(dvox - dpl) < 1e-5) continue;  // a tie: either may win
                const bool expect_red = plane_hit && (!h.hit || (rev ? dpl > dvox : dpl < dvox));
                const bool expect_empty = !plane_hit && !h.hit;
                plane_wins += expect_red && h.hit;
                voxels_win += !expect_red && plane_hit;
                const uint32_t c = images[0][i];
                const bool is_red = (c & 0xFFu) > 20u && ((c >> 8) & 0xFFu) == 0u && ((c >> 16) & 0xFFu) == 0u;
                const bool is_empty = (c >> 24) == 0u;
                ++checked;
                if (expect_empty ? !is_empty : (expect_red != is_red || is_empty)) {
                    if (wrong < 3)
                        ADD_FAILURE() << s.name << " pixel " << x << "," << y << ": colour " << std::hex << c << std::dec
                                      << " expected " << (expect_empty ? "nothing" : expect_red ? "the plane" : "voxels");
                    ++wrong;
                }
            }
        std::printf("[hybrid] %-14s occlusion: %ld pixels checked (plane in front of voxels in %ld, behind in %ld), "
                    "%ld wrong; draw orders differ in %ld, early termination changes %ld\n",
                    s.name, checked, plane_wins, voxels_win, wrong, differ_order, differ_early);
        EXPECT_GT(plane_wins, 200);
        EXPECT_GT(voxels_win, 200);
        EXPECT_EQ(wrong, 0) << s.name;
        EXPECT_EQ(differ_order, 0) << s.name;
        EXPECT_EQ(differ_early, 0) << s.name;

        // 3. Early termination saves work: the pass's iteration heat map (colour = iterations / 64,
        // about 4 steps of the 8-bit channel per iteration) drawn over the plane with the depth
        // test off, without and with the depth copy; the map saturates at 64 iterations, which
        // these depth-4 rays stay far below. A ray stopped at the plane walks its full
        // path's prefix, then at most 3 more advances to its parent's exit, where the t_max test
        // stops it (the full ray may find its voxel 1 iteration after that point): no pixel may cost
        // more than 2 iterations more, and the pixels where the plane hides voxels must cost less.
        std::vector<uint32_t> heat[2];
        for (int e = 0; e < 2; ++e) {
            clear_target(rev);
            slice_mesh.draw(model, view, proj, glm::vec3(1.0f, 0.0f, 0.0f), pn);
            rkgl::SvoDrawParams hp = params;
            hp.show_iterations = true;
            if (e == 1) hp.depth_texture = target.copy_depth();
            glDepthFunc(GL_ALWAYS);
            obj.draw(model, view, proj, s.conv, hp);
            set_convention(s.conv);
            heat[e] = read_color(target);
        }
        long more = 0, fewer = 0, much_more = 0;
        double sum_full = 0.0, sum_early = 0.0;
        for (size_t i = 0; i < heat[0].size(); ++i) {
            const int a0 = int(heat[0][i] & 0xFFu), a1 = int(heat[1][i] & 0xFFu);
            more += a1 > a0;
            much_more += a1 > a0 + 8;
            fewer += a1 < a0;
            sum_full += a0;
            sum_early += a1;
        }
        std::printf("[hybrid] %-14s early termination: %ld pixels walk fewer iterations, %ld more; total %.0f%% of the "
                    "full walk\n", s.name, fewer, more, 100.0 * sum_early / std::max(sum_full, 1.0));
        EXPECT_EQ(much_more, 0) << s.name;
        EXPECT_LT(sum_early, 0.9 * sum_full) << s.name;
        EXPECT_GT(fewer, 200) << s.name;
    }
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
}

TEST(GpuHybrid, VoxelPassBuildsUnderEveryFeatureSet)
{
    // The sample voxel pass under every feature set svo_defines gives (LOD, shadows, and the
    // reflection, refraction and absorption that materials ask for): each program builds, and the
    // buffers of the secondary rays are declared only in programs that cast them.
    SvoMaterial mirror, clear, tinted;
    mirror.reflectance = 0.7f;
    clear.base_color.a = 0.3f;
    tinted.base_color.a = 0.3f;
    tinted.absorption = glm::vec3(0.2f, 0.1f, 0.0f);
    const std::vector<std::vector<SvoMaterial>> sets = {{}, {mirror}, {clear}, {mirror, tinted}};
    int built = 0;
    for (int lod = 0; lod < 2; ++lod)
        for (int shadows = 0; shadows < 2; ++shadows)
            for (const std::vector<SvoMaterial>& mats : sets) {
                SvoSceneDesc d;
                d.lod = lod != 0;
                d.shadows = shadows != 0;
                Status st;
                const std::vector<ShaderDefine> defs = svo_defines(d, mats, &st);
                ASSERT_TRUE(st.ok()) << st.message;
                const SvoMaterialNeeds need = svo_material_needs(mats);
                const std::string fs = rkgl::resolved_shader(rkgl::svo_fragment_source(), "svo_pass.frag", parity::shader_dir(),
                                                             {parity::shader_dir()}, defs);
                const GLuint prog = rkgl::build_program({{GL_VERTEX_SHADER, rkgl::fullscreen_vertex_source()}, {GL_FRAGMENT_SHADER, fs}});
                auto active = [&](const char* block) {
                    return glGetProgramResourceIndex(prog, GL_SHADER_STORAGE_BLOCK, block) != GL_INVALID_INDEX;
                };
                const bool bounce = need.reflection || need.refraction;
                std::string what = "lod " + std::to_string(lod) + " shadows " + std::to_string(shadows) + " materials " +
                                   std::to_string(mats.size());
                // A block that is read is active on every driver; one that is declared and not read
                // may be reported either way (Mesa reports it), one not declared never is. So: the
                // buffers a feature reads are active where it is on, and absent where no feature
                // that declares them is.
                EXPECT_TRUE(active("RkSvoWords")) << what;
                EXPECT_EQ(active("RkSurface"), bounce) << what;  // the bounce's per-material table, read by it
                if (bounce) {
                    EXPECT_TRUE(active("RkSvoMaterialIds")) << what;
                }
                if (need.refraction) {
                    EXPECT_TRUE(active("RkSvoMedia")) << what;
                }
                // svo_secondary.glsl (which declares the media buffers) only where a secondary ray is cast.
                if (!bounce && !d.shadows) {
                    EXPECT_FALSE(active("RkSvoMaterialIds")) << what;
                    EXPECT_FALSE(active("RkSvoMedia")) << what;
                }
                glDeleteProgram(prog);
                ++built;
            }
    std::printf("[hybrid] voxel pass: %d feature sets built, secondary-ray buffers only where a feature casts rays\n", built);
}
