// raykit — bench_shadow.cpp: the shadow filters of shaders/raykit/shadow_filter.glsl, each one's
// error against exact visibility against its cost (issue 15 item 7).
//
// Suite "shadow", one family: BM_shadow/<filter>/taps:<n>.
//   - Scene: a ground square with three spheres, a thin floating plate and a thin wall, lit by a sun
//     of angular diameter 0.05 rad (an area light: a penumbra of 5 cm, 3 texels, per metre of gap); a
//     1024 x 1024 orthographic shadow map made by casting one ray per texel centre (what a
//     rasteriser stores there), looked up through the C++ twin of the texture unit (ShadowMapCpu:
//     a bilinear 2x2 compare per tap, as a GPU's LINEAR compare does).
//   - Inputs: the surface points a 160 x 120 camera sees facing the sun, with a slope-scaled bias that
//     covers each filter's kernel (lookups()) and a per-pixel rotation.
//   - Error: |filtered lit fraction - exact visible fraction of the sun's disk| at each point, the
//     exact fraction from 256 stratified rays over the disk cast against the analytic scene in
//     double. Every filter is compared with the same soft truth: a hard filter is wrong by up to 1
//     inside penumbrae, a fixed-width PCF by the difference between its width and the penumbra's.
//   - Speed: one filtered lookup per call (the taps' bilinear compares on the CPU twin).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_common.hpp"
#include "raykit/shadow_filter.hpp"
#include "shadow_scene.hpp"

namespace rkbench {
namespace {

using glm::dvec3;
using raykit::uint;
using raykit::uvec2;
using raykit::vec2;
using raykit::vec3;

const char* const kFam = "shadow_filters";
constexpr double kSunDiameter = 0.05;  // radians
constexpr int kMapSize = 1024;

/// The bench scene (tests/shadow_scene.hpp's analytic scene type): ground |x|, |z| <= 6, three
/// spheres, a floating plate and a thin wall.
rktest::Scene bench_scene()
{
    rktest::Scene s;
    s.spheres = {{dvec3(-2.0, 1.0, -1.0), 1.0}, {dvec3(2.4, 0.5, 1.6), 0.5}, {dvec3(0.6, 2.0, 2.2), 0.35}};
    s.boxes = {{dvec3(-1.2, 1.1, 1.5), dvec3(1.0, 1.15, 3.0)}, {dvec3(2.9, 0.0, -3.2), dvec3(2.95, 1.8, -0.2)}};
    return s;
}

/// The bench's world: the scene, the light's orthographic map (tests/shadow_scene.hpp's render_map:
/// one ray per texel centre), and the camera points that face the sun with their exact visibility.
struct World {
    rktest::Scene scene = bench_scene();
    rktest::LightMap lm;
    struct Point {
        dvec3 p, n;
        double exact;  // visible fraction of the sun's disk
    };
    std::vector<Point> points;
};

const World& world()
{
    static const World w = [] {
        World W;
        W.lm = rktest::render_map(W.scene, dvec3(0.4, -0.8, 0.3), kMapSize, 6.0, false);
        // The camera's visible points that face the sun, with the exact soft visibility.
        const dvec3 L = -W.lm.dir;
        const double tr = std::tan(0.5 * kSunDiameter);
        rktest::for_each_camera_hit(W.scene, 160, 120, [&](dvec3 p, dvec3 n) {
            if (glm::dot(n, L) <= 0.05) return;  // facing away or grazing: dark by N.L
            int seen = 0, total = 0;
            for (int a = 0; a < 16; ++a)
                for (int b = 0; b < 16; ++b) {
                    // Stratified over the disk (concentric map of the 16 x 16 cell centres).
                    const vec2 s = raykit::concentric_disk(vec2(float(-1.0 + (a + 0.5) / 8.0), float(-1.0 + (b + 0.5) / 8.0)));
                    const dvec3 Lk = glm::normalize(L + tr * (double(s.x) * W.lm.right + double(s.y) * W.lm.up));
                    double ts;
                    dvec3 ns;
                    ++total;
                    if (!W.scene.hit(p + 1e-7 * n, Lk, 1e-9, ts, ns)) ++seen;
                }
            W.points.push_back({p, n, double(seen) / total});
        });
        return W;
    }();
    return w;
}

struct Lookup {
    vec3 uvz;
    float phi;
};

/// The lookups of every scored point for a filter reaching `kernel` texels from the centre: a
/// slope-scaled bias that covers the kernel (0.5 texel of depth, plus 1 + kernel texels per unit
/// slope, at most 10 + kernel: a tilted receiver's own depth changes by that much under the taps),
/// and a per-point rotation (rk_sh_rotation of the point's index laid out 160 wide, standing in for
/// its pixel).
std::vector<Lookup> lookups(double kernel)
{
    const World& W = world();
    const double td = W.lm.texel() / W.lm.range;
    std::vector<Lookup> out;
    for (size_t k = 0; k < W.points.size(); ++k) {
        const World::Point& q = W.points[k];
        const float ndl = float(glm::dot(q.n, -W.lm.dir));
        vec3 uvz = W.lm.project(q.p);
        uvz.z -= raykit::rk_sh_slope_bias(ndl, float(0.5 * td), float((1.0 + kernel) * td), float((10.0 + kernel) * td));
        out.push_back({uvz, raykit::rk_sh_rotation(uvec2(uint(k % 160u), uint(k / 160u)))});
    }
    return out;
}

template <class Filter>
void row(const std::string& variant, const std::string& params, const std::string& function, double kernel, Filter f)
{
    const World& W = world();
    const std::vector<Lookup> in = lookups(kernel);
    Accuracy acc;
    for (size_t k = 0; k < in.size(); ++k) acc.add(double(f(in[k])), W.points[k].exact, W.points[k].exact);
    std::vector<Lookup> inputs;
    for (size_t k = 0; k < kInputs; ++k) inputs.push_back(in[(k * 7919u) % in.size()]);
    add_bench({variant, params, kFam, function,
               "visible fraction of a 0.05 rad sun disk (256 rays, double) at " + std::to_string(in.size()) + " camera points"},
              acc, inputs, f);
}

void register_all()
{
    using namespace raykit;
    add_family(kFam,
               "Shadow filters against exact visibility: one filtered lookup of a 1024^2 map per call (C++ twin of "
               "the texture unit); error = |lit fraction - visible fraction of the sun's disk|.");
    const World& W = world();
    const ShadowMapCpu* m = &W.lm.map;
    const float radius = float(1.5 / kMapSize);
    row("compare", "taps:1", "rk_sh_compare(map, uv, ref) (one hardware 2x2 compare)", 0.5,
        [m](const Lookup& l) { return rk_sh_compare(*m, vec2(l.uvz.x, l.uvz.y), l.uvz.z); });
    static vec2 thesis[16], poisson[16];
    const std::vector<vec2> tg = pcf_jittered_grid(2, 4, 5u), pd = poisson_disk(16, 5u);
    for (int i = 0; i < 16; ++i) {
        thesis[i] = i < 8 ? tg[size_t(i)] : vec2(0.0f);
        poisson[i] = pd[size_t(i)];
    }
    row("thesis", "taps:8", "rk_sh_pcf_taps(map, uvz, 1.5 texels, pcf_jittered_grid(2, 4), 8, 0)", 2.0,
        [m, radius](const Lookup& l) { return rk_sh_pcf_taps(*m, l.uvz, radius, thesis, 8u, 0.0f); });
    row("poisson", "taps:16", "rk_sh_pcf_taps(map, uvz, 1.5 texels, poisson_disk(16), 16, phi)", 2.0,
        [m, radius](const Lookup& l) { return rk_sh_pcf_taps(*m, l.uvz, radius, poisson, 16u, l.phi); });
    for (uint n : {8u, 16u, 32u})
        row("vogel", "taps:" + std::to_string(n), "rk_sh_pcf_vogel(map, uvz, 1.5 texels, " + std::to_string(n) + ", phi)", 2.0,
            [m, radius, n](const Lookup& l) { return rk_sh_pcf_vogel(*m, l.uvz, radius, n, l.phi); });
    const float wide = float(4.0 / kMapSize);
    row("vogel", "taps:16,texels:4", "rk_sh_pcf_vogel(map, uvz, 4 texels, 16, phi)", 4.5,
        [m, wide](const Lookup& l) { return rk_sh_pcf_vogel(*m, l.uvz, wide, 16u, l.phi); });
    // PCSS for a directional light: a virtual light very far away and wide in proportion, so that
    // (d_receiver - d_blocker) w_light / d_blocker is the gap times the sun's angular diameter.
    const double virtual_d = 1e4 * W.lm.range;
    const float w_light = float(2.0 * virtual_d * std::tan(0.5 * kSunDiameter));
    const float search = float(2.0 * kSunDiameter / W.lm.size);  // covers a 2-unit gap's penumbra
    const float d_near = float(virtual_d), d_range = float(W.lm.range), uv_per_unit = float(1.0 / W.lm.size), min_r = float(0.5 / kMapSize);
    for (uint n : {16u, 32u})
        row("pcss", "taps:" + std::to_string(n), "rk_sh_pcss(map, map, uvz, ..., " + std::to_string(n) + ", phi) (blocker search + Vogel)", 4.0,
            [=](const Lookup& l) { return rk_sh_pcss(*m, *m, l.uvz, search, w_light, d_near, d_range, uv_per_unit, min_r, n, l.phi); });
}

const SuiteRegistrar registrar(
    {"shadow", 37, "Shadow filters: shaders/raykit/shadow_filter.glsl", "bench/bench_shadow.cpp", "lookup",
     "BM_shadow/compare/taps:1",
     {"shadow_filters"},
     "- **ns/lookup**: one filtered shadow lookup (every tap a bilinear 2x2 compare of the C++ twin of the "
     "texture unit, as on a GPU with LINEAR compare filtering) of a 1024 x 1024 map, for the points a camera sees "
     "facing the sun, with a slope-scaled bias that covers the filter's kernel (1 + kernel texels of depth per unit "
     "slope: without it a wide kernel shadows a tilted receiver with itself) and a per-pixel rotation.\n"
     "- **max / mean abs err**: |lit fraction - exact visible fraction of the sun's disk| (0.05 rad, 256 "
     "stratified rays per point cast against the analytic scene in double), over about 9,400 camera points of a "
     "ground with spheres, a floating plate and a thin wall. **worst at**: the exact visibility there. Most "
     "points are fully lit or fully shadowed, where every filter is exact, so the maxima sit at a few penumbra "
     "points and the means are small; the plot shows the mean.\n"
     "- Fixed-radius filters (thesis, Poisson, Vogel: 1.5 texels; one Vogel row at 4) blur every edge by the "
     "same width, too much at contact and too little far from the blocker; PCSS widens its filter with the "
     "blocker distance, which is what the soft truth does, and skips the filter where its search finds no "
     "blocker. More taps of one kernel lower the noise, not the bias of a wrong width.",
     "On a GPU each tap is one hardware compare (the 2x2 for free) and one texture fetch: cost grows with "
     "the tap count as here, and PCSS's blocker search doubles it. The error columns carry over "
     "(tests/gpu/parity_shadow_filter.cpp checks the twin against the driver's texture unit).",
     "", "mean"},
    &register_all);

}  // namespace
}  // namespace rkbench
