// raykit-voxelize: glTF (.gltf / .glb) -> raykit sparse voxel octree file (.rksvo).
//
//   raykit-voxelize in.gltf|in.glb out.rksvo (--depth N | --voxel-size S) [--solid] [--budget MB]
//                   [--attributes color,normal,material] [--pointer-bits N] [--threads N]
//                   [--preview PREVIEW.png] [--quiet]
//
// Loads the glTF with raykit/svo_gltf.hpp, estimates the memory (estimate_svo_memory), builds the
// octree (build_svo), writes it (svo_save_file) and prints a summary. Exit codes: 0 success,
// 1 load / build / save failure (the SvoStatus message is printed), 2 bad arguments.
#if RAYKIT_VOXELIZE_TINYGLTF_IMPL
// No prebuilt tinygltf library was found: compile its implementation here.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#else
#include <stb/stb_image_write.h>  // libstb provides the implementation (linked beside tinygltf)
#endif

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include <unistd.h>

#include "raykit/svo_build.hpp"
#include "raykit/svo_file.hpp"
#include "raykit/svo_gltf.hpp"

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;

const char* const kUsage =
    "usage: raykit-voxelize IN.gltf|IN.glb OUT.rksvo (--depth N | --voxel-size S) [options]\n"
    "\n"
    "Voxelises every triangle of the glTF's default scene into a raykit sparse voxel octree file.\n"
    "\n"
    "  --depth N              levels below the root, 1..20 (voxels = root cube / 2^N)\n"
    "  --voxel-size S         largest voxel edge in the file's units (> 0); picks the depth\n"
    "  --solid                also fill the inside of closed meshes (default: surface only)\n"
    "  --budget MB            fail instead of using more than MB MiB of memory (> 0)\n"
    "  --attributes LIST      comma-separated subset of color,normal,material, or none\n"
    "                         (default: color,normal)\n"
    "  --pointer-bits N       near-pointer bits of the packer, 4..23 (default 23)\n"
    "  --threads N            worker threads, 0 = all cores (default 0)\n"
    "  --preview FILE.png     also write three orthographic views of the voxels (front, side,\n"
    "                         top; at most 512 pixels a side, shaded by the stored normals)\n"
    "  --quiet                print errors only\n"
    "  --help                 show this text\n"
    "\n"
    "Exit status: 0 success, 1 load/build/save failure, 2 bad arguments.\n";

/// Three orthographic views of the voxels (looking along -z, -x and -y), side by side: the nearest
/// voxel per pixel at level min(depth, 9), its stored colour (white without one), lit by its stored
/// normal (or shaded by distance without normals). Returns false when the PNG cannot be written.
bool write_preview(const raykit::SvoTree& t, const std::string& path)
{
    const uint32_t level = std::min<uint32_t>(t.depth, 9u), shift = t.depth - level, side = 1u << level, gap = 8;
    const uint32_t width = 3 * side + 2 * gap, height = side;
    std::vector<int32_t> depth(3ull * side * side, -1);
    std::vector<glm::vec3> colour(3ull * side * side, glm::vec3(0.0f));
    const glm::vec3 light = glm::normalize(glm::vec3(0.45f, 0.75f, 0.5f));
    raykit::svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t a) {
        const glm::uvec3 p = c >> shift;
        const glm::vec3 col = t.color.empty() ? glm::vec3(1.0f) : glm::vec3(raykit::rk_svo_unpack_color(t.color[a]));
        const bool lit = !t.normal.empty();
        const float shade = lit ? 0.3f + 0.7f * std::max(0.0f, glm::dot(raykit::rk_svo_unpack_normal(t.normal[a]), light)) : 1.0f;
        // Pixel (u, v) and nearness per view: front looks along -z, side along -x, top along -y.
        const uint32_t u[3] = {p.x, side - 1 - p.z, p.x}, v[3] = {side - 1 - p.y, side - 1 - p.y, p.z};
        const uint32_t nearness[3] = {p.z, p.x, p.y};
        for (uint32_t k = 0; k < 3; ++k) {
            const size_t i = (size_t(k) * side + v[k]) * side + u[k];
            if (int32_t(nearness[k]) <= depth[i]) continue;
            depth[i] = int32_t(nearness[k]);
            const float fog = lit ? 1.0f : 0.45f + 0.55f * float(nearness[k] + 1) / float(side);
            colour[i] = col * (shade * fog);
        }
    });
    std::vector<uint8_t> rgb(size_t(width) * height * 3, 40);
    for (uint32_t k = 0; k < 3; ++k)
        for (uint32_t y = 0; y < side; ++y)
            for (uint32_t x = 0; x < side; ++x) {
                const size_t i = (size_t(k) * side + y) * side + x;
                if (depth[i] < 0) continue;
                const glm::vec3 s = raykit::rk_srgb_encode(glm::clamp(colour[i], glm::vec3(0.0f), glm::vec3(1.0f)));
                uint8_t* o = &rgb[(size_t(y) * width + k * (side + gap) + x) * 3];
                for (int ch = 0; ch < 3; ++ch) o[ch] = uint8_t(raykit::rk_svo_pack_unorm8(s[ch]));
            }
    return stbi_write_png(path.c_str(), int(width), int(height), 3, rgb.data(), int(width) * 3) != 0;
}

int usage_error(const std::string& msg)
{
    std::fprintf(stderr, "raykit-voxelize: %s\n(run 'raykit-voxelize --help' for usage)\n", msg.c_str());
    return kExitUsage;
}

bool parse_int(const std::string& s, long lo, long hi, long& out)
{
    if (s.empty()) return false;
    char* end = nullptr;
    errno = 0;
    const long v = std::strtol(s.c_str(), &end, 10);
    if (errno != 0 || end != s.c_str() + s.size() || v < lo || v > hi) return false;
    out = v;
    return true;
}

bool parse_positive(const std::string& s, double& out)
{
    if (s.empty()) return false;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s.c_str(), &end);
    if (errno != 0 || end != s.c_str() + s.size() || !std::isfinite(v) || !(v > 0.0)) return false;
    out = v;
    return true;
}

bool parse_attributes(const std::string& s, uint32_t& out)
{
    out = 0;
    if (s == "none") return true;
    size_t start = 0;
    for (;;) {
        const size_t comma = s.find(',', start);
        const std::string name = s.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        if (name == "color" || name == "colour") out |= RK_SVO_ATTR_COLOR;
        else if (name == "normal") out |= RK_SVO_ATTR_NORMAL;
        else if (name == "material") out |= RK_SVO_ATTR_MATERIAL;
        else return false;
        if (comma == std::string::npos) return true;
        start = comma + 1;
    }
}

std::string bytes_text(uint64_t b)
{
    char buf[64];
    if (b < 10ull * 1024) std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(b));
    else if (b < 10ull * 1024 * 1024) std::snprintf(buf, sizeof buf, "%.1f KiB", double(b) / 1024.0);
    else if (b < 10ull * 1024 * 1024 * 1024) std::snprintf(buf, sizeof buf, "%.1f MiB", double(b) / (1024.0 * 1024.0));
    else std::snprintf(buf, sizeof buf, "%.2f GiB", double(b) / (1024.0 * 1024.0 * 1024.0));
    return buf;
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Progress on stderr: a bar redrawn at most 10 times a second on a terminal (after the first
/// 0.3 s, so quick builds print nothing), else a plain line per stage and per quarter for builds
/// that take over a second. Safe to call from any thread.
class Progress {
public:
    explicit Progress(bool enabled) : enabled_(enabled), tty_(isatty(STDERR_FILENO) != 0), t0_(Clock::now()) {}

    bool update(float fraction, const char* stage)
    {
        if (!enabled_) return true;
        std::lock_guard<std::mutex> lock(mutex_);
        const double t = since(t0_);
        const float f = fraction > 0.0f ? (fraction < 1.0f ? fraction : 1.0f) : 0.0f;
        const std::string s = stage ? stage : "";
        if (tty_) {
            if (t < 0.3 || (drawn_ && t - last_draw_ < 0.1 && s == stage_)) return true;
            const int width = 40, fill = int(f * float(width) + 0.5f);
            std::fprintf(stderr, "\r[%s%s] %3d%% %-12s", std::string(size_t(fill), '#').c_str(),
                         std::string(size_t(width - fill), '.').c_str(), int(f * 100.0f + 0.5f), s.c_str());
            std::fflush(stderr);
            drawn_ = true;
            last_draw_ = t;
        } else if (t >= 1.0) {
            const int quarter = int(f * 4.0f);
            if (s != stage_ || quarter != quarter_) {
                std::fprintf(stderr, "raykit-voxelize: %s %d%% (%.1f s)\n", s.c_str(), int(f * 100.0f + 0.5f), t);
                quarter_ = quarter;
            }
        }
        stage_ = s;
        return true;
    }

    void finish()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (drawn_) std::fprintf(stderr, "\r%70s\r", "");
        drawn_ = false;
    }

private:
    bool enabled_, tty_;
    Clock::time_point t0_;
    std::mutex mutex_;
    bool drawn_ = false;
    double last_draw_ = 0.0;
    std::string stage_;
    int quarter_ = -1;
};

}  // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> positional;
    raykit::SvoBuildOptions opt;
    bool have_depth = false, have_size = false, quiet = false;
    std::string preview_path;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            std::fputs(kUsage, stdout);
            return 0;
        }
        if (a.size() < 2 || a.compare(0, 2, "--") != 0 || a == "--") {
            if (a == "--") {
                for (++i; i < argc; ++i) positional.push_back(argv[i]);
                break;
            }
            if (a.size() > 1 && a[0] == '-') return usage_error("unknown option '" + a + "'");
            positional.push_back(a);
            continue;
        }
        std::string value;
        bool inline_value = false;
        const size_t eq = a.find('=');
        if (eq != std::string::npos) {
            value = a.substr(eq + 1);
            a = a.substr(0, eq);
            inline_value = true;
        }
        const bool takes_value = a == "--depth" || a == "--voxel-size" || a == "--budget" || a == "--attributes" ||
                                 a == "--pointer-bits" || a == "--threads" || a == "--preview";
        const bool flag = a == "--solid" || a == "--quiet";
        if (!takes_value && !flag) return usage_error("unknown option '" + a + "'");
        if (flag) {
            if (inline_value) return usage_error("option '" + a + "' takes no value");
            if (a == "--solid") opt.fill = raykit::SvoFill::solid;
            else quiet = true;
            continue;
        }
        if (!inline_value) {
            if (i + 1 >= argc) return usage_error("option '" + a + "' needs a value");
            value = argv[++i];
        }
        if (a == "--depth") {
            long v = 0;
            if (!parse_int(value, 1, long(RK_SVO_MAX_DEPTH), v))
                return usage_error("--depth must be an integer in 1.." + std::to_string(RK_SVO_MAX_DEPTH) + ", not '" + value + "'");
            opt.depth = int(v);
            have_depth = true;
        } else if (a == "--voxel-size") {
            double v = 0;
            if (!parse_positive(value, v) || !(v <= 3.0e38))
                return usage_error("--voxel-size must be a positive number, not '" + value + "'");
            opt.voxel_size = float(v);
            have_size = true;
        } else if (a == "--budget") {
            double v = 0;
            if (!parse_positive(value, v) || v > 1.0e12) return usage_error("--budget must be a positive number of MiB, not '" + value + "'");
            opt.memory_budget = uint64_t(v * 1024.0 * 1024.0);
            if (opt.memory_budget == 0) opt.memory_budget = 1;
        } else if (a == "--attributes") {
            if (!parse_attributes(value, opt.attributes))
                return usage_error("--attributes takes a comma-separated subset of color,normal,material (or none), not '" +
                                   value + "'");
        } else if (a == "--pointer-bits") {
            long v = 0;
            if (!parse_int(value, 4, 23, v)) return usage_error("--pointer-bits must be an integer in 4..23, not '" + value + "'");
            opt.pointer_bits = uint32_t(v);
        } else if (a == "--preview") {
            if (value.empty()) return usage_error("--preview needs a file name");
            preview_path = value;
        } else if (a == "--threads") {
            long v = 0;
            if (!parse_int(value, 0, 4096, v)) return usage_error("--threads must be an integer in 0..4096, not '" + value + "'");
            opt.threads = int(v);
        }
    }
    if (positional.size() != 2)
        return usage_error(positional.size() < 2 ? "expected an input glTF and an output file" : "too many arguments");
    if (have_depth == have_size) return usage_error("give exactly one of --depth and --voxel-size");
    const std::string in_path = positional[0], out_path = positional[1];

    // Load.
    const Clock::time_point t_load = Clock::now();
    raykit::SvoMeshData mesh;
    raykit::SvoStatus st;
    raykit::SvoGltfStats gs;
    if (!raykit::load_gltf_mesh(in_path, mesh, st, &gs)) {
        std::fprintf(stderr, "raykit-voxelize: %s\n", st.message.c_str());
        return kExitFailure;
    }
    const double seconds_load = since(t_load);
    if (!quiet)
        for (const std::string& w : gs.warnings) std::fprintf(stderr, "raykit-voxelize: warning: %s\n", w.c_str());
    const raykit::SvoMesh view = mesh.view();

    // Estimate, build.
    const uint64_t estimate = raykit::estimate_svo_memory(view, opt, st);
    if (estimate == 0) {
        std::fprintf(stderr, "raykit-voxelize: %s\n", st.message.c_str());
        return kExitFailure;
    }
    Progress progress(!quiet);
    opt.progress = [&progress](float f, const char* stage) { return progress.update(f, stage); };
    raykit::SvoTree tree;
    raykit::SvoBuildStats bs;
    const bool built = raykit::build_svo(view, opt, tree, st, &bs);
    progress.finish();
    if (!built) {
        std::fprintf(stderr, "raykit-voxelize: %s\n", st.message.c_str());
        return kExitFailure;
    }

    // Save.
    const Clock::time_point t_save = Clock::now();
    if (!raykit::svo_save_file(tree, out_path, st)) {
        std::fprintf(stderr, "raykit-voxelize: %s\n", st.message.c_str());
        return kExitFailure;
    }
    const double seconds_save = since(t_save);
    if (!preview_path.empty() && !write_preview(tree, preview_path)) {
        std::fprintf(stderr, "raykit-voxelize: cannot write the preview '%s'\n", preview_path.c_str());
        return kExitFailure;
    }
    if (quiet) return 0;

    const uint64_t structure = tree.structure_bytes(), attributes = tree.attribute_bytes();
    std::printf("raykit-voxelize: %s -> %s\n", in_path.c_str(), out_path.c_str());
    std::printf("  input      %zu nodes, %zu primitives, %zu vertices, %zu triangles\n", gs.nodes, gs.primitives,
                gs.vertices, gs.triangles);
    std::printf("  skipped    %zu point and %zu line primitives, %zu without POSITION; %zu triangles with bad indices,"
                " %zu stray indices\n",
                gs.skipped_points, gs.skipped_lines, gs.skipped_no_position, gs.dropped_bad_index, gs.dropped_incomplete);
    std::printf("  triangles  %zu used of %zu (skipped: %zu degenerate, %zu non-finite, %zu bad index, %zu outside)\n",
                bs.triangles_used, bs.triangles_in, bs.skipped_degenerate, bs.skipped_non_finite, bs.skipped_bad_index,
                bs.skipped_outside);
    const double voxel = tree.depth ? double(tree.root_size) / double(1ull << tree.depth) : 0.0;
    std::printf("  octree     depth %u, voxel size %.6g, root cube (%.6g, %.6g, %.6g) + %.6g, %s\n", tree.depth, voxel,
                double(tree.root_min.x), double(tree.root_min.y), double(tree.root_min.z), double(tree.root_size),
                opt.fill == raykit::SvoFill::solid ? "solid" : "surface");
    std::printf("  voxels     %llu leaves (%llu surface, %llu interior)\n", static_cast<unsigned long long>(tree.voxel_count),
                static_cast<unsigned long long>(bs.surface_voxels), static_cast<unsigned long long>(bs.interior_voxels));
    std::printf("  per level ");
    for (size_t l = 0; l < tree.level_nodes.size(); ++l)
        std::printf(" %zu:%llu", l, static_cast<unsigned long long>(tree.level_nodes[l]));
    std::printf("\n");
    const double per_voxel = tree.voxel_count ? double(structure + attributes) / double(tree.voxel_count) : 0.0;
    const double per_voxel_s = tree.voxel_count ? double(structure) / double(tree.voxel_count) : 0.0;
    std::printf("  bytes      structure %s, attributes %s; %.3f B per leaf voxel (%.3f structure only)\n",
                bytes_text(structure).c_str(), bytes_text(attributes).c_str(), per_voxel, per_voxel_s);
    std::printf("  memory     estimated peak %s, measured peak %s\n", bytes_text(estimate).c_str(),
                bytes_text(bs.peak_bytes).c_str());
    std::printf("  time       load %.3f s, voxelize %.3f s, fill %.3f s, pack %.3f s (build %.3f s), save %.3f s\n", seconds_load,
                bs.seconds_voxelize, bs.seconds_fill, bs.seconds_pack, bs.seconds_total, seconds_save);
    return 0;
}
