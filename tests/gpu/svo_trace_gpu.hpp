// Runs rk_svo_trace on the driver (a compute shader over a ray buffer) and compares it with the C++
// build, for parity_svo_trace.cpp (RK_SVO_TRAVERSE_LOD=0) and parity_svo_trace_lod.cpp (=1): the two
// translation units compile the C++ traversal with different macros into one executable, which is
// itself the check that the builds do not collide (svo_traverse.hpp's inline namespaces).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/svo_traverse.hpp"
#include "svo_trace_rays.hpp"
#include "rk_svo_gl.hpp"

namespace svotrace_gpu {

/// One traced ray, as both builds report it.
struct Out {
    uint32_t hit, t_bits, level, cx, cy, cz, face, attr, iterations, bound;  ///< bound: rk_svo_trace_iteration_bound
};

inline uint32_t face_code(glm::vec3 n)
{
    for (int a = 0; a < 3; ++a)
        if (n[a] != 0.0f) return static_cast<uint32_t>(2 * a + (n[a] > 0.0f ? 1 : 0));
    return 7u;
}

/// rk_svo_trace of every ray with this translation unit's C++ build (its RK_SVO_TRAVERSE_* macros;
/// the rk_svo_tree parameter's type carries them, so each build gets its own function).
inline std::vector<Out> cpu_trace(const std::vector<uint32_t>& words, const raykit::rk_svo_tree& tree,
                                  const std::vector<svotrace::Ray>& rays, glm::vec2 cone)
{
    std::vector<Out> out(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
        const raykit::rk_svo_trace_hit h = raykit::rk_svo_trace(words.data(), tree, rays[i].origin, rays[i].dir, rays[i].t_max, cone);
        uint32_t tb;
        std::memcpy(&tb, &h.t, 4);
        out[i] = {h.hit ? 1u : 0u, tb, h.level, h.cell.x, h.cell.y, h.cell.z, face_code(h.normal),
                  h.hit ? raykit::rk_svo_trace_attr(words.data(), tree, h) : 0u, h.iterations,
                  raykit::rk_svo_trace_iteration_bound(tree)};
    }
    return out;
}

/// rk_svo_trace of every ray on the driver, words from an SSBO or the R32UI texture layout.
inline std::vector<Out> gpu_trace(const raykit::SvoTree& t, const raykit::rk_svo_tree& tree,
                                  const std::vector<svotrace::Ray>& rays, bool lod, glm::vec2 cone, bool texture)
{
    using namespace raykit;
    const std::vector<uint32_t> words = t.gpu_words();
    std::string src = "#version 450 core\n#extension GL_GOOGLE_include_directive : require\n";
    src += "layout(local_size_x = 64) in;\n";
    src += "layout(std430, binding = 1) readonly buffer Rays { vec4 rk_rays[]; };\n";
    src += "layout(std430, binding = 2) writeonly buffer Out { uint rk_out[]; };\n";
    src += "layout(location = 0) uniform uint rk_n;\n";
    src += "layout(location = 1) uniform uvec4 rk_tree_u;\nlayout(location = 2) uniform vec4 rk_tree_f;\n";
    src += "layout(location = 3) uniform vec2 rk_cone;\n";
    src += "#include \"raykit/svo_traverse.glsl\"\n";
    src += "uint face_code(vec3 n) { if (n.x != 0.0) return n.x > 0.0 ? 1u : 0u; if (n.y != 0.0) return n.y > 0.0 ? 3u : 2u;\n"
           "  if (n.z != 0.0) return n.z > 0.0 ? 5u : 4u; return 7u; }\n";
    src += "void main() {\n  uint i = gl_GlobalInvocationID.x;\n  if (i >= rk_n) return;\n";
    src += "  rk_svo_tree tr; tr.depth = rk_tree_u.x; tr.max_level = rk_tree_u.y; tr.desc_words = rk_tree_u.z;\n"
           "  tr.brick_base_word = rk_tree_u.w; tr.root_min = rk_tree_f.xyz; tr.root_size = rk_tree_f.w;\n";
    src += "  vec4 a = rk_rays[2u * i]; vec4 b = rk_rays[2u * i + 1u];\n";
    src += "  rk_svo_trace_hit h = rk_svo_trace(0u, tr, a.xyz, b.xyz, b.w, rk_cone);\n";
    src += "  uint o = 10u * i;\n";
    src += "  rk_out[o] = h.hit ? 1u : 0u; rk_out[o + 1u] = floatBitsToUint(h.t); rk_out[o + 2u] = h.level;\n"
           "  rk_out[o + 3u] = h.cell.x; rk_out[o + 4u] = h.cell.y; rk_out[o + 5u] = h.cell.z;\n"
           "  rk_out[o + 6u] = face_code(h.normal); rk_out[o + 7u] = h.hit ? rk_svo_trace_attr(0u, tr, h) : 0u;\n"
           "  rk_out[o + 8u] = h.iterations; rk_out[o + 9u] = rk_svo_trace_iteration_bound(tr);\n}\n";
    std::vector<ShaderDefine> defs = {{"RK_SVO_WORDS_BINDING", "0"},
                                      {"RK_SVO_BUFFER_TEXTURE", texture ? "1" : "0"},
                                      {"RK_SVO_TRAVERSE_LOD", lod ? "1" : "0"}};
    src = rkgl::resolved_shader(src, "svo_trace.comp", parity::shader_dir(), {parity::shader_dir()}, defs);
    GLuint prog = rkgl::build_program({{GL_COMPUTE_SHADER, src}});
    const rkgl::SvoWordsGl bound_words(words, texture);
    std::vector<glm::vec4> rv;
    rv.reserve(2 * rays.size());
    for (const svotrace::Ray& r : rays) {
        rv.push_back(glm::vec4(r.origin, 0.0f));
        rv.push_back(glm::vec4(r.dir, r.t_max));
    }
    GLuint brays = rkgl::make_buffer(rv.size() * sizeof(glm::vec4), rv.data());
    GLuint bout = rkgl::make_buffer(rays.size() * sizeof(Out), nullptr);
    glUseProgram(prog);
    glUniform1ui(0, static_cast<GLuint>(rays.size()));
    glUniform4ui(1, tree.depth, tree.max_level, tree.desc_words, tree.brick_base_word);
    glUniform4f(2, tree.root_min.x, tree.root_min.y, tree.root_min.z, tree.root_size);
    glUniform2f(3, cone.x, cone.y);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, brays);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, bout);
    glDispatchCompute(static_cast<GLuint>((rays.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<Out> out(rays.size());
    glGetNamedBufferSubData(bout, 0, static_cast<GLsizeiptr>(out.size() * sizeof(Out)), out.data());
    GLuint bufs[2] = {brays, bout};
    glDeleteBuffers(2, bufs);
    glDeleteProgram(prog);
    return out;
}

inline float float_of(uint32_t u)
{
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

/// The parameter interval [t0, t1] in which the ray (in double) is inside the node box grown by
/// `grow` root sizes on every side (negative shrinks); false when it never is.
inline bool node_interval(const svotrace::Ray& r, const Out& o, glm::vec3 root_min, float root_size, double grow,
                          double& t0, double& t1)
{
    const double cs = double(root_size) / double(1u << o.level);
    const glm::dvec3 lo = glm::dvec3(root_min) + cs * glm::dvec3(o.cx, o.cy, o.cz) - grow * double(root_size);
    const double w = cs + 2.0 * grow * double(root_size);
    if (w <= 0.0) return false;
    t0 = 0.0;
    t1 = double(r.t_max);
    for (int a = 0; a < 3; ++a) {
        const double oa = r.origin[a], da = r.dir[a];
        if (da == 0.0) {
            if (oa < lo[a] || oa > lo[a] + w) return false;
            continue;
        }
        double ta = (lo[a] - oa) / da, tb = (lo[a] + w - oa) / da;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::fmax(t0, ta);
        t1 = std::fmin(t1, tb);
    }
    return t0 <= t1;
}

/// Whether o + t * dir (double) lies on the node's box surface within `tol` root sizes (or, for
/// t = 0, anywhere in the grown box: the origin is inside the node).
inline bool on_node(const svotrace::Ray& r, double t, const Out& o, glm::vec3 root_min, float root_size, double tol)
{
    const double cs = double(root_size) / double(1u << o.level);
    const glm::dvec3 lo = glm::dvec3(root_min) + cs * glm::dvec3(o.cx, o.cy, o.cz);
    const glm::dvec3 p = glm::dvec3(r.origin) + t * glm::dvec3(r.dir);
    return svotrace::surface_distance(p, lo, cs, t == 0.0) <= tol * double(root_size);
}

/// Compares driver and C++ results ray by ray: the same node (level and cell), attribute and entry
/// face for every ray (the face may differ only where the ray enters through an edge), both hit
/// points on the node's surface within `tol` root sizes (on_node). Exceptions are ties: where
/// the builds report different nodes, or one misses, each reported node must be touched by the
/// exact (double) ray within `tol`, and neither build may have passed through the other's node
/// shrunk by `tol`: two equally valid first hits of a ray that grazes an edge, corner or face.
/// For origins far from the root the tolerance grows by 8 float ULPs of the origin's distance
/// (in root sizes), the rounding of the ray's start (documented in svo_traverse.glsl). Ties may
/// be at most 1 % of the rays (0-0.6 % measured), and the C++ build must hit at least `min_hits`
/// times, counting only the rays aimed at voxels (family 10) where the set has any (a set that
/// misses tests nothing).
inline long compare(const char* what, const std::vector<svotrace::Ray>& rays, const std::vector<Out>& gpu,
                    const std::vector<Out>& cpu, glm::vec3 root_min, float root_size, double tol, long min_hits)
{
    long bad = 0, ties = 0, face_ties = 0, hits = 0, aimed = 0, aimed_hits = 0;
    double worst_t = 0.0;
    const glm::dvec3 centre = glm::dvec3(root_min) + 0.5 * double(root_size);
    for (size_t i = 0; i < rays.size(); ++i) {
        const Out& g = gpu[i];
        const Out& c = cpu[i];
        const svotrace::Ray& r = rays[i];
        hits += c.hit ? 1 : 0;
        aimed += r.family == 10 ? 1 : 0;
        aimed_hits += r.family == 10 && c.hit ? 1 : 0;
        const glm::dvec3 d(r.dir);
        const double dl = glm::length(d);
        const double dist = glm::length(glm::dvec3(r.origin) - centre) / double(root_size);
        const double tol_i = tol + 8.0 * 0x1p-24 * dist;
        const double tunit = double(root_size) / dl;  // t per root size along the ray
        bool ok = true;
        const bool same = g.hit == c.hit && (!g.hit || (g.level == c.level && g.cx == c.cx && g.cy == c.cy && g.cz == c.cz));
        if (same && g.hit) {
            // Both hit points on the node's surface: a conditioning-free check of t (a grazing
            // entry amplifies position rounding into t).
            const double tg = float_of(g.t_bits), tc = float_of(c.t_bits);
            const double dt = std::fabs(tg - tc) / tunit;
            worst_t = std::fmax(worst_t, dt);
            ok = g.attr == c.attr && on_node(r, tg, g, root_min, root_size, tol_i) && on_node(r, tc, c, root_min, root_size, tol_i);
            // The entry faces may differ only at an edge or corner: a hit point on both face planes.
            if (ok && g.face != c.face && tg > 0.0 && tc > 0.0) {
                ++face_ties;
                const double cs = double(root_size) / double(1u << g.level);
                const glm::dvec3 lo = glm::dvec3(root_min) + cs * glm::dvec3(g.cx, g.cy, g.cz);
                auto on_face = [&](double t, uint32_t face) {
                    if (face > 5u) return false;
                    const int ax = int(face / 2);
                    const double plane = (face & 1u) ? lo[ax] + cs : lo[ax];
                    const double p = double(r.origin[ax]) + t * double(r.dir[ax]);
                    return std::fabs(p - plane) <= tol_i * double(root_size) + 1e-6 * std::fabs(plane);
                };
                // (One build's t may carry a grazing axis's conditioning; the other then marks the edge.)
                ok = (on_face(tg, c.face) && on_face(tg, g.face)) || (on_face(tc, g.face) && on_face(tc, c.face));
            }
        } else if (!same) {
            ++ties;
            const Out* both[2] = {&g, &c};
            for (int k = 0; k < 2 && ok; ++k) {
                const Out& x = *both[k];
                const Out& y = *both[1 - k];
                if (!x.hit) continue;
                double t0, t1;
                const double tx = float_of(x.t_bits);
                // x's node is touched by the exact ray near where x says.
                ok = node_interval(r, x, root_min, root_size, tol_i, t0, t1) && tx >= t0 - tol_i * tunit - 8e-7 * tx &&
                     tx <= t1 + tol_i * tunit + 8e-7 * tx;
                // y did not pass through x's node (shrunk) before reporting its own.
                if (ok && node_interval(r, x, root_min, root_size, -tol_i, t0, t1) && t1 - t0 > 2.0 * tol_i * tunit)
                    ok = y.hit && float_of(y.t_bits) <= t0 + tol_i * tunit + 8e-7 * t0;
            }
        }
        ok = ok && g.bound == c.bound;  // the same loop bound (rk_svo_trace_iteration_bound) in both builds
        if (!ok) {
            if (bad < 5)
                ADD_FAILURE() << what << " ray " << i << " (" << svotrace::family_names[r.family] << ") o=(" << r.origin.x
                              << "," << r.origin.y << "," << r.origin.z << ") d=(" << r.dir.x << "," << r.dir.y << ","
                              << r.dir.z << ") t_max " << r.t_max << ": gpu hit " << g.hit << " t " << float_of(g.t_bits)
                              << " L" << g.level << " (" << g.cx << "," << g.cy << "," << g.cz << ") attr " << g.attr
                              << " | cpu hit " << c.hit << " t " << float_of(c.t_bits) << " L" << c.level << " (" << c.cx
                              << "," << c.cy << "," << c.cz << ") attr " << c.attr;
            ++bad;
        }
    }
    std::printf("[parity] rk_svo_trace %-34s %7zu rays, %6ld hits: %ld mismatches, %ld ties, %ld edge-face ties, worst |t_gpu - t_cpu| %.2e root\n",
                what, rays.size(), hits, bad, ties, face_ties, worst_t);
    EXPECT_EQ(bad, 0) << what;
    EXPECT_LE(ties, long(rays.size() / 100)) << what;
    EXPECT_GE(aimed > 0 ? aimed_hits : hits, min_hits) << what;
    return ties;
}

}  // namespace svotrace_gpu
