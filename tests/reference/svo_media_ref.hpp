// Float64 reference for refraction through voxel media (svo_secondary.glsl's
// rk_svo_refract_through / rk_svo_march), written apart from the shader from its documented
// contract: a plain cell-by-cell walk in double, no code of the shader's reused. Only std, GLM and
// the suite's float64 Fresnel (reference/fresnel_ref.hpp).
//
// World. A grid of unit cells [0, side)^3 (cell c is the box [c, c + 1]); the caller says which
// cells are occupied and, for those, their medium {n, absorb rgb per unit length}. Empty cells and
// everything outside the grid are the outside medium n_out without absorption.
//
// Optics (every step in double):
//   - From the origin (in empty space) the ray goes straight (a 3D DDA over the cells) until it
//     enters an occupied cell: an ENTRY through the face crossed, whose axis is the normal. The
//     first entry gives the first-surface reflectance and mirror direction. An entry always counts
//     as an interface (even into a medium of index n_out), as the contract's "surfaces crossed
//     (entries, ...)" and the slab test's count (1 for index 1.0) say.
//   - Inside, cell by cell: absorption exp(-absorb * segment) per cell segment; at every face
//     crossed into a cell of a different index (an empty cell has n_out) Snell's law about that
//     face's axis normal: total internal reflection mirrors the ray (it stays in its cell, counted
//     as an interface); otherwise it refracts and the transmittance is multiplied by 1 - R, R the
//     exact unpolarised dielectric Fresnel reflectance. A face between equal indices is no
//     interface. Crossing into an empty cell is an EXIT: the leaving ray (exit point, direction) is
//     recorded and the ray goes on straight to the next entry.
//   - A re-entry close behind an exit continues the same leg: an entry into the second or third
//     cell after an exit (the cells the ray crosses within a voxel of the exit, which the shader's
//     march looks at before it gives the ray back) is an interface but not a new entry.
//   - At most max_surfaces entries: an entry that would exceed them is not made and the trace
//     stops, incomplete, with the last exit as the leaving ray (`more_follow`). `complete` means
//     the ray escaped the grid: no further entry lies ahead, whatever the budget.
//
// Honesty (ties). The exact path can pass arbitrarily close to a cell edge or corner, where the
// order in which two faces are crossed decides the outcome, or refract arbitrarily close to the
// critical angle. A float32 tracer cannot be expected to agree there, so the trace records:
//   edge_margin      the smallest distance (voxels, the crossing point's distance to the other
//                    lattice planes) at which a face crossing passes an edge or corner whose
//                    surrounding cells' media depend on more than one axis (an edge where only one
//                    axis matters, e.g. inside a flat wall, is no ambiguity);
//   critical_margin  the smallest |cos^2 theta_t| (= |1 - eta^2 sin^2 theta_i|) at an interface;
//   min_cos_i        the most grazing incidence at any interface.
// A test flags a ray as a tie (edge_margin, critical_margin) when the margin is below its epsilon,
// and leaves it out (counted). (A new entry after an exit lies at least a voxel along the ray: the
// entries before that continue the leg, above. So a tracer that restarts a leg less than a voxel
// past an exit, as the shader does, cannot step past one; nothing needs flagging for that.)
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <glm/glm.hpp>

#include "reference/fresnel_ref.hpp"

namespace rkref {

/// A voxel's medium: refractive index and Beer–Lambert absorption per unit length.
struct VoxelMedium {
    double n = 1.0;
    glm::dvec3 absorb{0.0};
};

/// One event on the path (for tests that want to know where the ray went).
struct MediaEvent {
    enum Kind { entry, entry_reflection, change, internal_reflection, exit };
    Kind kind;
    glm::ivec3 from;   ///< the cell the ray was in
    glm::ivec3 to;     ///< the cell across the face (== from's neighbour even under reflection)
    int axis;          ///< the face's axis
    glm::dvec3 point;  ///< where it crossed (or reflected)
    glm::dvec3 dir;    ///< direction after the event
};

struct MediaTraceOptions {
    double edge_window = 0.05;               ///< edge/corner distances at or above this are not examined
    long max_steps = 1L << 22;               ///< cells visited, a guard
    int lookahead_cells = 3;                 ///< an entry into cells 2..this after an exit continues the leg
    std::vector<MediaEvent>* events = nullptr;  ///< optional event log (appended to)
};

struct MediaTrace {
    bool hit = false;                  ///< at least one entry was made
    double reflectance = 0.0;          ///< Fresnel reflectance at the first entry
    glm::dvec3 reflect_dir{0.0};       ///< mirror direction at the first entry
    glm::dvec3 entry_normal{0.0};      ///< first entered face's axis normal, facing the incoming ray
    glm::dvec3 entry_point{0.0};       ///< where the first entry happened
    glm::dvec3 exit_point{0.0};        ///< the leaving ray: the last exit (the origin when !hit)
    glm::dvec3 dir{0.0};               ///< its direction (the unit incident direction when !hit)
    glm::dvec3 transmittance{1.0};     ///< product of (1 - R) at refractions and the absorption
    unsigned interfaces = 0;           ///< entries + refractions + internal reflections + exits
    unsigned entries = 0, exits = 0;
    bool complete = true;              ///< escaped the grid: no further entry ahead
    bool more_follow = false;          ///< stopped by the budget with another entry ahead
    bool stuck = false;                ///< max_steps reached (never in a sane world)
    double path_inside = 0.0;          ///< length travelled through occupied cells
    double edge_margin = std::numeric_limits<double>::infinity();
    double critical_margin = std::numeric_limits<double>::infinity();
    double min_cos_i = std::numeric_limits<double>::infinity();
};

namespace media_detail {

/// Snell at a face of axis `a` from index n1 to n2: returns false under total internal reflection
/// (d then mirrored); else d refracted. k receives cos^2 theta_t (negative under TIR), cos_i the
/// incidence cosine, R the Fresnel reflectance.
inline bool snell_axis(glm::dvec3& d, int a, double n1, double n2, double& k, double& cos_i, double& R)
{
    const double eta = n1 / n2;
    double tang2 = 0.0;
    for (int j = 0; j < 3; ++j)
        if (j != a) tang2 += d[j] * d[j];
    cos_i = std::abs(d[a]);
    k = 1.0 - eta * eta * tang2;
    if (k <= 0.0) {
        R = 1.0;
        d[a] = -d[a];
        return false;
    }
    R = ref::fresnel(std::min(cos_i, 1.0), n2 / n1);  // the suite's float64 Fresnel (reference/fresnel_ref.hpp)
    const double s = d[a] >= 0.0 ? 1.0 : -1.0;
    for (int j = 0; j < 3; ++j)
        if (j != a) d[j] *= eta;
    d[a] = s * std::sqrt(k);
    return true;
}

}  // namespace media_detail

/// Traces the ray origin + t * dir (origin in empty space; dir nonzero, normalised here) through
/// the voxel world, up to max_surfaces entries. See the file comment for the model.
template <class Occupied, class Medium>
MediaTrace trace_voxel_media(int side, Occupied occupied, Medium medium, double n_out, glm::dvec3 origin, glm::dvec3 dir,
                             unsigned max_surfaces, const MediaTraceOptions& opt = MediaTraceOptions())
{
    using glm::dvec3;
    using glm::ivec3;
    MediaTrace r;
    dvec3 D = dir / glm::length(dir);
    r.exit_point = origin;
    r.dir = D;
    auto in_grid = [&](ivec3 c) { return c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < side && c.y < side && c.z < side; };
    auto occ = [&](ivec3 c) -> bool { return in_grid(c) && occupied(c); };
    // What the ray sees in a cell: empty (n_out), or occupied with an index. Absorption alone does
    // not change a path, so it is left out of the tie test.
    auto key = [&](ivec3 c) -> double { return occ(c) ? medium(c).n : -1.0; };
    auto log = [&](MediaEvent::Kind kind, ivec3 from, ivec3 to, int axis, dvec3 p) {
        if (opt.events) opt.events->push_back(MediaEvent{kind, from, to, axis, p, D});
    };

    dvec3 S = origin;  // start of the current straight leg
    ivec3 C(int(std::floor(S.x)), int(std::floor(S.y)), int(std::floor(S.z)));
    bool inside = false;
    VoxelMedium cur;
    int cells_out = 0;      // empty cells since the last exit, the one it led into included
    for (long step = 0; step < opt.max_steps; ++step) {
        if (!inside) {
            bool away = false;
            for (int a = 0; a < 3; ++a)
                away = away || (C[a] < 0 && D[a] <= 0.0) || (C[a] >= side && D[a] >= 0.0);
            if (away) {
                r.complete = true;  // nothing more ahead
                return r;
            }
        }
        // Next face of cell C along D.
        int a = -1;
        double t = std::numeric_limits<double>::infinity();
        for (int j = 0; j < 3; ++j) {
            if (D[j] == 0.0) continue;
            const double plane = double(C[j] + (D[j] > 0.0 ? 1 : 0));
            const double tj = std::max((plane - S[j]) / D[j], 0.0);
            if (tj < t) {
                t = tj;
                a = j;
            }
        }
        dvec3 X = S + t * D;
        X[a] = double(C[a] + (D[a] > 0.0 ? 1 : 0));
        for (int j = 0; j < 3; ++j)
            if (j != a) X[j] = std::min(std::max(X[j], double(C[j])), double(C[j] + 1));
        if (inside) {
            r.transmittance *= glm::exp(-cur.absorb * t);
            r.path_inside += t;
        }
        ivec3 N = C;
        N[a] += D[a] > 0.0 ? 1 : -1;
        S = X;

        // Tie test: edges/corners of the crossed face within edge_window of X.
        {
            int near_axes[2];
            double near_dist[2];
            int nn = 0;
            for (int j = 0; j < 3; ++j) {
                if (j == a) continue;
                const double dist = std::abs(X[j] - std::round(X[j]));
                if (dist < opt.edge_window) {
                    near_axes[nn] = j;
                    near_dist[nn] = dist;
                    ++nn;
                }
            }
            // Every non-empty subset of the near axes: an edge (one) or the corner (both).
            for (int mask = 1; mask < (1 << nn); ++mask) {
                int axes[3] = {a, 0, 0};
                int na = 1;
                double margin = 0.0;
                for (int i = 0; i < nn; ++i)
                    if (mask & (1 << i)) {
                        axes[na++] = near_axes[i];
                        margin = std::max(margin, near_dist[i]);
                    }
                if (margin >= r.edge_margin) continue;
                // The 2^na cells around the edge/corner: bit i picks the side of axes[i].
                double keys[8];
                for (int b = 0; b < (1 << na); ++b) {
                    ivec3 c = C;
                    for (int i = 0; i < na; ++i) {
                        const int lo = i == 0 ? std::min(C[a], N[a]) : int(std::round(X[axes[i]])) - 1;
                        c[axes[i]] = lo + ((b >> i) & 1);
                    }
                    keys[b] = key(c);
                }
                // Ambiguous when the media depend on more than one of these axes.
                int depends = 0;
                for (int i = 0; i < na; ++i) {
                    bool dep = false;
                    for (int b = 0; b < (1 << na); ++b)
                        if (!((b >> i) & 1) && keys[b] != keys[b | (1 << i)]) dep = true;
                    depends += dep ? 1 : 0;
                }
                if (depends > 1) r.edge_margin = margin;
            }
        }

        if (!inside) {
            if (!occ(N)) {
                C = N;
                ++cells_out;
                continue;
            }
            // An entry, or a re-entry that continues the leg.
            const bool continues = r.exits > 0 && cells_out < opt.lookahead_cells;
            if (!continues && r.entries >= max_surfaces) {
                r.complete = false;
                r.more_follow = true;
                return r;
            }
            const VoxelMedium m = medium(N);
            if (!continues) ++r.entries;
            ++r.interfaces;
            dvec3 Din = D;
            double k = 0.0, cos_i = 0.0, R = 0.0;
            const bool refracted = media_detail::snell_axis(Din, a, n_out, m.n, k, cos_i, R);
            r.critical_margin = std::min(r.critical_margin, std::abs(k));
            r.min_cos_i = std::min(r.min_cos_i, cos_i);
            if (!r.hit) {
                r.hit = true;
                r.reflectance = R;
                r.reflect_dir = D;
                r.reflect_dir[a] = -D[a];
                r.entry_normal = dvec3(0.0);
                r.entry_normal[a] = D[a] > 0.0 ? -1.0 : 1.0;
                r.entry_point = X;
            }
            D = Din;
            if (!refracted) {  // mirrored: stays in the empty cell, leaving from this face
                log(MediaEvent::entry_reflection, C, N, a, X);
                r.exit_point = X;
                r.dir = D;
                // Off a re-entry the leg goes on (the next cells are looked at again); off an
                // entry the next object is a new entry.
                cells_out = continues ? 1 : opt.lookahead_cells;
                continue;
            }
            r.transmittance *= 1.0 - R;
            log(MediaEvent::entry, C, N, a, X);
            C = N;
            cur = m;
            inside = true;
            continue;
        }
        // Inside: the next cell's index.
        const bool next_occ = occ(N);
        const VoxelMedium next = next_occ ? medium(N) : VoxelMedium{n_out, dvec3(0.0)};
        if (next.n != cur.n) {
            ++r.interfaces;
            double k = 0.0, cos_i = 0.0, R = 0.0;
            const bool refracted = media_detail::snell_axis(D, a, cur.n, next.n, k, cos_i, R);
            r.critical_margin = std::min(r.critical_margin, std::abs(k));
            r.min_cos_i = std::min(r.min_cos_i, cos_i);
            if (!refracted) {  // mirrored: stays in this cell
                log(MediaEvent::internal_reflection, C, N, a, X);
                continue;
            }
            r.transmittance *= 1.0 - R;
        }
        if (!next_occ) {
            ++r.exits;
            r.exit_point = X;
            r.dir = D;
            cells_out = 1;
            log(MediaEvent::exit, C, N, a, X);
            C = N;
            inside = false;
            continue;
        }
        if (next.n != cur.n) log(MediaEvent::change, C, N, a, X);
        C = N;
        cur = next;
    }
    r.stuck = true;
    r.complete = false;
    return r;
}

}  // namespace rkref
