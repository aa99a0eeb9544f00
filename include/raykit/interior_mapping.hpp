// raykit — interior_mapping.hpp: the CPU build of shaders/raykit/interior_mapping.glsl (the
// interior-mapping trace, varying walls, per-room randomness) plus CPU-only helpers: the camera in
// object space, a room grid aligned with a building's windows, room queries and lit statistics.
//
// Every rk_* function is compiled from the very same text the GPU runs (docs/dialect.md);
// tests/gpu/parity_interior.cpp checks that both builds agree on a real driver. Define
// RK_IM_VARYING_WALLS / RK_IM_NUDGE before including this header to change them, as in GLSL.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "raykit/common.hpp"
#include "raykit/hash.hpp"

namespace raykit {
#include "raykit/interior_mapping.glsl"

/// The fields of rk_im_grid for gpu_pack (raykit/gpu_layout.hpp). In a block, origin is at byte 16
/// (12 in the C++ struct): upload with gpu_pack, never memcpy.
template <class V>
void rk_gpu_fields(V& v, const rk_im_grid& s)
{
    v("room_size", s.room_size);
    v("origin", s.origin);
}

/// camera_to_object_space: the camera position in a building's object space,
/// inverse(world_from_object) * (cam_world, 1), computed in double precision (inverse and
/// product) and rounded once to float. This is the `cam` uniform of rk_im_trace. A singular
/// matrix (no inverse) or a w of 0 returns cam_world unchanged. Cost: one 4x4 double inverse.
inline glm::vec3 camera_to_object_space(const glm::mat4& world_from_object, glm::vec3 cam_world)
{
    const glm::dmat4 m(world_from_object);
    if (std::abs(glm::determinant(m)) < 1e-300) return cam_world;
    const glm::dvec4 c = glm::inverse(m) * glm::dvec4(glm::dvec3(cam_world), 1.0);
    if (c.w == 0.0 || !std::isfinite(c.w)) return cam_world;
    return glm::vec3(glm::dvec3(c) / c.w);
}

namespace detail {
/// The number of rooms K <= n, K a divisor of n (so n bays split into K rooms of n / K bays),
/// nearest to `rooms` (ties: the fewer rooms), n >= 1.
inline int nearest_room_count(int n, int rooms)
{
    int best = 1;
    for (int k = 2; k <= n; ++k) {
        if (n % k != 0) continue;
        if (std::abs(k - rooms) < std::abs(best - rooms)) best = k;
    }
    return best;
}

/// One horizontal axis of room_grid_for_building: room size along [lo, hi].
inline float room_size_along(float lo, float hi, int rooms, float window_pitch)
{
    const double width = std::max(static_cast<double>(hi) - lo, 1e-6);
    const int r = std::max(rooms, 1);
    if (!(window_pitch > 0.0f)) return static_cast<float>(width / r);
    // N window bays of equal width fill the facade (the pitch is stretched to fit exactly).
    const int bays = std::max(1, static_cast<int>(std::lround(width / window_pitch)));
    const int count = nearest_room_count(bays, r);
    return static_cast<float>(width / bays * (bays / count));
}
}  // namespace detail

/// room_grid_for_building: an rk_im_grid for a box-shaped building with extent [extent_min,
/// extent_max] (object space) such that every facade lies on a grid plane and interior walls
/// fall halfway between windows. THE RULE, per horizontal axis (x with rooms_x and
/// window_pitch_x, z likewise): the facade of width W holds N = max(1, round(W / pitch)) window
/// bays of equal width b = W / N (the pitch stretched so that N bays fill the facade exactly),
/// window j centred at extent_min + (j + 0.5) b, so bay boundaries extent_min + k b are halfway
/// between neighbouring windows. The facade holds M rooms of N / M bays each, M the divisor of N
/// nearest to rooms_x (ties: the fewer rooms), so the room count is as close to rooms_x as it can
/// be while both facades stay on walls: room_size = (N / M) b, origin = extent_min, walls at
/// extent_min + k (N / M) b (M = rooms_x whenever rooms_x divides N). A pitch <= 0
/// ignores windows: room_size = W / rooms. Vertically: room_size.y = height / floors (floors
/// clamped >= 1), origin.y = extent_min.y. Facades lying exactly on grid planes are handled by
/// the trace's nudge rule. Cost: O(N) (divisor search).
inline rk_im_grid room_grid_for_building(glm::vec3 extent_min, glm::vec3 extent_max, int floors, int rooms_x,
                                         int rooms_z, float window_pitch_x, float window_pitch_z)
{
    rk_im_grid g;
    g.origin = extent_min;
    g.room_size.x = detail::room_size_along(extent_min.x, extent_max.x, rooms_x, window_pitch_x);
    g.room_size.y = detail::room_size_along(extent_min.y, extent_max.y, floors, 0.0f);
    g.room_size.z = detail::room_size_along(extent_min.z, extent_max.z, rooms_z, window_pitch_z);
    return g;
}

/// room_at: the room (grid cell) containing an object-space point (rk_im_room_at), for gameplay
/// queries: "which room is the player looking at, is it lit?". Exact for |grid coordinate| < 2^22
/// rooms (the trace's domain; far from the origin use a local origin, interior_mapping.glsl);
/// the room the trace reports for a ray starting in that room. Cost: 3 sub, 3 div, 3 floor.
inline glm::ivec3 room_at(glm::vec3 point, const rk_im_grid& grid) { return rk_im_room_at(point, grid); }

/// lit_fraction: the fraction of `rooms` with rk_im_room_lit(room, c, seed). Its expectation is
/// c (clamped to [0, 1]) with binomial standard deviation sqrt(c (1 - c) / rooms.size()); 0 for
/// an empty list. Exact count (rk_im_room_lit is bit-identical on the GPU); cost: one PCG3D hash
/// per room.
inline double lit_fraction(float c, const std::vector<glm::ivec3>& rooms, std::uint32_t seed)
{
    if (rooms.empty()) return 0.0;
    std::size_t lit = 0;
    for (const glm::ivec3& r : rooms) lit += rk_im_room_lit(r, c, seed) ? 1u : 0u;
    return static_cast<double>(lit) / static_cast<double>(rooms.size());
}

/// lit_fraction over a block of rooms: every room index in [first, first + count) per axis
/// (a whole building: first = (0,0,0), count = (rooms_x, floors, rooms_z)).
inline double lit_fraction(float c, glm::ivec3 first, glm::ivec3 count, std::uint32_t seed)
{
    long total = 0, lit = 0;
    for (int y = 0; y < count.y; ++y)
        for (int z = 0; z < count.z; ++z)
            for (int x = 0; x < count.x; ++x) {
                ++total;
                lit += rk_im_room_lit(first + glm::ivec3(x, y, z), c, seed) ? 1 : 0;
            }
    return total > 0 ? static_cast<double>(lit) / static_cast<double>(total) : 0.0;
}

}  // namespace raykit
