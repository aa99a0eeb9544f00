// svo_trace_packet8 / svo_trace_packet16 / svo_trace_packets (raykit/svo_trace_packet.hpp: 8 or 16
// coherent rays sharing one traversal; 16 on AVX-512 lanes where the CPU has them, else as two 8-ray
// packets, which must give the same bits) against rk_svo_trace per ray, on camera-tile packets,
// random coherent packets and adversarial packets (every family of svo_trace_rays.hpp:
// axis-parallel, through edges and corners, origins inside and on the lattice, mixed octants, far
// origins, short t_max)
// over random trees and voxelised meshes at depths 3, 6, 10 and 16 (and coarse max_level stops).
// Each ray must give rk_svo_trace's hit flag, level and cell, and t within kTol root sizes (plus
// 8 ULPs of a far origin's distance); where it does not, the packet's answer is checked against the
// float64 brute-force reference (tests/reference/svo_dda_ref.hpp) with the acceptance rule of
// test_svo_traverse: a hit on an occupied cell the exact ray touches, entered no earlier than the
// first touch and no later than the first solid voxel (within tolerance); a miss only when the exact
// ray passes through no voxel by more than the tolerance. Counts are printed.
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
#include "svo_test_pack.hpp"
#include "svo_trace_rays.hpp"

using namespace raykit;

namespace {

constexpr double kTol = 2e-6;

struct Tally {
    long rays = 0, hits = 0, exact = 0, same_cell = 0, ties = 0, ties_flag = 0, bad = 0;
    double worst_dt = 0.0;  // worst |t - t_rk| in root sizes among same-cell answers (near origins)
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

/// Whether `h` (the packet's answer for `r`) passes test_svo_traverse's acceptance rule.
bool acceptable(const SvoTree& t, uint32_t level, const std::vector<glm::ivec3>& cells, const SvoRay& r, const rk_svo_trace_hit& h,
                std::string& why)
{
    const double rs = double(t.root_size);
    const double tol = ray_tol(r, t) * rs;
    const rkref::DdaRay dr{glm::dvec3(r.origin), glm::dvec3(r.dir), double(r.t_max)};
    const rkref::DdaHit ref = rkref::brute_first_hit(cells, int(level), glm::dvec3(t.root_min), rs, dr, 4.0 * tol, tol);
    if (!h.hit) {
        why = "missed a voxel the ray passes through";
        return !ref.solid;
    }
    if (h.level != level) {
        why = "wrong level";
        return false;
    }
    if (!std::binary_search(cells.begin(), cells.end(), glm::ivec3(h.cell), [](glm::ivec3 a, glm::ivec3 b) {
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
                  const std::vector<rk_svo_trace_hit>& pk, const std::vector<rk_svo_trace_hit>& one, Tally& total);

/// Traces `rays` as packets (row-major frame `width` wide in 4x2 and 4x4 tiles, or consecutive
/// groups of 8 and of 16 when width is 0) and compares every ray with rk_svo_trace. The 16-ray
/// packets (AVX-512 lanes where the CPU has them, else two 8-ray packets) must give the 8-ray
/// packets' answers bit for bit.
void compare(const char* what, const SvoTree& t, const std::vector<SvoRay>& rays, size_t width, Tally& total,
             uint32_t max_level = ~0u)
{
    const rk_svo_tree tree = svo_trace_tree(t, max_level);
    const std::vector<uint32_t> words = t.gpu_words();
    std::vector<rk_svo_trace_hit> pk8(rays.size()), pk(rays.size()), one(rays.size());
    for (size_t i = 0; i < rays.size(); ++i)
        one[i] = rk_svo_trace(words.data(), tree, rays[i].origin, rays[i].dir, rays[i].t_max, glm::vec2(0.0f));
    for (unsigned lanes : {8u, 16u}) {
        if (width > 0)
            svo_trace_packets(words.data(), tree, rays.data(), rays.size(), width, pk.data(), 4u, lanes / 4u);
        else
            for (size_t i = 0; i < rays.size(); i += lanes) {
                const unsigned n = unsigned(std::min<size_t>(lanes, rays.size() - i));
                if (lanes == 8u)
                    svo_trace_packet8(words.data(), tree, rays.data() + i, pk.data() + i, n);
                else
                    svo_trace_packet16(words.data(), tree, rays.data() + i, pk.data() + i, n);
            }
        if (lanes == 8u) {
            pk8 = pk;
        } else {
            long differ = 0;
            for (size_t i = 0; i < rays.size(); ++i) differ += bit_equal(pk[i], pk8[i]) ? 0 : 1;
            EXPECT_EQ(differ, 0) << what << ": 16-ray packets differ from 8-ray packets";
        }
        const std::string label = std::string(what) + (lanes == 16u ? " x16" : "");
        compare_hits(label.c_str(), t, tree, rays, pk, one, total);
    }
}

/// Tallies packet answers `pk` against rk_svo_trace's `one` (see compare).
void compare_hits(const char* what, const SvoTree& t, const rk_svo_tree& tree, const std::vector<SvoRay>& rays,
                  const std::vector<rk_svo_trace_hit>& pk, const std::vector<rk_svo_trace_hit>& one, Tally& total)
{
    std::vector<glm::ivec3> cells;
    Tally tl;
    const double rs = double(t.root_size);
    for (size_t i = 0; i < rays.size(); ++i) {
        const rk_svo_trace_hit &a = pk[i], &b = one[i];
        ++tl.rays;
        tl.hits += b.hit ? 1 : 0;
        EXPECT_TRUE(std::isfinite(a.t)) << what;
        if (bit_equal(a, b)) {
            ++tl.exact;
            continue;
        }
        const double dl = glm::length(glm::dvec3(rays[i].dir));
        if (a.hit == b.hit && a.level == b.level && a.cell == b.cell) {
            const double dt = std::abs(double(a.t) - double(b.t)) * dl / rs;
            if (dt <= ray_tol(rays[i], t)) {
                ++tl.same_cell;
                if (ray_tol(rays[i], t) < 10.0 * kTol) tl.worst_dt = std::max(tl.worst_dt, dt);
                continue;
            }
        }
        if (cells.empty()) cells = cells_at(t, tree.max_level);
        std::string why;
        if (acceptable(t, tree.max_level, cells, rays[i], a, why)) {
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
    total.exact += tl.exact;
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

void all_sets(const std::string& name, const SvoTree& t, Tally& total, size_t scale)
{
    compare((name + " camera 3/4 view").c_str(), t, camera(t, glm::vec3(0.45f, 0.35f, 1.0f), 128, 96), 128, total);
    compare((name + " camera axis-aligned").c_str(), t, camera(t, glm::vec3(0.0f, 0.0f, 1.0f), 96, 96), 96, total);
    compare((name + " camera from below, wide").c_str(), t, camera(t, glm::vec3(-0.3f, -1.0f, 0.2f), 64, 64, 0.9f, 1.2f), 64, total);
    compare((name + " camera inside the root").c_str(), t, camera(t, glm::vec3(0.2f, 0.1f, 1.0f), 64, 48, 0.2f, 0.8f), 64, total);
    compare((name + " coherent packets").c_str(), t, coherent_packets(t, 500 * scale, 7), 0, total);
    compare((name + " adversarial mixed").c_str(), t, adversarial(t, 4000 * scale, 11, false), 0, total);
    compare((name + " adversarial by family").c_str(), t, adversarial(t, 4000 * scale, 13, true), 0, total);
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
    EXPECT_GT(total.hits, total.rays / 10) << what;
}

}  // namespace

TEST(SvoTracePacket, RandomTrees)
{
    unsigned tw = 0u, th = 0u;
    svo_trace_packet_best_tile(tw, th);
    std::printf("[packet] 16-ray packets on %s\n", th == 4u ? "AVX-512 lanes" : "two 8-ray packets (no AVX-512F here)");
    Tally total;
    for (uint32_t depth : {1u, 2u, 3u, 6u, 10u}) {
        const size_t side3 = size_t(1) << (3 * std::min(depth, 8u));
        const size_t counts[] = {1, std::max<size_t>(1, side3 / 100), side3 / 8 + 1, side3 / 2 + 1};
        for (int k = 0; k < 4; ++k) {
            svotest::PackOptions po;
            po.pointer_bits = (k & 1) ? 4 : 23;
            SvoTree t = svotest::pack_cells(depth, svotest::random_cells(depth, std::min<size_t>(counts[k], 12000), 7 * depth + k), po);
            t.root_min = glm::vec3(-2.0f, 0.5f, 8.0f);
            t.root_size = 4.0f;
            all_sets("random d" + std::to_string(depth) + " k" + std::to_string(k), t, total, 1);
        }
    }
    {
        SvoTree t = svotest::pack_cells(16, svotest::random_cells(16, 2500, 5));
        t.root_min = glm::vec3(-1024.0f);
        t.root_size = 2048.0f;
        all_sets("random d16", t, total, 2);
    }
    {
        // Depth 16 with hits: a cluster of voxels around the centre, seen by narrow cameras.
        std::vector<glm::uvec3> cells;
        for (uint32_t z = 0; z < 24; ++z)
            for (uint32_t y = 0; y < 24; ++y)
                for (uint32_t x = 0; x < 24; ++x)
                    if (svotest::test_hash((uint64_t(z) << 20) | (uint64_t(y) << 10) | x) % 3u == 0u)
                        cells.push_back(glm::uvec3(32756u) + glm::uvec3(x, y, z));
        SvoTree t = svotest::pack_cells(16, cells);
        t.root_min = glm::vec3(-1024.0f);
        t.root_size = 2048.0f;
        compare("clustered d16 camera", t, camera(t, glm::vec3(0.45f, 0.35f, 1.0f), 128, 96, 1.6f, 2.5e-4f), 128, total);
        compare("clustered d16 camera axis-aligned", t, camera(t, glm::vec3(0.0f, 0.0f, 1.0f), 96, 96, 1.6f, 2.5e-4f), 96, total);
        compare("clustered d16 camera close", t, camera(t, glm::vec3(-0.3f, 0.8f, 0.2f), 64, 64, 1e-3f, 0.6f), 64, total);
    }
    expect_totals("random trees", total);
}

TEST(SvoTracePacket, VoxelisedMeshes)
{
    struct Build {
        const char* name;
        SvoMeshData mesh;
        int depth;
        SvoFill fill;
    };
    std::vector<Build> builds;
    builds.push_back({"torus d3 surface", rkmesh::torus(48, 24), 3, SvoFill::surface});
    builds.push_back({"menger d6 solid", rkmesh::menger_sponge(2), 6, SvoFill::solid});
    builds.push_back({"torus_69120 d10 surface", rkmesh::torus(192, 180), 10, SvoFill::surface});
    builds.push_back({"uv_sphere_69632 d10 surface", rkmesh::uv_sphere(256, 137), 10, SvoFill::surface});
    builds.push_back({"figure d10 surface", rkmesh::figure(), 10, SvoFill::surface});
    builds.push_back({"far torus d6", rkmesh::transformed(rkmesh::torus(32, 16), 1.0, glm::dvec3(3e4, -2e4, 1e4)), 6, SvoFill::surface});
    Tally total;
    for (Build& b : builds) {
        SvoTree t;
        std::string why;
        if (!svotrace::build_colour_tree(b.mesh, b.depth, b.fill, t, why)) {
            ADD_FAILURE() << b.name << ": " << why;
            continue;
        }
        all_sets(b.name, t, total, 1);
        for (uint32_t level : {1u, 2u, uint32_t(b.depth) - 1u}) {
            const std::string coarse = std::string(b.name) + " max_level " + std::to_string(level);
            compare((coarse + " camera").c_str(), t, camera(t, glm::vec3(0.45f, 0.35f, 1.0f), 64, 48), 64, total, level);
            compare((coarse + " adversarial").c_str(), t, adversarial(t, 2000, 40 + level, false), 0, total, level);
        }
    }
    expect_totals("meshes", total);
}

TEST(SvoTracePacket, NoNanOnHostileInput)
{
    SvoTree t = svotest::pack_cells(6, svotest::random_cells(6, 3000, 3));
    const std::vector<uint32_t> words = t.gpu_words();
    const rk_svo_tree tree = svo_trace_tree(t);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<float> U(-1.0f, 1.0f);
    const float odd[] = {0.0f, -0.0f, 1e-38f, -1e-45f, 1e30f, -3e38f, 1.0f, 0.5f};
    std::vector<SvoRay> all;
    for (int p = 0; p < 2000; ++p) {
        SvoRay r[8];
        rk_svo_trace_hit h[8];
        for (SvoRay& s : r) {
            s.origin = glm::vec3(U(rng), U(rng), U(rng)) * (p % 3 == 0 ? 1e30f : 2.0f);
            s.dir = glm::vec3(odd[rng() % 8], odd[rng() % 8], odd[rng() % 8]) * ((rng() & 1) ? 1.0f : U(rng));
            s.t_max = (rng() % 4 == 0) ? -1.0f : 3e38f;
        }
        svo_trace_packet8(words.data(), tree, r, h);
        for (const rk_svo_trace_hit& x : h) {
            EXPECT_FALSE(std::isnan(x.t));
            EXPECT_FALSE(std::isnan(x.normal.x) || std::isnan(x.normal.y) || std::isnan(x.normal.z));
        }
        all.insert(all.end(), r, r + 8);
    }
    // The same rays against rk_svo_trace (huge and zero directions, far origins, negative t_max).
    Tally total;
    compare("hostile input", t, all, 0, total);
    EXPECT_EQ(total.bad, 0);
}
