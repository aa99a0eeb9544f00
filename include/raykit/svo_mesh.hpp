// raykit — svo_mesh.hpp: what the octree builder (svo_build.hpp) takes: a triangle mesh as plain
// arrays (non-owning views, so an engine hands over its own buffers), its materials and base-colour
// images, and the build options. C++ only; needs GLM alone. raykit/svo_gltf.hpp fills an
// SvoMeshData from a glTF file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "raykit/svo_format.hpp"

namespace raykit {

/// How texture coordinates outside [0, 1] are folded (glTF sampler wrap modes).
enum class SvoWrap : uint8_t { repeat = 0, clamp = 1, mirror = 2 };

/// A base-colour image: 8-bit channels, rows top to bottom (texture coordinate v = 0 is the first
/// row, as in glTF). `channels` 1 (grey), 2 (grey + alpha), 3 (RGB) or 4 (RGBA). Colour channels
/// are sRGB-encoded when `srgb` (glTF base colour textures are), alpha is linear. Non-owning.
struct SvoImageView {
    const uint8_t* pixels = nullptr;
    int width = 0, height = 0;
    int channels = 4;
    size_t row_stride = 0;  ///< bytes between rows; 0 = width * channels
    bool srgb = true;
    SvoWrap wrap_s = SvoWrap::repeat, wrap_t = SvoWrap::repeat;
};

/// A material of the input mesh: the SvoMaterial values stored in the tree, plus the base-colour
/// texture (an index into SvoMesh::textures, -1 for none).
struct SvoMeshMaterial {
    SvoMaterial values;
    int base_color_texture = -1;
};

/// A triangle mesh as views of the caller's arrays. Strides are in bytes (0 = tightly packed).
/// Optional arrays may be null. Triangles: `indices` (3 per triangle) or, when null, vertices
/// 3i, 3i+1, 3i+2. Triangles with an index out of range, a non-finite position or zero area are
/// skipped and counted (SvoBuildStats).
struct SvoMesh {
    const float* positions = nullptr;  ///< xyz per vertex (required)
    size_t position_stride = 0;
    size_t vertex_count = 0;
    const float* normals = nullptr;    ///< xyz per vertex (optional; face normals otherwise)
    size_t normal_stride = 0;
    const float* uvs = nullptr;        ///< uv per vertex (optional; needed for textures)
    size_t uv_stride = 0;
    const uint32_t* indices = nullptr;
    size_t triangle_count = 0;
    const uint16_t* material_ids = nullptr;  ///< per triangle (optional; material 0 otherwise)
    const SvoMeshMaterial* materials = nullptr;  ///< optional: one white material otherwise
    size_t material_count = 0;
    const SvoImageView* textures = nullptr;
    size_t texture_count = 0;
};

/// An owning mesh (what the glTF loader and the test generators fill). view() is valid while the
/// object lives and is not modified.
struct SvoMeshData {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  ///< empty or one per position
    std::vector<glm::vec2> uvs;      ///< empty or one per position
    std::vector<uint32_t> indices;   ///< 3 per triangle
    std::vector<uint16_t> material_ids;  ///< empty or one per triangle
    std::vector<SvoMeshMaterial> materials;
    std::vector<std::vector<uint8_t>> images;  ///< pixel storage the texture views may point into
    std::vector<SvoImageView> textures;

    SvoMesh view() const
    {
        SvoMesh m;
        m.positions = positions.empty() ? nullptr : &positions[0].x;
        m.vertex_count = positions.size();
        m.normals = normals.size() == positions.size() && !normals.empty() ? &normals[0].x : nullptr;
        m.uvs = uvs.size() == positions.size() && !uvs.empty() ? &uvs[0].x : nullptr;
        m.indices = indices.empty() ? nullptr : indices.data();
        m.triangle_count = indices.size() / 3;
        m.material_ids = material_ids.size() == m.triangle_count && !material_ids.empty() ? material_ids.data() : nullptr;
        m.materials = materials.empty() ? nullptr : materials.data();
        m.material_count = materials.size();
        m.textures = textures.empty() ? nullptr : textures.data();
        m.texture_count = textures.size();
        return m;
    }
};

/// Surface: voxels that a triangle overlaps (a closed mesh gives a closed shell). Solid: surface
/// plus every voxel whose centre is inside the mesh (crossing parity along +x; needs a closed mesh).
enum class SvoFill : uint8_t { surface = 0, solid = 1 };

/// A parallel-for an engine can supply to run the build on its own job system: call body(i) for
/// every i in [0, count), in any order and on any threads, and return when all are done.
using SvoParallelFor = std::function<void(size_t count, const std::function<void(size_t)>& body)>;

/// Build options. Defaults: depth 10, surface, colour + normal, automatic bounds, all cores.
struct SvoBuildOptions {
    int depth = 10;            ///< levels below the root, 1..RK_SVO_MAX_DEPTH (20)
    float voxel_size = 0.0f;   ///< > 0: depth = the smallest giving voxels <= voxel_size (overrides depth)
    SvoFill fill = SvoFill::surface;
    uint32_t attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL;  ///< RK_SVO_ATTR_* streams to store
    /// Compact level of detail: the level-(depth-1) nodes inside bricks store no attributes; a
    /// traversal stopping there reads its brick's (one level coarser). Saves about a quarter of
    /// every attribute stream on surfaces (RK_SVO_ATTR_SHARED_SUB in the tree and the file).
    bool shared_sub_attributes = false;
    /// Root cube. Automatic (bounds_min/bounds_size unused): the smallest cube centred on the
    /// mesh's bounding box. Fixed: the given cube; triangles outside it are clipped away.
    bool fixed_bounds = false;
    glm::vec3 bounds_min{0.0f};
    float bounds_size = 0.0f;
    int threads = 0;           ///< worker threads of the built-in pool; 0 = std::thread::hardware_concurrency
    SvoParallelFor parallel_for;  ///< when set, used instead of the built-in pool
    uint64_t memory_budget = 0;   ///< bytes; 0 = no limit. Checked against the estimate and during the build
    uint32_t pointer_bits = 23;   ///< 4..23: near-pointer range of the packer (small values force far pointers)
    /// Called with the fraction done (0..1) and the current stage; return false to cancel.
    std::function<bool(float fraction, const char* stage)> progress;
};

/// What a build did and measured.
struct SvoBuildStats {
    size_t triangles_in = 0;
    size_t triangles_used = 0;
    size_t skipped_degenerate = 0;   ///< zero area after snapping to the lattice
    size_t skipped_non_finite = 0;   ///< a NaN or infinite coordinate
    size_t skipped_bad_index = 0;    ///< an index >= vertex_count
    size_t skipped_outside = 0;      ///< entirely outside fixed bounds, or too far outside to represent
    uint64_t surface_voxels = 0;
    uint64_t interior_voxels = 0;    ///< solid fill only
    uint64_t estimated_peak_bytes = 0;
    uint64_t peak_bytes = 0;         ///< largest sum of the builder's live allocations
    double seconds_voxelize = 0.0, seconds_fill = 0.0, seconds_pack = 0.0, seconds_total = 0.0;
};

}  // namespace raykit
