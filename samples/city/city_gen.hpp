// raykit sample city — city_gen.hpp: the procedural city (CPU, deterministic from a seed).
//
// A grid of blocks cut by streets and one wide boulevard (along x, at z = 0); each block is split
// into lots holding one building each: mostly boxes of varied footprint and height (taller towards
// the centre), some round towers (cylinders, so that interior mapping runs on curved walls). Every
// building gets a room grid from raykit::room_grid_for_building (its walls on the building's
// outline, an integer number of rooms per facade), a lit probability c, a seed, a facade and an
// interior style. The mesh is one vertex buffer (position, normal, building index) drawn in one call.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "raykit/interior_mapping.hpp"

namespace city {

using raykit::vec3;

/// What the shaders read per building (std430 SSBO, 4 vec4 = 64 bytes).
/// Object space of a building = world space translated by (-center_x, 0, -center_z) (the
/// local-origin rule of interior_mapping.glsl).
struct BuildingGpu {
    float origin[3];     // room grid origin (object space)
    float lit;           // lit probability c of its rooms
    float room[3];       // room size (x wall pitch, y storey, z wall pitch)
    float seed;          // uint seed stored as float (< 2^24, exact)
    float kind;          // 0 box, 1 cylinder
    float facade;        // facade texture layer
    float center_x, center_z;
    float bay_x, bay_z;  // window pitch along x and z (cylinder: along the arc, both)
    float height;
    float tint;          // facade tint variation in [0, 1)
};
static_assert(sizeof(BuildingGpu) == 64, "std430 layout");

struct Building {
    int kind = 0;  // 0 box, 1 cylinder
    float cx = 0, cz = 0, hx = 0, hz = 0, height = 0;
    raykit::rk_im_grid grid;  // object space (origin relative to (cx, 0, cz))
    float bay_x = 4.0f, bay_z = 4.0f;
    float lit = 0.3f;
    std::uint32_t seed = 0;
    int facade = 0;
};

struct Vertex {
    float pos[3];
    float normal[3];
    float id;  // building index (exact as a float)
};

/// Small deterministic generator (splitmix64).
struct Rng {
    std::uint64_t s;
    explicit Rng(std::uint64_t seed) : s(seed) {}
    std::uint64_t next()
    {
        std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    float uniform() { return static_cast<float>(next() >> 40) * (1.0f / 16777216.0f); }
    float range(float a, float b) { return a + (b - a) * uniform(); }
};

struct CityLayout {
    int blocks_x = 9, blocks_z = 8;
    float block = 44.0f;       // block size (m)
    float street = 14.0f;      // street width (m)
    float boulevard = 30.0f;   // width of the boulevard along x at z = 0
    float sidewalk = 3.0f;
    float pitch() const { return block + street; }
};

/// Number of facade texture layers (city_textures.hpp makes this many).
constexpr int kFacadeLayers = 6;

struct City {
    CityLayout layout;
    std::vector<Building> buildings;
    std::vector<Vertex> vertices;
    float extent = 0.0f;  // half size of the built area (m)
    int cylinders = 0;
};

/// The x-range (or z-range) of block index i: blocks are centred on the origin; along z the middle
/// street is the wide boulevard.
inline void block_span(const CityLayout& L, int i, int count, bool along_z, float& lo, float& hi)
{
    const float p = L.pitch();
    float c = (static_cast<float>(i) - 0.5f * static_cast<float>(count - 1)) * p;
    if (along_z) {
        // Shift blocks away from z = 0 to open the boulevard (count is even).
        const float extra = 0.5f * (L.boulevard - L.street);
        c += c > 0.0f ? extra : -extra;
    }
    lo = c - 0.5f * L.block;
    hi = c + 0.5f * L.block;
}

inline void add_quad(std::vector<Vertex>& v, vec3 a, vec3 b, vec3 c, vec3 d, vec3 n, float id)
{
    const vec3 q[6] = {a, b, c, a, c, d};
    for (const vec3& p : q) v.push_back(Vertex{{p.x, p.y, p.z}, {n.x, n.y, n.z}, id});
}

inline void add_box(std::vector<Vertex>& v, const Building& b, float id)
{
    const float x0 = b.cx - b.hx, x1 = b.cx + b.hx, z0 = b.cz - b.hz, z1 = b.cz + b.hz, h = b.height;
    add_quad(v, vec3(x0, 0, z1), vec3(x1, 0, z1), vec3(x1, h, z1), vec3(x0, h, z1), vec3(0, 0, 1), id);
    add_quad(v, vec3(x1, 0, z0), vec3(x0, 0, z0), vec3(x0, h, z0), vec3(x1, h, z0), vec3(0, 0, -1), id);
    add_quad(v, vec3(x1, 0, z1), vec3(x1, 0, z0), vec3(x1, h, z0), vec3(x1, h, z1), vec3(1, 0, 0), id);
    add_quad(v, vec3(x0, 0, z0), vec3(x0, 0, z1), vec3(x0, h, z1), vec3(x0, h, z0), vec3(-1, 0, 0), id);
    add_quad(v, vec3(x0, h, z1), vec3(x1, h, z1), vec3(x1, h, z0), vec3(x0, h, z0), vec3(0, 1, 0), id);
}

inline void add_cylinder(std::vector<Vertex>& v, const Building& b, float id, int segments)
{
    const float r = b.hx, h = b.height;
    for (int i = 0; i < segments; ++i) {
        const float a0 = 6.2831853f * static_cast<float>(i) / static_cast<float>(segments);
        const float a1 = 6.2831853f * static_cast<float>(i + 1) / static_cast<float>(segments);
        const vec3 n0(std::cos(a0), 0, std::sin(a0)), n1(std::cos(a1), 0, std::sin(a1));
        const vec3 p0(b.cx + r * n0.x, 0, b.cz + r * n0.z), p1(b.cx + r * n1.x, 0, b.cz + r * n1.z);
        const vec3 q[6] = {p0, p1 + vec3(0, h, 0), p1, p0, p0 + vec3(0, h, 0), p1 + vec3(0, h, 0)};
        const vec3 nn[6] = {n0, n1, n1, n0, n0, n1};
        for (int k = 0; k < 6; ++k) {
            v.push_back(Vertex{{q[k].x, q[k].y, q[k].z}, {nn[k].x, nn[k].y, nn[k].z}, id});
        }
        const vec3 c(b.cx, h, b.cz);
        const vec3 t[3] = {c, p1 + vec3(0, h, 0), p0 + vec3(0, h, 0)};
        for (const vec3& p : t) v.push_back(Vertex{{p.x, p.y, p.z}, {0, 1, 0}, id});
    }
}

/// Builds the city. `segments`: facets of a round tower (its normals are smooth).
inline City make_city(std::uint64_t seed, int segments = 48)
{
    City city;
    const CityLayout& L = city.layout;
    Rng rng(seed);
    float max_extent = 0.0f;
    for (int bz = 0; bz < L.blocks_z; ++bz) {
        for (int bx = 0; bx < L.blocks_x; ++bx) {
            float x0, x1, z0, z1;
            block_span(L, bx, L.blocks_x, false, x0, x1);
            block_span(L, bz, L.blocks_z, true, z0, z1);
            max_extent = std::max({max_extent, std::abs(x0), std::abs(x1), std::abs(z0), std::abs(z1)});
            const float dist = std::sqrt(0.5f * (x0 + x1) * 0.5f * (x0 + x1) + 0.5f * (z0 + z1) * 0.5f * (z0 + z1));
            const float centrality = std::exp(-dist * dist / (2.0f * 150.0f * 150.0f));
            // Lots: 1x1, 2x1, 1x2 or 2x2 split of the block (inset by the sidewalk).
            const float in = L.sidewalk;
            const float u = rng.uniform();
            const int nx = u < 0.2f ? 1 : 2;
            const int nz = u < 0.2f ? 1 : (u < 0.45f ? 1 : 2);
            const float lw = (x1 - x0 - 2.0f * in) / static_cast<float>(nx);
            const float ld = (z1 - z0 - 2.0f * in) / static_cast<float>(nz);
            for (int lz = 0; lz < nz; ++lz) {
                for (int lx = 0; lx < nx; ++lx) {
                    Building b;
                    const float lot_x0 = x0 + in + lw * static_cast<float>(lx);
                    const float lot_z0 = z0 + in + ld * static_cast<float>(lz);
                    const float gap = 1.0f;
                    const bool round = rng.uniform() < 0.11f && lw > 14.0f && ld > 14.0f;
                    b.height = std::round(rng.range(10.0f, 28.0f) + centrality * rng.range(10.0f, 85.0f));
                    if (round) {
                        b.kind = 1;
                        ++city.cylinders;
                        const float r = 0.5f * std::min(lw, ld) - gap - rng.range(0.0f, 3.0f);
                        b.hx = b.hz = r;
                        b.cx = lot_x0 + 0.5f * lw;
                        b.cz = lot_z0 + 0.5f * ld;
                        b.height += 12.0f;
                    } else {
                        // Varied footprint: flush to the street side, shrunk from the inner sides.
                        const float sx = lw - gap - rng.range(0.0f, 0.3f) * lw;
                        const float sz = ld - gap - rng.range(0.0f, 0.3f) * ld;
                        b.hx = 0.5f * sx;
                        b.hz = 0.5f * sz;
                        b.cx = lx == 0 ? lot_x0 + b.hx : lot_x0 + lw - b.hx;
                        b.cz = lz == 0 ? lot_z0 + b.hz : lot_z0 + ld - b.hz;
                        if (nx == 1) b.cx = lot_x0 + 0.5f * lw;
                        if (nz == 1) b.cz = lot_z0 + 0.5f * ld;
                    }
                    // Room grid from raykit: windows every `pitch` (stretched to fill each
                    // facade exactly), rooms of 1 or 2 bays, storeys of about `storey`.
                    const float storey = rng.range(3.1f, 3.7f);
                    const float pitch = rng.range(3.4f, 5.0f);
                    const int floors = std::max(2, static_cast<int>(std::lround(b.height / storey)));
                    const int bays_per_room = rng.uniform() < 0.5f ? 1 : 2;
                    const float w = 2.0f * b.hx, d = 2.0f * b.hz;
                    const int bays_x = std::max(1, static_cast<int>(std::lround(w / pitch)));
                    const int bays_z = std::max(1, static_cast<int>(std::lround(d / pitch)));
                    b.grid = raykit::room_grid_for_building(vec3(-b.hx, 0.0f, -b.hz), vec3(b.hx, b.height, b.hz), floors,
                                                            std::max(1, bays_x / bays_per_room),
                                                            std::max(1, bays_z / bays_per_room), pitch, pitch);
                    b.bay_x = w / static_cast<float>(bays_x);
                    b.bay_z = d / static_cast<float>(bays_z);
                    if (b.kind == 1) {
                        const float circ = 6.2831853f * b.hx;
                        b.bay_x = b.bay_z = circ / std::max(1.0f, std::round(circ / pitch));
                    }
                    b.lit = rng.range(0.15f, 0.6f);
                    b.seed = static_cast<std::uint32_t>(rng.next() & 0xFFFFFFu);
                    b.facade = b.height > 60.0f && rng.uniform() < 0.6f ? 3 : static_cast<int>(rng.next() % kFacadeLayers);
                    city.buildings.push_back(b);
                }
            }
        }
    }
    city.extent = max_extent;
    for (std::size_t i = 0; i < city.buildings.size(); ++i) {
        const Building& b = city.buildings[i];
        if (b.kind == 0) {
            add_box(city.vertices, b, static_cast<float>(i));
        } else {
            add_cylinder(city.vertices, b, static_cast<float>(i), segments);
        }
    }
    return city;
}

inline std::vector<BuildingGpu> building_table(const City& city, float lit_scale)
{
    std::vector<BuildingGpu> t;
    for (const Building& b : city.buildings) {
        BuildingGpu g{};
        g.origin[0] = b.grid.origin.x;
        g.origin[1] = b.grid.origin.y;
        g.origin[2] = b.grid.origin.z;
        g.lit = std::min(1.0f, b.lit * lit_scale);
        g.room[0] = b.grid.room_size.x;
        g.room[1] = b.grid.room_size.y;
        g.room[2] = b.grid.room_size.z;
        g.seed = static_cast<float>(b.seed);
        g.kind = static_cast<float>(b.kind);
        g.facade = static_cast<float>(b.facade);
        g.center_x = b.cx;
        g.center_z = b.cz;
        g.bay_x = b.bay_x;
        g.bay_z = b.bay_z;
        g.height = b.height;
        g.tint = static_cast<float>((b.seed >> 4) % 1000u) / 1000.0f;
        t.push_back(g);
    }
    return t;
}

}  // namespace city
