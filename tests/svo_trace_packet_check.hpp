// The checks of test_svo_trace_packet (see its comment), shared by its default build
// (test_svo_trace_packet.cpp) and its level-of-detail build (parts/test_svo_trace_packet/lod.cpp):
// included once per translation unit, after that unit's RK_SVO_* macros; everything is TU-local.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "raykit/svo_build.hpp"
#include "raykit/svo_trace_packet.hpp"
#include "reference/svo_dda_ref.hpp"
#include "reference/svo_meshes.hpp"
#include "svo_secondary_rays.hpp"
#include "svo_test_pack.hpp"
#include "svo_trace_rays.hpp"

using namespace raykit;

namespace {

constexpr double kTol = 2e-6;

struct Tally {
    long rays = 0, hits = 0, exact = 0, same_cell = 0, ties = 0, ties_flag = 0, bad = 0;
    long coarse = 0;  // rk_svo_trace hits above the tree's max_level (footprint stops in a LOD build)
    long exact_hits = 0;  // rk_svo_trace's hits the packets answered bit for bit
    double worst_dt = 0.0;  // worst |t - t_rk| in root sizes among same-cell answers (near origins)
    long secondary = 0, secondary_hits = 0;  // secondary rays from primary hits, and how many hit
};

double ray_tol(const SvoRay& r, const SvoTree& t)
{
    const double rs = double(t.root_size);
    return kTol + 8.0 * 0x1p-24 * glm::length(glm::dvec3(r.origin) - (glm::dvec3(t.root_min) + 0.5 * rs)) / rs;
}

bool bit_equal(const rk_svo_trace_hit& a, const rk_svo_trace_hit& b)
{
    return a.hit == b.hit && (!a.hit || (a.t == b.t && a.level == b.level && a.cell == b.cell && a.normal == b.normal &&
                                         a.node == b.node && a.brick_bit == b.brick_bit && a.brick_mask == b.brick_mask));
}

/// The occupied cells of `t` at `level`, for the brute-force reference.
std::vector<glm::ivec3> cells_at(const SvoTree& t, uint32_t level)
{
    std::vector<glm::ivec3> out;
    const uint32_t sh = t.depth - level;
    svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t) { out.push_back(glm::ivec3(c >> sh)); });
    std::sort(out.begin(), out.end(), [](glm::ivec3 a, glm::ivec3 b) {
        return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z);
    });
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

/// Whether `h` (the packet's answer for `r`) passes test_svo_traverse's acceptance rule: `cells`
/// are the occupied cells at `level`, the tree's leaf level for this trace. A LOD build's hit above
/// that level (`coarse`: its occupied cells at h.level) must also be a node the exact ray touches,
/// no later than the first solid leaf, and no wider than the footprint `cone` where it was entered.
bool acceptable(const SvoTree& t, uint32_t level, const std::vector<glm::ivec3>& cells, const SvoRay& r, const rk_svo_trace_hit& h,
                std::string& why, const std::vector<glm::ivec3>* coarse = nullptr, glm::vec2 cone = glm::vec2(0.0f))
{
    const double rs = double(t.root_size);
    const double tol = ray_tol(r, t) * rs;
    const rkref::DdaRay dr{glm::dvec3(r.origin), glm::dvec3(r.dir), double(r.t_max)};
    const rkref::DdaHit ref = rkref::brute_first_hit(cells, int(level), glm::dvec3(t.root_min), rs, dr, 4.0 * tol, tol);
    if (!h.hit) {
        why = "missed a voxel the ray passes through";
        return !ref.solid;
    }
    const bool is_coarse = coarse != nullptr && h.level < level;
    if (is_coarse) {
        const double size = rs / double(1u << h.level);
        const double dist = double(h.t) * glm::length(glm::dvec3(r.dir));
        if (size > (double(cone.x) + double(cone.y) * dist) * (1.0 + 1e-5) + tol) {
            why = "stopped at a node wider than the footprint";
            return false;
        }
        level = h.level;
    } else if (h.level != level) {
        why = "wrong level";
        return false;
    }
    const std::vector<glm::ivec3>& occupied = is_coarse ? *coarse : cells;
    if (!std::binary_search(occupied.begin(), occupied.end(), glm::ivec3(h.cell), [](glm::ivec3 a, glm::ivec3 b) {
            return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z);
        })) {
        why = "empty cell reported";
        return false;
    }
    if (!rkref::ray_touches_cell(glm::dvec3(t.root_min), rs, int(level), glm::ivec3(h.cell), dr, tol, nullptr)) {
        why = "hit a cell the exact ray does not come near";
        return false;
    }
    const double dl = glm::length(glm::dvec3(r.dir));
    if (ref.solid && (double(h.t) - ref.t_solid) * dl > 4.0 * tol + 8.0 * 0x1p-24 * ref.t_solid * dl) {
        why = "later than the first solid voxel";
        return false;
    }
    return true;
}

void compare_hits(const char* what, const SvoTree& t, const rk_svo_tree& tree, const std::vector<SvoRay>& rays,
                  const std::vector<rk_svo_trace_hit>& pk, const std::vector<rk_svo_trace_hit>& one, Tally& total, glm::vec2 cone);

/// `rays` as 16-ray packets on AVX2 registers (svo_packet_detail::packet16_avx2, whatever the CPU
/// has beyond AVX2): 4x4 tiles of a frame `width` wide, or consecutive groups of 16 when width is 0.
/// Without AVX2 (or a tree the packets do not take) rk_svo_trace answers.
void trace_avx2_16(const std::vector<uint32_t>& words, const rk_svo_tree& tree, const std::vector<SvoRay>& rays, size_t width,
                   std::vector<rk_svo_trace_hit>& out, glm::vec2 cone)
{
    const auto avx2_16 = [](const uint32_t* w, const rk_svo_tree& tr, const SvoRay* const* rp, rk_svo_trace_hit* const* hp, unsigned k,
                            glm::vec2 c) {
        if (!svo_packet_detail::packet16_avx2(w, tr, rp, hp, k, c))
            for (unsigned i = 0; i < k; ++i) *hp[i] = rk_svo_trace(w, tr, rp[i]->origin, rp[i]->dir, rp[i]->t_max, c);
    };
    svo_packet_detail::trace_tiles(words.data(), tree, rays.data(), rays.size(), width > 0 ? width : 16u, out.data(), width > 0 ? 4u : 16u,
                                   width > 0 ? 4u : 1u, cone, avx2_16);
}

/// Traces `rays` as packets (row-major frame `width` wide in 4x2, 4x4 and 8x4 tiles, or consecutive
/// groups of 8, 16 and 32 when width is 0) and compares every ray with rk_svo_trace. The 16- and
/// 32-ray packets (AVX-512 lanes where the CPU has them, else two AVX2 registers per value), and the
/// 16-ray packets on AVX2 registers whatever the CPU has, must give the 8-ray packets' answers bit
/// for bit.
void compare(const char* what, const SvoTree& t, const std::vector<SvoRay>& rays, size_t width, Tally& total,
             uint32_t max_level = ~0u, glm::vec2 cone = glm::vec2(0.0f))
{
    const rk_svo_tree tree = svo_trace_tree(t, max_level);
    const std::vector<uint32_t> words = t.gpu_words();
    std::vector<rk_svo_trace_hit> pk8(rays.size()), pk(rays.size()), one(rays.size());
    for (size_t i = 0; i < rays.size(); ++i)
        one[i] = rk_svo_trace(words.data(), tree, rays[i].origin, rays[i].dir, rays[i].t_max, cone);
    for (unsigned lanes : {8u, 16u, 32u, 17u}) {  // 17: 16 rays on AVX2 registers (packet16_avx2)
        if (lanes == 17u)
            trace_avx2_16(words, tree, rays, width, pk, cone);
        else if (width > 0)
            svo_trace_packets(words.data(), tree, rays.data(), rays.size(), width, pk.data(), lanes == 32u ? 8u : 4u, lanes == 8u ? 2u : 4u,
                              cone);
        else
            for (size_t i = 0; i < rays.size(); i += lanes) {
                const unsigned n = unsigned(std::min<size_t>(lanes, rays.size() - i));
                if (lanes == 8u)
                    svo_trace_packet8(words.data(), tree, rays.data() + i, pk.data() + i, n, cone);
                else if (lanes == 16u)
                    svo_trace_packet16(words.data(), tree, rays.data() + i, pk.data() + i, n, cone);
                else
                    svo_trace_packet32(words.data(), tree, rays.data() + i, pk.data() + i, n, cone);
            }
        if (lanes == 8u) {
            pk8 = pk;
        } else {
            long differ = 0;
            for (size_t i = 0; i < rays.size(); ++i) differ += bit_equal(pk[i], pk8[i]) ? 0 : 1;
            EXPECT_EQ(differ, 0) << what << ": " << (lanes == 17u ? std::string("16-ray (AVX2)") : std::to_string(lanes) + "-ray")
                                 << " packets differ from 8-ray packets";
        }
        const std::string label = std::string(what) + (lanes == 8u ? "" : lanes == 16u ? " x16" : lanes == 32u ? " x32" : " x16 AVX2");
        compare_hits(label.c_str(), t, tree, rays, pk, one, total, cone);
    }
}

/// Tallies packet answers `pk` against rk_svo_trace's `one` (see compare).
void compare_hits(const char* what, const SvoTree& t, const rk_svo_tree& tree, const std::vector<SvoRay>& rays,
                  const std::vector<rk_svo_trace_hit>& pk, const std::vector<rk_svo_trace_hit>& one, Tally& total, glm::vec2 cone)
{
    std::vector<glm::ivec3> cells[RK_SVO_MAX_DEPTH + 1];
    Tally tl;
    const double rs = double(t.root_size);
    for (size_t i = 0; i < rays.size(); ++i) {
        const rk_svo_trace_hit &a = pk[i], &b = one[i];
        ++tl.rays;
        tl.hits += b.hit ? 1 : 0;
        tl.coarse += b.hit && b.level < tree.max_level ? 1 : 0;
        EXPECT_TRUE(std::isfinite(a.t)) << what;
        if (bit_equal(a, b)) {
            ++tl.exact;
            tl.exact_hits += b.hit ? 1 : 0;
            continue;
        }
        const double dl = glm::length(glm::dvec3(rays[i].dir));
        // The same cell has the same entry planes (the same set-up, the same expressions), so the
        // same face normal, whatever distance either walk reached it at.
        if (a.hit && b.hit && a.level == b.level && a.cell == b.cell && a.normal != b.normal) {
            if (tl.bad++ < 4)
                ADD_FAILURE() << what << ": ray " << i << ": the same cell as rk_svo_trace with another normal: (" << a.normal.x << ","
                              << a.normal.y << "," << a.normal.z << ") against (" << b.normal.x << "," << b.normal.y << "," << b.normal.z
                              << ")";
            continue;
        }
        if (a.hit == b.hit && a.level == b.level && a.cell == b.cell) {
            const double dt = std::abs(double(a.t) - double(b.t)) * dl / rs;
            if (dt <= ray_tol(rays[i], t)) {
                ++tl.same_cell;
                if (ray_tol(rays[i], t) < 10.0 * kTol) tl.worst_dt = std::max(tl.worst_dt, dt);
                continue;
            }
        }
        // A LOD build's hit above the leaf level is judged at its own level too.
        const uint32_t leaf = tree.max_level;
        if (cells[leaf].empty()) cells[leaf] = cells_at(t, leaf);
        const bool coarse = RK_SVO_TRAVERSE_LOD && a.hit && a.level < leaf;
        if (coarse && cells[a.level].empty()) cells[a.level] = cells_at(t, a.level);
        std::string why;
        if (acceptable(t, leaf, cells[leaf], rays[i], a, why, coarse ? &cells[a.level] : nullptr, cone)) {
            ++tl.ties;
            tl.ties_flag += a.hit != b.hit ? 1 : 0;
            continue;
        }
        if (tl.bad++ < 4)
            ADD_FAILURE() << what << ": ray " << i << " o=(" << rays[i].origin.x << "," << rays[i].origin.y << ","
                          << rays[i].origin.z << ") d=(" << rays[i].dir.x << "," << rays[i].dir.y << "," << rays[i].dir.z
                          << ") t_max=" << rays[i].t_max << ": " << why << "; packet hit " << a.hit << " t " << a.t << " L"
                          << a.level << " (" << a.cell.x << "," << a.cell.y << "," << a.cell.z << "), rk_svo_trace hit " << b.hit
                          << " t " << b.t << " L" << b.level << " (" << b.cell.x << "," << b.cell.y << "," << b.cell.z << ")";
    }
    std::printf("[packet] %-40s %7ld rays %6ld hits: %7ld bit-exact, %4ld same cell (t within tol), %3ld accepted ties (%ld hit/miss), %ld bad; "
                "worst dt %.1e root\n",
                what, tl.rays, tl.hits, tl.exact, tl.same_cell, tl.ties, tl.ties_flag, tl.bad, tl.worst_dt);
    total.rays += tl.rays;
    total.hits += tl.hits;
    total.coarse += tl.coarse;
    total.exact += tl.exact;
    total.exact_hits += tl.exact_hits;
    total.same_cell += tl.same_cell;
    total.ties += tl.ties;
    total.ties_flag += tl.ties_flag;
    total.bad += tl.bad;
    total.worst_dt = std::max(total.worst_dt, tl.worst_dt);
}

/// A w x h pinhole frame looking at the root's centre from direction `from`.
std::vector<SvoRay> camera(const SvoTree& t, glm::vec3 from, int w, int h, float dist = 1.6f, float fov = 0.45f)
{
    const glm::vec3 centre = t.root_min + glm::vec3(0.5f * t.root_size);
    const glm::vec3 eye = centre + glm::normalize(from) * (dist * t.root_size);
    const glm::vec3 f = glm::normalize(centre - eye);
    const glm::vec3 up = std::abs(f.y) > 0.99f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::vec3 r = glm::normalize(glm::cross(f, up));
    const glm::vec3 u = glm::cross(r, f);
    std::vector<SvoRay> out;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float sx = (2.0f * (float(x) + 0.5f) / float(w) - 1.0f) * fov;
            const float sy = (2.0f * (float(y) + 0.5f) / float(h) - 1.0f) * fov;
            SvoRay s;
            s.origin = eye;
            s.dir = glm::normalize(f + sx * r + sy * u);
            out.push_back(s);
        }
    return out;
}

/// Random coherent packets: 8 rays from one origin (outside or inside the root) with directions
/// within `spread` radians of a random one, and packets of parallel rays with nearby origins.
std::vector<SvoRay> coherent_packets(const SvoTree& t, size_t packets, uint64_t seed)
{
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    auto rand_dir = [&]() {
        for (;;) {
            glm::vec3 d(2.0f * U(rng) - 1.0f, 2.0f * U(rng) - 1.0f, 2.0f * U(rng) - 1.0f);
            const float l = glm::length(d);
            if (l > 0.05f && l <= 1.0f) return d / l;
        }
    };
    const float rs = t.root_size;
    std::vector<SvoRay> out;
    for (size_t p = 0; p < packets; ++p) {
        const glm::vec3 target = t.root_min + rs * glm::vec3(U(rng), U(rng), U(rng));
        const glm::vec3 d0 = rand_dir();
        const int kind = int(p % 4);
        const float spread = std::pow(10.0f, -4.0f + 3.0f * U(rng));
        const glm::vec3 o0 = kind == 1 ? t.root_min + rs * glm::vec3(U(rng), U(rng), U(rng)) : target - d0 * (rs * (0.7f + 2.0f * U(rng)));
        for (int i = 0; i < 8; ++i) {
            SvoRay s;
            if (kind < 3) {
                s.origin = o0;
                s.dir = glm::normalize(d0 + spread * (glm::vec3(U(rng), U(rng), U(rng)) - 0.5f));
            } else {  // parallel rays, nearby origins (an orthographic tile)
                s.origin = o0 + spread * rs * (glm::vec3(U(rng), U(rng), U(rng)) - 0.5f);
                s.dir = d0;
            }
            if (kind == 2) s.t_max = rs * (0.5f + 2.0f * U(rng));
            out.push_back(s);
        }
    }
    return out;
}

/// The adversarial families of svo_trace_rays.hpp, as packets: consecutive rays (mixed families and
/// octants in one packet) and packets of one family each.
std::vector<SvoRay> adversarial(const SvoTree& t, size_t n, uint64_t seed, bool by_family)
{
    std::vector<svotrace::Ray> rays = svotrace::make_rays(n, t.root_min, t.root_size, t.depth, seed);
    if (by_family)
        std::stable_sort(rays.begin(), rays.end(), [](const svotrace::Ray& a, const svotrace::Ray& b) { return a.family < b.family; });
    std::vector<SvoRay> out;
    for (const svotrace::Ray& r : rays) {
        SvoRay s;
        s.origin = r.origin;
        s.dir = r.dir;
        s.t_max = r.t_max;
        out.push_back(s);
    }
    return out;
}

/// Every ray set above on `t`, tallied into `total`; `cone` is the primary rays' footprint (LOD
/// builds). The secondary sets (traced without a footprint) are left out with `secondary` false.
void all_sets(const std::string& name, const SvoTree& t, Tally& total, size_t scale, glm::vec2 cone = glm::vec2(0.0f),
              bool secondary = true)
{
    const uint32_t all = ~0u;
    compare((name + " camera 3/4 view").c_str(), t, camera(t, glm::vec3(0.45f, 0.35f, 1.0f), 128, 96), 128, total, all, cone);
    compare((name + " camera axis-aligned").c_str(), t, camera(t, glm::vec3(0.0f, 0.0f, 1.0f), 96, 96), 96, total, all, cone);
    compare((name + " camera from below, wide").c_str(), t, camera(t, glm::vec3(-0.3f, -1.0f, 0.2f), 64, 64, 0.9f, 1.2f), 64, total,
            all, cone);
    compare((name + " camera inside the root").c_str(), t, camera(t, glm::vec3(0.2f, 0.1f, 1.0f), 64, 48, 0.2f, 0.8f), 64, total, all,
            cone);
    if (secondary) {
        // Secondary rays as packets, from the 3/4 view's hits: shadow rays towards a sun, towards a
        // sun along +y (axis-parallel rays, parallel to the lattice's planes) and towards a point
        // light inside the root, and mirror reflections (a tile's reflections may fall in several
        // octants). Without a footprint: a pixel's cone would stop a secondary ray at once in the
        // coarse node that holds its own surface.
        const size_t vw = 96;
        const std::vector<SvoRay> view = camera(t, glm::vec3(0.45f, 0.35f, 1.0f), int(vw), 64);
        const glm::vec3 centre = t.root_min + glm::vec3(0.5f * t.root_size);
        const glm::vec3 sun = glm::normalize(glm::vec3(0.4f, 0.8f, 0.45f)), up(0.0f, 1.0f, 0.0f);
        const glm::vec3 lamp = centre + t.root_size * glm::vec3(0.3f, 0.45f, 0.2f);
        const rk_svo_tree tree = svo_trace_tree(t);
        const std::vector<uint32_t> words = t.gpu_words();
        const struct {
            const char* what;
            svotrace::Secondary kind;
            glm::vec3 light;
        } sets[] = {{" shadow rays, sun", svotrace::Secondary::sun, sun},
                    {" shadow rays, sun along +y", svotrace::Secondary::sun, up},
                    {" shadow rays, point light", svotrace::Secondary::point, lamp},
                    {" mirror reflections", svotrace::Secondary::mirror, glm::vec3(0.0f)}};
        for (const auto& set : sets) {
            const long rays0 = total.rays, hits0 = total.hits;  // rk_svo_trace's answers, tallied by compare
            compare((name + set.what).c_str(), t, svotrace::secondary_rays(words.data(), tree, view, set.kind, set.light), vw, total, all,
                    glm::vec2(0.0f));
            total.secondary += total.rays - rays0;
            total.secondary_hits += total.hits - hits0;
        }
    }
    compare((name + " coherent packets").c_str(), t, coherent_packets(t, 500 * scale, 7), 0, total, all, cone);
    compare((name + " adversarial mixed").c_str(), t, adversarial(t, 4000 * scale, 11, false), 0, total, all, cone);
    compare((name + " adversarial by family").c_str(), t, adversarial(t, 4000 * scale, 13, true), 0, total, all, cone);
}

/// The totals of a suite: no answer the float64 reference rejects; ties are rare (lattice-aligned
/// rays), so the packet gives rk_svo_trace's bits for almost every ray (measured: 99.9 % of the
/// random-tree rays, 99.8 % of the mesh rays); and it hits something.
void expect_totals(const char* what, const Tally& total)
{
    std::printf("[packet] %s: %ld rays, %ld hits: %ld bit-exact, %ld same cell, %ld accepted ties (%ld hit/miss), %ld bad\n", what,
                total.rays, total.hits, total.exact, total.same_cell, total.ties, total.ties_flag, total.bad);
    EXPECT_EQ(total.bad, 0) << what;
    EXPECT_GE(double(total.exact), 0.99 * double(total.rays)) << what;
    // Misses agree on the flag alone, so the hits are held to the same share on their own.
    EXPECT_GE(double(total.exact_hits), 0.99 * double(total.hits)) << what << ": " << total.exact_hits << " of " << total.hits
                                                                   << " hits bit for bit";
    EXPECT_GT(total.hits, total.rays / 10) << what;
    // The secondary sets start on surfaces and find some of them again (measured: 10 % of them hit on
    // the random trees, 14 % on the meshes, 19 % in the LOD build's sets).
    if (total.secondary > 0) {
        std::printf("[packet] %s: %ld secondary ray answers (every packet width), %ld hit\n", what, total.secondary, total.secondary_hits);
        EXPECT_GT(total.secondary_hits, total.secondary / 20) << what;
    }
}

}  // namespace
