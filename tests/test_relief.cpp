// Tests of shaders/raykit/relief.glsl (C++ build) and include/raykit/relief.hpp: the bilinear twin
// against an independent double-precision read; every method's hit-uv error against the exact
// first intersection with the bilinear surface (tests/relief_reference.hpp), printed by method and
// step budget; a thin spike that a coarse linear march steps over and cone stepping does not; the
// cone maps proven conservative by brute force (no cone contains a point of the surface above its
// apex, sampled 12 x 12 per cell), the fast builders against the exact ones with their build times;
// self-shadowing against an exact shadow ray; normal maps; finite results for adversarial inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "raykit/relief.hpp"
#include "relief_reference.hpp"

using namespace raykit;

namespace {

ReliefMapCpu make_map(const std::vector<double>& d, int w, int h, bool wrap)
{
    ReliefMapCpu m;
    m.width = w;
    m.height = h;
    m.wrap = wrap;
    for (double x : d) m.texels.push_back(vec2(float(x), 0.0f));
    return m;
}

relief_ref::Map ref_of(const ReliefMapCpu& m)
{
    relief_ref::Map r;
    r.w = m.width;
    r.h = m.height;
    r.wrap = m.wrap;
    for (const vec2& t : m.texels) r.d.push_back(double(t.x));
    return r;
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

struct Ray {
    vec2 uv;
    vec3 v;
};

/// Random rays: uv in [0, 1)², view directions up to 75 degrees from the normal.
std::vector<Ray> rays(int n, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    std::vector<Ray> out;
    for (int i = 0; i < n; ++i) {
        const float cz = 0.26f + 0.74f * U(rng), phi = 6.2831853f * U(rng), sz = std::sqrt(1.0f - cz * cz);
        out.push_back({vec2(U(rng), U(rng)), vec3(sz * std::cos(phi), sz * std::sin(phi), cz)});
    }
    return out;
}

/// The exact hit of a ray as rk_relief_delta defines it (same float delta, traced in double).
relief_ref::Hit exact_hit(const relief_ref::Map& r, const Ray& ray, float scale)
{
    const vec2 d = rk_relief_delta(ray.v, scale);
    return relief_ref::trace(r, double(ray.uv.x), double(ray.uv.y), double(d.x), double(d.y));
}

/// |hit uv - exact uv| in texels of a w-texel map.
double uv_err_texels(vec3 got, const relief_ref::Hit& h, int w)
{
    const double du = double(got.x) - h.u, dv = double(got.y) - h.v;
    return std::sqrt(du * du + dv * dv) * w;
}

TEST(Relief, ReadMatchesIndependentBilinear)
{
    const int w = 16;
    const std::vector<double> d = relief_ref::test_depths(w, w, 3u);
    for (bool wrap : {true, false}) {
        const ReliefMapCpu m = make_map(d, w, w, wrap);
        const relief_ref::Map r = ref_of(m);
        std::mt19937 rng(5u);
        std::uniform_real_distribution<float> U(-2.0f, 3.0f);
        double worst = 0.0;
        for (int i = 0; i < 20000; ++i) {
            const vec2 uv(U(rng), U(rng));
            worst = std::max(worst, std::abs(double(rk_relief_read(m, uv).x) - r.at(double(uv.x), double(uv.y))));
        }
        EXPECT_LT(worst, 2e-6) << (wrap ? "repeat" : "clamp to edge");
    }
}

TEST(Relief, FiniteForAdversarialInputs)
{
    const int w = 16;
    ReliefMapCpu m = make_map(relief_ref::test_depths(w, w, 3u), w, w, true);
    relief_build_cones(m);
    const float vals[] = {0.0f, -0.0f, 1e-45f, -1e-40f, 1.17549435e-38f, 1.0f, -1.0f, 0.5f, 1e-20f, -1e20f, 1e30f, 3.4028235e38f, -3.4028235e38f};
    int bad = 0;
    for (float a : vals)
        for (float b : vals)
            for (float c : vals) {
                const vec2 uv(a, b);
                const vec3 v(b, c, a);
                const float s = c;
                const vec3 r[] = {rk_relief_parallax(m, uv, v, s),   rk_relief_steep(m, uv, v, s, 8u),
                                  rk_relief_pom(m, uv, v, s, 8u),    rk_relief_relief(m, uv, v, s, 8u, 30u),
                                  rk_relief_cone(m, uv, v, s, 8u),   rk_relief_relaxed_cone(m, uv, v, s, 8u, 8u),
                                  vec3(rk_relief_shadow(m, vec3(a, b, c), v, s, 8u, a))};
                for (const vec3& x : r)
                    if (!std::isfinite(x.x) || !std::isfinite(x.y) || !std::isfinite(x.z)) ++bad;
            }
    EXPECT_EQ(bad, 0);
}

struct Method {
    std::string name;
    std::function<vec3(const ReliefMapCpu&, vec2, vec3, float)> fn;
    const ReliefMapCpu* map;
};

TEST(Relief, ErrorByStepBudget)
{
    const int w = 64;
    const float scale = 0.08f;  // 5 texels deep
    const std::vector<double> d = relief_ref::test_depths(w, w, 7u);
    ReliefMapCpu plain = make_map(d, w, w, true), cones = plain, relaxed = plain;
    relief_build_cones(cones);
    relief_build_relaxed_cones(relaxed, 16);
    const relief_ref::Map r = ref_of(plain);
    const std::vector<Ray> rs = rays(3000, 11u);
    std::vector<relief_ref::Hit> exact;
    for (const Ray& ray : rs) exact.push_back(exact_hit(r, ray, scale));

    std::vector<Method> ms;
    ms.push_back({"parallax (Welsh)", [](const ReliefMapCpu& m, vec2 uv, vec3 v, float s) { return rk_relief_parallax(m, uv, v, s); }, &plain});
    for (uint n : {8u, 16u, 32u, 64u})
        ms.push_back({"steep n=" + std::to_string(n), [n](const ReliefMapCpu& m, vec2 uv, vec3 v, float s) { return rk_relief_steep(m, uv, v, s, n); }, &plain});
    for (uint n : {8u, 16u, 32u, 64u})
        ms.push_back({"pom n=" + std::to_string(n), [n](const ReliefMapCpu& m, vec2 uv, vec3 v, float s) { return rk_relief_pom(m, uv, v, s, n); }, &plain});
    for (uint n : {8u, 16u, 32u})
        ms.push_back({"relief n=" + std::to_string(n) + "+6", [n](const ReliefMapCpu& m, vec2 uv, vec3 v, float s) { return rk_relief_relief(m, uv, v, s, n, 6u); }, &plain});
    for (uint n : {8u, 16u, 32u, 64u})
        ms.push_back({"cone n=" + std::to_string(n), [n](const ReliefMapCpu& m, vec2 uv, vec3 v, float s) { return rk_relief_cone(m, uv, v, s, n); }, &cones});
    for (uint n : {4u, 8u, 16u})
        ms.push_back({"relaxed n=" + std::to_string(n) + "+6", [n](const ReliefMapCpu& m, vec2 uv, vec3 v, float s) { return rk_relief_relaxed_cone(m, uv, v, s, n, 6u); }, &relaxed});

    std::printf("[relief] hit-uv error in texels vs the exact bilinear intersection (64^2 map, depth 5 texels, %zu rays up to 75 deg)\n", rs.size());
    std::printf("[relief] %-20s %10s %10s %10s %12s\n", "method", "max", "mean", "p99", ">1 texel");
    std::map<std::string, double> mean_of, p99_of;
    for (const Method& me : ms) {
        std::vector<double> e;
        for (size_t i = 0; i < rs.size(); ++i) e.push_back(uv_err_texels(me.fn(*me.map, rs[i].uv, rs[i].v, scale), exact[i], w));
        double mx = 0.0, sum = 0.0;
        int over = 0;
        for (double x : e) {
            mx = std::max(mx, x);
            sum += x;
            over += x > 1.0 ? 1 : 0;
        }
        std::sort(e.begin(), e.end());
        const double p99 = e[e.size() * 99 / 100];
        mean_of[me.name] = sum / double(e.size());
        p99_of[me.name] = p99;
        std::printf("[relief] %-20s %10.4f %10.4f %10.4f %11.2f%%\n", me.name.c_str(), mx, sum / double(e.size()), p99, 100.0 * over / double(e.size()));
    }
    // More steps help every marching method; refinement beats the bare linear search.
    EXPECT_LT(mean_of["steep n=64"], mean_of["steep n=8"]);
    EXPECT_LT(mean_of["pom n=32"], mean_of["steep n=32"]);
    EXPECT_LT(mean_of["relief n=32+6"], mean_of["steep n=32"]);
    EXPECT_LT(mean_of["cone n=64"], mean_of["cone n=8"]);
    EXPECT_LT(mean_of["pom n=64"], 0.05);
    EXPECT_LT(p99_of["relief n=32+6"], 0.25);
    EXPECT_LT(mean_of["cone n=64"], mean_of["parallax (Welsh)"]);
}

TEST(Relief, ThinSpikeTunnelsLinearNotCone)
{
    // A flat floor at depth 1 with one texel reaching the polygon (a bilinear spike 2 texels wide).
    const int w = 64;
    std::vector<double> d(size_t(w) * size_t(w), 1.0);
    d[size_t(32) * size_t(w) + 32u] = 0.0;
    ReliefMapCpu m = make_map(d, w, w, false);
    relief_build_cones_exact(m);
    ReliefMapCpu relaxed = m;
    relief_build_relaxed_cones_exact(relaxed);
    const relief_ref::Map r = ref_of(m);
    // Rays along +u through the spike's row, at several angles and start points.
    // Linear: "steps over" = its hit lies more than a texel beyond the spike. Cone stepping on the
    // conservative map never goes past the exact hit (t <= exact t): at worst it is still short of
    // it when the budget ends (the spike narrows every cone around it, so convergence is slow).
    int tunnels = 0, cone_past = 0, relaxed_past = 0, cases = 0, cone_close = 0;
    double worst_cone = 0.0;
    for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 4; ++b) {
            const float vz = 0.2f + 0.05f * float(a);
            const vec3 v(-std::sqrt(1.0f - vz * vz), 0.0f, vz);
            const float scale = 0.1f;
            const vec2 delta = rk_relief_delta(v, scale);
            // Start so that the ray reaches the spike's centre at depth 0.3 + 0.1 b.
            const float tc = 0.3f + 0.1f * float(b);
            const vec2 uv(32.5f / 64.0f - tc * delta.x, 32.5f / 64.0f);
            const relief_ref::Hit h = relief_ref::trace(r, double(uv.x), double(uv.y), double(delta.x), double(delta.y));
            ASSERT_LT(std::abs(h.u * 64.0 - 32.5), 1.0) << "the exact hit is on the spike";
            ++cases;
            const vec3 lin = rk_relief_steep(m, uv, v, scale, 8u);
            if (double(lin.x) * 64.0 > 33.5) ++tunnels;
            const vec3 cone = rk_relief_cone(m, uv, v, scale, 64u);
            if (double(cone.z) > h.t + 1e-5) ++cone_past;
            const vec3 rel = rk_relief_relaxed_cone(relaxed, uv, v, scale, 16u, 8u);
            if (double(rel.x) * 64.0 > 33.5) ++relaxed_past;
            const double ec = uv_err_texels(cone, h, w);
            worst_cone = std::max(worst_cone, ec);
            cone_close += ec < 1.0 ? 1 : 0;
        }
    std::printf("[relief] thin spike: an 8-layer linear march steps over it in %d / %d rays, 64 cone steps in %d (within a texel of the "
                "hit in %d, worst %.2f texels short), relaxed cones (16 + 8) in %d\n",
                tunnels, cases, cone_past, cone_close, worst_cone, relaxed_past);
    EXPECT_GE(tunnels, 8);
    EXPECT_EQ(cone_past, 0);
}

/// The brute-force proof: for every apex texel, no sample of the bilinear surface (sub x sub per
/// cell plus the texel centres) lies inside its cone. Returns the worst violation (> 0: a point
/// inside) and the mean of ratio / (dense sample bound), how much of the truly empty cone is used.
void check_conservative(const ReliefMapCpu& m, int sub, double& worst, double& tightness)
{
    const relief_ref::Map r = ref_of(m);
    struct P {
        double u, v, d;
    };
    std::vector<P> pts;
    const int nx = m.wrap ? m.width : m.width - 1, ny = m.wrap ? m.height : m.height - 1;
    for (int cy = 0; cy < ny; ++cy)
        for (int cx = 0; cx < nx; ++cx)
            for (int b = 0; b <= sub; ++b)
                for (int a = 0; a <= sub; ++a) {
                    const double u = (cx + 0.5 + double(a) / sub) / m.width, v = (cy + 0.5 + double(b) / sub) / m.height;
                    pts.push_back({u, v, r.at(u, v)});
                }
    worst = -1e300;
    double tsum = 0.0;
    // Apexes: every texel centre, then random points, where the shader mixes four texels' ratios.
    std::vector<vec2> apexes;
    for (int iy = 0; iy < m.height; ++iy)
        for (int ix = 0; ix < m.width; ++ix) apexes.push_back(vec2((float(ix) + 0.5f) / float(m.width), (float(iy) + 0.5f) / float(m.height)));
    const size_t n_centres = apexes.size();
    std::mt19937 rng(23u);
    std::uniform_real_distribution<float> U(-0.1f, 1.1f);
    for (int i = 0; i < 400; ++i) apexes.push_back(vec2(U(rng), U(rng)));
    for (size_t ai = 0; ai < apexes.size(); ++ai) {
        const double xu = double(apexes[ai].x), xv = double(apexes[ai].y), dx = r.at(xu, xv);
        const double c = double(rk_relief_read(m, apexes[ai]).y);
        double dense = 1.0;
        for (const P& p : pts) {
            if (p.d >= dx) continue;
            double du = p.u - xu, dv = p.v - xv;
            if (m.wrap) {
                du -= std::floor(du + 0.5);
                dv -= std::floor(dv + 0.5);
            } else {
                // Clamp to edge: the surface beyond the centres repeats the edge; the nearest copy of
                // an inner point to an outer apex is the point itself, nearer the apex projected.
                du = p.u - std::clamp(xu, 0.5 / m.width, 1.0 - 0.5 / m.width);
                dv = p.v - std::clamp(xv, 0.5 / m.height, 1.0 - 0.5 / m.height);
            }
            const double dist = std::sqrt(du * du + dv * dv);
            // Inside the cone: dist < c (dx - d). Violation measured in uv.
            worst = std::max(worst, c * (dx - p.d) - dist);
            dense = std::min(dense, dist / (dx - p.d));
        }
        if (ai < n_centres) tsum += dense > 0.0 ? c / dense : 1.0;
    }
    tightness = tsum / double(m.width * m.height);
}

TEST(Relief, ConeMapsAreConservative)
{
    struct Case {
        const char* name;
        int w;
        bool wrap;
        int spike;  // 0: test surface; 1: flat floor with a spike
    };
    for (const Case& cs : {Case{"surface 20^2 repeat", 20, true, 0}, Case{"surface 16^2 clamp", 16, false, 0}, Case{"spike 16^2 clamp", 16, false, 1}}) {
        std::vector<double> d;
        if (cs.spike) {
            d.assign(size_t(cs.w) * size_t(cs.w), 1.0);
            d[size_t(cs.w / 2) * size_t(cs.w) + size_t(cs.w / 2)] = 0.0;
        } else {
            d = relief_ref::test_depths(cs.w, cs.w, 9u);
        }
        ReliefMapCpu exact = make_map(d, cs.w, cs.w, cs.wrap), fast = exact;
        auto t0 = std::chrono::steady_clock::now();
        relief_build_cones_exact(exact);
        const double t_exact = seconds_since(t0);
        t0 = std::chrono::steady_clock::now();
        relief_build_cones(fast);
        const double t_fast = seconds_since(t0);
        double we = 0, te = 0, wf = 0, tf = 0;
        check_conservative(exact, 12, we, te);
        check_conservative(fast, 12, wf, tf);
        int narrower = 0;
        for (size_t i = 0; i < exact.texels.size(); ++i) narrower += fast.texels[i].y < exact.texels[i].y ? 1 : 0;
        std::printf("[relief] cones %s (apexes at texel centres and 400 random points): exact %.3f s, fast %.4f s; worst violation exact %.3g, fast %.3g uv (<= 0: none); "
                    "ratio / dense-sampled empty cone: exact %.3f, fast %.3f\n",
                    cs.name, t_exact, t_fast, we, wf, te, tf);
        EXPECT_LE(we, 1e-7) << cs.name;
        EXPECT_LE(wf, 1e-7) << cs.name;
        EXPECT_EQ(narrower, 0) << cs.name << ": the fast builder is never narrower than the exact one";
    }
}

TEST(Relief, BuildTimes)
{
    const int w = 128;
    const std::vector<double> d = relief_ref::test_depths(w, w, 13u);
    ReliefMapCpu m = make_map(d, w, w, true), rx = m;
    auto t0 = std::chrono::steady_clock::now();
    relief_build_cones(m);
    const double tc = seconds_since(t0);
    const int wr = 64;
    ReliefMapCpu small = make_map(relief_ref::test_depths(wr, wr, 13u), wr, wr, true), small_exact = small;
    t0 = std::chrono::steady_clock::now();
    relief_build_relaxed_cones(small, 8);
    const double tr = seconds_since(t0);
    const int we = 32;
    ReliefMapCpu e1 = make_map(relief_ref::test_depths(we, we, 13u), we, we, true), e2 = e1;
    t0 = std::chrono::steady_clock::now();
    relief_build_relaxed_cones_exact(e1);
    const double tre = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    relief_build_cones_exact(e2);
    const double tce = seconds_since(t0);
    double mc = 0;
    for (const vec2& t : m.texels) mc += double(t.y);
    std::printf("[relief] build times: cones fast 128^2 %.3f s (mean ratio %.3f); cones exact 32^2 %.3f s; relaxed window r=8 64^2 %.3f s; "
                "relaxed exact 32^2 %.3f s\n",
                tc, mc / double(m.texels.size()), tce, tr, tre);
    for (const vec2& t : m.texels) ASSERT_TRUE(t.y >= 0.0f && t.y <= 1.0f);
    // Relaxed cones are at least as wide as the empty ones on the same map, on average.
    double sr = 0, sc = 0;
    for (size_t i = 0; i < e1.texels.size(); ++i) {
        sr += double(e1.texels[i].y);
        sc += double(e2.texels[i].y);
    }
    std::printf("[relief] mean cone ratio 32^2: empty %.3f, relaxed %.3f\n", sc / double(e1.texels.size()), sr / double(e1.texels.size()));
    EXPECT_GE(sr, sc);
}

TEST(Relief, SelfShadowAgainstExactShadowRay)
{
    const int w = 64;
    const float scale = 0.08f;
    ReliefMapCpu m = make_map(relief_ref::test_depths(w, w, 7u), w, w, true);
    const relief_ref::Map r = ref_of(m);
    const std::vector<Ray> rs = rays(1500, 17u);
    std::mt19937 rng(19u);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    int agree = 0, shadowed = 0;
    const float bias = 0.01f;
    for (const Ray& ray : rs) {
        const relief_ref::Hit h = exact_hit(r, ray, scale);
        const float lz = 0.3f + 0.6f * U(rng), ph = 6.2831853f * U(rng), ls = std::sqrt(1.0f - lz * lz);
        const vec3 l(ls * std::cos(ph), ls * std::sin(ph), lz);
        const float lit = rk_relief_shadow(m, vec3(float(h.u), float(h.v), float(h.t)), l, scale, 64u, bias);
        const vec2 dl = rk_relief_delta(vec3(-l.x, -l.y, l.z), scale);
        const bool ex = relief_ref::shadowed(r, h.u, h.v, h.t, double(dl.x), double(dl.y), double(bias));
        agree += (lit < 0.5f) == ex ? 1 : 0;
        shadowed += ex ? 1 : 0;
    }
    std::printf("[relief] self-shadowing (64 samples, bias 0.01): agrees with the exact shadow ray at %d / %zu hits (%d shadowed)\n", agree,
                rs.size(), shadowed);
    EXPECT_GE(agree, int(rs.size() * 97 / 100));
    EXPECT_GT(shadowed, int(rs.size() / 20));
    // Light below the horizon: dark; straight above a flat map: lit.
    EXPECT_EQ(rk_relief_shadow(m, vec3(0.5f, 0.5f, 0.5f), vec3(1.0f, 0.0f, -0.1f), scale, 16u, bias), 0.0f);
    ReliefMapCpu flat = make_map(std::vector<double>(16, 0.5), 4, 4, true);
    EXPECT_EQ(rk_relief_shadow(flat, vec3(0.3f, 0.3f, 0.5f), vec3(0.5f, 0.0f, 0.8f), scale, 16u, bias), 1.0f);
}

TEST(Relief, NormalMap)
{
    // Depth rising linearly along u (clamped map): normal (s · dd/du, 0, 1) normalised.
    const int w = 8;
    std::vector<double> d;
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) d.push_back(double(x) / w);
    const ReliefMapCpu m = make_map(d, w, w, false);
    const float s = 0.1f;
    const std::vector<vec3> n = relief_normal_map(m, s);
    ASSERT_EQ(n.size(), size_t(w * w));
    const double k = 1.0 / std::sqrt(double(s) * s + 1.0);  // dd/du = 1 per uv
    for (int y = 0; y < w; ++y)
        for (int x = 0; x < w; ++x) {
            const vec3 v = n[size_t(y * w + x)];
            EXPECT_NEAR(v.x, s * k, 1e-6);
            EXPECT_NEAR(v.y, 0.0, 1e-6);
            EXPECT_NEAR(v.z, k, 1e-6);
        }
    // A flat map: straight up; heights to depths.
    const ReliefMapCpu f = relief_from_heights(2, 2, {1.0f, 0.25f, 2.0f, -1.0f});
    EXPECT_EQ(f.texels[1].x, 0.75f);
    EXPECT_EQ(f.texels[2].x, 0.0f);
    EXPECT_EQ(f.texels[3].x, 1.0f);
    for (const vec3& v : relief_normal_map(relief_from_heights(3, 3, std::vector<float>(9, 0.5f)), 0.2f)) EXPECT_EQ(v, vec3(0, 0, 1));
}

TEST(Relief, VerticalRayAndFlatMap)
{
    // Looking straight down: every method hits at uv itself, at the surface depth.
    const int w = 16;
    ReliefMapCpu m = make_map(relief_ref::test_depths(w, w, 3u), w, w, true);
    relief_build_cones(m);
    const relief_ref::Map r = ref_of(m);
    for (float u : {0.1f, 0.37f, 0.8f}) {
        const vec2 uv(u, 1.0f - u);
        const double want = r.at(double(uv.x), double(uv.y));
        EXPECT_NEAR(rk_relief_cone(m, uv, vec3(0, 0, 1), 0.1f, 4u).z, want, 1e-5);
        EXPECT_NEAR(rk_relief_relief(m, uv, vec3(0, 0, 1), 0.1f, 8u, 20u).z, want, 1e-5);
        EXPECT_NEAR(rk_relief_pom(m, uv, vec3(0, 0, 1), 0.1f, 8u).z, want, 1e-5);
        const vec3 p = rk_relief_pom(m, uv, vec3(0, 0, 1), 0.1f, 8u);
        EXPECT_EQ(p.x, uv.x);
        EXPECT_EQ(p.y, uv.y);
    }
}

}  // namespace

namespace {

TEST(Relief, DegenerateHeightfields)
{
    // One texel, a 2 x 1 strip, and heights with NaN (read as the deepest level): the generators
    // finish and every method returns finite hits inside [0, 1] depth.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<ReliefMapCpu> maps = {relief_from_heights(1, 1, {0.3f}), relief_from_heights(2, 1, {1.0f, 0.0f}),
                                      relief_from_heights(3, 3, {nan, 0.5f, 1.0f, 0.2f, nan, 0.9f, 0.0f, 1.0f, nan})};
    for (ReliefMapCpu& m : maps) {
        for (const vec2& t : m.texels) EXPECT_TRUE(std::isfinite(t.x) && t.x >= 0.0f && t.x <= 1.0f);
        ReliefMapCpu cones = m, relaxed = m;
        relief_build_cones(cones);
        relief_build_relaxed_cones(relaxed, 4);
        for (const vec2& t : cones.texels) EXPECT_TRUE(std::isfinite(t.y) && t.y >= 0.0f);
        for (const vec2& t : relaxed.texels) EXPECT_TRUE(std::isfinite(t.y) && t.y >= 0.0f);
        for (const vec3& v : {vec3(0.0f, 0.0f, 1.0f), glm::normalize(vec3(0.7f, -0.2f, 0.3f)), vec3(1.0f, 0.0f, 0.0f)}) {
            const vec2 uv(0.37f, 0.61f);
            const vec3 r[] = {rk_relief_steep(m, uv, v, 0.1f, 16u), rk_relief_pom(m, uv, v, 0.1f, 16u), rk_relief_relief(m, uv, v, 0.1f, 8u, 6u),
                              rk_relief_cone(cones, uv, v, 0.1f, 16u), rk_relief_relaxed_cone(relaxed, uv, v, 0.1f, 8u, 6u)};
            for (const vec3& h : r) {
                EXPECT_TRUE(std::isfinite(h.x) && std::isfinite(h.y) && std::isfinite(h.z));
                EXPECT_GE(h.z, 0.0f);
                EXPECT_LE(h.z, 1.0f);
            }
        }
    }
    // A one-texel map is flat: every method hits at its depth straight below... along the ray.
    const ReliefMapCpu one = relief_from_heights(1, 1, {0.3f});  // depth 0.7 everywhere
    const vec3 hit = rk_relief_pom(one, vec2(0.5f), glm::normalize(vec3(0.3f, 0.0f, 1.0f)), 0.1f, 32u);
    EXPECT_NEAR(hit.z, 0.7f, 1e-4f);
}

}  // namespace
