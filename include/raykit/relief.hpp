// raykit — relief.hpp: the CPU build of shaders/raykit/relief.glsl (steep parallax, parallax
// occlusion mapping, relief mapping, cone and relaxed cone stepping, self-shadowing) over a CPU map,
// ReliefMapCpu, whose read function rk_relief_read is the C++ twin of the GLSL textureLod(sampler2D,
// uv, 0.0) with LINEAR filtering: the four texels around uv weighted bilinearly, texel centres at
// (i + 0.5) / size, wrapped (GL_REPEAT, the default: tiling maps) or clamped (GL_CLAMP_TO_EDGE) as
// ReliefMapCpu::wrap says. tests/gpu/parity_relief.cpp checks it against the driver.
//
// Generators (C++ only): relief_from_heights (height -> depth), relief_normal_map (tangent-space
// normals of the bilinear surface at a depth scale), and the cone maps of channel y:
//   relief_build_cones_exact / relief_build_cones: conservative cones (Dummer 2006): cones (ratio
//     <= 1) opening upwards from the surface that contain no point of the bilinear surface, proven
//     by bounds for every bilinear mix of four texels' cones (see the functions), so cone stepping
//     never steps over a feature. _exact visits every cell of the map (O(n^4) texel pairs: tests, small maps); the
//     other prunes with a min-depth pyramid (a hierarchical max-height mip) and gives a ratio at
//     least as wide, as conservative.
//   relief_build_relaxed_cones_exact / relief_build_relaxed_cones: relaxed cones (Policarpo &
//     Oliveira 2007): for every other texel, the ray from the top of the apex's column through that
//     texel's surface point is followed into the solid to where it re-emerges; the cone must not
//     contain such an exit point. _exact visits every texel; the other only those within `radius`
//     texels (a window: faster, not bounded by the exact one).
//
// Like every header with option macros, the marching functions live in an inline namespace named
// after RK_RELIEF_MAX_STEPS (docs/dialect.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "raykit/common.hpp"
#include "raykit/normalmap.hpp"

namespace raykit {

/// A relief map on the CPU: width x height texels, row-major, row 0 at v = 0 (GL's upload order);
/// x = depth in [0, 1], y = cone ratio in [0, 1] (0 until a cone builder fills it). `wrap`: GL_REPEAT
/// (true) or GL_CLAMP_TO_EDGE (false); it must match the GPU sampler's wrap mode.
struct ReliefMapCpu {
    int width = 0, height = 0;
    std::vector<vec2> texels;
    bool wrap = true;
    bool valid() const
    {
        return width > 0 && height > 0 && texels.size() >= static_cast<size_t>(width) * static_cast<size_t>(height);
    }
    /// The texel at integer (x, y), wrapped or clamped.
    vec2 at(int x, int y) const
    {
        if (wrap) {
            x %= width;
            y %= height;
            if (x < 0) x += width;
            if (y < 0) y += height;
        } else {
            x = std::min(std::max(x, 0), width - 1);
            y = std::min(std::max(y, 0), height - 1);
        }
        return texels[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
    }
    float depth(int x, int y) const { return at(x, y).x; }
};

namespace detail {
/// Texel coordinate of uv along one axis for bilinear filtering: (floor index, fraction), wrapped
/// into [0, size) for REPEAT, clamped to [-1, size] for CLAMP_TO_EDGE (ReliefMapCpu::at clamps the
/// index again). Non-finite uv reads as 0.
inline void relief_axis(double uv, int size, bool wrap, int& i0, double& a)
{
    double f = uv * size - 0.5;
    if (!std::isfinite(f)) f = 0.0;
    if (wrap) {
        f = std::fmod(f, static_cast<double>(size));
        if (f < 0.0) f += size;
    } else {
        f = std::min(std::max(f, -1.0), static_cast<double>(size));
    }
    const double fl = std::floor(f);
    i0 = static_cast<int>(fl);
    a = f - fl;
}
}  // namespace detail

/// rk_relief_read (C++ twin of textureLod(sampler2D, uv, 0.0).xy with LINEAR filtering): the
/// bilinear average of the four texels around uv, wrapped or clamped as m.wrap says. An empty map
/// reads as (0, 0): a flat surface at the polygon.
inline vec2 rk_relief_read(const ReliefMapCpu& m, vec2 uv)
{
    if (!m.valid()) return vec2(0.0f);
    int x0 = 0, y0 = 0;
    double ax = 0.0, ay = 0.0;
    detail::relief_axis(static_cast<double>(uv.x), m.width, m.wrap, x0, ax);
    detail::relief_axis(static_cast<double>(uv.y), m.height, m.wrap, y0, ay);
    const vec2 a = m.at(x0, y0), b = m.at(x0 + 1, y0), c = m.at(x0, y0 + 1), d = m.at(x0 + 1, y0 + 1);
    const float fx = static_cast<float>(ax), fy = static_cast<float>(ay);
    const vec2 top = a * (1.0f - fx) + b * fx, bottom = c * (1.0f - fx) + d * fx;
    return top * (1.0f - fy) + bottom * fy;
}

#define RK_RELIEF_MAP const ReliefMapCpu&
#include "raykit/relief.glsl"

/// A depth map from a height map (row-major, width x height, 1 = the polygon's level, 0 = the
/// deepest): depth = 1 - clamp(height, 0, 1) (NaN: depth 1), cone ratios 0.
inline ReliefMapCpu relief_from_heights(int width, int height, const std::vector<float>& heights, bool wrap = true)
{
    ReliefMapCpu m;
    m.wrap = wrap;
    if (width <= 0 || height <= 0 || heights.size() < static_cast<size_t>(width) * static_cast<size_t>(height)) return m;
    m.width = width;
    m.height = height;
    m.texels.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
    for (size_t i = 0; i < m.texels.size(); ++i) {
        const float h = heights[i];
        m.texels[i] = vec2(1.0f - (h > 0.0f ? std::min(h, 1.0f) : 0.0f), 0.0f);
    }
    return m;
}

/// Tangent-space unit normals (row-major, one per texel) of the surface z = -depth_scale · d(u, v)
/// (uv units; T along +u, B along +v, N up): n ∝ (s ∂d/∂u, s ∂d/∂v, 1) with central differences
/// over two texels (wrapped or clamped as the map; at a clamped edge the difference spans one
/// texel). Pack with n · 0.5 + 0.5, or the two channels x, y for rk_nm_unpack_rg.
inline std::vector<vec3> relief_normal_map(const ReliefMapCpu& m, float depth_scale)
{
    std::vector<vec3> out;
    if (!m.valid()) return out;
    const double s = std::isfinite(depth_scale) ? std::min(std::max(static_cast<double>(depth_scale), 0.0), 1.0) : 0.0;
    out.resize(static_cast<size_t>(m.width) * static_cast<size_t>(m.height));
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            const int xl = m.wrap ? x - 1 : std::max(x - 1, 0), xr = m.wrap ? x + 1 : std::min(x + 1, m.width - 1);
            const int yl = m.wrap ? y - 1 : std::max(y - 1, 0), yr = m.wrap ? y + 1 : std::min(y + 1, m.height - 1);
            const double du = xr > xl ? (static_cast<double>(m.depth(xr, y)) - m.depth(xl, y)) * m.width / (xr - xl) : 0.0;
            const double dv = yr > yl ? (static_cast<double>(m.depth(x, yr)) - m.depth(x, yl)) * m.height / (yr - yl) : 0.0;
            const double nx = s * du, ny = s * dv, k = 1.0 / std::sqrt(nx * nx + ny * ny + 1.0);
            out[static_cast<size_t>(y) * static_cast<size_t>(m.width) + static_cast<size_t>(x)] =
                vec3(static_cast<float>(nx * k), static_cast<float>(ny * k), static_cast<float>(k));
        }
    return out;
}

namespace detail {

/// The cells of a map's bilinear surface: the squares between four texel centres. A wrapped map
/// has width x height of them (the last wraps to the first column / row); a clamped one
/// (width - 1) x (height - 1) (beyond the outer texel centres the surface repeats the edge, whose
/// points are no nearer to an apex inside: projecting onto the box of centres is a contraction).
struct ReliefCells {
    int nx = 0, ny = 0;
};
inline ReliefCells relief_cells(const ReliefMapCpu& m)
{
    ReliefCells c;
    c.nx = m.wrap ? m.width : m.width - 1;
    c.ny = m.wrap ? m.height : m.height - 1;
    return c;
}

/// The signed uv offset from a to b along one axis, the nearest periodic image for wrapped maps.
inline double relief_offset(double a, double b, bool wrap)
{
    double d = b - a;
    if (wrap) d -= std::floor(d + 0.5);
    return d;
}

/// The cells' slope bounds: largest |∂d/∂u| and |∂d/∂v| (per uv) of cell (cx, cy)'s bilinear patch
/// (at its edges: the partial derivative along u is linear in v).
inline void relief_cell_slopes(const ReliefMapCpu& m, int cx, int cy, double& gu, double& gv)
{
    const double c00 = m.depth(cx, cy), c10 = m.depth(cx + 1, cy), c01 = m.depth(cx, cy + 1), c11 = m.depth(cx + 1, cy + 1);
    gu = std::max(std::abs(c10 - c00), std::abs(c11 - c01)) * m.width;
    gv = std::max(std::abs(c01 - c00), std::abs(c11 - c10)) * m.height;
}

/// The distance from point (pu, pv) to the uv rectangle of cells [cx0, cx1) x [cy0, cy1) (nearest
/// periodic image for wrapped maps).
inline double relief_rect_distance(const ReliefMapCpu& m, double pu, double pv, int cx0, int cx1, int cy0, int cy1)
{
    const double W = m.width, H = m.height;
    const double cu = (cx0 + cx1 + 1) * 0.5 / W, hu = (cx1 - cx0) * 0.5 / W;
    const double cv = (cy0 + cy1 + 1) * 0.5 / H, hv = (cy1 - cy0) * 0.5 / H;
    const double du = std::max(std::abs(relief_offset(pu, cu, m.wrap)) - hu, 0.0), dv = std::max(std::abs(relief_offset(pv, cv, m.wrap)) - hv, 0.0);
    return std::sqrt(du * du + dv * dv);
}

/// The apex cell Q = (qx, qy) of a cone ratio: every surface point a of Q may be an apex, because
/// the shader interpolates ratios bilinearly between texel centres. dq: Q's deepest corner (no
/// apex is deeper); g: the slope bound over the 3 x 3 cells around Q (a segment from a in Q to y
/// in them stays in them, so d(a) - d(y) <= g |y - a|: a ratio >= 1 / g there).
struct ReliefApexCell {
    int qx = 0, qy = 0;
    double dq = 0.0, g = 0.0;
};

inline ReliefApexCell relief_apex_cell(const ReliefMapCpu& m, int qx, int qy)
{
    ReliefApexCell q;
    q.qx = qx;
    q.qy = qy;
    q.dq = std::max(std::max(m.depth(qx, qy), m.depth(qx + 1, qy)), std::max(m.depth(qx, qy + 1), m.depth(qx + 1, qy + 1)));
    double gu = 0.0, gv = 0.0;
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            double a = 0.0, b = 0.0;
            relief_cell_slopes(m, qx + i, qy + j, a, b);
            gu = std::max(gu, a);
            gv = std::max(gv, b);
        }
    q.g = std::sqrt(gu * gu + gv * gv);
    return q;
}

/// A conservative lower bound of |y - a| / (d(a) - d(y)) over the apexes a of cell Q and the points
/// y of cell (cx, cy) above them (the cone ratio that cell allows Q): the cell split into sub x sub
/// subcells; in each, with s its centre and (hu, hv) its half-size, d(y) >= d(s) - (Gu hu + Gv hv)
/// (Gu, Gv: the patch's slope bounds), d(a) <= dq and |y - a| >= dist(s, Q) - |(hu, hv)|; in the
/// 3 x 3 cells around Q also the slope bound 1 / g. Returns `limit` when the result would reach it.
inline double relief_cell_ratio(const ReliefMapCpu& m, const ReliefApexCell& q, int cx, int cy, int sub, double limit)
{
    const double W = m.width, H = m.height;
    const double c00 = m.depth(cx, cy), c10 = m.depth(cx + 1, cy), c01 = m.depth(cx, cy + 1), c11 = m.depth(cx + 1, cy + 1);
    const double mn = std::min(std::min(c00, c10), std::min(c01, c11));
    if (mn >= q.dq) return limit;
    auto near1 = [&](int a, int b, int n) {
        int d = a - b;
        if (m.wrap) d = ((d % n) + n + 1) % n - 1;
        return d >= -1 && d <= 1;
    };
    const bool neighbour = near1(cx, q.qx, m.width) && near1(cy, q.qy, m.height);
    const double floor_b = neighbour ? (q.g > 0.0 ? 1.0 / q.g : limit) : 0.0;
    if (floor_b >= limit) return limit;
    double gu = 0.0, gv = 0.0;
    relief_cell_slopes(m, cx, cy, gu, gv);
    const double u0 = (cx + 0.5) / W, v0 = (cy + 0.5) / H;
    const double hu = 0.5 / (sub * W), hv = 0.5 / (sub * H), rho = std::sqrt(hu * hu + hv * hv), margin = gu * hu + gv * hv;
    double best = limit;
    for (int b = 0; b < sub; ++b)
        for (int a = 0; a < sub; ++a) {
            const double fa = (a + 0.5) / sub, fb = (b + 0.5) / sub;
            const double ds = (c00 * (1.0 - fa) + c10 * fa) * (1.0 - fb) + (c01 * (1.0 - fa) + c11 * fa) * fb;
            const double gap = q.dq - (ds - margin);
            if (gap <= 0.0) continue;
            const double dist = std::max(relief_rect_distance(m, u0 + fa / W, v0 + fb / H, q.qx, q.qx + 1, q.qy, q.qy + 1) - rho, 0.0);
            best = std::min(best, std::max(dist / gap, floor_b));
        }
    return best;
}

/// Texel ratios from the cell ratios: each texel gets the smallest ratio of the cells it is a
/// corner of, so every bilinear mix of ratios inside a cell is at most that cell's ratio.
inline void relief_cells_to_texels(ReliefMapCpu& m, const std::vector<double>& cell_r, int nx, int ny)
{
    for (int iy = 0; iy < m.height; ++iy)
        for (int ix = 0; ix < m.width; ++ix) {
            double r = (nx > 0 && ny > 0) ? 1.0 : 0.0;
            for (int j = -1; j <= 0; ++j)
                for (int i = -1; i <= 0; ++i) {
                    int cx = ix + i, cy = iy + j;
                    if (m.wrap) {
                        cx = (cx + m.width) % m.width;
                        cy = (cy + m.height) % m.height;
                    }
                    if (cx < 0 || cy < 0 || cx >= nx || cy >= ny) continue;
                    r = std::min(r, cell_r[static_cast<size_t>(cy) * static_cast<size_t>(nx) + static_cast<size_t>(cx)]);
                }
            m.texels[static_cast<size_t>(iy) * static_cast<size_t>(m.width) + static_cast<size_t>(ix)].y = static_cast<float>(r);
        }
}

}  // namespace detail

/// relief_build_cones_exact: fills channel y with conservative cone ratios (in [0, 1]). The
/// shader mixes four texels' ratios bilinearly, so a ratio is bounded per cell (the square between
/// four texel centres) for an apex anywhere on the cell's surface, against every cell of the map
/// split into sub x sub subcells (detail::relief_cell_ratio: never wider than the true empty cone;
/// the gap shrinks as 1 / sub), and each texel gets the smallest ratio of its cells: every mix
/// inside a cell is then at most that cell's ratio. O((width · height)² · sub²): tests and maps up
/// to ~64². A clamped map under 2 texels on an axis (no cells) gets ratio 0.
inline void relief_build_cones_exact(ReliefMapCpu& m, int sub = 4)
{
    if (!m.valid()) return;
    const int s = std::min(std::max(sub, 1), 64);
    const detail::ReliefCells cells = detail::relief_cells(m);
    std::vector<double> cell_r(static_cast<size_t>(std::max(cells.nx, 0)) * static_cast<size_t>(std::max(cells.ny, 0)), 1.0);
    for (int qy = 0; qy < cells.ny; ++qy)
        for (int qx = 0; qx < cells.nx; ++qx) {
            const detail::ReliefApexCell q = detail::relief_apex_cell(m, qx, qy);
            double r = 1.0;
            for (int cy = 0; cy < cells.ny; ++cy)
                for (int cx = 0; cx < cells.nx; ++cx) r = std::min(r, detail::relief_cell_ratio(m, q, cx, cy, s, r));
            cell_r[static_cast<size_t>(qy) * static_cast<size_t>(cells.nx) + static_cast<size_t>(qx)] = r;
        }
    detail::relief_cells_to_texels(m, cell_r, cells.nx, cells.ny);
}

/// relief_build_cones: the same conservative cones, fast: a pyramid of the cells' minimum depths
/// (the highest point of a block of cells; a bilinear patch's extremes are at its corners) is
/// walked from the top, nearest blocks first, and a block is skipped when its distance from the
/// apex cell over its height above it already allows the ratio found so far. Leaf cells are bounded
/// as in relief_build_cones_exact, so the ratios are never narrower than its (a skipped block's
/// bound is exact geometry, no subcell margin) and as conservative. 0.2 s for 128² on one core.
inline void relief_build_cones(ReliefMapCpu& m, int sub = 4)
{
    if (!m.valid()) return;
    const int s = std::min(std::max(sub, 1), 64);
    const detail::ReliefCells cells = detail::relief_cells(m);
    // Level 0: one entry per cell; level k: blocks of 2^k x 2^k cells.
    std::vector<std::vector<float>> lv;
    std::vector<int> lw, lh;
    if (cells.nx > 0 && cells.ny > 0) {
        std::vector<float> base(static_cast<size_t>(cells.nx) * static_cast<size_t>(cells.ny));
        for (int cy = 0; cy < cells.ny; ++cy)
            for (int cx = 0; cx < cells.nx; ++cx)
                base[static_cast<size_t>(cy) * static_cast<size_t>(cells.nx) + static_cast<size_t>(cx)] =
                    std::min(std::min(m.depth(cx, cy), m.depth(cx + 1, cy)), std::min(m.depth(cx, cy + 1), m.depth(cx + 1, cy + 1)));
        lv.push_back(std::move(base));
        lw.push_back(cells.nx);
        lh.push_back(cells.ny);
        while (lw.back() > 1 || lh.back() > 1) {
            const int pw = lw.back(), ph = lh.back(), w = (pw + 1) / 2, h = (ph + 1) / 2;
            std::vector<float> next(static_cast<size_t>(w) * static_cast<size_t>(h), 2.0f);
            const std::vector<float>& prev = lv.back();
            for (int y = 0; y < ph; ++y)
                for (int x = 0; x < pw; ++x) {
                    float& dst = next[static_cast<size_t>(y / 2) * static_cast<size_t>(w) + static_cast<size_t>(x / 2)];
                    dst = std::min(dst, prev[static_cast<size_t>(y) * static_cast<size_t>(pw) + static_cast<size_t>(x)]);
                }
            lv.push_back(std::move(next));
            lw.push_back(w);
            lh.push_back(h);
        }
    }
    struct Node {
        int level, x, y;
    };
    std::vector<Node> stack;
    std::vector<double> cell_r(static_cast<size_t>(std::max(cells.nx, 0)) * static_cast<size_t>(std::max(cells.ny, 0)), 1.0);
    for (int qy = 0; qy < cells.ny; ++qy)
        for (int qx = 0; qx < cells.nx; ++qx) {
            const detail::ReliefApexCell q = detail::relief_apex_cell(m, qx, qy);
            const double qu = (qx + 1.0) / m.width, qv = (qy + 1.0) / m.height;  // Q's centre
            const double qr = 0.5 * std::sqrt(1.0 / (double(m.width) * m.width) + 1.0 / (double(m.height) * m.height));  // its half-diagonal
            double r = 1.0;
            stack.clear();
            stack.push_back({static_cast<int>(lv.size()) - 1, 0, 0});
            while (!stack.empty()) {
                const Node nd = stack.back();
                stack.pop_back();
                const size_t li = static_cast<size_t>(nd.level);
                const double mn = lv[li][static_cast<size_t>(nd.y) * static_cast<size_t>(lw[li]) + static_cast<size_t>(nd.x)];
                if (mn >= q.dq) continue;
                const int span = 1 << nd.level;
                const int cx0 = nd.x * span, cy0 = nd.y * span, cx1 = std::min(cx0 + span, cells.nx), cy1 = std::min(cy0 + span, cells.ny);
                const double dist = std::max(detail::relief_rect_distance(m, qu, qv, cx0, cx1, cy0, cy1) - qr, 0.0);
                if (dist / (q.dq - mn) >= r) continue;
                if (nd.level == 0) {
                    r = std::min(r, detail::relief_cell_ratio(m, q, nd.x, nd.y, s, r));
                    continue;
                }
                // Children, the farthest pushed first so the nearest is visited first.
                Node kids[4];
                double dk[4];
                int nk = 0;
                const int cl = nd.level - 1, cw = lw[static_cast<size_t>(cl)], ch = lh[static_cast<size_t>(cl)];
                for (int k = 0; k < 4; ++k) {
                    const int kx = nd.x * 2 + (k & 1), ky = nd.y * 2 + (k >> 1);
                    if (kx >= cw || ky >= ch) continue;
                    const int hs = 1 << cl;
                    kids[nk] = {cl, kx, ky};
                    dk[nk] = detail::relief_rect_distance(m, qu, qv, kx * hs, std::min(kx * hs + hs, cells.nx), ky * hs, std::min(ky * hs + hs, cells.ny));
                    ++nk;
                }
                for (int a = 0; a < nk; ++a)
                    for (int b = a + 1; b < nk; ++b)
                        if (dk[b] > dk[a]) {
                            std::swap(dk[a], dk[b]);
                            std::swap(kids[a], kids[b]);
                        }
                for (int a = 0; a < nk; ++a) stack.push_back(kids[a]);
            }
            cell_r[static_cast<size_t>(qy) * static_cast<size_t>(cells.nx) + static_cast<size_t>(qx)] = r;
        }
    detail::relief_cells_to_texels(m, cell_r, cells.nx, cells.ny);
}

namespace detail {

/// The bilinear depth at uv in double (the same weights as rk_relief_read, without its float
/// rounding), for the builders.
inline double relief_depth_d(const ReliefMapCpu& m, double u, double v)
{
    int x0 = 0, y0 = 0;
    double ax = 0.0, ay = 0.0;
    relief_axis(u, m.width, m.wrap, x0, ax);
    relief_axis(v, m.height, m.wrap, y0, ay);
    const double top = m.depth(x0, y0) * (1.0 - ax) + static_cast<double>(m.depth(x0 + 1, y0)) * ax;
    const double bottom = m.depth(x0, y0 + 1) * (1.0 - ax) + static_cast<double>(m.depth(x0 + 1, y0 + 1)) * ax;
    return top * (1.0 - ay) + bottom * ay;
}

/// The relaxed-cone constraint of texel (jx, jy) on apex (ix, iy) (Policarpo & Oliveira 2007): the
/// ray from (apex uv, depth 0) through the surface point of (jx, jy) is followed beyond it, in steps
/// of a quarter texel, while it is below the surface and above the apex's depth; where it
/// re-emerges (bisected), the cone must not reach: ratio <= |exit - apex| / (dx - exit depth).
/// Returns 1 when the ray does not re-emerge above the apex's depth (or after two map widths).
inline double relief_relaxed_pair(const ReliefMapCpu& m, int ix, int iy, double dx, int jx, int jy)
{
    const double W = m.width, H = m.height;
    const double xu = (ix + 0.5) / W, xv = (iy + 0.5) / H;
    const double ou = m.wrap ? relief_offset(xu, (jx + 0.5) / W, true) : (jx - ix) / W;
    const double ov = m.wrap ? relief_offset(xv, (jy + 0.5) / H, true) : (jy - iy) / H;
    const double dd = m.depth(jx, jy);
    if (dd >= dx || dd <= 1e-6) return 1.0;
    // Point at depth e: apex + (ou, ov) · e / dd.
    const double len = std::sqrt(ou * ou * W * W + ov * ov * H * H) / dd;  // texels per unit depth
    const double de = std::min(0.25 / std::max(len, 1e-9), (dx - dd) / 4.0);
    const int max_steps = 8 * std::max(m.width, m.height) + 8;
    auto below = [&](double e) { return relief_depth_d(m, xu + ou * e / dd, xv + ov * e / dd) <= e; };
    double e0 = dd;
    for (int k = 0; k < max_steps; ++k) {
        const double e1 = std::min(e0 + de, dx);
        if (!below(e1)) {
            double a = e0, b = e1;  // below at a (or dst itself), above at b
            for (int i = 0; i < 30; ++i) {
                const double mid = 0.5 * (a + b);
                (below(mid) ? a : b) = mid;
            }
            const double eu = ou * b / dd, ev = ov * b / dd;
            return std::min(1.0, std::sqrt(eu * eu + ev * ev) / std::max(dx - b, 1e-12));
        }
        if (e1 >= dx) break;
        e0 = e1;
    }
    return 1.0;
}

inline void relief_relaxed(ReliefMapCpu& m, int radius)
{
    if (!m.valid()) return;
    for (int iy = 0; iy < m.height; ++iy)
        for (int ix = 0; ix < m.width; ++ix) {
            const double dx = m.depth(ix, iy);
            double r = 1.0;
            int x0 = 0, x1 = m.width - 1, y0 = 0, y1 = m.height - 1;
            if (radius > 0) {
                x0 = ix - radius;
                x1 = ix + radius;
                y0 = iy - radius;
                y1 = iy + radius;
                if (!m.wrap) {
                    x0 = std::max(x0, 0);
                    y0 = std::max(y0, 0);
                    x1 = std::min(x1, m.width - 1);
                    y1 = std::min(y1, m.height - 1);
                } else if (2 * radius + 1 >= m.width) {
                    x0 = 0;
                    x1 = m.width - 1;
                }
                if (m.wrap && 2 * radius + 1 >= m.height) {
                    y0 = 0;
                    y1 = m.height - 1;
                }
            }
            for (int jy = y0; jy <= y1; ++jy)
                for (int jx = x0; jx <= x1; ++jx) {
                    if (jx == ix && jy == iy) continue;
                    const int wx = m.wrap ? ((jx % m.width) + m.width) % m.width : jx, wy = m.wrap ? ((jy % m.height) + m.height) % m.height : jy;
                    r = std::min(r, relief_relaxed_pair(m, ix, iy, dx, wx, wy));
                }
            m.texels[static_cast<size_t>(iy) * static_cast<size_t>(m.width) + static_cast<size_t>(ix)].y = static_cast<float>(r);
        }
}

}  // namespace detail

/// relief_build_relaxed_cones_exact: relaxed cone ratios (Policarpo & Oliveira 2007, in [0, 1])
/// over every pair of texels (detail::relief_relaxed_pair): O((width · height)² · march). Tests and
/// small maps.
inline void relief_build_relaxed_cones_exact(ReliefMapCpu& m) { detail::relief_relaxed(m, 0); }

/// relief_build_relaxed_cones: relaxed cone ratios from the texels within `radius` texels (a square
/// window, at least 1): O(width · height · radius² · march). Exits farther away are not seen, so
/// a ratio can be wider than the exact builder's (docs/relief.md measures the effect).
inline void relief_build_relaxed_cones(ReliefMapCpu& m, int radius = 16) { detail::relief_relaxed(m, std::max(radius, 1)); }

}  // namespace raykit
