// Tests of shaders/raykit/normalmap.glsl (C++ build) and include/raykit/tangents.hpp against
// analytic surfaces: a plane (exact frames, mirrored uv), a UV sphere and a cylinder (tangents along
// the parametric derivatives), degenerate uv triangles and bad input (finite unit outputs, clear
// errors), the derivative-based frame against the tangent-based one, unpacking and parallax.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "adversarial_checks.hpp"
#include "raykit/tangents.hpp"

using namespace raykit;
using glm::dvec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

double angle(dvec3 a, dvec3 b)
{
    a = glm::normalize(a);
    b = glm::normalize(b);
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

struct Mesh {
    std::vector<float> pos, nrm, uv;
    std::vector<uint32_t> idx;
    size_t vertices() const { return pos.size() / 3; }
    void vertex(dvec3 p, dvec3 n, double u, double v)
    {
        pos.insert(pos.end(), {float(p.x), float(p.y), float(p.z)});
        nrm.insert(nrm.end(), {float(n.x), float(n.y), float(n.z)});
        uv.insert(uv.end(), {float(u), float(v)});
    }
};

/// A (cols x rows) grid of a parametric surface f(u, v) -> (position, normal), u, v in [0, 1].
template <class F>
Mesh grid(int cols, int rows, F f, bool mirror_u = false)
{
    Mesh m;
    for (int j = 0; j <= rows; ++j)
        for (int i = 0; i <= cols; ++i) {
            const double u = double(i) / cols, v = double(j) / rows;
            dvec3 p, n;
            f(u, v, p, n);
            m.vertex(p, n, mirror_u ? 1.0 - u : u, v);
        }
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < cols; ++i) {
            const uint32_t a = uint32_t(j * (cols + 1) + i), b = a + 1, c = a + uint32_t(cols + 1), d = c + 1;
            m.idx.insert(m.idx.end(), {a, b, d, a, d, c});
        }
    return m;
}

std::vector<vec4> tangents(const Mesh& m)
{
    std::vector<vec4> t;
    Status st;
    EXPECT_TRUE(compute_tangents(m.pos.data(), m.nrm.data(), m.uv.data(), m.vertices(), m.idx.data(), m.idx.size() / 3, t, st))
        << st.message;
    return t;
}

void expect_frames_valid(const Mesh& m, const std::vector<vec4>& t)
{
    ASSERT_EQ(t.size(), m.vertices());
    for (size_t i = 0; i < t.size(); ++i) {
        const dvec3 T(t[i].x, t[i].y, t[i].z), N(m.nrm[3 * i], m.nrm[3 * i + 1], m.nrm[3 * i + 2]);
        ASSERT_TRUE(std::isfinite(T.x) && std::isfinite(T.y) && std::isfinite(T.z)) << i;
        ASSERT_NEAR(glm::length(T), 1.0, 1e-6) << i;
        ASSERT_LE(std::abs(glm::dot(T, glm::normalize(N))), 1e-6) << i << ": T is perpendicular to N";
        ASSERT_TRUE(t[i].w == 1.0f || t[i].w == -1.0f) << i;
    }
}

TEST(Tangents, PlaneIsExactAndMirroredUvIsLeftHanded)
{
    auto plane = [](double u, double v, dvec3& p, dvec3& n) {
        p = dvec3(2.0 * u, 3.0 * v, 0.0);
        n = dvec3(0.0, 0.0, 1.0);
    };
    const Mesh m = grid(4, 3, plane);
    const std::vector<vec4> t = tangents(m);
    expect_frames_valid(m, t);
    for (const vec4& x : t) EXPECT_EQ(x, vec4(1.0f, 0.0f, 0.0f, 1.0f));
    // B = w N x T = +y: along increasing v.
    const mat3 f = rk_nm_tbn(vec3(0, 0, 1), t[0]);
    EXPECT_EQ(f[1], vec3(0.0f, 1.0f, 0.0f));
    // Mirrored u: T along -x (increasing u), w = -1, and B still along increasing v.
    const Mesh mm = grid(4, 3, plane, true);
    const std::vector<vec4> tm = tangents(mm);
    expect_frames_valid(mm, tm);
    for (const vec4& x : tm) EXPECT_EQ(x, vec4(-1.0f, 0.0f, 0.0f, -1.0f));
    EXPECT_EQ(rk_nm_tbn(vec3(0, 0, 1), tm[0])[1], vec3(0.0f, 1.0f, 0.0f));
}

TEST(Tangents, ThesisSignErratum)
{
    // A skewed uv mapping (t1 != 0): position = u * X + v * Y with uv sheared. With the thesis's
    // printed "Q1 = s1 T - t1 B" the solved bitangent points the wrong way; with + it is exact.
    Mesh m;
    const dvec3 n(0, 0, 1);
    // uv -> position: p = (u + 0.5 v, v, 0): T = dp/du = (1, 0, 0), B = dp/dv = (0.5, 1, 0).
    for (auto uv : {glm::dvec2(0, 0), glm::dvec2(1, 0.2), glm::dvec2(0.3, 1)}) m.vertex(dvec3(uv.x + 0.5 * uv.y, uv.y, 0), n, uv.x, uv.y);
    m.idx = {0, 1, 2};
    const std::vector<vec4> t = tangents(m);
    EXPECT_NEAR(angle(dvec3(t[0].x, t[0].y, t[0].z), dvec3(1, 0, 0)), 0.0, 1e-6);
    EXPECT_EQ(t[0].w, 1.0f);
}

TEST(Tangents, SphereAndCylinderFollowTheParametricDerivatives)
{
    // UV sphere: u = longitude, v = latitude from the south pole; T = dP/du direction
    // (-sin phi, cos phi, 0), B = dP/dv, right-handed with the outward normal.
    auto sphere = [](double u, double v, dvec3& p, dvec3& n) {
        const double phi = 2.0 * kPi * u, th = kPi * (v - 0.5);
        n = dvec3(std::cos(th) * std::cos(phi), std::cos(th) * std::sin(phi), std::sin(th));
        p = 2.0 * n;
    };
    // Lengyel's sums are exact on the equator and follow dP/du to O(grid step) elsewhere: this
    // triangulation's diagonals make the rows above and below a vertex weigh unevenly (the error
    // grows towards the poles). Within 60 degrees of the equator, and halving with the step.
    double worst_by_size[2] = {0.0, 0.0};
    for (int g = 0; g < 2; ++g) {
        const int cols = 64 << g, rows = 32 << g;
        const Mesh s = grid(cols, rows, sphere);
        const std::vector<vec4> ts = tangents(s);
        expect_frames_valid(s, ts);
        for (int j = 1; j < rows; ++j) {
            const double lat = kPi * (double(j) / rows - 0.5);
            if (std::abs(lat) > kPi / 3.0 + 1e-9) continue;
            double row = 0.0;
            for (int i = 1; i < cols; ++i) {  // the u seam (vertices not shared) excluded
                const size_t k = size_t(j * (cols + 1) + i);
                const double phi = 2.0 * kPi * i / cols;
                row = std::max(row, angle(dvec3(ts[k].x, ts[k].y, ts[k].z), dvec3(-std::sin(phi), std::cos(phi), 0.0)));
                ASSERT_EQ(ts[k].w, 1.0f) << k;
            }
            if (j == rows / 2) {
                EXPECT_LE(row, 1e-6) << "the equator";
            }
            worst_by_size[g] = std::max(worst_by_size[g], row);
        }
    }
    EXPECT_LE(worst_by_size[0], 2.5e-3) << "64 x 32 sphere tangents vs dP/du within 60 degrees of the equator";
    EXPECT_LE(worst_by_size[1], 0.55 * worst_by_size[0]) << "and half that with half the step";
    // Cylinder around z: u around, v along the axis.
    auto cylinder = [](double u, double v, dvec3& p, dvec3& n) {
        const double phi = 2.0 * kPi * u;
        n = dvec3(std::cos(phi), std::sin(phi), 0.0);
        p = dvec3(n.x, n.y, 4.0 * v);
    };
    const Mesh c = grid(48, 5, cylinder);
    const std::vector<vec4> tc = tangents(c);
    expect_frames_valid(c, tc);
    double worst = 0.0;
    for (int j = 0; j <= 5; ++j)
        for (int i = 1; i < 48; ++i) {
            const size_t k = size_t(j * 49 + i);
            const double phi = 2.0 * kPi * i / 48.0;
            worst = std::max(worst, angle(dvec3(tc[k].x, tc[k].y, tc[k].z), dvec3(-std::sin(phi), std::cos(phi), 0.0)));
            const mat3 f = rk_nm_tbn(vec3(float(std::cos(phi)), float(std::sin(phi)), 0.0f), tc[k]);
            EXPECT_NEAR(f[1].z, 1.0f, 1e-5f) << "B along the axis (increasing v)";
        }
    EXPECT_LE(worst, 1e-5) << "cylinder tangents vs dP/du";
}

TEST(Tangents, DegenerateUvAndBadInput)
{
    Mesh m;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // A triangle with all uvs equal, one with collinear uvs, one with a NaN normal and one with a
    // zero normal, sharing nothing: every vertex falls back to the basis tangent.
    for (int t = 0; t < 4; ++t) {
        const dvec3 n = t == 2 ? dvec3(nan, 0, 1) : (t == 3 ? dvec3(0.0) : glm::normalize(dvec3(0.3, -0.2, 0.9)));
        m.vertex(dvec3(0, 0, t), n, 0.5, 0.5);
        m.vertex(dvec3(1, 0, t), n, t == 1 ? 0.6 : 0.5, t == 1 ? 0.6 : 0.5);
        m.vertex(dvec3(0, 1, t), n, t == 1 ? 0.7 : 0.5, t == 1 ? 0.7 : 0.5);
    }
    m.idx = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    std::vector<vec4> t;
    Status st;
    ASSERT_TRUE(compute_tangents(m.pos.data(), m.nrm.data(), m.uv.data(), m.vertices(), m.idx.data(), 4, t, st));
    for (size_t i = 0; i < t.size(); ++i) {
        const dvec3 T(t[i].x, t[i].y, t[i].z);
        ASSERT_TRUE(std::isfinite(T.x) && std::isfinite(T.y) && std::isfinite(T.z)) << i;
        ASSERT_NEAR(glm::length(T), 1.0, 1e-6) << i;
        EXPECT_EQ(t[i].w, 1.0f);
    }
    // Errors: an index out of range, missing arrays; an empty mesh is fine.
    m.idx[4] = 99;
    EXPECT_FALSE(compute_tangents(m.pos.data(), m.nrm.data(), m.uv.data(), m.vertices(), m.idx.data(), 4, t, st));
    EXPECT_NE(st.message.find("vertex 99"), std::string::npos) << st.message;
    EXPECT_FALSE(compute_tangents(nullptr, m.nrm.data(), m.uv.data(), m.vertices(), nullptr, 1, t, st));
    EXPECT_FALSE(compute_tangents(m.pos.data(), m.nrm.data(), m.uv.data(), 5, nullptr, 2, t, st)) << "6 vertices needed";
    EXPECT_TRUE(compute_tangents(nullptr, nullptr, nullptr, 0, nullptr, 0, t, st));
    EXPECT_TRUE(t.empty());
}

// ---------------------------------------------------------------------------------------------
// normalmap.glsl

TEST(NormalMap, TbnIsOrthonormalAndHandlesDegenerateTangents)
{
    std::mt19937 rng(2u);
    std::normal_distribution<float> g;
    for (int i = 0; i < 100000; ++i) {
        const vec3 n(g(rng), g(rng), g(rng));
        vec4 t(g(rng), g(rng), g(rng), i % 2 ? 1.0f : -1.0f);
        if (i % 7 == 0) t = vec4(n * 3.0f, 1.0f);               // parallel to n
        if (i % 11 == 0) t = vec4(0.0f, 0.0f, 0.0f, -1.0f);       // zero
        if (i % 13 == 0) t = vec4(n + vec3(1e-7f, 0, 0), 1.0f);  // almost parallel
        const mat3 f = rk_nm_tbn(n, t);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(glm::length(dvec3(f[c])), 1.0, 2e-6) << i;
        ASSERT_LE(std::abs(glm::dot(dvec3(f[0]), dvec3(f[2]))), 2e-6) << i;
        ASSERT_LE(std::abs(glm::dot(dvec3(f[1]), dvec3(f[2]))), 2e-6) << i;
        ASSERT_LE(std::abs(glm::dot(dvec3(f[0]), dvec3(f[1]))), 2e-6) << i;
        // Handedness: det(T, B, N) = sign(w).
        const double det = glm::dot(glm::cross(dvec3(f[0]), dvec3(f[1])), dvec3(f[2]));
        ASSERT_NEAR(det, t.w < 0.0f ? -1.0 : 1.0, 1e-5) << i;
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const mat3 f = rk_nm_tbn(vec3(nan, 0, 0), vec4(nan, 1, 0, 0));
    EXPECT_EQ(f[2], vec3(0, 0, 1));
    EXPECT_EQ(f[0], rk_nm_basis_tangent(vec3(0, 0, 1)));
    EXPECT_EQ(rk_nm_perturb(f, vec3(0.0f)), vec3(0, 0, 1));
}

TEST(NormalMap, CotangentFrameMatchesTheTangentFrame)
{
    // A plane p = u * su * A + v * sv * C (A = dP/du, C = dP/dv directions; C = N x A for a
    // right-handed chart, -N x A for a mirrored one) seen front-facing: the screen steps dp1, dp2
    // (dFdx, dFdy) satisfy (dp1 x dp2) . N > 0, and the uv derivatives follow from the chart. The
    // cotangent frame's T and B then point along dP/du and dP/dv, mirrored chart included, and the
    // normal-mapped normal equals the stored-tangent path's for an isotropic map.
    std::mt19937 rng(6u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int n = 0;
    for (int i = 0; i < 4000; ++i) {
        const bool mirrored = i % 2 == 1;
        const dvec3 A = glm::normalize(dvec3(u(rng), u(rng), u(rng)));
        const dvec3 N = glm::normalize(glm::cross(A, glm::normalize(dvec3(u(rng), u(rng), u(rng)))));
        const dvec3 C = (mirrored ? -1.0 : 1.0) * glm::cross(N, A);
        const double s = 1.0 + 0.5 * u(rng);
        // Screen steps on the plane, front-facing, not degenerate.
        dvec3 dp1 = u(rng) * A + u(rng) * C, dp2 = u(rng) * A + u(rng) * C;
        const double o = glm::dot(glm::cross(dp1, dp2), N);
        if (std::abs(o) < 0.05) continue;
        if (o < 0.0) std::swap(dp1, dp2);
        // uv derivatives: dp = s (du A + dv C).
        const glm::dvec2 d1(glm::dot(dp1, A) / s, glm::dot(dp1, C) / s), d2(glm::dot(dp2, A) / s, glm::dot(dp2, C) / s);
        const mat3 cf = rk_nm_cotangent_frame(vec3(N), vec3(dp1), vec3(dp2), vec2(d1), vec2(d2));
        ASSERT_LE(angle(dvec3(cf[0]), A), 2e-5) << i << (mirrored ? " mirrored" : "");
        ASSERT_LE(angle(dvec3(cf[1]), C), 2e-5) << i << (mirrored ? " mirrored" : "");
        const mat3 tf = rk_nm_tbn(vec3(N), vec4(vec3(A), mirrored ? -1.0f : 1.0f));
        const vec3 nts = glm::normalize(vec3(0.3f, -0.4f, 0.8f));
        ASSERT_LE(angle(dvec3(rk_nm_perturb(cf, nts)), dvec3(rk_nm_perturb(tf, nts))), 2e-5) << i;
        ++n;
    }
    EXPECT_GT(n, 3000);
    // Degenerate derivatives: a valid frame around n.
    const mat3 d = rk_nm_cotangent_frame(vec3(0, 1, 0), vec3(0.0f), vec3(0.0f), vec2(0.0f), vec2(0.0f));
    EXPECT_NEAR(glm::length(d[0]), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(d[0], d[2]), 0.0f, 1e-6f);
}

TEST(NormalMap, UnpackAndParallax)
{
    EXPECT_EQ(rk_nm_unpack_rg(vec2(0.5f, 0.5f)), vec3(0, 0, 1));
    std::mt19937 rng(9u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 100000; ++i) {
        const vec2 rg(u(rng), u(rng));
        const vec3 n = rk_nm_unpack_rg(rg);
        ASSERT_NEAR(glm::length(dvec3(n)), 1.0, 3e-7);
        ASSERT_GE(n.z, 0.0f);
        const double x = 2.0 * rg.x - 1.0, y = 2.0 * rg.y - 1.0;
        if (x * x + y * y < 0.99) {
            ASSERT_NEAR(n.x, x, 2e-7);
            ASSERT_NEAR(n.z, std::sqrt(1.0 - x * x - y * y), 4e-6);
        } else if (x * x + y * y > 1.0) {
            ASSERT_EQ(n.z, 0.0f) << "outside the disk: on the circle";
        }
    }
    // Parallax: 0 when h * scale + bias = 0 or the view is along the normal; bounded by |h s + b|.
    EXPECT_EQ(rk_nm_parallax_offset(vec2(0.3f, 0.7f), 0.5f, glm::normalize(vec3(0.5f, 0.2f, 0.3f)), 0.04f, -0.02f), vec2(0.3f, 0.7f));
    EXPECT_EQ(rk_nm_parallax_offset(vec2(0.3f, 0.7f), 0.9f, vec3(0, 0, 1), 0.04f, -0.02f), vec2(0.3f, 0.7f));
    const vec3 graze = glm::normalize(vec3(1.0f, 0.0f, 1e-6f));
    const vec2 o = rk_nm_parallax_offset(vec2(0.0f), 1.0f, graze, 0.04f, -0.02f);
    EXPECT_NEAR(o.x, 0.02f, 1e-7f) << "offset limiting: no division by v.z";
}

TEST(NormalMap, AdversarialInputsGiveFiniteUnitFrames)
{
    using rktest::adv::finite;
    using rktest::adv::Floats;
    using rktest::adv::S;
    using rktest::adv::Vecs;
    const Vecs all = Vecs::all();
    auto unit = [](vec3 v) { return finite(v) && std::abs(glm::length(dvec3(v)) - 1.0) <= 2e-6; };
    ADV("rk_nm_tbn / rk_nm_perturb", {
        const vec3 n = G.v3(all);
        const vec4 t = G.v4(all);
        const mat3 f = rk_nm_tbn(n, t);
        CHECK(unit(f[0]) && unit(f[1]) && unit(f[2]), S(f[0]) + S(f[1]) + S(f[2]));
        CHECK(unit(rk_nm_perturb(f, G.v3(all))), "perturb");
    });
    ADV("rk_nm_cotangent_frame", {
        const mat3 f = rk_nm_cotangent_frame(G.v3(all), G.v3(all), G.v3(all), G.v2(all), G.v2(all));
        CHECK(finite(f[0]) && finite(f[1]) && unit(f[2]), S(f[0]) + S(f[1]) + S(f[2]));
        CHECK(glm::length(dvec3(f[0])) <= 1.0 + 1e-6 && glm::length(dvec3(f[1])) <= 1.0 + 1e-6, "scaled by the larger");
    });
    ADV("rk_nm_unpack_rg / rk_nm_parallax_offset", {
        const vec3 n = rk_nm_unpack_rg(G.v2(Vecs::any()));
        CHECK(unit(n) && n.z >= 0.0f, S(n));
        const vec2 uv = rk_nm_parallax_offset(G.v2(Vecs::any()), G.f(Floats::all()), G.v3(Vecs::units()), G.f(Floats::any()),
                                              G.f(Floats::any()));
        CHECK(finite(uv), S(uv));
    });
}

}  // namespace
