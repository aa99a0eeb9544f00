// raykit bench — bench_svo_gl: frame time of octree ray casting on the driver (issue 11 item 7):
// the voxel pass of samples/common/rk_svo_gl.hpp (svo_traverse.glsl + svo_hybrid.glsl, one ray per
// pixel, colour and normal fetched at the hit) by mesh, depth and resolution, without and with
// level-of-detail stops, as a ratio to rasterising the source triangles from the same camera; and
// the image error of each LOD setting against the full-depth image next to its time saving.
//
// Scenes: rkmesh::figure() (1,024 triangles, the size of Gritzner's test mesh) and
// rkmesh::uv_sphere(256, 137) (69,632 triangles), voxelised at depths 8..11 (surface, colour +
// normal), each filling about half of the frame. Configurations per (mesh, depth, resolution):
// raster (the mesh, MeshGl), voxels (full depth), lod1 / lod2 / lod4 (stop at nodes no wider than
// 1, 2, 4 pixels), and compute: the same primary rays traced in a compute shader (8 x 8 groups, the
// hit's colour written to a buffer, no shading): rays per second where fragment shaders are not the
// whole chip (an H100 runs pixel shaders on 2 of its 66 TPCs) and without the fragment pipeline.
// Timing: a GL_TIME_ELAPSED query around each draw on a GPU; on llvmpipe, whose queries miss its
// deferred rasterisation, the wall clock between glFinish calls. Rounds interleave the configurations (round r
// draws every configuration, rotated), the median over rounds is reported with the quartiles, and
// ratios are per round against raster at the same round. On a software driver (llvmpipe) the times
// are CPU times of the rasteriser: compare ratios, not milliseconds.
// Image error: mean absolute difference over RGB (0..255 levels) between the LOD image and the
// full-detail image of the same tree, and the share of pixels that differ by more than 8 levels.
//
// Usage: bench_svo_gl [--rounds N] [--md FILE] [--png FILE] [--smoke]
//   --smoke: 128 x 96, depth 6, 2 rounds, sanity checks only (ctest bench.svo_gl.smoke).
// Exit codes: 0 done; 1 error or failed check; 77 no OpenGL 4.5 context (1 when CI=true).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "raykit/svo_build.hpp"
#include "reference/svo_meshes.hpp"
#include "rk_gl.hpp"
#include "rk_png.hpp"
#include "rk_svo_gl.hpp"

namespace {

struct Quartiles {
    double q1 = 0.0, median = 0.0, q3 = 0.0;
};

Quartiles quartiles(std::vector<double> v)
{
    Quartiles q;
    if (v.empty()) return q;
    std::sort(v.begin(), v.end());
    auto at = [&](double f) {
        const double x = f * double(v.size() - 1);
        const size_t i = size_t(x);
        const double w = x - double(i);
        return i + 1 < v.size() ? v[i] * (1.0 - w) + v[i + 1] * w : v[i];
    };
    q.q1 = at(0.25);
    q.median = at(0.5);
    q.q3 = at(0.75);
    return q;
}

struct Mesh {
    std::string name;
    raykit::SvoMeshData data;
    std::unique_ptr<rkgl::MeshGl> gl;
};

struct Row {
    std::string mesh, config;
    int depth = 0, width = 0, height = 0;
    Quartiles ms, ratio;
    double err = 0.0, err_px = 0.0;  // vs full detail (LOD rows)
    double voxels = 0.0;
    double rays_root = 0.0;  // pixels whose ray enters the root cube (the rays that traverse)
};

/// How many pixel-centre rays of a w x h frame (camera inv(proj * view)) enter the box [lo, lo + size]
/// (a float64 slab test): the rays the voxel pass traverses; the rest leave at the root clip.
size_t rays_entering_box(const glm::mat4& proj, const glm::mat4& view, int w, int h, glm::vec3 lo, float size)
{
    const glm::dmat4 inv = glm::inverse(glm::dmat4(proj) * glm::dmat4(view));
    size_t n = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double nx = 2.0 * (x + 0.5) / w - 1.0, ny = 2.0 * (y + 0.5) / h - 1.0;
            glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
            const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
            double t0 = 0.0, t1 = 1e300;
            for (int k = 0; k < 3; ++k) {
                const double lo_k = double(lo[k]), hi_k = double(lo[k]) + double(size);
                if (d[k] == 0.0) {
                    if (o[k] < lo_k || o[k] > hi_k) t1 = -1.0;
                    continue;
                }
                double ta = (lo_k - o[k]) / d[k], tb = (hi_k - o[k]) / d[k];
                if (ta > tb) std::swap(ta, tb);
                t0 = std::max(t0, ta);
                t1 = std::min(t1, tb);
            }
            n += t0 <= t1;
        }
    return n;
}

/// The compute form of the voxel pass (config "compute"): one invocation per pixel, the same ray
/// set-up and traversal as rk_svo_gl.hpp's fragment shader, the hit's colour word (0 for a miss)
/// written to a buffer.
const char* const kComputeSource = R"(#version 450 core
#extension GL_GOOGLE_include_directive : require
#include "raykit/svo_traverse.glsl"
#include "raykit/svo_hybrid.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 1) readonly buffer RkColors { uint rk_colors[]; };
layout(std430, binding = 3) writeonly buffer RkOut { uint rk_out[]; };
layout(location = 1) uniform mat4 u_clip_to_obj;
layout(location = 2) uniform float u_z_near_ndc;
layout(location = 3) uniform uvec4 u_tree;   // depth, max_level, desc_words, brick_base_word
layout(location = 4) uniform vec4 u_root;    // root_min, root_size
layout(location = 5) uniform uvec2 u_size;
void main()
{
    uvec2 px = gl_GlobalInvocationID.xy;
    if (px.x >= u_size.x || px.y >= u_size.y) return;
    vec2 ndc = (vec2(px) + 0.5) / vec2(u_size) * 2.0 - 1.0;
    vec3 o, d;
    rk_svo_pixel_ray(u_clip_to_obj, ndc, u_z_near_ndc, o, d);
    rk_svo_tree tree;
    tree.depth = u_tree.x; tree.max_level = u_tree.y; tree.desc_words = u_tree.z; tree.brick_base_word = u_tree.w;
    tree.root_min = u_root.xyz; tree.root_size = u_root.w;
    rk_svo_trace_hit h = rk_svo_trace(0u, tree, o, d, 3.402823e38, vec2(0.0));
    rk_out[px.y * u_size.x + px.x] = h.hit ? (rk_colors[rk_svo_trace_attr(0u, tree, h)] | 0xFF000000u) : 0u;
}
)";

/// "P; R": million pixel rays per second (every pixel of the frame casts one) and million rays
/// entering the root cube per second, at the row's median frame time.
std::string mrays(const Row& r)
{
    const double s = std::max(r.ms.median, 1e-9) * 1e-3;
    char b[64];
    std::snprintf(b, sizeof b, "%.0f; %.0f", double(r.width) * double(r.height) / s * 1e-6, r.rays_root / s * 1e-6);
    return b;
}

}  // namespace

int main(int argc, char** argv)
{
    bool smoke = false;
    int rounds = 7;
    std::string md_path, png_path;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--smoke") smoke = true;
        else if (a == "--rounds" && i + 1 < argc) rounds = std::max(1, std::atoi(argv[++i]));
        else if (a == "--md" && i + 1 < argc) md_path = argv[++i];
        else if (a == "--png" && i + 1 < argc) png_path = argv[++i];
        else {
            std::fprintf(stderr, "usage: bench_svo_gl [--rounds N] [--md FILE] [--png FILE] [--smoke]\n");
            return 1;
        }
    }
    if (smoke) rounds = 2;
    rkgl::HeadlessContext ctx;
    if (!ctx.create()) return rkgl::no_context_exit("bench_svo_gl", ctx.error());
    const std::string renderer = ctx.renderer();
    const bool software = renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
    std::printf("bench_svo_gl: %s\n", renderer.c_str());

    std::vector<Mesh> meshes;
    meshes.push_back({"figure (1,024 tris)", rkmesh::figure(), nullptr});
    if (!smoke) meshes.push_back({"uv_sphere (69,632 tris)", rkmesh::uv_sphere(256, 137), nullptr});
    for (Mesh& m : meshes) {
        raykit::SvoMeshMaterial mat;
        mat.values.base_color = glm::vec4(0.3f, 0.5f, 0.85f, 1.0f);
        m.data.materials.assign(1, mat);
        m.data.material_ids.assign(m.data.indices.size() / 3, 0);
        std::vector<glm::vec3> n = m.data.normals;
        if (n.size() != m.data.positions.size()) n.assign(m.data.positions.size(), glm::vec3(0.0f, 1.0f, 0.0f));
        m.gl = std::make_unique<rkgl::MeshGl>(m.data.positions, n, m.data.indices);
    }
    const std::vector<int> depths = smoke ? std::vector<int>{6} : std::vector<int>{8, 9, 10, 11};
    const std::vector<std::pair<int, int>> sizes = smoke ? std::vector<std::pair<int, int>>{{128, 96}}
                                                         : std::vector<std::pair<int, int>>{{640, 480}, {1280, 720}};
    const float lod_px[3] = {1.0f, 2.0f, 4.0f};
    const char* const configs[6] = {"raster", "voxels", "lod1", "lod2", "lod4", "compute"};
    constexpr int kConfigs = 6, kCompute = 5;
    const GLuint compute_prog = rkgl::build_program(
        {{GL_COMPUTE_SHADER, rkgl::resolved_shader(kComputeSource, "svo_bench.comp", RAYKIT_SHADER_DIR, {RAYKIT_SHADER_DIR}, {})}});
    GLuint query = 0;
    glGenQueries(1, &query);
    std::vector<Row> rows;
    bool ok = true;
    std::vector<unsigned char> showcase;
    int show_w = 0, show_h = 0;

    for (Mesh& m : meshes) {
        // Camera: looking at the bounding box's centre from a distance that fills about half the frame.
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const glm::vec3& p : m.data.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const glm::vec3 c = 0.5f * (lo + hi);
        const float r = 0.5f * glm::length(hi - lo);
        const glm::mat4 view = glm::lookAt(c + glm::normalize(glm::vec3(0.5f, 0.35f, 1.0f)) * (2.6f * r), c, glm::vec3(0.0f, 1.0f, 0.0f));
        for (int depth : depths) {
            raykit::SvoBuildOptions opt;
            opt.depth = depth;
            opt.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL;
            raykit::SvoTree tree;
            raykit::SvoStatus st;
            if (!raykit::build_svo(m.data.view(), opt, tree, st)) {
                std::fprintf(stderr, "bench_svo_gl: build failed: %s\n", st.message.c_str());
                return 1;
            }
            rkgl::SvoGlObject obj(tree, RAYKIT_SHADER_DIR);
            for (const auto& [w, h] : sizes) {
                rkgl::DepthTarget target(w, h);
                const float fov = 0.8f;
                const glm::mat4 proj = raykit::svo_perspective(fov, float(w) / float(h), 0.05f, 100.0f, raykit::SvoDepthConvention::gl_minus_one_to_one);
                glEnable(GL_DEPTH_TEST);
                glDepthFunc(GL_LESS);
                const double rays_root = double(rays_entering_box(proj, view, w, h, tree.root_min, tree.root_size));
                const GLuint out_buf = rkgl::make_buffer(size_t(w) * size_t(h) * 4, nullptr);
                const raykit::SvoHybridView hv = raykit::svo_hybrid_view(glm::mat4(1.0f), view, proj, raykit::SvoDepthConvention::gl_minus_one_to_one);
                auto draw = [&](int k) {
                    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
                    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                    glFinish();
                    const auto t0 = std::chrono::steady_clock::now();
                    glBeginQuery(GL_TIME_ELAPSED, query);
                    if (k == 0) {
                        m.gl->draw(glm::mat4(1.0f), view, proj, glm::vec3(0.3f, 0.5f, 0.85f), glm::vec3(0.4f, 0.8f, 0.45f));
                    } else if (k == kCompute) {
                        glUseProgram(compute_prog);
                        glUniformMatrix4fv(1, 1, GL_FALSE, &hv.clip_to_obj[0][0]);
                        glUniform1f(2, hv.z_near_ndc);
                        glUniform4ui(3, tree.depth, tree.depth, tree.desc_words, tree.gpu_brick_base_word());
                        glUniform4f(4, tree.root_min.x, tree.root_min.y, tree.root_min.z, tree.root_size);
                        glUniform2ui(5, GLuint(w), GLuint(h));
                        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, obj.words_buffer());
                        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, obj.colors_buffer());
                        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, out_buf);
                        glDispatchCompute(GLuint((w + 7) / 8), GLuint((h + 7) / 8), 1);
                    } else {
                        rkgl::SvoDrawParams p;
                        p.fov_y = fov;
                        p.lod_pixels = k >= 2 ? lod_px[k - 2] : 0.0f;
                        obj.draw(glm::mat4(1.0f), view, proj, raykit::SvoDepthConvention::gl_minus_one_to_one, p);
                    }
                    glEndQuery(GL_TIME_ELAPSED);
                    glFinish();
                    const double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                    GLuint64 ns = 0;
                    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
                    // llvmpipe's timer queries do not cover its deferred rasterisation: there the wall
                    // clock between two glFinish calls is the frame time; on a GPU, the query.
                    return software ? wall : double(ns) * 1e-6;
                };
                // Warm-up and images.
                std::vector<std::vector<unsigned char>> img(kConfigs);
                for (int k = 0; k < kConfigs; ++k) {
                    draw(k);
                    img[size_t(k)] = target.read_rgba8(false);
                }
                glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
                const std::vector<float> compute_words = rkgl::read_floats(out_buf, size_t(w) * size_t(h));
                std::vector<std::vector<double>> ms(kConfigs), ratio(kConfigs);
                for (int round = 0; round < rounds; ++round) {
                    double t[kConfigs];
                    for (int j = 0; j < kConfigs; ++j) {
                        const int k = (j + round) % kConfigs;
                        t[k] = draw(k);
                    }
                    for (int k = 0; k < kConfigs; ++k) {
                        ms[size_t(k)].push_back(t[k]);
                        ratio[size_t(k)].push_back(t[k] / std::max(t[0], 1e-6));
                    }
                }
                for (int k = 0; k < kConfigs; ++k) {
                    Row row;
                    row.mesh = m.name;
                    row.config = configs[k];
                    row.depth = depth;
                    row.width = w;
                    row.height = h;
                    row.ms = quartiles(ms[size_t(k)]);
                    row.ratio = quartiles(ratio[size_t(k)]);
                    row.voxels = double(tree.voxel_count);
                    row.rays_root = rays_root;
                    if (k >= 2 && k < kCompute) {
                        double sum = 0.0;
                        size_t big = 0;
                        const std::vector<unsigned char>& a = img[1];
                        const std::vector<unsigned char>& b = img[size_t(k)];
                        for (size_t i = 0; i + 3 < a.size(); i += 4) {
                            int dmax = 0;
                            for (int ch = 0; ch < 3; ++ch) {
                                const int d = std::abs(int(a[i + size_t(ch)]) - int(b[i + size_t(ch)]));
                                sum += d;
                                dmax = std::max(dmax, d);
                            }
                            big += dmax > 8;
                        }
                        row.err = sum / double(a.size() / 4 * 3);
                        row.err_px = 100.0 * double(big) / double(a.size() / 4);
                    }
                    rows.push_back(row);
                    std::printf("%-24s d%-2d %4dx%-4d %-6s %8.3f ms (q1 %.3f q3 %.3f) x%.2f raster%s%s\n", m.name.c_str(), depth, w, h,
                                configs[k], row.ms.median, row.ms.q1, row.ms.q3, row.ratio.median,
                                k >= 1 ? (" " + mrays(row)).c_str() : "",
                                k >= 2 && k < kCompute ? (" err " + std::to_string(row.err).substr(0, 5) + " lv").c_str() : "");
                }
                // Sanity: the voxels cover what the raster covers (a conservative surface voxelisation
                // covers a little more: silhouettes grow by up to a voxel; thin limbs at depth 6 by a third).
                // The compute pass must hit what the fragment pass hits (the same rays: pixel centres).
                size_t cov_r = 0, cov_v = 0, differ = 0;
                for (size_t i = 0; i + 3 < img[0].size(); i += 4) {
                    cov_r += img[0][i] + img[0][i + 1] + img[0][i + 2] > 0;
                    const bool frag_hit = img[1][i] + img[1][i + 1] + img[1][i + 2] > 0;  // cleared to black
                    cov_v += frag_hit;
                    uint32_t word;
                    std::memcpy(&word, &compute_words[i / 4], 4);
                    differ += (word != 0u) != frag_hit;
                }
                if (cov_r == 0 || double(cov_v) < 0.97 * double(cov_r) || double(cov_v) > 1.6 * double(cov_r) + 64.0) {
                    std::fprintf(stderr, "bench_svo_gl: coverage check failed: raster %zu px, voxels %zu px\n", cov_r, cov_v);
                    ok = false;
                }
                std::printf("%-24s d%-2d %4dx%-4d compute vs fragment pass: %zu of %zu hit pixels differ\n", m.name.c_str(), depth, w, h,
                            differ, cov_v);
                if (double(differ) > 1e-3 * double(cov_v) + 4.0) {
                    std::fprintf(stderr, "bench_svo_gl: the compute pass hits %zu pixels other than the fragment pass\n", differ);
                    ok = false;
                }
                glDeleteBuffers(1, &out_buf);
                if (!png_path.empty() && m.name == meshes[0].name && depth == depths.back() && w == sizes.back().first) {
                    // Full detail, LOD 4 px, and their difference x4, side by side.
                    show_w = 3 * w;
                    show_h = h;
                    showcase.assign(size_t(show_w) * size_t(h) * 4, 0);
                    for (int y = 0; y < h; ++y)
                        for (int x = 0; x < w; ++x) {
                            const size_t s = (size_t(h - 1 - y) * size_t(w) + size_t(x)) * 4;
                            for (int panel = 0; panel < 3; ++panel) {
                                const size_t dpx = (size_t(y) * size_t(show_w) + size_t(panel * w + x)) * 4;
                                for (int ch = 0; ch < 4; ++ch) {
                                    const int a = img[1][s + size_t(ch)], b = img[4][s + size_t(ch)];
                                    showcase[dpx + size_t(ch)] = panel == 0 ? (unsigned char)a : panel == 1 ? (unsigned char)b
                                                                 : ch == 3 ? (unsigned char)255 : (unsigned char)std::min(255, 4 * std::abs(a - b));
                                }
                            }
                        }
                }
            }
        }
    }
    glDeleteProgram(compute_prog);
    glDeleteQueries(1, &query);
    if (!png_path.empty() && !showcase.empty()) rkgl::write_png_rgba8(png_path, show_w, show_h, showcase.data());

    if (!md_path.empty()) {
        std::ofstream md(md_path);
        md << "| mesh | depth | size | config | frame ms (median, q1-q3) | x raster (median, q1-q3) | Mrays/s (pixels; rays into the root) | LOD error vs full (mean levels, % px > 8) |\n";
        md << "|---|---:|---|---|---:|---:|---:|---:|\n";
        char b[512];
        for (const Row& r : rows) {
            const bool fast = r.ms.median < 1.0;  // a GPU: three decimals keep two significant digits
            std::snprintf(b, sizeof b, fast ? "| %s | %d | %dx%d | %s | %.3f (%.3f-%.3f) | %.2f (%.2f-%.2f) | %s | %s |\n"
                                            : "| %s | %d | %dx%d | %s | %.2f (%.2f-%.2f) | %.2f (%.2f-%.2f) | %s | %s |\n",
                          r.mesh.c_str(), r.depth,
                          r.width, r.height, r.config.c_str(), r.ms.median, r.ms.q1, r.ms.q3, r.ratio.median, r.ratio.q1, r.ratio.q3,
                          r.config == "raster" ? "" : mrays(r).c_str(),
                          r.config.rfind("lod", 0) == 0 ? (std::to_string(r.err).substr(0, 5) + ", " + std::to_string(r.err_px).substr(0, 4) + " %").c_str()
                                                        : "");
            md << b;
        }
        // Time saving vs error, for the plot (scripts/bench_svo_gl.sh).
        std::ofstream dat(md_path + ".dat");
        dat << "# mesh depth width lod_px time_vs_full err_levels\n";
        for (const Row& r : rows) {
            if (r.config.rfind("lod", 0) != 0) continue;
            const Row* full = nullptr;
            for (const Row& f : rows)
                if (f.config == "voxels" && f.mesh == r.mesh && f.depth == r.depth && f.width == r.width) full = &f;
            if (full) dat << (r.mesh.rfind("figure", 0) == 0 ? "figure" : "sphere") << " " << r.depth << " " << r.width << " "
                          << r.config.substr(3) << " " << r.ms.median / std::max(full->ms.median, 1e-9) << " " << r.err << "\n";
        }
    }
    if (!ok) return 1;
    return 0;
}
