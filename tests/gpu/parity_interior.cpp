// GPU parity cases for shaders/raykit/hash.glsl and interior_mapping.glsl (see parity.hpp): every
// shared function, on thousands of ordinary and adversarial inputs. Integer results (hash halves,
// family, side, room, valid) are compared bit-exactly; t, depth, uv, derivatives and pos with the
// case's relative tolerance.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/interior_mapping.hpp"
#include "raykit/interior_surface.hpp"

using namespace raykit;
using parity::Domain;
namespace dom = parity::dom;

// A 32-bit key from two inputs in [0, 1] (16 bits each), exact in both languages.
#define RK_KEY(i, j) (uint(clamp(a[i], 0.0f, 1.0f) * 65535.0f) | (uint(clamp(a[j], 0.0f, 1.0f) * 65535.0f) << 16u))
// A uint output as two exactly representable floats.
#define RK_EMIT_U(k, v) o[k] = float((v) & 65535u); o[k + 1] = float((v) >> 16u);
// A small integer from an input in [-1, 1].
#define RK_INT(i) int(clamp(a[i], -1.0f, 1.0f) * 1000.0f)
// Every field of an rk_im_hit.
#define RK_EMIT_HIT(h)                                                                                        \
    o[0] = h.t; o[1] = h.depth; o[2] = float(h.family); o[3] = float(h.side); o[4] = float(h.room.x);         \
    o[5] = float(h.room.y); o[6] = float(h.room.z); o[7] = h.uv.x; o[8] = h.uv.y; o[9] = h.uv_dx.x;           \
    o[10] = h.uv_dx.y; o[11] = h.uv_dy.x; o[12] = h.uv_dy.y; o[13] = h.pos.x; o[14] = h.pos.y; o[15] = h.pos.z; \
    o[16] = h.valid ? 1.0f : 0.0f;
// The inputs of a trace row: raw (every adversarial value reaches the function) or structured
// (clamped to a scene-like range, then on-grid facades, parallel rays, grazing cameras). The
// on-grid snap goes through rk_im_grid_coord, whose subnormal coordinates are 0 on every build: a
// floor of (p - origin) / size computed here directly would put a point 1e-38 below the origin in
// another room on a flushing driver than on the CPU, before the trace even starts.
#define RK_TRACE_RAW                                                                                          \
    rk_im_grid g; g.room_size = vec3(a[9], a[10], a[11]); g.origin = vec3(a[12], a[13], a[14]);              \
    vec3 p = vec3(a[0], a[1], a[2]); vec3 cam = vec3(a[3], a[4], a[5]); vec3 n = vec3(a[6], a[7], a[8]);
// Raw values clamped to the documented exact domain (|grid coordinate| < 2^22 rooms).
#define RK_TRACE_DOMAIN                                                                                       \
    RK_TRACE_RAW_GRAD p = clamp(p, vec3(-1e5f), vec3(1e5f)); cam = clamp(cam, vec3(-1e5f), vec3(1e5f));      \
    g.origin = clamp(g.origin, vec3(-1e5f), vec3(1e5f));                                                      \
    g.room_size = clamp(abs(g.room_size), vec3(0.25f), vec3(1e4f));
#define RK_TRACE_RAW_GRAD RK_TRACE_RAW vec3 dpx = vec3(a[15], a[16], a[17]); vec3 dpy = vec3(a[18], a[19], a[20]);
#define RK_TRACE_SCENE                                                                                        \
    rk_im_grid g; g.room_size = clamp(vec3(a[9], a[10], a[11]), vec3(0.5f), vec3(5.0f));                     \
    g.origin = clamp(vec3(a[12], a[13], a[14]), vec3(-5.0f), vec3(5.0f));                                    \
    vec3 p = clamp(vec3(a[0], a[1], a[2]), vec3(-30.0f), vec3(30.0f));                                      \
    vec3 cam = clamp(vec3(a[3], a[4], a[5]), vec3(-100.0f), vec3(100.0f));                                  \
    vec3 n = vec3(0.0f, 0.0f, 1.0f);                                                                          \
    float rk_mode = clamp(a[15], 0.0f, 1.0f);                                                                    \
    if (rk_mode < 0.5f) p.z = g.origin.z + floor(rk_im_grid_coord(p, g).z) * g.room_size.z;                    \
    cam.z = p.z + abs(cam.z) * (rk_mode > 0.9f ? 1e-4f : 1.0f) + 1e-3f;                                          \
    if (rk_mode > 0.3f && rk_mode < 0.6f) cam.x = p.x;                                                              \
    if (rk_mode > 0.45f && rk_mode < 0.7f) cam.y = p.y;                                                             \
    if (rk_mode > 0.7f && rk_mode < 0.8f) p.x = g.origin.x + floor(rk_im_grid_coord(p, g).x) * g.room_size.x;         \
    vec3 dpx = clamp(vec3(a[16], a[17], 0.0f), vec3(-0.1f), vec3(0.1f));                                    \
    vec3 dpy = clamp(vec3(a[18], a[19], 0.0f), vec3(-0.1f), vec3(0.1f));

// RK_PARITY stringises its body without expanding macros; this wrapper expands them first so the
// shader receives the same expanded text as the C++ compiler.
#define RK_PARITY_X(...) RK_PARITY(__VA_ARGS__)

namespace {

const std::vector<int> kHitExact = {2, 3, 4, 5, 6, 16};

/// Whether two hit rows agree: the exact fields equal, the others within the trace tolerance.
/// Used by the hardware ties: each hit position component may also differ by 2 ulps of the
/// larger term it is computed from, max(|origin|, |pos - origin|): on the plane's axis pos = origin +
/// plane * size, which GLSL lets a driver contract into a fused multiply-add (NVIDIA does: it skips
/// the product's rounding, up to 0.5 ulp; the C++ build rounds it, 0.5 ulp), and the room size the
/// tie moved by an ulp to reproduce the driver's grid coordinate moves plane * size by about 1 ulp
/// (H200: 1.1 such ulps, 0.013 at 7.9e4 rooms from an origin at 1e5).
bool same_hit(const float* g, const float* h, const rk_im_grid& grid)
{
    for (int k = 0; k < 17; ++k) {
        const bool ex = std::find(kHitExact.begin(), kHitExact.end(), k) != kHitExact.end();
        double tol = 1e-5 + 1e-4 * std::abs(static_cast<double>(h[k]));
        if (k >= 13 && k <= 15) {
            const double o = grid.origin[k - 13];
            tol += std::ldexp(std::max(std::abs(o), std::abs(static_cast<double>(h[k]) - o)), -22);
        }
        if (ex ? g[k] != h[k] : !(std::abs(static_cast<double>(g[k]) - h[k]) <= tol)) return false;
    }
    return true;
}

using SceneTrace = rk_im_hit (*)(const float* a, vec3 p, vec3 cam, vec3 n, vec3 dpx, vec3 dpy, rk_im_grid g);

/// The hardware tie of the "scene" rows: they put p exactly on a grid plane (a facade, or a wall
/// plane the ray starts on), where the trace's "next plane strictly beyond" is decided by the last
/// ulp of the grid coordinate; a driver's fused multiply-adds (in the snap itself) and its 2.5-ulp
/// division (in rk_im_grid_coord) land on the other side. The input perturbation of the
/// conditioning allowance cannot reach it (the snap floors it away), so the row is a tie when the
/// C++ trace from the snapped p, cam and room size, each component moved by up to 4 ulps, gives the
/// GPU's hit.
bool hw_trace_tie_after_setup(SceneTrace trace, const float* a, const float* gpu, vec3 p, vec3 cam, vec3 n, vec3 dpx,
                              vec3 dpy, rk_im_grid g);

std::function<bool(const float*, const float*, const float*)> hw_scene_tie(SceneTrace trace)
{
    return [trace](const float* a, const float* gpu, const float*) {
        if (!parity::hardware_allowances()) return false;
        RK_TRACE_SCENE
        return hw_trace_tie_after_setup(trace, a, gpu, p, cam, n, dpx, dpy, g);
    };
}

/// The same for the "domain" rows, whose set-up clamps (a coordinate clamped to 1e5 cannot be moved
/// by moving the raw input): the C++ trace from the clamped p, cam, room size and origin.
std::function<bool(const float*, const float*, const float*)> hw_domain_tie(SceneTrace trace)
{
    return [trace](const float* a, const float* gpu, const float*) {
        if (!parity::hardware_allowances()) return false;
        RK_TRACE_DOMAIN
        if (hw_trace_tie_after_setup(trace, a, gpu, p, cam, n, dpx, dpy, g)) return true;
        for (int t = 0; t < 48; ++t) {  // the origin alone, +-1..8 ulps
            rk_im_grid gg = g;
            gg.origin[t / 16] = parity::ulp_step(gg.origin[t / 16], (t % 8 + 1) * ((t / 8) % 2 ? -1 : 1), true);
            float o[17] = {};
            rk_im_hit h = trace(a, p, cam, n, dpx, dpy, gg);
            RK_EMIT_HIT(h)
            if (same_hit(gpu, o, gg)) return true;
        }
        return false;
    };
}

bool hw_trace_tie_after_setup(SceneTrace trace, const float* a, const float* gpu, vec3 p, vec3 cam, vec3 n, vec3 dpx,
                              vec3 dpy, rk_im_grid g)
{
    {
        // p, cam and the room size each alone to +-1..4 ulps (the room size moves the grid coordinate
        // by ulps of itself, which p near the origin cannot), then 64 joint moves.
        for (int t = 0; t < 9 * 8 + 64; ++t) {
            vec3 pp = p, cc = cam;
            rk_im_grid gg = g;
            if (t < 72) {
                const int comp = t / 8, steps = (t % 4 + 1) * ((t / 4) % 2 ? -1 : 1);
                float& v = comp < 3 ? pp[comp] : (comp < 6 ? cc[comp - 3] : gg.room_size[comp - 6]);
                v = parity::ulp_step(v, steps, true);
            } else {
                for (int k = 0; k < 3; ++k) {
                    pp[k] = parity::ulp_step(pp[k], (t * 7 + k * 3) % 9 - 4, true);
                    cc[k] = parity::ulp_step(cc[k], (t * 5 + k * 11) % 9 - 4, true);
                    gg.room_size[k] = parity::ulp_step(gg.room_size[k], (t * 3 + k * 5) % 9 - 4, true);
                }
            }
            float o[17] = {};
            rk_im_hit h = trace(a, pp, cc, n, dpx, dpy, gg);
            RK_EMIT_HIT(h)
            if (same_hit(gpu, o, gg)) return true;
        }
        return false;
    }
}

rk_im_hit scene_trace_grad(const float*, vec3 p, vec3 cam, vec3 n, vec3 dpx, vec3 dpy, rk_im_grid g)
{
    return rk_im_trace_grad(p, cam, n, dpx, dpy, g);
}

rk_im_hit domain_trace_varying(const float* a, vec3 p, vec3 cam, vec3 n, vec3, vec3, rk_im_grid g)
{
    return rk_im_trace_varying(p, cam, n, g, vec3(a[21], a[22], a[23]), RK_KEY(24, 25));
}

rk_im_hit scene_trace_varying_grad(const float* a, vec3 p, vec3 cam, vec3 n, vec3 dpx, vec3 dpy, rk_im_grid g)
{
    return rk_im_trace_varying_grad(p, cam, n, dpx, dpy, g, vec3(a[21], a[22], a[23]), RK_KEY(24, 25));
}

std::vector<Domain> trace_domains(bool scene)
{
    std::vector<Domain> d;
    for (int i = 0; i < 3; ++i) d.push_back(dom::range(-30.0f, 30.0f));      // p
    for (int i = 0; i < 3; ++i) d.push_back(dom::range(-100.0f, 100.0f));    // cam
    for (int i = 0; i < 3; ++i) d.push_back(dom::signed_unit());             // n
    for (int i = 0; i < 3; ++i) d.push_back(dom::range(0.5f, 5.0f));         // room size
    for (int i = 0; i < 3; ++i) d.push_back(dom::range(-5.0f, 5.0f));        // origin
    if (scene) d.push_back(dom::unit());                                      // mode
    else d.push_back(dom::range(-0.1f, 0.1f));
    for (int i = 0; i < 5; ++i) d.push_back(dom::range(-0.1f, 0.1f));        // derivatives
    d.push_back(dom::unit());                                                 // jitter x
    d.push_back(dom::unit());                                                 // jitter y
    d.push_back(dom::unit());                                                 // jitter z
    d.push_back(dom::unit());                                                 // seed bits
    d.push_back(dom::unit());
    return d;
}

struct Entry {
    parity::Case c;
    std::vector<int> exact;
};

std::vector<Entry> interior_cases()
{
    const char* H = "raykit/hash.glsl";
    const char* I = "raykit/interior_mapping.glsl";
    const std::vector<Domain> u2 = {dom::unit(), dom::unit()};
    std::vector<Entry> e;
    e.push_back({RK_PARITY_X("rk_pcg3d", H, (dom::unit(), dom::unit(), dom::unit(), dom::unit(), dom::unit(), dom::unit()), 6,
                             uvec3 h = rk_pcg3d(uvec3(RK_KEY(0, 1), RK_KEY(2, 3), RK_KEY(4, 5)));
                             RK_EMIT_U(0, h.x) RK_EMIT_U(2, h.y) RK_EMIT_U(4, h.z)),
                 {0, 1, 2, 3, 4, 5}});
    e.push_back({RK_PARITY_X("rk_hash_u32", H, (dom::unit(), dom::unit()), 2, uint h = rk_hash_u32(RK_KEY(0, 1)); RK_EMIT_U(0, h)),
                 {0, 1}});
    e.push_back({RK_PARITY_X("rk_u32_to_unit", H, (dom::unit(), dom::unit()), 1, o[0] = rk_u32_to_unit(RK_KEY(0, 1));), {0}});
    e.push_back({RK_PARITY_X("rk_im_room_random", I, (dom::signed_unit(), dom::signed_unit(), dom::signed_unit(), dom::unit(), dom::unit()),
                             1, o[0] = rk_im_room_random(ivec3(RK_INT(0), RK_INT(1), RK_INT(2)), RK_KEY(3, 4));),
                 {0}});
    e.push_back({RK_PARITY_X("rk_im_face_random", I,
                             (dom::signed_unit(), dom::signed_unit(), dom::signed_unit(), dom::unit(), dom::unit(), dom::range(0.0f, 3.0f),
                              dom::signed_unit()),
                             1,
                             o[0] = rk_im_face_random(ivec3(RK_INT(0), RK_INT(1), RK_INT(2)), int(clamp(a[5], -1.0f, 4.0f)),
                                                      a[6] > 0.0f ? 1 : -1, RK_KEY(3, 4));),
                 {0}});
    e.push_back({RK_PARITY_X("rk_im_room_lit", I,
                             (dom::signed_unit(), dom::signed_unit(), dom::signed_unit(), dom::unit(), dom::unit(), dom::unit()), 1,
                             o[0] = rk_im_room_lit(ivec3(RK_INT(0), RK_INT(1), RK_INT(2)), a[5], RK_KEY(3, 4)) ? 1.0f : 0.0f;),
                 {0}});
    e.push_back({RK_PARITY_X("rk_im_jitter", I, (dom::signed_unit(), dom::unit(), dom::range(0.0f, 2.0f)), 3,
                             vec3 j = rk_im_jitter(vec3(a[0], a[1], a[2])); o[0] = j.x; o[1] = j.y; o[2] = j.z;),
                 {0, 1, 2}});
    e.push_back({RK_PARITY_X("rk_im_wall_offset", I, (dom::range(0.0f, 3.0f), dom::signed_unit(), dom::unit(), dom::unit(), dom::unit()),
                             1, o[0] = rk_im_wall_offset(int(clamp(a[0], 0.0f, 2.0f)), RK_INT(1), a[2], RK_KEY(3, 4));),
                 {0}});
    e.push_back({RK_PARITY_X("rk_im_grid_coord", I,
                             (dom::range(-100.0f, 100.0f), dom::range(-100.0f, 100.0f), dom::range(-100.0f, 100.0f), dom::range(0.5f, 5.0f),
                              dom::range(-5.0f, 5.0f)),
                             3, rk_im_grid g; g.room_size = vec3(a[3], a[3] * 1.5f, 2.0f); g.origin = vec3(a[4], 0.0f, -a[4]);
                             vec3 q = rk_im_grid_coord(vec3(a[0], a[1], a[2]), g); o[0] = q.x; o[1] = q.y; o[2] = q.z;),
                 {}});
    e.push_back({RK_PARITY_X("rk_im_room_at", I,
                             (dom::range(-100.0f, 100.0f), dom::range(-100.0f, 100.0f), dom::range(-100.0f, 100.0f), dom::range(0.5f, 5.0f),
                              dom::range(-5.0f, 5.0f)),
                             3, rk_im_grid g; g.room_size = vec3(a[3], a[3] * 1.5f, 2.0f); g.origin = vec3(a[4], 0.0f, -a[4]);
                             ivec3 r = rk_im_room_at(vec3(a[0], a[1], a[2]), g);
                             o[0] = float(r.x); o[1] = float(r.y); o[2] = float(r.z);),
                 {0, 1, 2}});
    e.push_back({RK_PARITY_X("rk_im_room_at_varying", I,
                             (dom::range(-100.0f, 100.0f), dom::range(-100.0f, 100.0f), dom::range(-100.0f, 100.0f), dom::range(0.5f, 5.0f),
                              dom::range(-5.0f, 5.0f), dom::unit(), dom::unit(), dom::unit()),
                             3, rk_im_grid g; g.room_size = vec3(a[3], a[3] * 1.5f, 2.0f); g.origin = vec3(a[4], 0.0f, -a[4]);
                             ivec3 r = rk_im_room_at_varying(vec3(a[0], a[1], a[2]), g, vec3(a[5], a[5], a[5]), RK_KEY(6, 7));
                             o[0] = float(r.x); o[1] = float(r.y); o[2] = float(r.z);),
                 {0, 1, 2}});

    // The traces. "raw": every adversarial value (1e30, -3.4e38, denormals, zero normals...)
    // reaches the function; outside the documented exact domain (|grid coordinate| >= 2^22 rooms)
    // only finiteness is promised, so these rows are checked for finite GPU outputs only (an
    // infinite tolerance: 3e38 was not, as values of opposite signs near FLT_MAX differ by more).
    // "domain": the same rows clamped into the exact domain, every field compared. "scene":
    // building-like rays: on-grid facades, parallel rays, cameras 1e-3 from the facade.
    parity::Case c;
    c = RK_PARITY_X("rk_im_trace raw (finite)", I, (Domain{}), 17, RK_TRACE_RAW rk_im_hit h = rk_im_trace(p, cam, n, g); RK_EMIT_HIT(h));
    c.inputs = trace_domains(false);
    c.abs_tol = std::numeric_limits<double>::infinity();
    e.push_back({c, {}});
    c = RK_PARITY_X("rk_im_trace_grad raw (finite)", I, (Domain{}), 17,
                    RK_TRACE_RAW_GRAD rk_im_hit h = rk_im_trace_grad(p, cam, n, dpx, dpy, g); RK_EMIT_HIT(h));
    c.inputs = trace_domains(false);
    c.abs_tol = std::numeric_limits<double>::infinity();
    e.push_back({c, {}});
    c = RK_PARITY_X("rk_im_trace_varying_grad raw (finite)", I, (Domain{}), 17,
                    RK_TRACE_RAW_GRAD rk_im_hit h = rk_im_trace_varying_grad(p, cam, n, dpx, dpy, g, vec3(a[21], a[22], a[23]),
                                                                              RK_KEY(24, 25));
                    RK_EMIT_HIT(h));
    c.inputs = trace_domains(false);
    c.abs_tol = std::numeric_limits<double>::infinity();
    e.push_back({c, {}});
    c = RK_PARITY_X("rk_im_trace domain", I, (Domain{}), 17, RK_TRACE_DOMAIN o[0] = dpx.x + dpy.x; /* unused here */ rk_im_hit h = rk_im_trace(p, cam, n, g); RK_EMIT_HIT(h));
    c.inputs = trace_domains(false);
    e.push_back({c, kHitExact});
    c = RK_PARITY_X("rk_im_trace_grad domain", I, (Domain{}), 17,
                    RK_TRACE_DOMAIN rk_im_hit h = rk_im_trace_grad(p, cam, n, dpx, dpy, g); RK_EMIT_HIT(h));
    c.inputs = trace_domains(false);
    e.push_back({c, kHitExact});
    c = RK_PARITY_X("rk_im_trace_grad scene", I, (Domain{}), 17,
                    RK_TRACE_SCENE rk_im_hit h = rk_im_trace_grad(p, cam, n, dpx, dpy, g); RK_EMIT_HIT(h));
    c.inputs = trace_domains(true);
    c.tie = hw_scene_tie(scene_trace_grad);
    e.push_back({c, kHitExact});
    c = RK_PARITY_X("rk_im_trace_varying domain", I, (Domain{}), 17,
                    RK_TRACE_DOMAIN o[0] = dpx.x + dpy.x; rk_im_hit h = rk_im_trace_varying(p, cam, n, g, vec3(a[21], a[22], a[23]), RK_KEY(24, 25));
                    RK_EMIT_HIT(h));
    c.inputs = trace_domains(false);
    c.tie = hw_domain_tie(domain_trace_varying);
    e.push_back({c, kHitExact});
    c = RK_PARITY_X("rk_im_trace_varying_grad scene", I, (Domain{}), 17,
                    RK_TRACE_SCENE rk_im_hit h = rk_im_trace_varying_grad(p, cam, n, dpx, dpy, g, vec3(a[21], a[22], a[23]),
                                                                           RK_KEY(24, 25));
                    RK_EMIT_HIT(h));
    c.inputs = trace_domains(true);
    c.tie = hw_scene_tie(scene_trace_varying_grad);
    e.push_back({c, kHitExact});
    // interior_surface.glsl: the texel choice of each room-texture mode, on the scene traces
    // (displaced walls, so the cube direction is exercised where the regular cell differs).
    const char* S = "raykit/interior_surface.glsl";
    c = RK_PARITY_X("rk_im_array_layer / rk_im_surface_kind", S, (Domain{}), 3,
                    RK_TRACE_SCENE rk_im_hit h = rk_im_trace_varying_grad(p, cam, n, dpx, dpy, g, vec3(a[21], a[22], a[23]), RK_KEY(24, 25));
                    o[0] = rk_im_array_layer(h, 1.0f + 7.0f * clamp(a[20], 0.0f, 1.0f), RK_KEY(24, 25));
                    o[1] = float(rk_im_surface_kind(h)); o[2] = rk_im_variant(h, 3.0f, RK_KEY(25, 24)););
    c.inputs = trace_domains(true);
    e.push_back({c, {0, 1, 2}});
    c = RK_PARITY_X("rk_im_cube_lookup", S, (Domain{}), 10,
                    RK_TRACE_SCENE rk_im_hit h = rk_im_trace_varying_grad(p, cam, n, dpx, dpy, g, vec3(a[21], a[22], a[23]), RK_KEY(24, 25));
                    rk_im_cube_coord cc = rk_im_cube_lookup(h, 1.0f + 15.0f * clamp(a[20], 0.0f, 1.0f), RK_KEY(24, 25));
                    o[0] = cc.dir.x; o[1] = cc.dir.y; o[2] = cc.dir.z; o[3] = cc.dx.x; o[4] = cc.dx.y; o[5] = cc.dx.z;
                    o[6] = cc.dy.x; o[7] = cc.dy.y; o[8] = cc.dy.z; o[9] = cc.layer;);
    c.inputs = trace_domains(true);
    c.abs_tol = 1e-5;
    c.rel_tol = 1e-4;
    e.push_back({c, {9}});
    c = RK_PARITY_X("rk_im_atlas_uv / rk_im_atlas_grad_scale", S,
                    (dom::unit(), dom::unit(), dom::unit(), dom::range(1.0f, 16.0f), dom::range(8.0f, 512.0f), dom::range(0.0f, 8.0f),
                     dom::range(0.0f, 8.0f), dom::range(-0.05f, 0.05f), dom::range(-0.05f, 0.05f), dom::range(-0.05f, 0.05f),
                     dom::range(-0.05f, 0.05f)),
                    4,
                    vec4 atlas = vec4(floor(clamp(a[3], 1.0f, 16.0f)), floor(clamp(a[4], 8.0f, 512.0f)), floor(clamp(a[5], 0.0f, 8.0f)), a[6]);
                    float index = floor(clamp(a[2], 0.0f, 1.0f) * (atlas.x * atlas.x - 1.0f));
                    float s; vec2 uv = rk_im_atlas_uv(vec2(a[0], a[1]), index, atlas, s);
                    o[0] = uv.x; o[1] = uv.y; o[2] = s;
                    o[3] = rk_im_atlas_grad_scale(vec2(a[7], a[8]) * s, vec2(a[9], a[10]) * s, atlas););
    c.abs_tol = 1e-6;
    c.rel_tol = 4e-7;
    e.push_back({c, {}});
    c = RK_PARITY_X("rk_im_cube_rotate", S, (dom::signed_unit(), dom::signed_unit(), dom::signed_unit(), dom::range(0.0f, 5.0f)), 3,
                    vec3 v = rk_im_cube_rotate(vec3(a[0], a[1], a[2]), int(clamp(a[3], 0.0f, 5.0f)));
                    o[0] = v.x; o[1] = v.y; o[2] = v.z;);
    e.push_back({c, {0, 1, 2}});
    return e;
}

}  // namespace

TEST(GpuParity, InteriorMapping)
{
    long rows = 0;
    for (Entry& en : interior_cases()) {
        // uv derivatives of grazing rays reach 1e6..1e30 and go through divisions (2.5 ulp in GLSL).
        if (en.c.n_out == 17 && en.c.abs_tol < 1.0) {
            en.c.abs_tol = 1e-5;
            en.c.rel_tol = 1e-4;
            // Domain rows with coordinates up to 1e5 and derivatives up to 1e10: on hardware, the
            // continuous fields within 1e-6 of the row's largest output (a fused origin + plane
            // size moves pos by an ulp of 1e5), the hit's identity still exact.
            if (!en.c.tie) en.c.tie = parity::hw_row_scale_tie(17, 1e-6, kHitExact);
        }
        const parity::Result r = parity::run(en.c, parity::shader_dir(), 4096, en.exact);
        rows += r.rows;
        EXPECT_TRUE(r.ok) << en.c.name << ": " << r.mismatches << " mismatches, worst " << r.worst;
        EXPECT_EQ(r.non_finite, 0) << en.c.name;
    }
    std::printf("[parity] interior: %ld input rows in total\n", rows);
}

TEST(GpuParity, InteriorTraceAutoVariants)
{
    // RK_IM_VARYING_WALLS selects the trace in the shader as in C++.
    for (int mode = 0; mode < 2; ++mode) {
        parity::Case c = RK_PARITY_X("rk_im_trace_auto", "raykit/interior_mapping.glsl", (Domain{}), 17,
                                     RK_TRACE_SCENE rk_im_hit h = rk_im_trace_auto(p, cam, n, dpx, dpy, g, vec3(a[21], a[22], a[23]),
                                                                                   RK_KEY(24, 25));
                                     RK_EMIT_HIT(h));
        c.name += " RK_IM_VARYING_WALLS=" + std::to_string(mode);
        c.inputs = trace_domains(true);
        c.defines = {{"RK_IM_VARYING_WALLS", std::to_string(mode)}};
        c.abs_tol = 1e-5;
        c.rel_tol = 1e-4;
        // The C++ side: this translation unit is built with the default (0); mode 1 is the varying trace.
        c.cpu = [mode](const float* a, float* o) {
            RK_TRACE_SCENE
            rk_im_hit h = mode ? rk_im_trace_varying_grad(p, cam, n, dpx, dpy, g, vec3(a[21], a[22], a[23]), RK_KEY(24, 25))
                               : rk_im_trace_grad(p, cam, n, dpx, dpy, g);
            RK_EMIT_HIT(h)
        };
        c.tie = hw_scene_tie(mode ? scene_trace_varying_grad : scene_trace_grad);
        const parity::Result r = parity::run(c, parity::shader_dir(), 2048, kHitExact);
        EXPECT_TRUE(r.ok) << c.name << ": worst " << r.worst;
    }
}
