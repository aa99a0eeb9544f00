// raykit sample city — city_textures.hpp: every texture of the demo, generated on the CPU at
// start-up (no image files): facades, room interiors, furniture sprites.
//
// All layers are `size` x `size` RGBA8 with sRGB-encoded colour (upload as GL_SRGB8_ALPHA8), row 0
// at v = 0 (the bottom: GL's upload order), so u runs along the facade / wall and v upwards.
//   facades   one tile = one window bay of one storey (the bays of room_grid_for_building: rooms
//             span 1 or 2 bays, so interior walls fall between windows);
//             alpha is the window mask: 1 = glass (interior mapped), 0 = wall. Layers: red brick,
//             beige brick, concrete bands, glass curtain wall, stucco, dark metal panels.
//   interior  RK_IM_SHADING 1's array: 4 ceilings (lamp, office tiles, beams, pendant), 4 floors
//             (planks, carpet with a rug, tiles, office carpet), 4 walls (wallpaper, plaster with a
//             picture and a door, brick, panelling with a shelf).
//   furniture two 4 x 4 sprite sheets (make_furniture): people (a 4-frame walk cycle) and small
//             objects near the window, big furniture near the back wall; u across the room, v from
//             floor to ceiling, alpha = coverage.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace city {

constexpr int kInteriorVariants = 4;  // V of RK_IM_SHADING 1
constexpr int kInteriorLayers = 3 * kInteriorVariants;
constexpr int kFurnitureFrames = 4;   // frames of the walking person
constexpr int kFurnitureLayers = 2;   // sprite sheets (= RK_IM_FURNITURE_LAYERS)
constexpr int kSheetCells = 16;       // 4 x 4 cells per sheet

struct Rgb {
    float r, g, b;
};

/// One RGBA8 layer, colours in linear [0, 1] until pack() encodes them to sRGB.
struct Layer {
    int n;
    std::vector<float> px;  // n * n * 4, linear rgb + alpha
    explicit Layer(int size) : n(size), px(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * 4u, 0.0f) {}
    float* at(int x, int y) { return &px[(static_cast<std::size_t>(y) * static_cast<std::size_t>(n) + static_cast<std::size_t>(x)) * 4u]; }
    void set(int x, int y, Rgb c, float a)
    {
        float* p = at(x, y);
        p[0] = c.r;
        p[1] = c.g;
        p[2] = c.b;
        p[3] = a;
    }
    /// Fills texels whose centre (u, v) in [0, 1]^2 satisfies `inside(u, v)`.
    template <class F>
    void fill(F&& inside, Rgb c, float a)
    {
        for (int y = 0; y < n; ++y) {
            for (int x = 0; x < n; ++x) {
                const float u = (static_cast<float>(x) + 0.5f) / static_cast<float>(n);
                const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(n);
                if (inside(u, v)) set(x, y, c, a);
            }
        }
    }
    void rect(float u0, float v0, float u1, float v1, Rgb c, float a = 1.0f)
    {
        fill([&](float u, float v) { return u >= u0 && u < u1 && v >= v0 && v < v1; }, c, a);
    }
    void ellipse(float cu, float cv, float ru, float rv, Rgb c, float a = 1.0f)
    {
        fill([&](float u, float v) { return (u - cu) * (u - cu) / (ru * ru) + (v - cv) * (v - cv) / (rv * rv) <= 1.0f; }, c, a);
    }
    /// A thick line segment (capsule) from (u0, v0) to (u1, v1) of radius r.
    void segment(float u0, float v0, float u1, float v1, float r, Rgb c, float a = 1.0f)
    {
        fill(
            [&](float u, float v) {
                const float du = u1 - u0, dv = v1 - v0;
                const float h = std::clamp(((u - u0) * du + (v - v0) * dv) / std::max(du * du + dv * dv, 1e-12f), 0.0f, 1.0f);
                const float eu = u - u0 - h * du, ev = v - v0 - h * dv;
                return eu * eu + ev * ev <= r * r;
            },
            c, a);
    }
};

inline float hash2(int x, int y, std::uint32_t seed)
{
    std::uint32_t h = static_cast<std::uint32_t>(x) * 374761393u + static_cast<std::uint32_t>(y) * 668265263u + seed * 2246822519u;
    h = (h ^ (h >> 13)) * 1274126177u;
    h ^= h >> 16;
    return static_cast<float>(h & 0xFFFFFFu) / 16777216.0f;
}

inline Rgb scale(Rgb c, float k) { return Rgb{c.r * k, c.g * k, c.b * k}; }
inline Rgb mixc(Rgb a, Rgb b, float t) { return Rgb{a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t}; }

inline std::uint8_t to_srgb8(float x)
{
    x = std::clamp(x, 0.0f, 1.0f);
    const float s = x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
    return static_cast<std::uint8_t>(std::lround(s * 255.0f));
}

/// Appends the layer as RGBA8 (sRGB colour, linear alpha).
inline void pack(const Layer& l, std::vector<std::uint8_t>& out)
{
    for (std::size_t i = 0; i < l.px.size(); i += 4) {
        out.push_back(to_srgb8(l.px[i]));
        out.push_back(to_srgb8(l.px[i + 1]));
        out.push_back(to_srgb8(l.px[i + 2]));
        out.push_back(static_cast<std::uint8_t>(std::lround(std::clamp(l.px[i + 3], 0.0f, 1.0f) * 255.0f)));
    }
}

// Brick bond over the tile: `rows` courses per tile, bricks twice as long as high; mortar lines.
inline void brick(Layer& l, Rgb base, Rgb mortar, int rows, std::uint32_t seed)
{
    const int n = l.n;
    const float course = static_cast<float>(n) / static_cast<float>(rows);
    const float len = 2.0f * course;
    for (int y = 0; y < n; ++y) {
        const int row = static_cast<int>(static_cast<float>(y) / course);
        const float fy = static_cast<float>(y) - static_cast<float>(row) * course;
        for (int x = 0; x < n; ++x) {
            const float xs = static_cast<float>(x) + (row % 2 ? 0.5f * len : 0.0f);
            const int col = static_cast<int>(xs / len);
            const float fx = xs - static_cast<float>(col) * len;
            const bool m = fy < 1.0f || fx < 1.0f;
            const float var = 0.75f + 0.5f * hash2(col % 64, row, seed) + 0.08f * hash2(x, y, seed + 1u);
            l.set(x, y, m ? mortar : scale(base, var), 0.0f);
        }
    }
}

inline void noise_fill(Layer& l, Rgb base, float amount, std::uint32_t seed)
{
    for (int y = 0; y < l.n; ++y) {
        for (int x = 0; x < l.n; ++x) {
            const float k = 1.0f + amount * (hash2(x, y, seed) - 0.5f) + 0.5f * amount * (hash2(x / 4, y / 4, seed + 9u) - 0.5f);
            l.set(x, y, scale(base, k), 0.0f);
        }
    }
}

// The window opening [u0,u1] x [v0,v1]: glass (alpha 1, black rgb) inside a frame of width fw.
inline void window(Layer& l, float u0, float v0, float u1, float v1, float fw, Rgb frame, bool mullion)
{
    l.rect(u0 - fw, v0 - fw, u1 + fw, v1 + fw, frame, 0.0f);
    l.rect(u0, v0, u1, v1, Rgb{0.0f, 0.0f, 0.0f}, 1.0f);
    if (mullion) {
        const float um = 0.5f * (u0 + u1);
        l.rect(um - 0.5f * fw, v0, um + 0.5f * fw, v1, frame, 0.0f);
    }
}

inline std::vector<std::uint8_t> make_facades(int size)
{
    std::vector<std::uint8_t> out;
    const float px = 1.0f / static_cast<float>(size);
    for (int layer = 0; layer < 6; ++layer) {
        Layer l(size);
        switch (layer) {
        case 0:  // red brick, tall windows with a stone sill and lintel
            brick(l, Rgb{0.33f, 0.10f, 0.06f}, Rgb{0.35f, 0.33f, 0.30f}, 24, 11u);
            l.rect(0.20f, 0.20f, 0.80f, 0.26f, Rgb{0.50f, 0.48f, 0.44f}, 0.0f);
            l.rect(0.22f, 0.86f, 0.78f, 0.92f, Rgb{0.50f, 0.48f, 0.44f}, 0.0f);
            window(l, 0.25f, 0.26f, 0.75f, 0.86f, 3.0f * px, Rgb{0.75f, 0.74f, 0.70f}, true);
            break;
        case 1:  // beige brick, narrower windows
            brick(l, Rgb{0.52f, 0.40f, 0.24f}, Rgb{0.42f, 0.40f, 0.36f}, 24, 23u);
            l.rect(0.28f, 0.22f, 0.72f, 0.27f, Rgb{0.30f, 0.30f, 0.30f}, 0.0f);
            window(l, 0.31f, 0.27f, 0.69f, 0.88f, 3.0f * px, Rgb{0.08f, 0.09f, 0.10f}, false);
            break;
        case 2:  // concrete with a horizontal band per storey, wide windows
            noise_fill(l, Rgb{0.38f, 0.38f, 0.36f}, 0.25f, 37u);
            l.rect(0.0f, 0.0f, 1.0f, 0.12f, Rgb{0.30f, 0.30f, 0.29f}, 0.0f);
            window(l, 0.08f, 0.32f, 0.92f, 0.84f, 2.0f * px, Rgb{0.12f, 0.12f, 0.13f}, true);
            break;
        case 3:  // glass curtain wall: thin dark mullions, spandrel at floor level
            noise_fill(l, Rgb{0.06f, 0.07f, 0.08f}, 0.1f, 41u);
            l.rect(0.02f, 0.14f, 0.98f, 0.98f, Rgb{0.0f, 0.0f, 0.0f}, 1.0f);
            l.rect(0.0f, 0.10f, 1.0f, 0.14f, Rgb{0.20f, 0.21f, 0.22f}, 0.0f);
            break;
        case 4:  // stucco with a cornice line, shutters
            noise_fill(l, Rgb{0.60f, 0.55f, 0.45f}, 0.12f, 53u);
            l.rect(0.0f, 0.95f, 1.0f, 1.0f, Rgb{0.70f, 0.66f, 0.58f}, 0.0f);
            l.rect(0.13f, 0.28f, 0.25f, 0.82f, Rgb{0.12f, 0.22f, 0.14f}, 0.0f);
            l.rect(0.75f, 0.28f, 0.87f, 0.82f, Rgb{0.12f, 0.22f, 0.14f}, 0.0f);
            window(l, 0.27f, 0.28f, 0.73f, 0.82f, 3.0f * px, Rgb{0.80f, 0.80f, 0.78f}, true);
            break;
        default:  // dark metal panels, ribbon windows
            noise_fill(l, Rgb{0.10f, 0.09f, 0.08f}, 0.15f, 61u);
            for (int k = 0; k < 8; ++k) l.rect(static_cast<float>(k) / 8.0f, 0.0f, static_cast<float>(k) / 8.0f + px, 1.0f, Rgb{0.05f, 0.05f, 0.05f}, 0.0f);
            window(l, 0.06f, 0.18f, 0.94f, 0.90f, 2.0f * px, Rgb{0.16f, 0.16f, 0.17f}, true);
            break;
        }
        pack(l, out);
    }
    return out;
}

inline std::vector<std::uint8_t> make_interiors(int size)
{
    // Layer order of interior_shading.glsl's RK_IM_SHADING 1: [0, V) ceilings, [V, 2V) floors,
    // [2V, 3V) walls, V = kInteriorVariants.
    std::vector<std::uint8_t> out;
    const float px = 1.0f / static_cast<float>(size);
    auto opaque = [](Layer& l) {
        for (std::size_t i = 3; i < l.px.size(); i += 4) l.px[i] = 1.0f;
    };
    // Ceilings.
    {  // plaster with a round lamp
        Layer l(size);
        l.rect(0.0f, 0.0f, 1.0f, 1.0f, Rgb{0.80f, 0.79f, 0.76f});
        l.ellipse(0.5f, 0.5f, 0.16f, 0.16f, Rgb{0.9f, 0.88f, 0.8f});
        l.ellipse(0.5f, 0.5f, 0.10f, 0.10f, Rgb{1.0f, 0.97f, 0.9f});
        pack(l, out);
    }
    {  // office tiles with a light panel
        Layer l(size);
        l.rect(0.0f, 0.0f, 1.0f, 1.0f, Rgb{0.70f, 0.70f, 0.70f});
        for (int k = 0; k <= 4; ++k) {
            const float u = static_cast<float>(k) / 4.0f;
            l.rect(u - px, 0.0f, u + px, 1.0f, Rgb{0.45f, 0.45f, 0.45f});
            l.rect(0.0f, u - px, 1.0f, u + px, Rgb{0.45f, 0.45f, 0.45f});
        }
        l.rect(0.27f, 0.27f, 0.73f, 0.48f, Rgb{1.0f, 1.0f, 1.0f});
        pack(l, out);
    }
    {  // wooden beams
        Layer l(size);
        l.rect(0.0f, 0.0f, 1.0f, 1.0f, Rgb{0.62f, 0.58f, 0.50f});
        for (int k = 0; k < 4; ++k) l.rect(0.0f, 0.1f + 0.25f * static_cast<float>(k), 1.0f, 0.18f + 0.25f * static_cast<float>(k), Rgb{0.25f, 0.14f, 0.07f});
        l.ellipse(0.5f, 0.5f, 0.06f, 0.06f, Rgb{1.0f, 0.95f, 0.8f});
        pack(l, out);
    }
    {  // plain with a pendant lamp shade
        Layer l(size);
        noise_fill(l, Rgb{0.72f, 0.70f, 0.66f}, 0.05f, 83u);
        opaque(l);
        l.ellipse(0.5f, 0.5f, 0.13f, 0.13f, Rgb{0.85f, 0.55f, 0.25f});
        l.ellipse(0.5f, 0.5f, 0.07f, 0.07f, Rgb{1.0f, 0.9f, 0.7f});
        pack(l, out);
    }
    // Floors.
    {  // wooden planks
        Layer l(size);
        const int planks = 8;
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                const int p = x * planks / size;
                const float shift = hash2(p, 0, 17u);
                const float along = static_cast<float>(y) * px + shift;
                const int seg = static_cast<int>(along * 2.0f);
                const bool gap = (x * planks) % size < planks || static_cast<int>(along * 2.0f * static_cast<float>(size)) % size < 2;
                const float k = 0.8f + 0.4f * hash2(p, seg, 19u) + 0.1f * hash2(x, y / 3, 23u);
                l.set(x, y, gap ? Rgb{0.08f, 0.05f, 0.03f} : scale(Rgb{0.36f, 0.20f, 0.09f}, k), 1.0f);
            }
        }
        pack(l, out);
    }
    {  // carpet with a rug
        Layer l(size);
        noise_fill(l, Rgb{0.25f, 0.10f, 0.10f}, 0.35f, 29u);
        opaque(l);
        l.rect(0.2f, 0.25f, 0.8f, 0.75f, Rgb{0.55f, 0.45f, 0.25f});
        l.rect(0.25f, 0.30f, 0.75f, 0.70f, Rgb{0.20f, 0.25f, 0.45f});
        pack(l, out);
    }
    {  // chequered tiles
        Layer l(size);
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                const bool c = ((x * 8 / size) + (y * 8 / size)) % 2 == 0;
                l.set(x, y, c ? Rgb{0.70f, 0.70f, 0.68f} : Rgb{0.12f, 0.12f, 0.14f}, 1.0f);
            }
        }
        pack(l, out);
    }
    {  // grey office carpet
        Layer l(size);
        noise_fill(l, Rgb{0.22f, 0.23f, 0.25f}, 0.3f, 31u);
        opaque(l);
        pack(l, out);
    }
    // Walls (u along the wall, v = 0 at the floor).
    {  // wallpaper, vertical stripes, baseboard
        Layer l(size);
        l.rect(0.0f, 0.0f, 1.0f, 1.0f, Rgb{0.62f, 0.56f, 0.42f});
        for (int k = 0; k < 12; ++k) {
            const float u = (static_cast<float>(k) + 0.3f) / 12.0f;
            l.rect(u, 0.0f, u + 0.035f, 1.0f, Rgb{0.50f, 0.38f, 0.30f});
        }
        l.rect(0.0f, 0.0f, 1.0f, 0.06f, Rgb{0.25f, 0.16f, 0.10f});
        pack(l, out);
    }
    {  // plaster with a framed picture and a door
        Layer l(size);
        l.rect(0.0f, 0.0f, 1.0f, 1.0f, Rgb{0.55f, 0.60f, 0.62f});
        l.rect(0.12f, 0.45f, 0.48f, 0.75f, Rgb{0.20f, 0.12f, 0.06f});
        l.rect(0.14f, 0.47f, 0.46f, 0.73f, Rgb{0.70f, 0.45f, 0.20f});
        l.ellipse(0.30f, 0.58f, 0.08f, 0.06f, Rgb{0.85f, 0.75f, 0.30f});
        l.rect(0.66f, 0.0f, 0.88f, 0.72f, Rgb{0.35f, 0.22f, 0.12f});
        l.rect(0.84f, 0.34f, 0.86f, 0.37f, Rgb{0.75f, 0.70f, 0.45f});
        l.rect(0.0f, 0.0f, 1.0f, 0.04f, Rgb{0.9f, 0.9f, 0.88f});
        pack(l, out);
    }
    {  // exposed brick
        Layer l(size);
        brick(l, Rgb{0.40f, 0.16f, 0.09f}, Rgb{0.45f, 0.42f, 0.38f}, 20, 71u);
        opaque(l);
        pack(l, out);
    }
    {  // wood panelling below, green paint above, a shelf with books
        Layer l(size);
        l.rect(0.0f, 0.0f, 1.0f, 1.0f, Rgb{0.18f, 0.35f, 0.25f});
        for (int k = 0; k < 10; ++k) {
            const float u = static_cast<float>(k) / 10.0f;
            l.rect(u, 0.0f, u + 0.1f - px, 0.42f, scale(Rgb{0.35f, 0.20f, 0.09f}, 0.85f + 0.3f * hash2(k, 0, 5u)));
        }
        l.rect(0.0f, 0.42f, 1.0f, 0.45f, Rgb{0.25f, 0.14f, 0.06f});
        l.rect(0.55f, 0.66f, 0.95f, 0.68f, Rgb{0.25f, 0.14f, 0.06f});
        for (int k = 0; k < 7; ++k) {
            l.rect(0.57f + 0.05f * static_cast<float>(k), 0.68f, 0.60f + 0.05f * static_cast<float>(k), 0.76f + 0.03f * hash2(k, 1, 9u),
                   Rgb{0.6f * hash2(k, 2, 1u), 0.3f, 0.5f * hash2(k, 3, 2u)});
        }
        pack(l, out);
    }
    return out;
}

inline void person(Layer& l, float phase, Rgb c)
{
    // About 1.75 m tall in a 3.3 m storey (v = 0 is the floor).
    const float s = std::sin(phase), k = std::cos(phase), h = 0.74f;
    const float cx = 0.5f;
    l.ellipse(cx, 0.66f * h, 0.040f, 0.050f * h, c);                   // head
    l.segment(cx, 0.58f * h, cx, 0.36f * h, 0.045f, c);                // torso
    l.segment(cx, 0.36f * h, cx + 0.09f * s, 0.02f, 0.028f, c);        // legs
    l.segment(cx, 0.36f * h, cx - 0.09f * s, 0.02f + 0.03f * std::abs(k), 0.028f, c);
    l.segment(cx, 0.56f * h, cx - 0.08f * s, 0.38f * h, 0.020f, c);    // arms
    l.segment(cx, 0.56f * h, cx + 0.08f * s, 0.38f * h, 0.020f, c);
}

/// A 4 x 4 sprite sheet (interior_furniture.glsl's flipbook layout: frame k in column k mod 4, row
/// k / 4, rows along +v); each cell is drawn by `draw(cell_layer, k)` into its own square.
template <class F>
Layer sheet(int cell, F&& draw)
{
    Layer s(4 * cell);
    for (int k = 0; k < 16; ++k) {
        Layer c(cell);
        draw(c, k);
        const int ox = (k % 4) * cell, oy = (k / 4) * cell;
        for (int y = 0; y < cell; ++y) {
            for (int x = 0; x < cell; ++x) {
                const float* src = c.at(x, y);
                float* dst = s.at(ox + x, oy + y);
                for (int i = 0; i < 4; ++i) dst[i] = src[i];
            }
        }
    }
    return s;
}

/// Two sprite sheets (a sampler2DArray of 2 layers, 4 cell x 4 cell texels each): layer 0, the
/// plane near the window: a walking person in 4 frames (cells 0..3: the flipbook of the demo's
/// people), a plant, a floor lamp, a chair, empty cells; layer 1, the plane near the back wall:
/// sofa, bookshelf, table with a lamp, desk with a monitor, and empty cells. The frame of a room
/// is chosen per room (rk_im_flipbook_room_uv), so empty cells leave rooms without furniture.
inline std::vector<std::uint8_t> make_furniture(int cell)
{
    std::vector<std::uint8_t> out;
    const Rgb dark{0.05f, 0.045f, 0.04f};
    const Rgb wood{0.18f, 0.10f, 0.05f};
    Layer near_sheet = sheet(cell, [&](Layer& l, int k) {
        if (k < kFurnitureFrames) {
            person(l, 6.2831853f * static_cast<float>(k) / static_cast<float>(kFurnitureFrames),
                   Rgb{0.07f + 0.05f * hash2(k, 0, 1u), 0.06f, 0.06f + 0.04f * hash2(k, 1, 1u)});
        } else if (k == 4 || k == 9) {  // plant in a pot
            const float cu = k == 4 ? 0.78f : 0.22f;
            l.rect(cu - 0.06f, 0.0f, cu + 0.06f, 0.12f, Rgb{0.35f, 0.16f, 0.08f});
            for (int j = 0; j < 9; ++j) {
                const float a = -1.2f + 0.3f * static_cast<float>(j);
                l.segment(cu, 0.12f, cu + 0.16f * std::sin(a), 0.12f + 0.35f * std::cos(a) * (0.7f + 0.3f * hash2(j, 0, 3u)), 0.025f,
                          Rgb{0.06f, 0.22f + 0.1f * hash2(j, 1, 4u), 0.05f});
            }
        } else if (k == 5) {  // floor lamp
            l.rect(0.14f, 0.0f, 0.16f, 0.55f, dark);
            l.rect(0.10f, 0.0f, 0.20f, 0.02f, dark);
            l.fill([](float u, float v) { return v > 0.52f && v < 0.64f && std::abs(u - 0.15f) < 0.04f + 0.4f * (0.64f - v); },
                   Rgb{0.95f, 0.8f, 0.5f}, 1.0f);
        } else if (k == 6) {  // chair
            l.rect(0.60f, 0.0f, 0.62f, 0.42f, wood);
            l.rect(0.60f, 0.18f, 0.72f, 0.21f, wood);
            l.rect(0.70f, 0.0f, 0.72f, 0.21f, wood);
        }
    });
    pack(near_sheet, out);
    Layer far_sheet = sheet(cell, [&](Layer& l, int k) {
        switch (k % 8) {
        case 0:  // sofa
            l.rect(0.12f, 0.05f, 0.88f, 0.22f, Rgb{0.30f, 0.08f, 0.06f});
            l.rect(0.14f, 0.22f, 0.86f, 0.36f, Rgb{0.26f, 0.07f, 0.05f});
            l.rect(0.08f, 0.05f, 0.16f, 0.28f, Rgb{0.22f, 0.06f, 0.04f});
            l.rect(0.84f, 0.05f, 0.92f, 0.28f, Rgb{0.22f, 0.06f, 0.04f});
            l.rect(0.14f, 0.0f, 0.17f, 0.05f, dark);
            l.rect(0.83f, 0.0f, 0.86f, 0.05f, dark);
            break;
        case 1:  // bookshelf
            l.rect(0.05f, 0.0f, 0.40f, 0.72f, Rgb{0.22f, 0.13f, 0.06f});
            for (int r = 0; r < 4; ++r) {
                const float v0 = 0.03f + 0.175f * static_cast<float>(r);
                for (int b = 0; b < 9; ++b) {
                    const float u0 = 0.07f + 0.036f * static_cast<float>(b);
                    l.rect(u0, v0, u0 + 0.03f, v0 + 0.12f + 0.03f * hash2(b, r, 7u),
                           Rgb{0.1f + 0.5f * hash2(b, r, 1u), 0.1f + 0.3f * hash2(b, r, 2u), 0.1f + 0.4f * hash2(b, r, 3u)});
                }
            }
            break;
        case 2:  // table with a lamp and two chairs
            l.rect(0.30f, 0.24f, 0.70f, 0.27f, wood);
            l.rect(0.33f, 0.0f, 0.35f, 0.24f, wood);
            l.rect(0.65f, 0.0f, 0.67f, 0.24f, wood);
            l.rect(0.20f, 0.0f, 0.22f, 0.40f, wood);
            l.rect(0.20f, 0.16f, 0.30f, 0.18f, wood);
            l.rect(0.78f, 0.0f, 0.80f, 0.40f, wood);
            l.rect(0.70f, 0.16f, 0.80f, 0.18f, wood);
            l.rect(0.49f, 0.27f, 0.51f, 0.40f, dark);
            l.fill([](float u, float v) { return v > 0.40f && v < 0.47f && std::abs(u - 0.5f) < 0.03f + 0.5f * (0.47f - v); },
                   Rgb{0.9f, 0.7f, 0.35f}, 1.0f);
            break;
        case 3:  // desk with a monitor
            l.rect(0.45f, 0.25f, 0.90f, 0.28f, Rgb{0.30f, 0.30f, 0.32f});
            l.rect(0.47f, 0.0f, 0.49f, 0.25f, dark);
            l.rect(0.86f, 0.0f, 0.88f, 0.25f, dark);
            l.rect(0.60f, 0.30f, 0.78f, 0.44f, Rgb{0.02f, 0.02f, 0.03f});
            l.rect(0.61f, 0.31f, 0.77f, 0.43f, Rgb{0.25f, 0.45f, 0.80f});
            l.rect(0.68f, 0.28f, 0.70f, 0.30f, dark);
            break;
        default:
            break;  // empty: no furniture at the back of this room
        }
    });
    pack(far_sheet, out);
    return out;
}

}  // namespace city
