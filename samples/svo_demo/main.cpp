// svo_demo: raykit's voxel demo. Meshes are voxelised on the CPU (svo_build.hpp), packed, uploaded
// and ray cast per pixel in a fragment shader (svo_traverse.glsl), writing depth the rasteriser
// understands (svo_hybrid.glsl), so the voxel objects and animated rasterised cubes occlude each
// other both ways with the ordinary depth test (Gritzner, "3D graphics rendering using a
// polygon-voxel-hybrid approach": static scenery as voxels, moving objects as triangles).
//
// Views written as PNG (headless EGL by default):
//   svo_hybrid.png  voxel figure, torus and Menger sponge with rasterised cubes flying through them
//                   over a rasterised floor, at two moments of the animation;
//   svo_lod.png     the same scene at full detail and with level-of-detail stops (nodes no wider
//                   than one and four pixels), with per-pixel iteration heat maps;
//   svo_glass.png   secondary rays (svo_secondary.glsl): shadows, a mirror and an absorbing glass
//                   sphere of index 1.5 in one voxelised scene, beside the primary-rays-only image.
// --window opens a GLFW window (when built with GLFW and a display exists): the cubes animate,
// L toggles LOD, H the heat map, Esc quits.
//
// Usage: svo_demo [--quick] [--window] [OUT_DIR]    (--quick: 320x180, checks, for the tests)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/svo_build.hpp"
#include "reference/svo_meshes.hpp"
#include "rk_gl.hpp"
#include "rk_png.hpp"
#include "rk_svo_gl.hpp"
#include "rk_text.hpp"

#ifdef SVO_DEMO_HAVE_GLFW
#include <GLFW/glfw3.h>
#endif

namespace {

using raykit::SvoDepthConvention;

/// One voxel object of the scene: its tree (kept alive for the GL object) and placement.
struct VoxelObject {
    std::unique_ptr<raykit::SvoTree> tree;
    std::unique_ptr<rkgl::SvoGlObject> gl;
    glm::mat4 model{1.0f};
};

raykit::SvoMeshData coloured(raykit::SvoMeshData m, glm::vec3 colour)
{
    raykit::SvoMeshMaterial mat;
    mat.values.base_color = glm::vec4(colour, 1.0f);
    m.materials.assign(1, mat);
    m.material_ids.assign(m.indices.size() / 3, 0);
    return m;
}

bool build(const raykit::SvoMeshData& mesh, int depth, raykit::SvoFill fill, const glm::mat4& model, const std::string& shaders,
           std::vector<VoxelObject>& out)
{
    raykit::SvoBuildOptions opt;
    opt.depth = depth;
    opt.fill = fill;
    opt.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL;
    VoxelObject v;
    v.tree = std::make_unique<raykit::SvoTree>();
    raykit::SvoStatus st;
    const auto t0 = std::chrono::steady_clock::now();
    if (!raykit::build_svo(mesh.view(), opt, *v.tree, st)) {
        std::fprintf(stderr, "svo_demo: build failed: %s\n", st.message.c_str());
        return false;
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::printf("svo_demo: %zu triangles -> depth %d, %llu voxels, %.1f KiB of geometry, %.0f ms\n", mesh.indices.size() / 3,
                depth, static_cast<unsigned long long>(v.tree->voxel_count), double(v.tree->structure_bytes()) / 1024.0, ms);
    v.gl = std::make_unique<rkgl::SvoGlObject>(*v.tree, shaders);
    v.model = model;
    out.push_back(std::move(v));
    return true;
}

using Target = rkgl::DepthTarget;

struct Scene {
    std::vector<VoxelObject> voxels;
    std::unique_ptr<rkgl::MeshGl> floor, cube;
    glm::vec3 light = glm::normalize(glm::vec3(0.5f, 0.9f, 0.35f));
};

bool make_scene(Scene& s, const std::string& shaders, bool quick)
{
    const int d = quick ? 8 : 10;
    // A figure (1k triangles), a torus and a solid Menger sponge, placed on the floor y = 0.
    if (!build(coloured(rkmesh::figure(), glm::vec3(0.25f, 0.45f, 0.85f)), d, raykit::SvoFill::surface,
               glm::translate(glm::mat4(1.0f), glm::vec3(-1.2f, 0.0f, 0.0f)), shaders, s.voxels))
        return false;
    if (!build(coloured(rkmesh::torus(96, 48, 1.0, 0.35), glm::vec3(0.95f, 0.68f, 0.22f)), d - 1, raykit::SvoFill::surface,
               glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, 0.74f, 0.4f)) *
                   glm::rotate(glm::mat4(1.0f), 0.35f, glm::vec3(0.0f, 0.0f, 1.0f)) * glm::scale(glm::mat4(1.0f), glm::vec3(0.7f)),
               shaders, s.voxels))
        return false;
    if (!build(coloured(rkmesh::menger_sponge(3), glm::vec3(0.78f, 0.74f, 0.70f)), d - 2, raykit::SvoFill::solid,
               glm::translate(glm::mat4(1.0f), glm::vec3(1.9f, 0.0f, -1.4f)) * glm::scale(glm::mat4(1.0f), glm::vec3(1.1f)), shaders,
               s.voxels))
        return false;
    auto quad = [](float h) {
        return std::vector<glm::vec3>{{-h, 0.0f, -h}, {h, 0.0f, -h}, {h, 0.0f, h}, {-h, 0.0f, h}};
    };
    s.floor = std::make_unique<rkgl::MeshGl>(quad(8.0f), std::vector<glm::vec3>(4, glm::vec3(0.0f, 1.0f, 0.0f)),
                                             std::vector<uint32_t>{0, 2, 1, 0, 3, 2});
    const raykit::SvoMeshData box = rkmesh::box(glm::dvec3(-0.5), glm::dvec3(0.5));
    std::vector<glm::vec3> pos, nrm;
    std::vector<uint32_t> idx;
    for (size_t t = 0; t + 2 < box.indices.size(); t += 3) {  // flat-shaded: own vertices per face
        const glm::vec3 a = box.positions[box.indices[t]], b = box.positions[box.indices[t + 1]], c = box.positions[box.indices[t + 2]];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (const glm::vec3& p : {a, b, c}) {
            idx.push_back(uint32_t(pos.size()));
            pos.push_back(p);
            nrm.push_back(n);
        }
    }
    s.cube = std::make_unique<rkgl::MeshGl>(pos, nrm, idx);
    return true;
}

/// The secondary-rays scene: one tree (reflections and refractions see only their own tree) with a
/// checker floor of closed tiles, a glass sphere (index 1.5, absorbing a little red), a mirror slab
/// and a gold torus, all solid so the glass has an inside to march through.
bool make_glass_scene(std::vector<VoxelObject>& out, const std::string& shaders, bool quick)
{
    raykit::SvoMeshData m;
    std::vector<uint16_t> ids;
    auto add = [&](const raykit::SvoMeshData& part, uint16_t id) {
        rkmesh::append(m, part);
        ids.resize(m.indices.size() / 3, id);
    };
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            const glm::dvec3 lo(-2.0 + 0.5 * i, -0.12, -2.0 + 0.5 * j);
            add(rkmesh::box(lo, lo + glm::dvec3(0.5, 0.12, 0.5)), uint16_t((i + j) & 1));
        }
    add(rkmesh::icosphere(4, 0.55, glm::dvec3(-0.45, 0.56, 0.25)), 2);
    add(rkmesh::box(glm::dvec3(-0.1, 0.0, -1.35), glm::dvec3(1.6, 1.3, -1.15), glm::dvec3(0.0, -0.45, 0.0)), 3);
    add(rkmesh::torus(64, 32, 0.42, 0.14, glm::dvec3(0.95, 0.3, 0.45)), 4);
    m.material_ids = ids;
    auto mat = [](glm::vec4 c, float refl, float ior, glm::vec3 absorb) {
        raykit::SvoMeshMaterial x;
        x.values.base_color = c;
        x.values.reflectance = refl;
        x.values.ior = ior;
        x.values.absorption = absorb;
        return x;
    };
    m.materials = {mat(glm::vec4(0.85f, 0.85f, 0.82f, 1.0f), 0.0f, 1.5f, glm::vec3(0.0f)),
                   mat(glm::vec4(0.22f, 0.24f, 0.28f, 1.0f), 0.0f, 1.5f, glm::vec3(0.0f)),
                   mat(glm::vec4(0.95f, 0.97f, 1.0f, 0.06f), 0.0f, 1.5f, glm::vec3(0.9f, 0.25f, 0.1f)),
                   mat(glm::vec4(0.7f, 0.72f, 0.75f, 1.0f), 0.85f, 1.5f, glm::vec3(0.0f)),
                   mat(glm::vec4(0.95f, 0.68f, 0.22f, 1.0f), 0.0f, 1.5f, glm::vec3(0.0f))};
    raykit::SvoBuildOptions opt;
    opt.depth = quick ? 7 : 9;
    opt.fill = raykit::SvoFill::solid;
    opt.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;
    VoxelObject v;
    v.tree = std::make_unique<raykit::SvoTree>();
    raykit::SvoStatus st;
    if (!raykit::build_svo(m.view(), opt, *v.tree, st)) {
        std::fprintf(stderr, "svo_demo: glass scene build failed: %s\n", st.message.c_str());
        return false;
    }
    std::printf("svo_demo: glass scene, %zu triangles -> depth %d, %llu voxels\n", m.indices.size() / 3, opt.depth,
                static_cast<unsigned long long>(v.tree->voxel_count));
    v.gl = std::make_unique<rkgl::SvoGlObject>(*v.tree, shaders);
    out.push_back(std::move(v));
    return true;
}

/// The camera of a view.
struct Camera {
    glm::vec3 eye, target;
    float fov_y = 0.75f;
};

/// Draws the scene at animation time `time` into `target` (bound): floor and cubes rasterised,
/// then the voxel objects ray cast with early termination against the copied depth.
void draw_scene(const Scene& s, const Target& target, int w, int h, const Camera& cam, float time, const rkgl::SvoDrawParams& p)
{
    target.bind();
    const glm::mat4 view = glm::lookAt(cam.eye, cam.target, glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::mat4 proj = raykit::svo_perspective(cam.fov_y, float(w) / float(h), 0.05f, 60.0f, SvoDepthConvention::gl_minus_one_to_one);
    if (p.show_iterations) {
        // Heat map: every voxel object's iterations summed per pixel (additive, no depth test).
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        rkgl::SvoDrawParams q = p;
        q.fov_y = cam.fov_y;
        for (const VoxelObject& v : s.voxels) v.gl->draw(v.model, view, proj, SvoDepthConvention::gl_minus_one_to_one, q);
        glDisable(GL_BLEND);
        return;
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glClearColor(0.55f, 0.66f, 0.80f, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    s.floor->draw(glm::mat4(1.0f), view, proj, glm::vec3(0.42f, 0.45f, 0.40f), s.light);
    // Five cubes orbiting through the voxel objects.
    for (int i = 0; i < 5; ++i) {
        const float a = time * 0.6f + 6.2831853f * float(i) / 5.0f;
        const glm::vec3 c(1.6f * std::cos(a) + 0.2f, 0.55f + 0.35f * std::sin(2.0f * a + float(i)), 1.1f * std::sin(a));
        const glm::mat4 m = glm::translate(glm::mat4(1.0f), c) * glm::rotate(glm::mat4(1.0f), time + float(i), glm::normalize(glm::vec3(1.0f, 0.6f, 0.3f))) *
                            glm::scale(glm::mat4(1.0f), glm::vec3(0.32f));
        const glm::vec3 col = i % 2 ? glm::vec3(0.85f, 0.20f, 0.22f) : glm::vec3(0.25f, 0.75f, 0.35f);
        s.cube->draw(m, view, proj, col, s.light);
    }
    rkgl::SvoDrawParams q = p;
    q.fov_y = cam.fov_y;
    q.light_dir_world = s.light;
    q.depth_texture = target.copy_depth();
    for (const VoxelObject& v : s.voxels) v.gl->draw(v.model, view, proj, SvoDepthConvention::gl_minus_one_to_one, q);
}

/// Pastes `src` (w x h, RGBA) into `dst` (dw wide) at (x0, y0).
void paste(std::vector<unsigned char>& dst, int dw, const std::vector<unsigned char>& src, int w, int h, int x0, int y0)
{
    for (int y = 0; y < h; ++y) std::memcpy(&dst[(size_t(y0 + y) * size_t(dw) + size_t(x0)) * 4], &src[size_t(y) * size_t(w) * 4], size_t(w) * 4);
}

/// Draws labels onto an RGBA image (top row first) through a temporary framebuffer.
void label(std::vector<unsigned char>& img, int w, int h, const std::vector<std::pair<glm::vec2, std::string>>& texts, float scale)
{
    Target t(w, h);
    std::vector<unsigned char> flipped(img.size());
    const size_t row = size_t(w) * 4;
    for (int y = 0; y < h; ++y) std::memcpy(&flipped[size_t(y) * row], &img[size_t(h - 1 - y) * row], row);
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA8, w, h);
    glTextureSubImage2D(tex, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
    GLuint read_fbo = 0;
    glCreateFramebuffers(1, &read_fbo);
    glNamedFramebufferTexture(read_fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    glBlitNamedFramebuffer(read_fbo, t.fbo(), 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glDeleteFramebuffers(1, &read_fbo);
    glDeleteTextures(1, &tex);
    t.bind();
    glDisable(GL_DEPTH_TEST);
    rkgl::TextOverlay o;
    for (const auto& [p, s] : texts) {
        o.rect(p.x - 6.0f, p.y - 5.0f, p.x + 7.0f * scale * float(s.size()) * 0.86f + 6.0f, p.y + 9.0f * scale, rkgl::rgba(0.0f, 0.0f, 0.0f, 0.55f));
        o.text(p.x, p.y, s, scale, rkgl::rgba(1.0f, 1.0f, 1.0f));
    }
    o.draw(w, h);
    img = t.read_rgba8(true);
}

/// Fraction of pixels of `img` that are not the sky colour, and its mean iteration grey level.
double non_sky_fraction(const std::vector<unsigned char>& img)
{
    size_t n = 0;
    for (size_t i = 0; i + 3 < img.size(); i += 4) n += !(img[i] == 140 && img[i + 1] == 168 && img[i + 2] == 204);
    return double(n) / double(img.size() / 4);
}

double mean_grey(const std::vector<unsigned char>& img)
{
    double s = 0.0;
    for (size_t i = 0; i + 3 < img.size(); i += 4) s += img[i];
    return s / double(img.size() / 4);
}

int run_headless(const std::string& out_dir, bool quick)
{
    rkgl::HeadlessContext ctx;
    if (!ctx.create()) return rkgl::no_context_exit("svo_demo", ctx.error());
    std::printf("svo_demo: renderer %s\n", ctx.renderer().c_str());
    Scene scene;
    if (!make_scene(scene, RAYKIT_SHADER_DIR, quick)) return 1;
    const int w = quick ? 320 : 1280, h = quick ? 180 : 720;
    Target target(w, h);
    const Camera cam{glm::vec3(-2.2f, 1.7f, 4.1f), glm::vec3(0.35f, 0.6f, -0.2f)};
    const float label_scale = quick ? 1.0f : 2.0f;

    // Hybrid: two moments of the animation, side by side.
    std::vector<unsigned char> hybrid(size_t(2 * w) * size_t(h) * 4);
    for (int k = 0; k < 2; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        draw_scene(scene, target, w, h, cam, 1.3f + 1.7f * float(k), rkgl::SvoDrawParams{});
        const std::vector<unsigned char> img = target.read_rgba8(true);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::printf("svo_demo: hybrid frame %d, %dx%d: %.1f ms (%s)\n", k, w, h, ms, ctx.renderer().c_str());
        paste(hybrid, 2 * w, img, w, h, k * w, 0);
    }
    label(hybrid, 2 * w, h,
          {{glm::vec2(12.0f, 10.0f), "voxels: ray cast (svo_traverse.glsl)"},
           {glm::vec2(12.0f, 10.0f + 14.0f * label_scale), "cubes, floor: rasterised; one depth buffer"},
           {glm::vec2(float(w) + 12.0f, 10.0f), "the same scene 1.7 s later"}},
          label_scale);
    const std::string hybrid_path = out_dir + "/svo_hybrid.png";
    if (!rkgl::write_png_rgba8(hybrid_path, 2 * w, h, hybrid.data())) return 1;

    // LOD: full detail, 1-pixel and 4-pixel nodes; colour and iteration heat map for each.
    const Camera far_cam{glm::vec3(-5.5f, 3.6f, 10.5f), glm::vec3(0.3f, 0.5f, 0.0f), 0.55f};
    std::vector<unsigned char> lod(size_t(3 * w) * size_t(2 * h) * 4);
    const float pixels[3] = {0.0f, 1.0f, 4.0f};
    double grey[3] = {0.0, 0.0, 0.0};
    std::vector<std::pair<glm::vec2, std::string>> lod_labels;
    for (int k = 0; k < 3; ++k) {
        rkgl::SvoDrawParams p;
        p.lod_pixels = pixels[k];
        draw_scene(scene, target, w, h, far_cam, 1.3f, p);
        paste(lod, 3 * w, target.read_rgba8(true), w, h, k * w, 0);
        p.show_iterations = true;
        draw_scene(scene, target, w, h, far_cam, 1.3f, p);
        const std::vector<unsigned char> heat = target.read_rgba8(true);
        grey[k] = mean_grey(heat);
        paste(lod, 3 * w, heat, w, h, k * w, h);
        char b[128];
        std::snprintf(b, sizeof b, k == 0 ? "full detail" : "LOD: nodes <= %g px", double(pixels[k]));
        lod_labels.push_back({glm::vec2(float(k * w) + 12.0f, 10.0f), b});
        std::snprintf(b, sizeof b, "loop iterations per pixel (white = 64)");
        lod_labels.push_back({glm::vec2(float(k * w) + 12.0f, float(h) + 10.0f), b});
    }
    label(lod, 3 * w, 2 * h, lod_labels, label_scale);
    const std::string lod_path = out_dir + "/svo_lod.png";
    if (!rkgl::write_png_rgba8(lod_path, 3 * w, 2 * h, lod.data())) return 1;
    std::printf("svo_demo: wrote %s, %s (mean iteration grey: full %.1f, 1 px %.1f, 4 px %.1f)\n", hybrid_path.c_str(),
                lod_path.c_str(), grey[0], grey[1], grey[2]);

    // Secondary rays: shadows, a mirror, glass; and the same view without them for comparison.
    std::vector<VoxelObject> glass;
    if (!make_glass_scene(glass, RAYKIT_SHADER_DIR, quick)) return 1;
    std::vector<unsigned char> glass_img(size_t(2 * w) * size_t(h) * 4);
    const Camera gcam{glm::vec3(-1.9f, 1.25f, 2.6f), glm::vec3(0.1f, 0.45f, -0.2f), 0.8f};
    double glass_ms = 0.0;
    for (int k = 0; k < 2; ++k) {
        target.bind();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glClearColor(0.62f, 0.70f, 0.80f, 1.0f);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        const glm::mat4 view = glm::lookAt(gcam.eye, gcam.target, glm::vec3(0.0f, 1.0f, 0.0f));
        const glm::mat4 proj = raykit::svo_perspective(gcam.fov_y, float(w) / float(h), 0.05f, 60.0f, SvoDepthConvention::gl_minus_one_to_one);
        rkgl::SvoDrawParams p;
        p.secondary = k == 1;
        p.light_dir_world = glm::normalize(glm::vec3(-0.45f, 0.8f, 0.35f));
        const auto t0 = std::chrono::steady_clock::now();
        glass[0].gl->draw(glass[0].model, view, proj, SvoDepthConvention::gl_minus_one_to_one, p);
        const std::vector<unsigned char> img = target.read_rgba8(true);
        if (k == 1) glass_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        paste(glass_img, 2 * w, img, w, h, k * w, 0);
    }
    std::printf("svo_demo: secondary-rays view %dx%d: %.1f ms, first draw with that program, so compilation included (%s)\n", w, h,
                glass_ms, ctx.renderer().c_str());
    label(glass_img, 2 * w, h,
          {{glm::vec2(12.0f, 10.0f), "primary rays only"},
           {glm::vec2(float(w) + 12.0f, 10.0f), "secondary rays (svo_secondary.glsl): shadows,"},
           {glm::vec2(float(w) + 12.0f, 10.0f + 14.0f * label_scale), "mirror, glass n = 1.5 absorbing red, Fresnel"}},
          label_scale);
    const std::string glass_path = out_dir + "/svo_glass.png";
    if (!rkgl::write_png_rgba8(glass_path, 2 * w, h, glass_img.data())) return 1;
    std::printf("svo_demo: wrote %s\n", glass_path.c_str());

    // Checks (the sample.svo_demo test): something drawn, and LOD saves iterations.
    const double drawn = non_sky_fraction(hybrid);
    if (drawn < 0.2 || !(grey[2] < grey[0])) {
        std::fprintf(stderr, "svo_demo: check failed: %.2f of the hybrid view drawn; iterations full %.1f vs LOD %.1f\n", drawn,
                     grey[0], grey[2]);
        return 1;
    }
    return 0;
}

#ifdef SVO_DEMO_HAVE_GLFW
int run_window()
{
    if (!glfwInit()) {
        std::fprintf(stderr, "svo_demo: no display (glfwInit failed)\n");
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    const int w = 1280, h = 720;
    GLFWwindow* win = glfwCreateWindow(w, h, "raykit voxels", nullptr, nullptr);
    if (!win) {
        glfwTerminate();
        std::fprintf(stderr, "svo_demo: could not open a window\n");
        return 1;
    }
    glfwMakeContextCurrent(win);
    glfwSwapInterval(1);
    int rc = 0;
    {
        Scene scene;
        if (!make_scene(scene, RAYKIT_SHADER_DIR, false)) rc = 1;
        Target target(w, h);
        rkgl::SvoDrawParams p;
        bool l_down = false, h_down = false;
        const auto start = std::chrono::steady_clock::now();
        while (rc == 0 && !glfwWindowShouldClose(win)) {
            glfwPollEvents();
            if (glfwGetKey(win, GLFW_KEY_ESCAPE) == GLFW_PRESS) glfwSetWindowShouldClose(win, 1);
            const bool l = glfwGetKey(win, GLFW_KEY_L) == GLFW_PRESS, hk = glfwGetKey(win, GLFW_KEY_H) == GLFW_PRESS;
            if (l && !l_down) p.lod_pixels = p.lod_pixels > 0.0f ? 0.0f : 1.0f;
            if (hk && !h_down) p.show_iterations = !p.show_iterations;
            l_down = l;
            h_down = hk;
            const float time = std::chrono::duration<float>(std::chrono::steady_clock::now() - start).count();
            const Camera cam{glm::vec3(5.8f * std::sin(0.1f * time), 2.0f, 5.8f * std::cos(0.1f * time)), glm::vec3(0.3f, 0.55f, 0.0f)};
            draw_scene(scene, target, w, h, cam, time, p);
            glBlitNamedFramebuffer(target.fbo(), 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glfwSwapBuffers(win);
        }
    }
    glfwDestroyWindow(win);
    glfwTerminate();
    return rc;
}
#endif

}  // namespace

int main(int argc, char** argv)
{
    bool quick = false, window = false;
    std::string out_dir = ".";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--quick") quick = true;
        else if (a == "--window") window = true;
        else if (a == "--help" || a == "-h") {
            std::printf("usage: svo_demo [--quick] [--window] [OUT_DIR]\n");
            return 0;
        } else out_dir = a;
    }
    if (window) {
#ifdef SVO_DEMO_HAVE_GLFW
        return run_window();
#else
        std::fprintf(stderr, "svo_demo: built without GLFW; rendering headless\n");
#endif
    }
    return run_headless(out_dir, quick);
}
