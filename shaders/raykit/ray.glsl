// raykit — ray.glsl: raycast primitives, the base the other ray-casting includes use: a ray
// against a plane (half-space), a sphere, an axis-aligned box and an ellipsoid (axis-aligned, or any
// linear transform of a unit sphere), each returning the interval of the ray inside the solid, and
// impostor helpers that raycast a sphere or an oriented box from a rasterised proxy's fragment and
// give the hit's window depth for OpenGL [-1, 1], Vulkan [0, 1] and reversed-Z.
//
// Conventions shared by every function here:
//   - The ray is o + t d, t in units of d: d need not be normalised; any finite d works. A
//     direction whose components are all below RK_FLT_MIN in magnitude (zero or denormal: a GPU may
//     flush denormals, so both builds read them as zero) is a point: the result is (-RK_FLT_MAX,
//     RK_FLT_MAX) when o is inside the solid (closed: the surface counts), a miss otherwise.
//   - The result is vec2(t_enter, t_exit), the whole line's interval inside the solid (negative
//     t lies behind the origin), clamped to [-RK_FLT_MAX, RK_FLT_MAX], RK_FLT_MAX standing for an
//     unbounded end. t_enter < 0 <= t_exit: the origin is inside. A miss is t_enter > t_exit, always
//     exactly RK_RAY_MISS = (RK_FLT_MAX, -RK_FLT_MAX). rk_ray_hit(t) is "the ray meets the solid at
//     some t >= 0", rk_ray_nearest(t) the first such t.
//   - A tangent ray gives t_enter == t_exit; whether a ray within float rounding of tangency hits or
//     misses is not defined (the tests allow either inside the rounding band they state).
//   - No finite input, ±0, denormals and ±FLT_MAX included, gives NaN or Inf in any output.
//   - Normals (the *_normals variants) are unit outward normals at the entry and the exit point,
//     vec3(0) for a miss and for an unbounded end.
//
// Literature: the sphere's discriminant from the closest-approach vector, Haines, Günther, Akenine-
// Möller, "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7, 2019); the
// box's slab test with a per-axis parallel case instead of IEEE infinities, Williams, Barrus,
// Morley, Shirley, "An Efficient and Robust Ray-Box Intersection Algorithm" (JGT 10(1), 2005).
// Errors measured against long double references: tests/test_ray.cpp; summary in docs/ray.md.
//
// Shared GLSL/C++ source (include/raykit/ray.hpp is the C++ build).
//
// @rk-es 310
// @rk-es300
#ifndef RK_RAY_GLSL
#define RK_RAY_GLSL

#include "common.glsl"
#include "gbuffer.glsl"

// The miss encoding: t_enter > t_exit.
#define RK_RAY_MISS vec2(RK_FLT_MAX, -RK_FLT_MAX)

/// rk_ray_hit: whether an interval from the functions below meets t >= 0 (the ray, not the whole
/// line, touches the solid): t.x <= t.y && t.y >= 0. Exact. Cost: 2 compares.
RK_INLINE bool rk_ray_hit(vec2 t) { return t.x <= t.y && t.y >= 0.0f; }

/// rk_ray_nearest: the first t >= 0 of an interval that rk_ray_hit accepts: t_enter, or t_exit when
/// the origin is inside (t_enter < 0). Meaningless for a miss (returns t.y). Exact. Cost: 1 select.
RK_INLINE float rk_ray_nearest(vec2 t) { return t.x >= 0.0f ? t.x : t.y; }

/// rk_ray_clamp3_: internal. Componentwise clamp to [-RK_FLT_MAX, RK_FLT_MAX] (an overflowed
/// difference or product becomes the largest float, never Inf).
RK_INLINE vec3 rk_ray_clamp3_(vec3 v) { return clamp(v, vec3(-RK_FLT_MAX), vec3(RK_FLT_MAX)); }

/// rk_ray_maxabs_: internal. The largest |component|.
RK_INLINE float rk_ray_maxabs_(vec3 v) { return max(max(abs(v.x), abs(v.y)), abs(v.z)); }

// ---------------------------------------------------------------------------------------------
// Plane (half-space)

/// rk_ray_shift_: internal. x 2^k (k = scale's exponent, scale = 2^k), by adding k to x's exponent
/// field where x and the result are normal floats (exact), else as x * scale. NVIDIA's compiler
/// moves constant factors across products and quotients (it turned (n / (m 2^-64)) into
/// n (1 / m) 2^64, and 1 / m is 0 for m above 2^126), even in `precise` expressions; a bit
/// operation is out of its reach. Same bits as x * scale.
RK_INLINE float rk_ray_shift_(float x, int k, float scale)
{
    uint b = floatBitsToUint(x);
    int e = int((b >> 23u) & 255u);
    bool ok = e >= 1 && e + k >= 1 && e + k <= 254;
    return ok ? uintBitsToFloat(b + uint(k * 8388608)) : x * scale;
}

RK_INLINE vec3 rk_ray_shift3_(vec3 v, int k, float scale)
{
    return vec3(rk_ray_shift_(v.x, k, scale), rk_ray_shift_(v.y, k, scale), rk_ray_shift_(v.z, k, scale));
}

/// rk_ray_dot64_: internal. dot(nb, x) 2^-64 for nb = n̂ 2^64 (|nb_i| <= 2^64), each product taken
/// between normal factors where it can reach RK_FLT_MIN: nb_i (x_i 2^-64) for |x_i| >= 2^-62, else
/// (nb_i 2^-64) x_i. Each term is at most RK_FLT_MAX.
RK_INLINE float rk_ray_mul64_(float nb, float x)
{
    // x 2^-64 through the exponent field (rk_ray_shift_; |x| >= 2^-62 keeps it normal), not by a
    // multiplication: NVIDIA's compiler moved the constant out of nb (x 2^-64), even a `precise`
    // one, and (nb x) 2^-64 overflows for x = 1e20 (then Inf - Inf = NaN downstream). Same bits as
    // nb * (x * 2^-64).
    bool xl = abs(x) >= 2.1684043e-19f;
    float xs = xl ? rk_ray_shift_(x, -64, 5.42101086e-20f) : x;
    float ns = xl ? nb : nb * 5.42101086e-20f;
    return ns * xs;
}

/// rk_ray_div3_: internal. rk_div (common.glsl) per component: divisors above 2^100 are scaled
/// first, since GLSL leaves division by values above 2^126 undefined (NVIDIA returns 0).
RK_INLINE vec3 rk_ray_div3_(vec3 a, vec3 b) { return vec3(rk_div(a.x, b.x), rk_div(a.y, b.y), rk_div(a.z, b.z)); }

RK_INLINE float rk_ray_dot64_(vec3 nb, vec3 x)
{
    return (rk_ray_mul64_(nb.x, x.x) + rk_ray_mul64_(nb.y, x.y)) + rk_ray_mul64_(nb.z, x.z);
}

/// rk_ray_plane: the interval of o + t d inside the closed half-space dot(n, p - p0) <= 0 (the
/// plane through p0 with normal n, n pointing out of the solid): the ray crosses the plane at
/// t = dot(n, p0 - o) / dot(n, d); entering (dot(n, d) < 0) gives (t, RK_FLT_MAX), leaving gives
/// (-RK_FLT_MAX, t). Parallel (|dot(n̂, d)| <= RK_FLT_MIN, n̂ = n / |n|): (-RK_FLT_MAX, RK_FLT_MAX)
/// when o is inside (on the plane counts, as does a distance dot(n̂, p0 - o) >= -RK_FLT_MIN, which
/// a GPU that flushes denormals reads as ±0), else RK_RAY_MISS. n need not be normalised; a zero (or
/// denormal, or non-finite) n reads as +z. Domain: any finite inputs.
/// Max error (t against a long double reference; 10^7 random rays with p0, o within 1e3 and random
/// n, d of lengths 1e-3..1e3, 10^7 within 1e6; no local refinement): |Δt| <= 2.4 ε (|p0 - o| +
/// |t| |d|) / |n̂·d|, ε = 2^-24 (the roundings of n̂ and of the two dot products: a grazing ray's t is
/// as ill-conditioned as that). Denormals: n̂ is held times 2^64 and each product n̂_i x_i formed
/// from normal factors, so a flushing GPU agrees with the CPU (the same bits as rk_normalize_safe
/// and dot where nothing underflows). Cost: 1 normalisation, 2 dot, 1 div, ~12 selects.
RK_INLINE vec2 rk_ray_plane(vec3 o, vec3 d, vec3 p0, vec3 n)
{
    // n̂ 2^64 (nb): n / |n| with its components down to 2^-190 normal, where n / |n| would leave those
    // below 2^-126 denormal (flushed to 0 by a GPU that flushes denormals, which then lost a term
    // such as n̂_y w_y = 2^-127 FLT_MAX). Dividing by m 2^-64 and rescaling by exact powers of two
    // gives rk_normalize_safe(n)'s bits times 2^64.
    float mn = rk_ray_maxabs_(n);
    bool nok = mn >= RK_FLT_MIN && abs(n.x) <= RK_FLT_MAX && abs(n.y) <= RK_FLT_MAX && abs(n.z) <= RK_FLT_MAX;
    vec3 nv = nok ? n : vec3(0.0f, 0.0f, 1.0f);
    float mv = nok ? mn : 1.0f;
    vec3 nb = mv >= 2.1684043e-19f ? nv / rk_ray_shift_(mv, -64, 5.42101086e-20f) : rk_ray_shift3_(nv, 64, 1.84467441e19f) / mv;
    vec3 p = nb * 5.42101086e-20f;  // n / m: largest component ±1 (those lost here add < 2^-252 to |p|²)
    nb = nb * inversesqrt(dot(p, p));
    vec3 w = rk_ray_clamp3_(p0 - o);
    // Each term n̂_i x_i is formed from two normal factors where it can matter (x_i 2^-64 for
    // |x_i| >= 2^-62, else n̂_i itself) and is at most RK_FLT_MAX, so a sum can overflow to ±Inf but
    // never give NaN; clamped.
    float num = clamp(rk_ray_dot64_(nb, w), -RK_FLT_MAX, RK_FLT_MAX);  // > -FLT_MIN: o is inside
    float den = clamp(rk_ray_dot64_(nb, d), -RK_FLT_MAX, RK_FLT_MAX);
    // On the plane counts as inside, and so does a distance below RK_FLT_MIN (a flushing GPU reads
    // it as ±0; deciding by its sign would differ between the builds).
    bool inside = num >= -RK_FLT_MIN;
    if (!(abs(den) > RK_FLT_MIN)) return inside ? vec2(-RK_FLT_MAX, RK_FLT_MAX) : RK_RAY_MISS;
    float t = clamp(rk_div(num, den), -RK_FLT_MAX, RK_FLT_MAX);  // |den| may exceed 2^126
    return den < 0.0f ? vec2(t, RK_FLT_MAX) : vec2(-RK_FLT_MAX, t);
}

/// rk_ray_plane_t: the t where o + t d crosses the plane through p0 with normal n (any sign of t:
/// negative is behind the origin), or RK_FLT_MAX when the ray is parallel (see rk_ray_plane; a
/// crossing beyond ±RK_FLT_MAX also reads as ±RK_FLT_MAX). Max error: rk_ray_plane's. Cost: that of
/// rk_ray_plane.
RK_INLINE float rk_ray_plane_t(vec3 o, vec3 d, vec3 p0, vec3 n)
{
    vec2 t = rk_ray_plane(o, d, p0, n);
    if (t.x > t.y) return RK_FLT_MAX;                                   // parallel, outside
    if (t.x == -RK_FLT_MAX && t.y == RK_FLT_MAX) return RK_FLT_MAX;     // parallel, inside
    return t.x == -RK_FLT_MAX ? t.y : t.x;
}

// ---------------------------------------------------------------------------------------------
// Sphere and ellipsoids

/// rk_ray_sphere_core_: internal. The sphere |p - c| <= r with w = o - c (finite), r >= 0: the
/// interval in units of d and the outward normals at both ends (vec3(0) where there is none).
/// The direction is brought to unit length u (scaled by its largest component first), and, when
/// |w| or r lies outside [2^-50, 2^50], w and r are scaled by 2^80 or 2^-80 (exact), so that no
/// square overflows or underflows. Then, following Haines et al. 2019: b = w·u, the closest
/// approach to the centre f = w - b u (a vector, so that |f|² carries no cancellation), the
/// half-chord h = sqrt((r - |f|)(r + |f|)), the roots -b ∓ h. Their alternative second root c/q
/// (c = |w|² - r²) is not used: c cancels for an origin near the surface, and q = -b - sign(b) h is
/// tiny for a tangent ray passing next to its origin, which c/q turns into a huge error.
/// Denormals (a GPU may flush them): u is held times 2^64 and its products formed from normal
/// factors, |f| below 2^-30 is taken from f scaled by its largest component, hit or miss is
/// |f| <= r, and h² below RK_FLT_MIN is taken as sqrt(r - |f|) sqrt(r + |f|); all exact powers of two
/// or branches that leave an ordinary ray's bits unchanged.
RK_INLINE vec2 rk_ray_sphere_core_(vec3 w, vec3 d, float r, RK_OUT(vec3) n_enter, RK_OUT(vec3) n_exit)
{
    n_enter = vec3(0.0f);
    n_exit = vec3(0.0f);
    float rr = r > 0.0f ? min(r, RK_FLT_MAX) : 0.0f;  // negative and NaN read as 0
    // Position scale: keep |w| and r in [2^-50, 2^50] (2^±80 are exact powers of two).
    float s = max(rk_ray_maxabs_(w), rr);
    float k = s > 1.1258999e15f ? 8.27180613e-25f : (s < 8.8817842e-16f ? 1.20892582e24f : 1.0f);
    int ke = s > 1.1258999e15f ? -80 : (s < 8.8817842e-16f ? 80 : 0);
    // Through the exponent field (rk_ray_shift_): a compiler that merges constant factors would
    // otherwise fold k into a caller's own scaling (2^64 2^80) before the small w is applied.
    vec3 ws = rk_ray_shift3_(w, ke, k);
    float rs = rk_ray_shift_(rr, ke, k);
    float m = rk_ray_maxabs_(d);
    if (!(m >= RK_FLT_MIN)) {
        // No direction: a point, inside or not.
        return dot(ws, ws) <= rs * rs ? vec2(-RK_FLT_MAX, RK_FLT_MAX) : RK_RAY_MISS;
    }
    // Direction: dn = d / m (largest component ±1; above 2^100 scaled by 2^-100 first, exact, since
    // GLSL defines division only for divisors up to 2^126), u = dn / |dn|.
    bool big = m > 1.2676506e30f;
    float mm = big ? rk_ray_shift_(m, -100, 7.8886091e-31f) : m;
    // dn and u are formed times 2^64 (dn64, u64; exact powers of two, so the same bits): a component
    // of d down to 2^-190 of the largest stays normal, and the products with u below are taken by
    // rk_ray_mul64_ between normal factors. d / m alone left such components denormal, flushed by a
    // GPU: a ray (1, 2^-130, 0) from 2^128 away then passed its target 1 unit off.
    vec3 db = big ? rk_ray_shift3_(d, -100, 7.8886091e-31f) : d;
    vec3 dn64 = mm >= 2.1684043e-19f ? db / rk_ray_shift_(mm, -64, 5.42101086e-20f) : rk_ray_shift3_(db, 64, 1.84467441e19f) / mm;
    vec3 dn = dn64 * 5.42101086e-20f;
    float len = sqrt(dot(dn, dn));  // in [1, sqrt(3)]
    vec3 u64 = dn64 / len;
    vec3 u = u64 * 5.42101086e-20f;
    float b = rk_ray_dot64_(u64, ws);
    vec3 bu = vec3(rk_ray_mul64_(u64.x, b), rk_ray_mul64_(u64.y, b), rk_ray_mul64_(u64.z, b));
    vec3 f = ws - bu;
    // |f|: below 2^-30 (|f|² < 2^-60), from f scaled by its largest component, so that no square
    // underflows (a GPU that flushes denormals read |f| = 1e-22 as 0, a hit for r = 0); components
    // below RK_FLT_MIN count as 0 in both builds. A NaN (an overflowed matrix product of the
    // ellipsoid_m variants) reaches sqrt and misses below.
    float lf2 = dot(f, f);
    float mf = rk_ray_maxabs_(f);
    float lf = !(lf2 < 8.67361738e-19f) ? sqrt(lf2) : (mf > RK_FLT_MIN ? mf * length(f / mf) : 0.0f);
    // Hit or miss from |f| <= r itself, not from the sign of h², which underflows to ±0 for a tiny
    // sphere or a near-tangent ray.
    if (!(lf <= rs)) return RK_RAY_MISS;
    RK_PRECISE float h2 = (rs - lf) * (rs + lf);
    // Below RK_FLT_MIN (denormal, or flushed to 0 on a GPU) h² is taken as the product of the roots.
    float h = h2 > RK_FLT_MIN ? sqrt(h2) : sqrt(rs - lf) * sqrt(rs + lf);
    // Outward normals at the entry and exit points, f -/+ h u relative to the centre (from the
    // closest-approach vector, not from o + t d - c, which cancels for a distant origin).
    vec3 hu = vec3(rk_ray_mul64_(u64.x, h), rk_ray_mul64_(u64.y, h), rk_ray_mul64_(u64.z, h));
    n_enter = rk_normalize_safe(f - hu, -u);
    n_exit = rk_normalize_safe(f + hu, u);
    vec2 t = vec2(-b - h, -b + h);
    // Back to units of d: t / (len * m) / k, dividing step by step so that nothing overflows
    // (clamped where the true value does) and exact powers of two stay exact.
    t = t / len;
    t = clamp(t / mm, vec2(-RK_FLT_MAX), vec2(RK_FLT_MAX));
    t = clamp(t * (1.0f / k), vec2(-RK_FLT_MAX), vec2(RK_FLT_MAX));
    if (big) t *= 7.8886091e-31f;
    return t;
}

/// rk_ray_sphere_normals: the interval of o + t d inside the ball |p - c| <= r and the unit
/// outward normals at the entry and the exit point (rk_ray_sphere, plus the normals). The normals
/// are computed from the closest-approach vector (f ∓ h u) / r, not from o + t d - c.
/// Max error of the normals (the rays of rk_ray_sphere's bound, h >= 0.01 r): 5.2 ε (1 + |o - c| / h)
/// rad, ε = 2^-24: a few ε, plus the hit point's own rounding against the radius (a sphere 10^6 radii
/// away has its hit point, and so its normal, only to about ulp(10^6 r) / r). Cost: rk_ray_sphere's
/// + 2 normalisations.
RK_INLINE vec2 rk_ray_sphere_normals(vec3 o, vec3 d, vec3 c, float r, RK_OUT(vec3) n_enter, RK_OUT(vec3) n_exit)
{
    return rk_ray_sphere_core_(rk_ray_clamp3_(o - c), d, r, n_enter, n_exit);
}

/// rk_ray_sphere: the interval (t_enter, t_exit) of o + t d inside the ball |p - c| <= r (r < 0
/// reads as 0); RK_RAY_MISS when the line misses it. Stable for distant and grazing rays: the
/// discriminant comes from the closest-approach vector (Haines et al. 2019), so an origin 10^6
/// radii away keeps t to a few ulps where the textbook b² - c is noise beyond ~4·10^3 radii
/// (tests/test_ray.cpp shows both).
/// Domain: any finite inputs. Max error (against long double; 10^7 random rays with |o - c| in
/// [0, 100] r, r in [0.01, 100], and 10^7 with a unit sphere 1e4..1e6 from an origin near 0, both
/// with direction lengths 1e-3..1e3; no local refinement): |Δt| |d| <= 3.9 ε (|o - c| + r)
/// (1 + r / h), ε = 2^-24, h the exact half-chord (0 for a tangent ray): a few ε relative to t away
/// from tangency (4.8e-7 at 1e4..1e6 radii for h >= 0.43 r, where the textbook formula misses 14-18 %
/// of the rays and is up to 7e-4 off on the rest), growing as the ray grazes, where t itself is
/// ill-conditioned. A ray whose exact h² is below 4 ε (|o - c| + r) r may hit or miss (the only
/// flips seen in those 2 x 10^7 rays).
/// Cost: ~45 flops, ~12 selects, 2 sqrt, 4 div (+ 1 div, 1 sqrt for |f| < 2^-30; + 1 sqrt for
/// h² <= RK_FLT_MIN).
RK_INLINE vec2 rk_ray_sphere(vec3 o, vec3 d, vec3 c, float r)
{
    vec3 ne;
    vec3 nx;
    return rk_ray_sphere_core_(rk_ray_clamp3_(o - c), d, r, ne, nx);
}

/// rk_ray_ellipsoid_normals: the interval of o + t d inside the axis-aligned ellipsoid with centre
/// c and semi-axes `radii` (|(p - c) / radii| <= 1), and the unit outward normals at entry and exit.
/// The ray is scaled per axis by q = radii / r_min (r_min the smallest semi-axis, so q >= 1 and
/// nothing overflows) and cast against the sphere of radius r_min: t is unchanged by the scaling. A
/// normal is the sphere's divided by q, normalised (the gradient of |(p - c) / radii|²). |radii| is
/// floored at RK_FLT_MIN (a flat ellipsoid is a disc, and stays finite).
/// Max error (10^7 random rays, radii in [0.1, 10], |o - c| up to 100 max radius): that of
/// rk_ray_sphere in the scaled space: |Δt| |d'| <= 2.0 ε (|o' - c'| + |t| |d'| + 1) (1 + 1 / h'),
/// ε = 2^-24, primes in the unit sphere's space ((o - c) / radii, d / radii; h' the half-chord
/// there). A flat ellipsoid (q up to 2^254) is cast with the position (r_min < 2^-60, |o - c| <
/// 2^60) and the direction (|d| < 2^60) scaled by 2^64 first, and its normals taken as
/// (2^100 n_sphere) / q, so that no scaled component is denormal (exact powers of two: the same bits
/// where none was). A disc (smallest semi-axis below 2^-60) is hit by the CPU build and by drivers
/// that keep denormals; a driver that flushes them may miss it, its scaled radius being subnormal
/// (seen on NVIDIA; docs/gpu-drivers.md). Cost: rk_ray_sphere's + 9 div + ~6 flops (+ 2
/// normalisations for the normals).
RK_INLINE vec2 rk_ray_ellipsoid_normals(vec3 o, vec3 d, vec3 c, vec3 radii, RK_OUT(vec3) n_enter, RK_OUT(vec3) n_exit)
{
    vec3 rad = max(abs(radii), vec3(RK_FLT_MIN));
    float rmin = min(min(rad.x, rad.y), rad.z);
    vec3 q = min(rk_div3(rad, rmin), vec3(RK_FLT_MAX));  // >= 1 (rk_div3: rmin may exceed 2^126)
    vec3 ne;
    vec3 nx;
    // A flat ellipsoid's q reaches 2^254, which leaves w / q and d / q denormal (a flushing GPU then
    // saw a disc of radius 3 as an infinite slab). The position is scaled by 2^64 first where it
    // cannot overflow and r_min < 2^-60, the direction where |d| < 2^60 (t rescaled after): exact
    // powers of two, which change no bit of an unscaled result.
    vec3 w = rk_ray_clamp3_(o - c);
    float sw = rk_ray_maxabs_(w) < 1.1529215e18f && rmin < 8.67361738e-19f ? 1.84467441e19f : 1.0f;
    bool sd = rk_ray_maxabs_(d) < 1.1529215e18f;
    int swe = sw > 1.0f ? 64 : 0;
    vec2 t = rk_ray_sphere_core_(rk_ray_div3_(rk_ray_shift3_(w, swe, sw), q),
                                 rk_ray_div3_(sd ? rk_ray_shift3_(d, 64, 1.84467441e19f) : d, q), rk_ray_shift_(rmin, swe, sw), ne, nx);
    // t in units of d: times 2^64 for the direction's scale, over 2^64 for the position's; ±RK_FLT_MAX
    // (a miss, an unbounded or a clamped end) stays.
    float ts = sd ? (sw > 1.0f ? 1.0f : 1.84467441e19f) : (sw > 1.0f ? 5.42101086e-20f : 1.0f);
    t = vec2(abs(t.x) >= RK_FLT_MAX ? t.x : t.x * ts, abs(t.y) >= RK_FLT_MAX ? t.y : t.y * ts);
    t = clamp(t, vec2(-RK_FLT_MAX), vec2(RK_FLT_MAX));
    // The gradient of |(p - c) / radii|² is parallel to n_sphere / q (each at most 1, finite), taken
    // as (2^100 n_sphere) / q so that a component over q up to 2^226 stays normal.
    n_enter = rk_normalize_safe(rk_ray_div3_(ne * 1.2676506e30f, q), vec3(0.0f));
    n_exit = rk_normalize_safe(rk_ray_div3_(nx * 1.2676506e30f, q), vec3(0.0f));
    return t;
}

/// rk_ray_ellipsoid: rk_ray_ellipsoid_normals without the normals. Cost: rk_ray_sphere's + 9 div + ~6 flops.
RK_INLINE vec2 rk_ray_ellipsoid(vec3 o, vec3 d, vec3 c, vec3 radii)
{
    vec3 ne;
    vec3 nx;
    return rk_ray_ellipsoid_normals(o, d, c, radii, ne, nx);
}

/// rk_ray_ellipsoid_m_normals: the interval of o + t d inside the ellipsoid {c + M q : |q| <= 1}
/// for any invertible 3x3 M (rotation, scale, shear), given to_unit = inverse(M): the ray is mapped
/// to (to_unit (o - c), to_unit d) and cast against the unit sphere (t is unchanged by a linear
/// map). Normals: transpose(to_unit) n_sphere, normalised. A singular to_unit gives a degenerate
/// (infinite cylinder or slab) solid, still finite. Max error (10^7 random rays, random rotations
/// times scales in [0.1, 10]): |Δt| |d'| <= 2.1 ε (|A| |o - c| + |t| |A| |d| + 1) (1 + 1 / h'),
/// A = to_unit, |A| its entries' magnitudes, d' = A d, h' the half-chord in the unit space: the
/// matrix products' rounding scales with |A| |o - c|, not |A (o - c)| (any error of to_unit itself
/// is the caller's). Cost: rk_ray_sphere's + 2 mat3 * vec3 (+ 2 transposed
/// products and 2 normalisations for the normals).
RK_INLINE vec2 rk_ray_ellipsoid_m_normals(vec3 o, vec3 d, vec3 c, mat3 to_unit, RK_OUT(vec3) n_enter, RK_OUT(vec3) n_exit)
{
    vec3 ws = rk_ray_clamp3_(to_unit * rk_ray_clamp3_(o - c));
    vec3 ds = rk_ray_clamp3_(to_unit * d);
    vec3 ne;
    vec3 nx;
    vec2 t = rk_ray_sphere_core_(ws, ds, 1.0f, ne, nx);
    // transpose(A) v = (A[0]·v, A[1]·v, A[2]·v) (columns): no transpose() needed.
    n_enter = rk_normalize_safe(rk_ray_clamp3_(vec3(dot(to_unit[0], ne), dot(to_unit[1], ne), dot(to_unit[2], ne))), vec3(0.0f));
    n_exit = rk_normalize_safe(rk_ray_clamp3_(vec3(dot(to_unit[0], nx), dot(to_unit[1], nx), dot(to_unit[2], nx))), vec3(0.0f));
    return t;
}

/// rk_ray_ellipsoid_m: rk_ray_ellipsoid_m_normals without the normals. Cost: rk_ray_sphere's +
/// 2 mat3 * vec3.
RK_INLINE vec2 rk_ray_ellipsoid_m(vec3 o, vec3 d, vec3 c, mat3 to_unit)
{
    vec3 ws = rk_ray_clamp3_(to_unit * rk_ray_clamp3_(o - c));
    vec3 ds = rk_ray_clamp3_(to_unit * d);
    vec3 ne;
    vec3 nx;
    return rk_ray_sphere_core_(ws, ds, 1.0f, ne, nx);
}

// ---------------------------------------------------------------------------------------------
// Axis-aligned box

/// rk_ray_box_axis_: internal. The axis (0, 1, 2) whose plane the ray crosses last among the
/// per-axis values tv (largest, or smallest when `smallest`); on an exact tie (an edge or corner,
/// or a ray in a face plane) the axis it crosses most steeply (largest |d|), never a parallel one.
RK_INLINE uint rk_ray_box_axis_(vec3 tv, vec3 ad, bool smallest)
{
    vec3 v = smallest ? -tv : tv;
    uint ax = (v.y > v.x || (v.y == v.x && ad.y > ad.x)) ? 1u : 0u;
    float vb = ax == 0u ? v.x : v.y;
    float ab = ax == 0u ? ad.x : ad.y;
    if (v.z > vb || (v.z == vb && ad.z > ab)) ax = 2u;
    return ax;
}

/// rk_ray_box_normals: the interval of o + t d inside the closed box spanned by the corners lo and
/// hi (componentwise min and max, so their order does not matter), and the unit outward face
/// normals at the entry and the exit point; at an edge or corner the face the ray crosses most
/// steeply. Slab method (Kay and Kajiya; Williams et al. 2005) with each axis's t computed by a
/// division (lo_i - o_i) / d_i, so one rounding each: an axis with |d_i| < RK_FLT_MIN is parallel
/// and, instead of 1 / d_i = ±Inf (Williams et al.'s IEEE trick, which gives 0 * Inf = NaN for an
/// origin on that slab's plane), bounds nothing when lo_i <= o_i <= hi_i and misses otherwise.
/// An origin on a face, edge or corner is inside (t_enter <= 0 <= t_exit, t = ±0 exactly there).
/// A per-axis crossing with |t| <= RK_FLT_MIN is t = 0 in both builds (a GPU that flushes denormals
/// stores it as ±0; ordering the CPU's denormal against it picked other faces, or a miss).
/// Domain: any finite inputs. Max error (against long double; 10^7 random rays with boxes and
/// origins within 1e3, 10^7 within 1e6, some on faces and edges, direction components 0, -0,
/// 1e-30, -1e-40): |Δt| <= 2 ε |t|, ε = 2^-24 (1.99 ε measured; in the CPU build provably: the
/// subtraction and the division each round once, to half an ulp; GLSL allows its division 2.5
/// ulps) for |t| > RK_FLT_MIN, and t = 0 exactly when o is on the plane (or |t| <= RK_FLT_MIN).
/// Cost: 6 div, ~30 flops and selects.
RK_INLINE vec2 rk_ray_box_normals(vec3 o, vec3 d, vec3 lo, vec3 hi, RK_OUT(vec3) n_enter, RK_OUT(vec3) n_exit)
{
    n_enter = vec3(0.0f);
    n_exit = vec3(0.0f);
    vec3 bmin = min(lo, hi);
    vec3 bmax = max(lo, hi);
    vec3 ga = rk_ray_clamp3_(bmin - o);
    vec3 gb = rk_ray_clamp3_(bmax - o);
    vec3 ad = abs(d);
    bvec3 par = bvec3(!(ad.x >= RK_FLT_MIN), !(ad.y >= RK_FLT_MIN), !(ad.z >= RK_FLT_MIN));
    // A parallel axis: inside its slab iff ga <= 0 <= gb; the divisor is then a dummy 1.
    if ((par.x && !(ga.x <= 0.0f && gb.x >= 0.0f)) || (par.y && !(ga.y <= 0.0f && gb.y >= 0.0f)) ||
        (par.z && !(ga.z <= 0.0f && gb.z >= 0.0f)))
        return RK_RAY_MISS;
    vec3 dd = vec3(par.x ? 1.0f : d.x, par.y ? 1.0f : d.y, par.z ? 1.0f : d.z);
    // Quotients may overflow to ±Inf (finite / tiny); clamped. No 0 * Inf, so never NaN.
    vec3 ta = rk_ray_clamp3_(rk_ray_div3_(ga, dd));  // |d_i| may exceed 2^126
    vec3 tb = rk_ray_clamp3_(rk_ray_div3_(gb, dd));
    // A crossing with |t| < RK_FLT_MIN is t = 0 in both builds (a flushing GPU stores it as ±0, and
    // the comparisons below would otherwise order it differently from the CPU's denormal).
    ta = vec3(abs(ta.x) <= RK_FLT_MIN ? 0.0f : ta.x, abs(ta.y) <= RK_FLT_MIN ? 0.0f : ta.y, abs(ta.z) <= RK_FLT_MIN ? 0.0f : ta.z);
    tb = vec3(abs(tb.x) <= RK_FLT_MIN ? 0.0f : tb.x, abs(tb.y) <= RK_FLT_MIN ? 0.0f : tb.y, abs(tb.z) <= RK_FLT_MIN ? 0.0f : tb.z);
    vec3 tn = min(ta, tb);
    vec3 tf = max(ta, tb);
    tn = vec3(par.x ? -RK_FLT_MAX : tn.x, par.y ? -RK_FLT_MAX : tn.y, par.z ? -RK_FLT_MAX : tn.z);
    tf = vec3(par.x ? RK_FLT_MAX : tf.x, par.y ? RK_FLT_MAX : tf.y, par.z ? RK_FLT_MAX : tf.z);
    float t0 = max(max(tn.x, tn.y), tn.z);
    float t1 = min(min(tf.x, tf.y), tf.z);
    if (!(t0 <= t1)) return RK_RAY_MISS;
    if (par.x && par.y && par.z) return vec2(t0, t1);  // a point inside: no faces
    vec3 adn = vec3(par.x ? 0.0f : ad.x, par.y ? 0.0f : ad.y, par.z ? 0.0f : ad.z);
    uint ae = rk_ray_box_axis_(tn, adn, false);
    uint ax = rk_ray_box_axis_(tf, adn, true);
    float se = (ae == 0u ? d.x : (ae == 1u ? d.y : d.z)) > 0.0f ? -1.0f : 1.0f;
    float sx = (ax == 0u ? d.x : (ax == 1u ? d.y : d.z)) > 0.0f ? 1.0f : -1.0f;
    n_enter = vec3(ae == 0u ? se : 0.0f, ae == 1u ? se : 0.0f, ae == 2u ? se : 0.0f);
    n_exit = vec3(ax == 0u ? sx : 0.0f, ax == 1u ? sx : 0.0f, ax == 2u ? sx : 0.0f);
    return vec2(t0, t1);
}

/// rk_ray_box: rk_ray_box_normals without the normals. Max error: the same (|Δt| <= 2 ε |t|).
/// Cost: 6 div, ~26 flops.
RK_INLINE vec2 rk_ray_box(vec3 o, vec3 d, vec3 lo, vec3 hi)
{
    vec3 ne;
    vec3 nx;
    return rk_ray_box_normals(o, d, lo, hi, ne, nx);
}

// ---------------------------------------------------------------------------------------------
// Impostors
//
// A sphere or box drawn as a rasterised proxy (a screen-aligned quad, a bounding box, a light
// volume's mesh) whose fragments raycast the real surface. The fragment shader passes its view ray
// and writes the returned depth (gl_FragDepth) and normal; it discards when the function returns
// false. View space: the camera at the origin looking down -z (as in gbuffer.glsl). A perspective
// camera's view ray is o = vec3(0), d = the fragment's interpolated view-space position on the
// proxy (no normalisation needed).
//
// Depth: through rk_gb_window_depth(-p.z, k) (gbuffer.glsl), k = rk_gb_depth_params(near, far,
// reversed): one function of the view distance covers OpenGL's [-1, 1] NDC and Vulkan's [0, 1]
// (the same window depth) and reversed-Z, with infinite far planes. Chosen over svo_hybrid.glsl's
// rk_svo_window_depth(obj_to_clip, p, depth_range) because the hit is already in view space, so the
// depth needs only -p.z and three uniforms, not a mat4 product and a division per fragment, and
// because it is the inverse of rk_gb_linear_depth: a deferred pass reading the depth back gets the
// hit's distance within 2e-7 relative. It assumes a perspective projection: for an orthographic
// one, or to project through the very matrix the rasteriser uses (svo_hybrid.glsl), pass the
// returned view-space point to rk_svo_window_depth(projection, p, depth_range) instead.

/// rk_ray_impostor_finish_: internal. The first hit at t >= 0 of an interval: point, normal (the
/// exit normal when the origin is inside) and window depth; false, zeros and the far plane's depth
/// (k.z: 1 usual, 0 reversed-Z) for none.
RK_INLINE bool rk_ray_impostor_finish_(vec3 o, vec3 d, vec2 t, vec3 ne, vec3 nx, vec3 k, RK_OUT(vec3) p, RK_OUT(vec3) n,
                                       RK_OUT(float) depth)
{
    p = vec3(0.0f);
    n = vec3(0.0f);
    depth = k.z;
    if (!rk_ray_hit(t)) return false;
    bool inside = t.x < 0.0f;
    float th = inside ? t.y : t.x;
    p = rk_ray_clamp3_(o + th * d);
    n = inside ? nx : ne;
    depth = rk_gb_window_depth(-p.z, k);
    return true;
}

/// rk_ray_impostor_sphere: raycasts the view-space sphere (centre c, radius r) along a fragment's
/// view ray o + t d (see above) and returns whether it hits at some t >= 0; then p is the view-space
/// point of the first such hit (the far side when the camera is inside the sphere), n the unit
/// outward normal there and depth its window depth for k = rk_gb_depth_params(near, far, reversed)
/// (through rk_gb_window_depth: see above for why that one). A point in front of the near plane gets
/// the near plane's depth (clamped); the caller may discard it. Misses: false, p = n = 0, depth =
/// the far plane's (k.z). Max error: rk_ray_sphere's for t (p = o + t d, one more rounding); the
/// depth within 0.6 ε (ε = 2^-24) of the float64 projection of the exact hit through each
/// convention's matrix (OpenGL, Vulkan, reversed-Z finite and infinite; a sphere 5 units away seen
/// through 4096 pixels: tests/test_ray.cpp, where rk_svo_window_depth through the float matrix gives
/// 1.7 ε). A direction above 2^100 is scaled by 2^-100 first (exact), so that t (about distance /
/// |d|) is not denormal, which a flushing GPU read as 0 (p = o). Cost: rk_ray_sphere_normals' +
/// 1 fma + 2 div + 4 flops.
RK_INLINE bool rk_ray_impostor_sphere(vec3 o, vec3 d, vec3 c, float r, vec3 k, RK_OUT(vec3) p, RK_OUT(vec3) n,
                                      RK_OUT(float) depth)
{
    vec3 ne;
    vec3 nx;
    // A direction above 2^100 is scaled by 2^-100 first (exact; t scales by 2^100): its t, of the
    // order of distance / |d|, would otherwise be denormal, and t d lost on a flushing GPU.
    vec3 dd = rk_ray_maxabs_(d) > 1.2676506e30f ? d * 7.8886091e-31f : d;
    vec2 t = rk_ray_sphere_normals(o, dd, c, r, ne, nx);
    return rk_ray_impostor_finish_(o, dd, t, ne, nx, k, p, n, depth);
}

/// rk_ray_impostor_box: as rk_ray_impostor_sphere for an oriented box in view space: the points
/// c + q with |(view_to_box q)_i| <= half_extent_i. view_to_box maps view-space offsets to the box's
/// axes (for a box whose view-space axes are the unit columns of R: transpose(R); a scale in it
/// scales the extents). The ray is mapped into the box's frame, cast with rk_ray_box (t is unchanged
/// by the linear map), and the normal mapped back with transpose(view_to_box), normalised. The hit
/// point is o + t d in view space, so its depth needs no inverse matrix. Max error: rk_ray_box's in
/// the box's frame, after the matrix product's rounding of the mapped ray. Cost: rk_ray_box_normals'
/// + 2 mat3 * vec3 + 1 normalisation + 2 div.
RK_INLINE bool rk_ray_impostor_box(vec3 o, vec3 d, vec3 c, mat3 view_to_box, vec3 half_extent, vec3 k, RK_OUT(vec3) p,
                                   RK_OUT(vec3) n, RK_OUT(float) depth)
{
    vec3 ob = rk_ray_clamp3_(view_to_box * rk_ray_clamp3_(o - c));
    vec3 db = rk_ray_clamp3_(view_to_box * d);
    vec3 e = abs(half_extent);
    vec3 ne;
    vec3 nx;
    vec2 t = rk_ray_box_normals(ob, db, -e, e, ne, nx);
    ne = rk_normalize_safe(vec3(dot(view_to_box[0], ne), dot(view_to_box[1], ne), dot(view_to_box[2], ne)), vec3(0.0f));
    nx = rk_normalize_safe(vec3(dot(view_to_box[0], nx), dot(view_to_box[1], nx), dot(view_to_box[2], nx)), vec3(0.0f));
    return rk_ray_impostor_finish_(o, d, t, ne, nx, k, p, n, depth);
}

#endif  // RK_RAY_GLSL
