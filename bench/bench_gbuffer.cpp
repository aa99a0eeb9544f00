// raykit — bench_gbuffer.cpp: unit-vector encodings of shaders/raykit/gbuffer.glsl, bits against
// angular error against cost (issue 15 item 7): octahedral (float; SNORM and UNORM fields of 8 to 16
// bits; the precise four-candidate encoder), the thesis's hemisphere remapping and Lambert's
// equal-area map, each as one encode + decode round trip of a unit vector.
//
// Suite "gbuffer", one family: BM_gbuffer/<map>/<storage>.
//   - Speed: one round trip per call over kInputs random unit directions (z >= 0 for the hemisphere).
//   - Error: the angle (radians) between the decoded direction and the input, in float64, over
//     400,000 random directions (RAYKIT_BENCH_GBUFFER_DIRS=n for n: docs/deferred.md's table used 10^7)
//     plus poles, folds, the equator and the neighbourhood of -z.
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "raykit/gbuffer.hpp"

namespace rkbench {
namespace {

using raykit::uint;
using raykit::vec2;
using raykit::vec3;

const char* const kFam = "unit_vectors";

long directions()
{
    const char* e = std::getenv("RAYKIT_BENCH_GBUFFER_DIRS");
    const long n = e ? std::atol(e) : 0;
    return n > 0 ? n : 400000;
}

std::vector<vec3> error_directions(bool upper)
{
    std::vector<vec3> d;
    Rng rng(15u);
    for (long i = 0, n = directions(); i < n; ++i) d.push_back(rng.unit_vector());
    for (int i = 0; i < 4000; ++i) {
        const double t = 2.0 * 3.14159265358979323846 * i / 4000.0;
        const double c = std::cos(t), s = std::sin(t);
        for (const glm::dvec3& v : {glm::dvec3(c, s, 0.0), glm::dvec3(c, s, 1e-3), glm::dvec3(c, s, -1e-3),
                                     glm::dvec3(1e-4 * c, 1e-4 * s, -1.0), glm::dvec3(1e-4 * c, 1e-4 * s, 1.0),
                                     glm::dvec3(c, 0.0, s), glm::dvec3(0.0, c, s)})
            d.push_back(vec3(glm::normalize(v)));
    }
    if (upper)
        for (vec3& v : d) v.z = std::abs(v.z);
    return d;
}

template <class RoundTrip>
Accuracy angle_error(const std::vector<vec3>& dirs, RoundTrip rt)
{
    Accuracy acc;
    for (const vec3& v : dirs) {
        const glm::dvec3 a = glm::normalize(glm::dvec3(v)), b = glm::normalize(glm::dvec3(rt(v)));
        acc.add(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)), 0.0, d(v.z));
    }
    return acc;
}

std::string against(bool upper)
{
    return std::string("angle (rad) to the input, float64; ") + std::to_string(directions()) +
           (upper ? " random directions with z >= 0" : " random directions") + " + poles, folds, equator, -z";
}

template <class RoundTrip>
void row(const std::string& variant, const std::string& params, const std::string& function, bool upper, RoundTrip rt)
{
    static const std::vector<vec3> all = error_directions(false), up = error_directions(true);
    const Accuracy acc = angle_error(upper ? up : all, rt);
    std::vector<vec3> inputs = make_inputs<vec3>([](Rng& r, std::size_t) { return r.unit_vector(); });
    if (upper)
        for (vec3& v : inputs) v.z = std::abs(v.z);
    add_bench({variant, params, kFam, function, against(upper)}, acc, inputs, rt);
}

void register_all()
{
    using namespace raykit;
    add_family(kFam,
               "Unit vectors in two components: octahedral, hemisphere remapping (z >= 0 only) and Lambert "
               "equal-area; one encode + decode per call; error = angle to the input.");
    row("oct", "float", "rk_gb_oct_decode(rk_gb_oct_encode(n))", false, [](vec3 n) { return rk_gb_oct_decode(rk_gb_oct_encode(n)); });
    for (uint b : {8u, 10u, 12u, 16u}) {
        const std::string bs = std::to_string(b);
        row("oct", "snorm:" + bs, "rk_gb_oct_unpack_snorm(rk_gb_oct_pack_snorm(n, " + bs + "), " + bs + ")", false,
            [b](vec3 n) { return rk_gb_oct_unpack_snorm(rk_gb_oct_pack_snorm(n, b), b); });
        row("oct_precise", "snorm:" + bs, "rk_gb_oct_unpack_snorm(rk_gb_oct_pack_snorm_precise(n, " + bs + "), " + bs + ")",
            false, [b](vec3 n) { return rk_gb_oct_unpack_snorm(rk_gb_oct_pack_snorm_precise(n, b), b); });
        if (b == 8u || b == 16u)
            row("oct", "unorm:" + bs, "rk_gb_oct_unpack_unorm(rk_gb_oct_pack_unorm(n, " + bs + "), " + bs + ")", false,
                [b](vec3 n) { return rk_gb_oct_unpack_unorm(rk_gb_oct_pack_unorm(n, b), b); });
    }
    row("hemi", "float", "rk_gb_hemi_decode(rk_gb_hemi_encode(n)), z >= 0", true,
        [](vec3 n) { return rk_gb_hemi_decode(rk_gb_hemi_encode(n)); });
    row("lambert", "float", "rk_gb_lambert_decode(rk_gb_lambert_encode(n))", false,
        [](vec3 n) { return rk_gb_lambert_decode(rk_gb_lambert_encode(n)); });
    for (uint b : {8u, 16u}) {
        const std::string bs = std::to_string(b);
        row("hemi", "snorm:" + bs, "hemisphere remapping in two " + bs + "-bit SNORM fields, z >= 0", true,
            [b](vec3 n) { return rk_gb_hemi_decode(rk_gb_unpack_snorm2(rk_gb_pack_snorm2(rk_gb_hemi_encode(n), b), b)); });
        row("lambert", "snorm:" + bs, "Lambert equal-area in two " + bs + "-bit SNORM fields", false,
            [b](vec3 n) { return rk_gb_lambert_decode(rk_gb_unpack_snorm2(rk_gb_pack_snorm2(rk_gb_lambert_encode(n), b), b)); });
    }
}

const SuiteRegistrar registrar(
    {"gbuffer", 35, "G-buffer unit vectors: shaders/raykit/gbuffer.glsl", "bench/bench_gbuffer.cpp", "round trip",
     "BM_gbuffer/oct/float",
     {"unit_vectors"},
     "- **ns/round trip**: one encode and one decode of a random unit vector (the pack into a uint "
     "included for the quantised rows), the arguments loaded per call from the pre-generated array.\n"
     "- **max / mean abs err**: the angle in radians between the decoded direction and the input, in "
     "float64, over 400,000 random directions plus rings through the poles, the folds, the equator and around "
     "-z (the hemisphere rows: their mirror images with z >= 0, its only domain). **worst at**: the input's z.\n"
     "- Octahedral SNORM with b bits per field has the analytic maximum 3 sqrt(2) / (2 (2^(b-1) - 1)) (half a "
     "step on both fields at an octant face centre): 1.67e-2, 4.15e-3, 1.04e-3 and 6.47e-5 rad for b = 8, 10, "
     "12, 16; the precise encoder lowers the maximum by a third for seven to nine times the round trip's cost. "
     "UNORM has no code for 0 and loses a little at +z. The hemisphere's and Lambert's maxima sit at their "
     "singular points (the equator, -z): see docs/deferred.md for the errors away from them.",
     "On a GPU the encoders cost ALU only (a division, a few selects; the precise encoder four decodes); the "
     "decode is about ten ALU operations and one inversesqrt. The error columns carry over (same source, "
     "IEEE float32), up to the driver's inversesqrt and division precision (tests/gpu/parity_gbuffer.cpp)."},
    &register_all);

}  // namespace
}  // namespace rkbench
