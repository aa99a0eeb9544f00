// Float64 brute-force references for interior mapping and its hashes, written independently of
// shaders/raykit/interior_mapping.glsl and hash.glsl. Nothing from raykit is included.
//
// The interior is real geometry here: a box building whose rooms are separated by explicit wall
// planes (axis a, plane position X listed one by one, possibly displaced per wall), and a ray from
// the camera through the facade point p is intersected with EVERY listed plane of the building in
// double precision; the nearest crossing beyond the facade is the hit. The room is the cell that
// contains the midpoint of the segment from p to the hit (found by searching the plane list).
// The only convention shared with the library is the documented facade rule: a plane lying within
// `facade_eps` room units of the facade along the facade's axis is the facade itself (not a hit).
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace ref_im {

// ---- hashes, from their papers' definitions --------------------------------------------------

/// PCG3D as defined by Jarzynski & Olano (JCGT 2020, listing "pcg3d"): an LCG step on each lane
/// (multiplier 1664525, increment 1013904223), then lane mixing x += y*z, y += z*x, z += x*y, an
/// xorshift by 16 on every lane, and the same mixing again. Written over a plain array.
inline void pcg3d(const std::uint32_t in[3], std::uint32_t out[3])
{
    std::uint32_t v[3];
    for (int i = 0; i < 3; ++i) v[i] = static_cast<std::uint32_t>(in[i] * 1664525ull + 1013904223ull);
    auto mix = [&v]() {
        for (int i = 0; i < 3; ++i) {
            const int j = (i + 1) % 3, k = (i + 2) % 3;
            v[i] = static_cast<std::uint32_t>(v[i] + static_cast<std::uint64_t>(v[j]) * v[k]);
        }
    };
    mix();
    for (int i = 0; i < 3; ++i) v[i] ^= v[i] >> 16;
    mix();
    for (int i = 0; i < 3; ++i) out[i] = v[i];
}

/// PCG-RXS-M-XS-32 output (O'Neill 2014, Table/§6.3.4) applied to one LCG step (PCG's 32-bit
/// multiplier 747796405, increment 2891336453), in 64-bit arithmetic reduced mod 2^32.
inline std::uint32_t pcg_rxs_m_xs(std::uint32_t x)
{
    const std::uint64_t mod = 1ull << 32;
    const std::uint32_t state = static_cast<std::uint32_t>((x * 747796405ull + 2891336453ull) % mod);
    const unsigned rshift = (state >> 28) + 4u;
    const std::uint32_t word = static_cast<std::uint32_t>((((state >> rshift) ^ state) * 277803737ull) % mod);
    return (word >> 22) ^ word;
}

/// The exact value of a 24-bit unit mapping: top 24 bits / 2^24.
inline double unit24(std::uint32_t x) { return std::ldexp(static_cast<double>(x >> 8), -24); }

// ---- brute-force room tracer -----------------------------------------------------------------

struct Grid {
    double room[3];
    double origin[3];
};

/// Wall offset in room units for wall k of an axis; the regular grid is the zero function.
using WallOffset = std::function<double(int axis, long k)>;

/// The explicit plane list of one axis: every wall that can bound a room of the building (its
/// extent plus two rooms of margin), at object-space coordinate origin + (k + offset(k)) room.
struct PlaneList {
    std::vector<double> x;   // object-space positions, ascending in k
    std::vector<long> k;     // wall indices
};

inline PlaneList planes_for(int axis, double lo, double hi, const Grid& g, const WallOffset& off)
{
    PlaneList pl;
    const long k0 = static_cast<long>(std::floor((lo - g.origin[axis]) / g.room[axis])) - 2;
    const long k1 = static_cast<long>(std::ceil((hi - g.origin[axis]) / g.room[axis])) + 2;
    for (long k = k0; k <= k1; ++k) {
        const double o = off ? off(axis, k) : 0.0;
        pl.x.push_back(g.origin[axis] + (static_cast<double>(k) + o) * g.room[axis]);
        pl.k.push_back(k);
    }
    return pl;
}

/// The cell index of coordinate v among the planes: wall k with x_k <= v < x_{k+1}.
inline long cell_of(const PlaneList& pl, double v)
{
    long cell = pl.k.front() - 1;
    for (size_t i = 0; i < pl.x.size(); ++i) {
        if (pl.x[i] <= v) cell = pl.k[i];
    }
    return cell;
}

struct Hit {
    bool valid = false;
    int family = -1;        // axis of the nearest plane (ties: x, then z, then y)
    int side = 0;
    long room[3] = {0, 0, 0};
    double t = 0;           // ray fraction
    double t_family[3];     // nearest crossing per family (inf when none)
    double pos[3];
    double mid_grid[3];     // midpoint of p..hit in grid units (for ambiguity checks)
    double uv[2];           // on the hit face, normalised across the room's actual width
};

/// Traces the ray cam -> p through a box building [lo, hi] whose facade is the face of axis
/// `face_axis` with outward sign `face_sign` (p lies on it). Enumerates all planes of the three
/// families; a plane of face_axis within facade_eps room units of p along that axis is the
/// facade (skipped), and the room containing the segment start is taken behind it.
inline Hit trace(const double p[3], const double cam[3], int face_axis, int face_sign, const double lo[3],
                 const double hi[3], const Grid& g, const WallOffset& off, double facade_eps)
{
    Hit h;
    double dir[3];
    for (int a = 0; a < 3; ++a) dir[a] = p[a] - cam[a];
    h.valid = dir[face_axis] * face_sign < 0.0;
    if (!h.valid) return h;
    PlaneList pl[3];
    for (int a = 0; a < 3; ++a) pl[a] = planes_for(a, lo[a], hi[a], g, off);
    double skipped = std::numeric_limits<double>::quiet_NaN();
    h.t = std::numeric_limits<double>::infinity();
    for (int a : {0, 2, 1}) {  // tie order: x wall, z wall, floor/ceiling
        h.t_family[a] = std::numeric_limits<double>::infinity();
        if (dir[a] == 0.0) continue;
        for (double x : pl[a].x) {
            const double t = (x - cam[a]) / dir[a];
            if (!(t > 1.0)) continue;
            if (a == face_axis && std::abs(x - p[a]) <= facade_eps * g.room[a]) {
                skipped = x;
                continue;
            }
            if (t < h.t_family[a]) h.t_family[a] = t;
            if (t < h.t) {
                h.t = t;
                h.family = a;
            }
        }
    }
    h.side = dir[h.family] > 0 ? 1 : -1;
    for (int a = 0; a < 3; ++a) h.pos[a] = cam[a] + h.t * dir[a];
    for (int a = 0; a < 3; ++a) {
        const double mid = cam[a] + 0.5 * (1.0 + h.t) * dir[a];
        h.mid_grid[a] = (mid - g.origin[a]) / g.room[a];
        h.room[a] = cell_of(pl[a], mid);
        // The segment start lies in the skipped facade sliver: the room is the one behind it.
        if (a == face_axis && !std::isnan(skipped) && (skipped - mid) * dir[a] > 0.0) h.room[a] += dir[a] > 0 ? 1 : -1;
    }
    const int ua = h.family == 0 ? 2 : 0, vb = h.family == 1 ? 2 : 1;
    const int axes[2] = {ua, vb};
    for (int j = 0; j < 2; ++j) {
        const int a = axes[j];
        double wlo = 0, whi = 1;
        for (size_t i = 0; i < pl[a].k.size(); ++i) {
            if (pl[a].k[i] == h.room[a]) wlo = pl[a].x[i];
            if (pl[a].k[i] == h.room[a] + 1) whi = pl[a].x[i];
        }
        h.uv[j] = (h.pos[a] - wlo) / (whi - wlo);
    }
    return h;
}

}  // namespace ref_im
