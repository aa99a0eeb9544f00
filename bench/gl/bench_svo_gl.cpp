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
// 1, 2, 4 pixels).
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
};

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
    const char* const configs[5] = {"raster", "voxels", "lod1", "lod2", "lod4"};
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
                auto draw = [&](int k) {
                    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
                    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
                    glFinish();
                    const auto t0 = std::chrono::steady_clock::now();
                    glBeginQuery(GL_TIME_ELAPSED, query);
                    if (k == 0) {
                        m.gl->draw(glm::mat4(1.0f), view, proj, glm::vec3(0.3f, 0.5f, 0.85f), glm::vec3(0.4f, 0.8f, 0.45f));
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
                std::vector<std::vector<unsigned char>> img(5);
                for (int k = 0; k < 5; ++k) {
                    draw(k);
                    img[size_t(k)] = target.read_rgba8(false);
                }
                std::vector<std::vector<double>> ms(5), ratio(5);
                for (int round = 0; round < rounds; ++round) {
                    double t[5];
                    for (int j = 0; j < 5; ++j) {
                        const int k = (j + round) % 5;
                        t[k] = draw(k);
                    }
                    for (int k = 0; k < 5; ++k) {
                        ms[size_t(k)].push_back(t[k]);
                        ratio[size_t(k)].push_back(t[k] / std::max(t[0], 1e-6));
                    }
                }
                for (int k = 0; k < 5; ++k) {
                    Row row;
                    row.mesh = m.name;
                    row.config = configs[k];
                    row.depth = depth;
                    row.width = w;
                    row.height = h;
                    row.ms = quartiles(ms[size_t(k)]);
                    row.ratio = quartiles(ratio[size_t(k)]);
                    row.voxels = double(tree.voxel_count);
                    if (k >= 2) {
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
                    std::printf("%-24s d%-2d %4dx%-4d %-6s %8.2f ms (q1 %.2f q3 %.2f) x%.2f raster%s\n", m.name.c_str(), depth, w, h,
                                configs[k], row.ms.median, row.ms.q1, row.ms.q3, row.ratio.median,
                                k >= 2 ? (" err " + std::to_string(row.err).substr(0, 5) + " lv").c_str() : "");
                }
                // Sanity: the voxels cover what the raster covers (a conservative surface voxelisation
                // covers a little more: silhouettes grow by up to a voxel; thin limbs at depth 6 by a third).
                size_t cov_r = 0, cov_v = 0;
                for (size_t i = 0; i + 3 < img[0].size(); i += 4) {
                    cov_r += img[0][i] + img[0][i + 1] + img[0][i + 2] > 0;
                    cov_v += img[1][i] + img[1][i + 1] + img[1][i + 2] > 0;
                }
                if (cov_r == 0 || double(cov_v) < 0.97 * double(cov_r) || double(cov_v) > 1.6 * double(cov_r) + 64.0) {
                    std::fprintf(stderr, "bench_svo_gl: coverage check failed: raster %zu px, voxels %zu px\n", cov_r, cov_v);
                    ok = false;
                }
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
    glDeleteQueries(1, &query);
    if (!png_path.empty() && !showcase.empty()) rkgl::write_png_rgba8(png_path, show_w, show_h, showcase.data());

    if (!md_path.empty()) {
        std::ofstream md(md_path);
        md << "| mesh | depth | size | config | frame ms (median, q1-q3) | x raster (median, q1-q3) | LOD error vs full (mean levels, % px > 8) |\n";
        md << "|---|---:|---|---|---:|---:|---:|\n";
        char b[512];
        for (const Row& r : rows) {
            std::snprintf(b, sizeof b, "| %s | %d | %dx%d | %s | %.2f (%.2f-%.2f) | %.2f (%.2f-%.2f) | %s |\n", r.mesh.c_str(), r.depth,
                          r.width, r.height, r.config.c_str(), r.ms.median, r.ms.q1, r.ms.q3, r.ratio.median, r.ratio.q1, r.ratio.q3,
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
