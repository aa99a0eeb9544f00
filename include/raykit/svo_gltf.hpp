// raykit — svo_gltf.hpp: glTF 2.0 (.gltf / .glb) -> SvoMeshData, the input of build_svo
// (svo_build.hpp). Opt-in: the only raykit header that needs tinygltf.
//
// Using it (tinygltf 2.x, Debian package libtinygltf-dev):
// - either link the prebuilt library (CMake: find_package(TinyGLTF CONFIG), target
//   TinyGLTF::TinyGLTF; Debian's is built with exceptions and links libstb),
// - or compile tinygltf's implementation in exactly one translation unit, as usual:
//     #define TINYGLTF_IMPLEMENTATION
//     #define STB_IMAGE_IMPLEMENTATION
//     #define STB_IMAGE_WRITE_IMPLEMENTATION
//     #include "raykit/svo_gltf.hpp"
//   That needs nlohmann/json.hpp (Debian: nlohmann-json3-dev) and <stb_image.h> on the include
//   path (Debian puts stb in /usr/include/stb: add -I/usr/include/stb, or define
//   TINYGLTF_NO_INCLUDE_STB_IMAGE and TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE and include
//   <stb/stb_image.h> and <stb/stb_image_write.h> first).
// -fno-exceptions / -fno-rtti: this header uses neither, and needs no define. tinygltf and
// nlohmann::json detect -fno-exceptions themselves (JSON is then parsed without exceptions and a
// parse error is an ordinary error); nlohmann's other internal errors become std::abort(), so for
// hostile input prefer to compile the implementation TU (or link the prebuilt library) with
// exceptions on, which mixes fine with an -fno-exceptions program.
//
// What is loaded: every mesh primitive reachable from the default scene (scene 0 when "scene" is
// absent; every root node when there are no scenes), with node transforms (matrix or TRS, composed
// down the hierarchy; normals by the inverse transpose, renormalised; a negative determinant flips
// the winding). Modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN; POINTS and LINES* are skipped and
// counted. Attributes POSITION, NORMAL, TEXCOORD_n (n = the material's baseColorTexture.texCoord);
// float or, per KHR_mesh_quantization, (normalized) 8/16-bit components; sparse accessors applied.
// Primitives without normals get flat normals (their triangles are de-indexed) when any other
// primitive has normals; when none has, SvoMeshData::normals stays empty (the builder then uses
// face normals). Skins, morph targets, cameras, lights and KHR_texture_transform are ignored (the
// mesh is taken in its bind pose; a warning is recorded).
// Materials: one SvoMeshMaterial per glTF material, in order, plus one default white material at
// the end when some primitive has none. Mapping:
//   base_color   = pbrMetallicRoughness.baseColorFactor (linear RGBA)
//   texture      = pbrMetallicRoughness.baseColorTexture: a PNG or JPEG (GIF and BMP also read)
//                  decoded to 8-bit RGBA, sRGB; sampler wrap modes CLAMP_TO_EDGE /
//                  MIRRORED_REPEAT / REPEAT -> SvoWrap; a texture whose image comes only from an
//                  extension (KTX2, WebP) is ignored with a warning
//   reflectance  = metallicFactor * (1 - roughnessFactor), clamped to [0, 1]: polished metal is a
//                  mirror, rough metal (glTF's default 1, 1) and dielectrics reflect nothing here
//   ior          = KHR_materials_ior.ior (default 1.5; values outside [1, 1e6] are ignored)
//   absorption   = -ln(KHR_materials_volume.attenuationColor) / attenuationDistance (0 without it;
//                  per unit of the file's space, node scale not applied)
//
// Robustness: every accessor, view, buffer, index, node, material, texture and image reference is
// checked before use (64-bit checked arithmetic); a hostile file gives an error, never a crash,
// and allocations are bounded by the file's own bytes and SvoGltfLimits (JSON nesting is checked
// before tinygltf's recursive parse, image sizes in the image headers before decoding). Triangles
// with an index out of range are dropped and counted. External URIs are read relative to the
// file's folder, as tinygltf does (absolute paths too). Errors: SvoError::io (a file that cannot
// be read, a missing external buffer or image), corrupt (invalid JSON, GLB or glTF structure,
// with the mesh, primitive and accessor named), invalid_argument (an unsupported required
// extension such as Draco), too_large (SvoGltfLimits exceeded, more than 65536 materials).
#pragma once

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "raykit/svo_mesh.hpp"

namespace raykit {

/// What load_gltf_mesh read and what it left out. Counters are per loaded instance (a mesh used by
/// two nodes counts twice).
struct SvoGltfStats {
    size_t nodes = 0;                ///< nodes visited from the scene's roots
    size_t mesh_instances = 0;       ///< visited nodes with a mesh
    size_t primitives = 0;           ///< primitives turned into triangles
    size_t triangles = 0;            ///< triangles emitted
    size_t vertices = 0;             ///< vertices emitted
    size_t dropped_bad_index = 0;    ///< triangles dropped: an index >= the primitive's vertex count
    size_t dropped_incomplete = 0;   ///< trailing indices of a TRIANGLES list not forming a triangle
    size_t skipped_points = 0;       ///< POINTS primitives skipped
    size_t skipped_lines = 0;        ///< LINES, LINE_LOOP, LINE_STRIP primitives skipped
    size_t skipped_no_position = 0;  ///< primitives without POSITION skipped (as the spec allows)
    size_t materials = 0;            ///< SvoMeshData::materials written (glTF's + the default)
    size_t textures = 0;             ///< base-colour textures written
    std::vector<std::string> warnings;  ///< ignored features and tinygltf warnings (at most 64)
};

/// Bounds on what a file may make the loader allocate beyond its own bytes (a small glTF can
/// instance a large mesh from many nodes). Exceeding one is SvoError::too_large.
struct SvoGltfLimits {
    uint64_t max_vertices = 1ull << 28;   ///< output vertices (<= 2^32 - 1 in any case)
    uint64_t max_triangles = 1ull << 28;  ///< output triangles
    uint32_t max_node_depth = 1024;       ///< levels of the node hierarchy
    uint64_t max_file_bytes = 0xFFFFFFFFull;  ///< the file (tinygltf takes at most 4 GiB - 1)
    /// Per image, read from its PNG / JPEG / GIF / BMP header before decoding (other formats are
    /// refused). The default admits 8192 x 8192; decoding may briefly take twice the RGBA8 size.
    uint64_t max_image_pixels = 1ull << 26;
    uint32_t max_json_depth = 128;            ///< nesting of JSON arrays and objects (tinygltf recurses on it)
};

namespace detail::gltf {

inline bool add_u64(uint64_t a, uint64_t b, uint64_t& r)
{
    r = a + b;
    return r >= a;
}
inline bool mul_u64(uint64_t a, uint64_t b, uint64_t& r)
{
    if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a) return false;
    r = a * b;
    return true;
}

inline int component_size(int ct)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

inline int type_components(int t)
{
    switch (t) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

inline std::string type_name(int t)
{
    switch (t) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "type " + std::to_string(t);
    }
}

inline std::string component_name(int ct)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_INT: return "int";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    default: return "componentType " + std::to_string(ct);
    }
}

/// double -> float without the undefined behaviour of an out-of-range conversion: +-inf beyond
/// the float range, NaN stays NaN.
inline float to_float(double x)
{
    if (x > double(std::numeric_limits<float>::max())) return std::numeric_limits<float>::infinity();
    if (x < -double(std::numeric_limits<float>::max())) return -std::numeric_limits<float>::infinity();
    return float(x);
}

/// Little-endian reads, independent of the host's byte order.
inline uint32_t read_le(const uint8_t* p, int bytes)
{
    uint32_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
    return v;
}

/// One component as float: floats as stored; integers normalised per the glTF rules when
/// `normalized` (unsigned: c / max; signed: max(c / max, -1)), else converted as they are.
inline float decode_component(const uint8_t* p, int ct, bool normalized)
{
    switch (ct) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
        const uint32_t u = read_le(p, 4);
        float f;
        std::memcpy(&f, &u, 4);
        return f;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? float(p[0]) / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const int v = int(p[0]) - (p[0] >= 128 ? 256 : 0);
        return normalized ? std::fmax(float(v) / 127.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const uint32_t v = read_le(p, 2);
        return normalized ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const uint32_t u = read_le(p, 2);
        const int v = int(u) - (u >= 32768u ? 65536 : 0);
        return normalized ? std::fmax(float(v) / 32767.0f, -1.0f) : float(v);
    }
    default: return 0.0f;
    }
}

/// What an accessor may hold for one use (a semantic or the indices).
struct AccessorRule {
    const char* what;   ///< "POSITION", "NORMAL", "TEXCOORD_0", "indices"
    int type;           ///< required TINYGLTF_TYPE_*
    bool allow_float;
    bool allow_8_16;       ///< byte / unsigned byte / short / unsigned short
    bool require_normalized_ints;
    bool allow_u32;
    bool indices;          ///< unsigned only, not normalized, no float
};

struct Loader {
    const tinygltf::Model& m;
    SvoStatus& st;
    SvoGltfStats& stats;
    const SvoGltfLimits& lim;

    void warn(const std::string& w)
    {
        if (stats.warnings.size() < 64) stats.warnings.push_back(w);
    }

    bool fail(SvoError e, const std::string& msg) { return st.fail(e, "glTF: " + msg); }

    /// A bufferView's bytes, checked against its buffer.
    bool view_bytes(int vi, const std::string& where, const uint8_t*& data, uint64_t& length, uint64_t& stride)
    {
        if (vi < 0 || size_t(vi) >= m.bufferViews.size())
            return fail(SvoError::corrupt, where + " refers to bufferView " + std::to_string(vi) + ", which does not exist (" +
                                               std::to_string(m.bufferViews.size()) + " bufferViews)");
        const tinygltf::BufferView& v = m.bufferViews[size_t(vi)];
        const std::string vname = "bufferView " + std::to_string(vi);
        if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size())
            return fail(SvoError::corrupt, where + ": " + vname + " refers to buffer " + std::to_string(v.buffer) +
                                               ", which does not exist (" + std::to_string(m.buffers.size()) + " buffers)");
        const std::vector<unsigned char>& b = m.buffers[size_t(v.buffer)].data;
        uint64_t end = 0;
        if (!add_u64(uint64_t(v.byteOffset), uint64_t(v.byteLength), end) || end > b.size())
            return fail(SvoError::corrupt, where + ": " + vname + " (byteOffset " + std::to_string(v.byteOffset) +
                                               ", byteLength " + std::to_string(v.byteLength) + ") exceeds buffer " +
                                               std::to_string(v.buffer) + " (" + std::to_string(b.size()) + " bytes)");
        data = b.data() + v.byteOffset;
        length = v.byteLength;
        stride = v.byteStride;
        return true;
    }

    /// Validates accessor `ai` against `rule` (type, component type, count <= max_count, every
    /// byte range in 64-bit checked arithmetic, sparse indices < count) and decodes it into
    /// `out_f` (count * components floats) or `out_u` (integers: indices, exact beyond 2^24).
    bool read_accessor(int ai, const AccessorRule& rule, const std::string& where, std::vector<float>* out_f,
                       std::vector<uint32_t>* out_u, uint64_t max_count)
    {
        const std::string aname = where + ": " + rule.what + " accessor " + std::to_string(ai);
        if (ai < 0 || size_t(ai) >= m.accessors.size())
            return fail(SvoError::corrupt, aname + " does not exist (" + std::to_string(m.accessors.size()) + " accessors)");
        const tinygltf::Accessor& a = m.accessors[size_t(ai)];
        const int ct = a.componentType;
        const int comps = type_components(a.type);
        const int csize = component_size(ct);
        bool ct_ok = false;
        if (ct == TINYGLTF_COMPONENT_TYPE_FLOAT) ct_ok = rule.allow_float;
        else if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) ct_ok = rule.allow_u32;
        else if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
            ct_ok = rule.allow_8_16 && (!rule.require_normalized_ints || a.normalized);
        else if (ct == TINYGLTF_COMPONENT_TYPE_BYTE || ct == TINYGLTF_COMPONENT_TYPE_SHORT)
            ct_ok = rule.allow_8_16 && !rule.indices && (!rule.require_normalized_ints || a.normalized);
        if (rule.indices && a.normalized) ct_ok = false;
        if (a.type != rule.type || !ct_ok || csize == 0)
            return fail(SvoError::corrupt, aname + " holds " + type_name(a.type) + " of " + (a.normalized ? "normalized " : "") +
                                               component_name(ct) + ", which raykit does not accept for " + rule.what);
        if (a.count == 0) return fail(SvoError::corrupt, aname + " has count 0");
        if (uint64_t(a.count) > max_count)
            return fail(SvoError::too_large, aname + " has count " + std::to_string(a.count) + ", over the limit " +
                                                 std::to_string(max_count));
        const uint64_t elem = uint64_t(comps) * uint64_t(csize);
        const uint64_t count = a.count;
        // Base values: a bufferView, or zeros under sparse values.
        const uint8_t* base = nullptr;
        uint64_t stride = elem;
        if (a.bufferView >= 0) {
            const uint8_t* vdata = nullptr;
            uint64_t vlen = 0, vstride = 0;
            if (!view_bytes(a.bufferView, aname, vdata, vlen, vstride)) return false;
            if (vstride != 0) {
                if (vstride < elem)
                    return fail(SvoError::corrupt, aname + ": byteStride " + std::to_string(vstride) + " of bufferView " +
                                                       std::to_string(a.bufferView) + " is smaller than the element size " +
                                                       std::to_string(elem));
                stride = vstride;
            }
            uint64_t last = 0, end = 0;
            if (!mul_u64(stride, count - 1, last) || !add_u64(last, uint64_t(a.byteOffset), end) || !add_u64(end, elem, end) ||
                end > vlen)
                return fail(SvoError::corrupt, aname + ": byteOffset " + std::to_string(a.byteOffset) + " + stride " +
                                                   std::to_string(stride) + " * (count " + std::to_string(count) + " - 1) + " +
                                                   std::to_string(elem) + " bytes exceeds bufferView " +
                                                   std::to_string(a.bufferView) + " (" + std::to_string(vlen) + " bytes)");
            base = vdata + a.byteOffset;
        } else if (!a.sparse.isSparse) {
            return fail(SvoError::corrupt, aname + " has neither a bufferView nor sparse values");
        } else if (rule.indices) {
            return fail(SvoError::corrupt, aname + " is sparse without a bufferView (not allowed for indices)");
        }
        if (out_f) {
            uint64_t n = 0;
            if (!mul_u64(count, uint64_t(comps), n)) return fail(SvoError::too_large, aname + ": count overflows");
            out_f->assign(size_t(n), 0.0f);
            if (base)
                for (uint64_t i = 0; i < count; ++i)
                    for (int c = 0; c < comps; ++c)
                        (*out_f)[size_t(i * uint64_t(comps)) + size_t(c)] =
                            decode_component(base + i * stride + uint64_t(c) * uint64_t(csize), ct, a.normalized);
        } else if (out_u) {
            out_u->assign(size_t(count), 0u);
            for (uint64_t i = 0; i < count; ++i) (*out_u)[size_t(i)] = read_le(base + i * stride, csize);
        }
        if (!a.sparse.isSparse) return true;
        // Sparse: `count` (index, value) pairs replace elements of the base values.
        const std::string sname = aname + " (sparse)";
        if (a.sparse.count <= 0 || uint64_t(a.sparse.count) > count)
            return fail(SvoError::corrupt, sname + ": count " + std::to_string(a.sparse.count) + " not in 1.." +
                                               std::to_string(count));
        const uint64_t sc = uint64_t(a.sparse.count);
        const int ict = a.sparse.indices.componentType;
        if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
            return fail(SvoError::corrupt, sname + ": indices have " + component_name(ict) + ", not an unsigned type");
        const int isize = component_size(ict);
        const uint8_t *idata = nullptr, *vdata = nullptr;
        uint64_t ilen = 0, vlen = 0, unused = 0, iend = 0, vend = 0;
        if (a.sparse.indices.byteOffset < 0 || a.sparse.values.byteOffset < 0)
            return fail(SvoError::corrupt, sname + ": negative byteOffset");
        if (!view_bytes(a.sparse.indices.bufferView, sname + " indices", idata, ilen, unused)) return false;
        if (!view_bytes(a.sparse.values.bufferView, sname + " values", vdata, vlen, unused)) return false;
        if (!mul_u64(sc, uint64_t(isize), iend) || !add_u64(iend, uint64_t(a.sparse.indices.byteOffset), iend) || iend > ilen)
            return fail(SvoError::corrupt, sname + ": indices exceed bufferView " + std::to_string(a.sparse.indices.bufferView));
        if (!mul_u64(sc, elem, vend) || !add_u64(vend, uint64_t(a.sparse.values.byteOffset), vend) || vend > vlen)
            return fail(SvoError::corrupt, sname + ": values exceed bufferView " + std::to_string(a.sparse.values.bufferView));
        idata += a.sparse.indices.byteOffset;
        vdata += a.sparse.values.byteOffset;
        for (uint64_t k = 0; k < sc; ++k) {
            const uint64_t target = read_le(idata + k * uint64_t(isize), isize);
            if (target >= count)
                return fail(SvoError::corrupt, sname + ": index " + std::to_string(target) + " >= count " + std::to_string(count));
            const uint8_t* src = vdata + k * elem;
            if (out_u) (*out_u)[size_t(target)] = read_le(src, csize);
            if (out_f)
                for (int c = 0; c < comps; ++c)
                    (*out_f)[size_t(target * uint64_t(comps)) + size_t(c)] =
                        decode_component(src + uint64_t(c) * uint64_t(csize), ct, a.normalized);
        }
        return true;
    }

    /// The node's local matrix (column-major glTF matrix, or T * R * S).
    bool local_matrix(size_t ni, glm::dmat4& out)
    {
        const tinygltf::Node& n = m.nodes[ni];
        const std::string nname = "node " + std::to_string(ni) + (n.name.empty() ? "" : " '" + n.name + "'");
        auto finite = [](const std::vector<double>& v) {
            for (double x : v)
                if (!std::isfinite(x)) return false;
            return true;
        };
        if (!finite(n.matrix) || !finite(n.translation) || !finite(n.rotation) || !finite(n.scale))
            return fail(SvoError::corrupt, nname + " has a non-finite transform");
        out = glm::dmat4(1.0);
        if (!n.matrix.empty()) {
            if (n.matrix.size() != 16) return fail(SvoError::corrupt, nname + ": matrix has " + std::to_string(n.matrix.size()) + " values, not 16");
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) out[c][r] = n.matrix[size_t(c * 4 + r)];
            return true;
        }
        if (!n.translation.empty() && n.translation.size() != 3)
            return fail(SvoError::corrupt, nname + ": translation has " + std::to_string(n.translation.size()) + " values, not 3");
        if (!n.rotation.empty() && n.rotation.size() != 4)
            return fail(SvoError::corrupt, nname + ": rotation has " + std::to_string(n.rotation.size()) + " values, not 4");
        if (!n.scale.empty() && n.scale.size() != 3)
            return fail(SvoError::corrupt, nname + ": scale has " + std::to_string(n.scale.size()) + " values, not 3");
        glm::dmat4 r(1.0);
        if (!n.rotation.empty()) {
            double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
            const double len = std::sqrt(x * x + y * y + z * z + w * w);
            if (!(len > 0.0) || !std::isfinite(len)) return fail(SvoError::corrupt, nname + ": rotation is not a unit quaternion");
            x /= len, y /= len, z /= len, w /= len;
            // Columns of the rotation matrix (glm: r[column][row]).
            r[0] = glm::dvec4(1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0);
            r[1] = glm::dvec4(2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0);
            r[2] = glm::dvec4(2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0);
        }
        glm::dmat4 s(1.0);
        if (!n.scale.empty()) s[0][0] = n.scale[0], s[1][1] = n.scale[1], s[2][2] = n.scale[2];
        glm::dmat4 t(1.0);
        if (!n.translation.empty()) t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
        out = t * r * s;
        return true;
    }

    struct Instance {
        size_t mesh;
        glm::dmat4 world;
    };

    /// Walks the default scene's node trees (iteratively; each node at most once).
    bool collect(std::vector<Instance>& inst)
    {
        std::vector<int> roots;
        if (!m.scenes.empty()) {
            int si = m.defaultScene < 0 ? 0 : m.defaultScene;
            if (size_t(si) >= m.scenes.size())
                return fail(SvoError::corrupt, "default scene " + std::to_string(si) + " does not exist (" +
                                                   std::to_string(m.scenes.size()) + " scenes)");
            roots = m.scenes[size_t(si)].nodes;
        } else {
            std::vector<uint8_t> has_parent(m.nodes.size(), 0);
            for (const tinygltf::Node& n : m.nodes)
                for (int c : n.children)
                    if (c >= 0 && size_t(c) < m.nodes.size()) has_parent[size_t(c)] = 1;
            for (size_t i = 0; i < m.nodes.size(); ++i)
                if (!has_parent[i]) roots.push_back(int(i));
        }
        struct Item {
            int node;
            uint32_t depth;
            glm::dmat4 parent;
        };
        std::vector<uint8_t> visited(m.nodes.size(), 0);
        std::vector<Item> stack;
        for (size_t k = roots.size(); k-- > 0;) stack.push_back({roots[k], 0u, glm::dmat4(1.0)});
        while (!stack.empty()) {
            const Item it = stack.back();
            stack.pop_back();
            if (it.node < 0 || size_t(it.node) >= m.nodes.size())
                return fail(SvoError::corrupt, "node " + std::to_string(it.node) + " does not exist (" +
                                                   std::to_string(m.nodes.size()) + " nodes)");
            const size_t ni = size_t(it.node);
            if (visited[ni])
                return fail(SvoError::corrupt, "node " + std::to_string(ni) +
                                                   " is reached twice (a cycle, or a node with two parents)");
            visited[ni] = 1;
            if (it.depth >= lim.max_node_depth)
                return fail(SvoError::too_large, "node " + std::to_string(ni) + " is deeper than " +
                                                     std::to_string(lim.max_node_depth) + " levels of hierarchy");
            glm::dmat4 local;
            if (!local_matrix(ni, local)) return false;
            const glm::dmat4 world = it.parent * local;
            ++stats.nodes;
            const tinygltf::Node& n = m.nodes[ni];
            if (n.mesh >= 0) {
                if (size_t(n.mesh) >= m.meshes.size())
                    return fail(SvoError::corrupt, "node " + std::to_string(ni) + " refers to mesh " + std::to_string(n.mesh) +
                                                       ", which does not exist (" + std::to_string(m.meshes.size()) + " meshes)");
                inst.push_back({size_t(n.mesh), world});
                ++stats.mesh_instances;
                if (n.skin >= 0) warn("node " + std::to_string(ni) + ": skin ignored (bind pose used)");
            }
            for (size_t k = n.children.size(); k-- > 0;) stack.push_back({n.children[k], it.depth + 1u, world});
        }
        return true;
    }

    /// Converts one glTF image (tinygltf-decoded) to 8-bit pixels in out.images; returns its slot.
    bool image_pixels(size_t ii, SvoMeshData& out, std::vector<int>& image_slot, int& slot)
    {
        if (image_slot[ii] >= 0) {
            slot = image_slot[ii];
            return true;
        }
        const tinygltf::Image& img = m.images[ii];
        const std::string iname = "image " + std::to_string(ii) + (img.name.empty() ? "" : " '" + img.name + "'");
        if (img.image.empty() || img.width <= 0 || img.height <= 0) {
            const bool external = !img.uri.empty() && img.uri.compare(0, 5, "data:") != 0;
            return fail(external ? SvoError::io : SvoError::corrupt,
                        iname + (external ? " ('" + img.uri + "')" : std::string()) + " could not be loaded or decoded");
        }
        if (img.component < 1 || img.component > 4 || (img.bits != 8 && img.bits != 16))
            return fail(SvoError::corrupt, iname + ": unsupported " + std::to_string(img.component) + " channels of " +
                                               std::to_string(img.bits) + " bits");
        uint64_t texels = 0, bytes = 0;
        if (!mul_u64(uint64_t(img.width), uint64_t(img.height), texels) ||
            !mul_u64(texels, uint64_t(img.component) * uint64_t(img.bits / 8), bytes) || bytes != img.image.size())
            return fail(SvoError::corrupt, iname + ": pixel data size does not match " + std::to_string(img.width) + "x" +
                                               std::to_string(img.height));
        std::vector<uint8_t> px(size_t(texels * uint64_t(img.component)));
        if (img.bits == 8) {
            std::memcpy(px.data(), img.image.data(), px.size());
        } else {
            for (size_t i = 0; i < px.size(); ++i) {  // stb returns host-order 16-bit values
                uint16_t v;
                std::memcpy(&v, &img.image[2 * i], 2);
                px[i] = uint8_t((uint32_t(v) * 255u + 32767u) / 65535u);
            }
        }
        out.images.push_back(std::move(px));
        slot = image_slot[ii] = int(out.images.size() - 1);
        return true;
    }

    static SvoWrap wrap_of(int mode)
    {
        switch (mode) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return SvoWrap::clamp;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return SvoWrap::mirror;
        default: return SvoWrap::repeat;
        }
    }

    /// Materials and their base-colour textures.
    bool materials(SvoMeshData& out)
    {
        std::vector<int> image_slot(m.images.size(), -1);
        std::vector<int> texture_slot(m.textures.size(), -1);
        struct Pending {
            int image_slot;
            size_t texture;
        };
        std::vector<Pending> pending;  // views are made once every image is in place
        for (size_t mi = 0; mi < m.materials.size(); ++mi) {
            const tinygltf::Material& mat = m.materials[mi];
            const std::string mname = "material " + std::to_string(mi) + (mat.name.empty() ? "" : " '" + mat.name + "'");
            const tinygltf::PbrMetallicRoughness& pbr = mat.pbrMetallicRoughness;
            SvoMeshMaterial mm;
            if (pbr.baseColorFactor.size() == 4) {
                for (int c = 0; c < 4; ++c) {
                    const double v = pbr.baseColorFactor[size_t(c)];
                    if (!std::isfinite(to_float(v))) return fail(SvoError::corrupt, mname + ": baseColorFactor not a finite float");
                    mm.values.base_color[c] = float(v);
                }
            } else if (!pbr.baseColorFactor.empty()) {
                return fail(SvoError::corrupt, mname + ": baseColorFactor has " + std::to_string(pbr.baseColorFactor.size()) +
                                                   " values, not 4");
            }
            const double metal = std::isfinite(pbr.metallicFactor) ? pbr.metallicFactor : 1.0;
            const double rough = std::isfinite(pbr.roughnessFactor) ? pbr.roughnessFactor : 1.0;
            const double refl = metal * (1.0 - rough);
            mm.values.reflectance = float(refl > 0.0 ? (refl < 1.0 ? refl : 1.0) : 0.0);
            auto ext = mat.extensions.find("KHR_materials_ior");
            if (ext != mat.extensions.end() && ext->second.IsObject() && ext->second.Has("ior")) {
                const tinygltf::Value& v = ext->second.Get("ior");
                const double ior = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
                if (ior >= 1.0 && ior <= 1.0e6) mm.values.ior = float(ior);
                else warn(mname + ": KHR_materials_ior.ior ignored (not a number in [1, 1e6])");
            }
            ext = mat.extensions.find("KHR_materials_volume");
            if (ext != mat.extensions.end() && ext->second.IsObject()) {
                const tinygltf::Value& o = ext->second;
                double dist = std::numeric_limits<double>::infinity();
                if (o.Has("attenuationDistance") && o.Get("attenuationDistance").IsNumber())
                    dist = o.Get("attenuationDistance").GetNumberAsDouble();
                const tinygltf::Value& col = o.Get("attenuationColor");
                if (o.Has("attenuationColor") && col.IsArray() && col.ArrayLen() == 3 && dist > 0.0 && std::isfinite(dist)) {
                    for (int c = 0; c < 3; ++c) {
                        const double a = col.Get(c).IsNumber() ? col.Get(c).GetNumberAsDouble() : 1.0;
                        const double cl = std::isfinite(a) ? (a > 1e-6 ? (a < 1.0 ? a : 1.0) : 1e-6) : 1.0;
                        mm.values.absorption[c] = float(std::min(-std::log(cl) / dist, 1.0e30));
                    }
                }
            }
            const int ti = pbr.baseColorTexture.index;
            if (ti >= 0) {
                if (size_t(ti) >= m.textures.size())
                    return fail(SvoError::corrupt, mname + ": baseColorTexture " + std::to_string(ti) + " does not exist (" +
                                                       std::to_string(m.textures.size()) + " textures)");
                if (pbr.baseColorTexture.extensions.count("KHR_texture_transform"))
                    warn(mname + ": KHR_texture_transform ignored");
                if (texture_slot[size_t(ti)] < 0) {
                    const tinygltf::Texture& tex = m.textures[size_t(ti)];
                    if (tex.source < 0) {
                        warn(mname + ": texture " + std::to_string(ti) + " has no core image source (ignored)");
                    } else {
                        if (size_t(tex.source) >= m.images.size())
                            return fail(SvoError::corrupt, "texture " + std::to_string(ti) + " refers to image " +
                                                               std::to_string(tex.source) + ", which does not exist (" +
                                                               std::to_string(m.images.size()) + " images)");
                        if (tex.sampler >= 0 && size_t(tex.sampler) >= m.samplers.size())
                            return fail(SvoError::corrupt, "texture " + std::to_string(ti) + " refers to sampler " +
                                                               std::to_string(tex.sampler) + ", which does not exist");
                        int slot = -1;
                        if (!image_pixels(size_t(tex.source), out, image_slot, slot)) return false;
                        texture_slot[size_t(ti)] = int(pending.size());
                        pending.push_back({slot, size_t(ti)});
                    }
                }
                mm.base_color_texture = texture_slot[size_t(ti)];
            }
            out.materials.push_back(mm);
        }
        for (const Pending& p : pending) {
            const tinygltf::Texture& tex = m.textures[p.texture];
            const tinygltf::Image& img = m.images[size_t(tex.source)];
            SvoImageView v;
            v.pixels = out.images[size_t(p.image_slot)].data();
            v.width = img.width;
            v.height = img.height;
            v.channels = img.component;
            v.row_stride = size_t(img.width) * size_t(img.component);
            v.srgb = true;
            if (tex.sampler >= 0) {
                v.wrap_s = wrap_of(m.samplers[size_t(tex.sampler)].wrapS);
                v.wrap_t = wrap_of(m.samplers[size_t(tex.sampler)].wrapT);
            }
            out.textures.push_back(v);
        }
        return true;
    }

    bool convert(SvoMeshData& out)
    {
        for (const std::string& e : m.extensionsRequired)
            if (e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression")
                return fail(SvoError::invalid_argument, "the file requires extension " + e + ", which raykit does not support");
        std::vector<Instance> inst;
        if (!collect(inst)) return false;
        if (!materials(out)) return false;
        const size_t gltf_materials = out.materials.size();

        // Which outputs exist at all: normals / texture coordinates when any primitive has them.
        bool any_normals = false, any_uvs = false, any_default_material = false;
        for (const Instance& in : inst)
            for (const tinygltf::Primitive& p : m.meshes[in.mesh].primitives) {
                const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
                if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
                    continue;
                if (!p.attributes.count("POSITION")) continue;
                any_normals = any_normals || p.attributes.count("NORMAL") != 0;
                any_uvs = any_uvs || p.attributes.count(texcoord_name(p)) != 0;
                any_default_material = any_default_material || p.material < 0;
            }
        if (any_default_material) out.materials.push_back(SvoMeshMaterial{});
        if (out.materials.size() > 65536)
            return fail(SvoError::too_large, std::to_string(out.materials.size()) + " materials (at most 65536)");
        stats.materials = out.materials.size();
        stats.textures = out.textures.size();

        for (const Instance& in : inst) {
            const tinygltf::Mesh& mesh = m.meshes[in.mesh];
            for (size_t pi = 0; pi < mesh.primitives.size(); ++pi)
                if (!primitive(in, mesh, pi, gltf_materials, any_normals, any_uvs, out)) return false;
        }
        stats.vertices = out.positions.size();
        stats.triangles = out.indices.size() / 3;
        return true;
    }

    std::string texcoord_name(const tinygltf::Primitive& p) const
    {
        int set = 0;
        if (p.material >= 0 && size_t(p.material) < m.materials.size()) {
            const tinygltf::TextureInfo& t = m.materials[size_t(p.material)].pbrMetallicRoughness.baseColorTexture;
            if (t.index >= 0 && t.texCoord >= 0) set = t.texCoord;
        }
        return "TEXCOORD_" + std::to_string(set);
    }

    bool primitive(const Instance& in, const tinygltf::Mesh& mesh, size_t pi, size_t gltf_materials, bool any_normals,
                   bool any_uvs, SvoMeshData& out)
    {
        const tinygltf::Primitive& p = mesh.primitives[pi];
        const std::string where = "mesh " + std::to_string(in.mesh) + (mesh.name.empty() ? "" : " '" + mesh.name + "'") +
                                  " primitive " + std::to_string(pi);
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        switch (mode) {
        case TINYGLTF_MODE_POINTS: ++stats.skipped_points; return true;
        case TINYGLTF_MODE_LINE: case TINYGLTF_MODE_LINE_LOOP: case TINYGLTF_MODE_LINE_STRIP: ++stats.skipped_lines; return true;
        case TINYGLTF_MODE_TRIANGLES: case TINYGLTF_MODE_TRIANGLE_STRIP: case TINYGLTF_MODE_TRIANGLE_FAN: break;
        default: return fail(SvoError::corrupt, where + ": mode " + std::to_string(p.mode) + " is not a glTF primitive mode");
        }
        auto pos_it = p.attributes.find("POSITION");
        if (pos_it == p.attributes.end()) {
            ++stats.skipped_no_position;
            warn(where + ": no POSITION attribute (skipped)");
            return true;
        }
        uint16_t material = 0;
        if (p.material >= 0) {
            if (size_t(p.material) >= gltf_materials)
                return fail(SvoError::corrupt, where + " refers to material " + std::to_string(p.material) +
                                                   ", which does not exist (" + std::to_string(gltf_materials) + " materials)");
            material = uint16_t(p.material);
        } else {
            material = uint16_t(gltf_materials);  // the default material, appended after glTF's
        }
        // Vertex attributes.
        const uint64_t max_vertices = lim.max_vertices < 0xFFFFFFFFull ? lim.max_vertices : 0xFFFFFFFFull;
        std::vector<float> pos, nrm, uv;
        // Counts are compared before anything is decoded: POSITION must have real bytes (so its
        // count is bounded by the file), and the other attributes must match its count (so a
        // sparse or zero-filled attribute cannot request more than that).
        auto accessor_count = [&](int ai, const char* what, uint64_t& count) {
            if (ai < 0 || size_t(ai) >= m.accessors.size())
                return fail(SvoError::corrupt, where + ": " + what + " accessor " + std::to_string(ai) + " does not exist (" +
                                                   std::to_string(m.accessors.size()) + " accessors)");
            count = m.accessors[size_t(ai)].count;
            return true;
        };
        uint64_t n64 = 0, other = 0;
        if (!accessor_count(pos_it->second, "POSITION", n64)) return false;
        if (m.accessors[size_t(pos_it->second)].bufferView < 0)
            return fail(SvoError::corrupt, where + ": POSITION accessor " + std::to_string(pos_it->second) +
                                               " has no bufferView (sparse-only positions are not accepted)");
        const AccessorRule pos_rule{"POSITION", TINYGLTF_TYPE_VEC3, true, true, false, false, false};
        if (!read_accessor(pos_it->second, pos_rule, where, &pos, nullptr, max_vertices)) return false;
        const size_t n = pos.size() / 3;
        auto nrm_it = p.attributes.find("NORMAL");
        if (nrm_it != p.attributes.end()) {
            if (!accessor_count(nrm_it->second, "NORMAL", other)) return false;
            if (other != n64)
                return fail(SvoError::corrupt, where + ": NORMAL accessor " + std::to_string(nrm_it->second) + " has count " +
                                                   std::to_string(other) + ", POSITION " + std::to_string(n64));
            const AccessorRule rule{"NORMAL", TINYGLTF_TYPE_VEC3, true, true, true, false, false};
            if (!read_accessor(nrm_it->second, rule, where, &nrm, nullptr, n64)) return false;
        }
        const std::string tc = texcoord_name(p);
        auto uv_it = p.attributes.find(tc);
        if (uv_it != p.attributes.end()) {
            if (!accessor_count(uv_it->second, tc.c_str(), other)) return false;
            if (other != n64)
                return fail(SvoError::corrupt, where + ": " + tc + " accessor " + std::to_string(uv_it->second) + " has count " +
                                                   std::to_string(other) + ", POSITION " + std::to_string(n64));
            const AccessorRule rule{tc.c_str(), TINYGLTF_TYPE_VEC2, true, true, false, false, false};
            if (!read_accessor(uv_it->second, rule, where, &uv, nullptr, n64)) return false;
        } else if (p.material >= 0 && out.materials[material].base_color_texture >= 0) {
            warn(where + ": textured material but no " + tc + " (texel (0, 0) used)");
        }
        // Indices -> triangle list.
        std::vector<uint32_t> idx;
        if (p.indices >= 0) {
            const AccessorRule rule{"indices", TINYGLTF_TYPE_SCALAR, false, true, false, true, true};
            const uint64_t max_idx = lim.max_triangles * 3u + 2u;
            if (!read_accessor(p.indices, rule, where, nullptr, &idx, max_idx)) return false;
        } else {
            idx.resize(n);
            for (size_t i = 0; i < n; ++i) idx[i] = uint32_t(i);
        }
        std::vector<uint32_t> tris;
        const size_t k = idx.size();
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            tris.assign(idx.begin(), idx.begin() + std::ptrdiff_t(k - k % 3));
            stats.dropped_incomplete += k % 3;
        } else if (k >= 3) {
            tris.reserve(3 * (k - 2));
            for (size_t i = 0; i + 2 < k; ++i) {
                if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {  // p_i = {v_i, v_{i+1+i%2}, v_{i+2-i%2}}
                    tris.push_back(idx[i]);
                    tris.push_back(idx[i + 1 + i % 2]);
                    tris.push_back(idx[i + 2 - i % 2]);
                } else {  // fan: p_i = {v_{i+1}, v_{i+2}, v_0}
                    tris.push_back(idx[i + 1]);
                    tris.push_back(idx[i + 2]);
                    tris.push_back(idx[0]);
                }
            }
        }
        // Drop triangles with an index out of range; flip winding for mirroring transforms.
        const bool flip = glm::determinant(glm::dmat3(in.world)) < 0.0;
        size_t kept = 0;
        for (size_t t = 0; t + 2 < tris.size(); t += 3) {
            uint32_t a = tris[t], b = tris[t + 1], c = tris[t + 2];
            if (a >= n || b >= n || c >= n) {
                ++stats.dropped_bad_index;
                continue;
            }
            if (flip) std::swap(b, c);
            tris[kept++] = a, tris[kept++] = b, tris[kept++] = c;
        }
        tris.resize(kept);
        const size_t ntri = kept / 3;
        const bool flat = any_normals && nrm.empty();  // de-indexed with face normals
        const uint64_t new_vertices = flat ? uint64_t(kept) : uint64_t(n);
        uint64_t total_v = 0, total_t = 0;
        if (!add_u64(out.positions.size(), new_vertices, total_v) || total_v > max_vertices)
            return fail(SvoError::too_large, where + ": more than " + std::to_string(max_vertices) + " vertices in all");
        if (!add_u64(out.indices.size() / 3, ntri, total_t) || total_t > lim.max_triangles)
            return fail(SvoError::too_large, where + ": more than " + std::to_string(lim.max_triangles) + " triangles in all");

        const glm::dmat4& w = in.world;
        const glm::dmat3 nm = glm::transpose(glm::inverse(glm::dmat3(w)));
        auto xform = [&](size_t v) {
            const glm::dvec4 q = w * glm::dvec4(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0);
            return glm::vec3(to_float(q.x), to_float(q.y), to_float(q.z));
        };
        auto unit = [](glm::dvec3 d) {
            const double l = glm::length(d);
            return l > 0.0 && std::isfinite(l) ? glm::vec3(d / l) : glm::vec3(0.0f);
        };
        const uint32_t base = uint32_t(out.positions.size());
        if (!flat) {
            for (size_t v = 0; v < n; ++v) {
                out.positions.push_back(xform(v));
                if (any_normals)
                    out.normals.push_back(unit(nm * glm::dvec3(nrm[3 * v], nrm[3 * v + 1], nrm[3 * v + 2])));
                if (any_uvs) out.uvs.push_back(uv.empty() ? glm::vec2(0.0f) : glm::vec2(uv[2 * v], uv[2 * v + 1]));
            }
            for (size_t i = 0; i < kept; ++i) out.indices.push_back(base + tris[i]);
        } else {
            for (size_t t = 0; t < ntri; ++t) {
                glm::dvec3 P[3];
                for (int j = 0; j < 3; ++j) {
                    const size_t v = tris[3 * t + size_t(j)];
                    P[j] = glm::dvec3(w * glm::dvec4(pos[3 * v], pos[3 * v + 1], pos[3 * v + 2], 1.0));
                }
                const glm::vec3 fn = unit(glm::cross(P[1] - P[0], P[2] - P[0]));
                for (int j = 0; j < 3; ++j) {
                    const size_t v = tris[3 * t + size_t(j)];
                    out.positions.push_back(glm::vec3(to_float(P[j].x), to_float(P[j].y), to_float(P[j].z)));
                    out.normals.push_back(fn);
                    if (any_uvs) out.uvs.push_back(uv.empty() ? glm::vec2(0.0f) : glm::vec2(uv[2 * v], uv[2 * v + 1]));
                    out.indices.push_back(base + uint32_t(3 * t + size_t(j)));
                }
            }
        }
        out.material_ids.insert(out.material_ids.end(), ntri, material);
        ++stats.primitives;
        return true;
    }
};

/// Nesting depth of JSON text stays within `max_depth` (checked before parsing: tinygltf converts
/// extras and extensions recursively).
inline bool json_depth_ok(const unsigned char* p, size_t n, uint32_t max_depth)
{
    uint32_t depth = 0;
    bool in_string = false, escaped = false;
    for (size_t i = 0; i < n; ++i) {
        const unsigned char c = p[i];
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > max_depth) return false;
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return true;
}

#ifndef TINYGLTF_NO_STB_IMAGE
/// Width and height from the header of a PNG, JPEG, GIF or BMP image; false for other formats
/// and for a PNG with a chunk running past the end of the data.
inline bool sniff_image_size(const unsigned char* b, size_t n, uint64_t& w, uint64_t& h)
{
    auto be16 = [b](size_t i) { return uint64_t(b[i]) << 8 | b[i + 1]; };
    auto be32 = [&](size_t i) { return be16(i) << 16 | be16(i + 2); };
    if (n >= 24 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0) {
        // Every chunk must fit in the data: stb grows its IDAT buffer by a chunk's announced
        // length before reading it.
        for (size_t i = 8; i + 8 <= n;) {
            const uint64_t len = be32(i);
            if (len + 12 > n - i) return false;
            const bool end = std::memcmp(b + i + 4, "IEND", 4) == 0;
            i += size_t(12 + len);
            if (end) break;
        }
        w = be32(16), h = be32(20);
        return true;
    }
    if (n >= 10 && (std::memcmp(b, "GIF87a", 6) == 0 || std::memcmp(b, "GIF89a", 6) == 0)) {
        w = read_le(b + 6, 2), h = read_le(b + 8, 2);
        return true;
    }
    if (n >= 26 && b[0] == 'B' && b[1] == 'M') {
        const uint32_t uw = read_le(b + 18, 4), uh = read_le(b + 22, 4);
        w = uw >= 0x80000000u ? uint64_t(0x100000000ull - uw) : uw;  // heights may be negative (top-down)
        h = uh >= 0x80000000u ? uint64_t(0x100000000ull - uh) : uh;
        return true;
    }
    if (n >= 4 && b[0] == 0xFF && b[1] == 0xD8) {  // JPEG: walk the marker segments to a SOFn
        size_t i = 2;
        while (i + 9 < n) {
            if (b[i] != 0xFF) return false;
            const unsigned mk = b[i + 1];
            if (mk == 0xFF) {
                ++i;
                continue;
            }
            if (mk == 0x01 || (mk >= 0xD0 && mk <= 0xD8)) {
                i += 2;
                continue;
            }
            if (mk >= 0xC0 && mk <= 0xCF && mk != 0xC4 && mk != 0xC8 && mk != 0xCC) {
                h = be16(i + 5), w = be16(i + 7);
                return true;
            }
            const uint64_t len = be16(i + 2);
            if (len < 2) return false;
            i += size_t(2 + len);
        }
    }
    return false;
}

/// tinygltf's image loader behind a format and size check: only PNG and JPEG (glTF's image
/// formats) and GIF and BMP (sizes readable from their headers) reach stb, and an image whose
/// header announces more than `max_pixels` pixels is refused before stb allocates for it.
inline bool guarded_load_image(tinygltf::Image* image, const int image_idx, std::string* err, std::string* warn, int req_width,
                               int req_height, const unsigned char* bytes, int size, void* user)
{
    const uint64_t max_pixels = *static_cast<const uint64_t*>(user);
    uint64_t w = 0, h = 0;
    if (size <= 0 || !sniff_image_size(bytes, size_t(size), w, h)) {
        if (err) *err += "image[" + std::to_string(image_idx) + "] is not a (complete) PNG, JPEG, GIF or BMP image\n";
        return false;
    }
    if (w * h > max_pixels) {
        if (err)
            *err += "image[" + std::to_string(image_idx) + "] is " + std::to_string(w) + "x" + std::to_string(h) +
                    ", over the limit of " + std::to_string(max_pixels) + " pixels\n";
        return false;
    }
    return tinygltf::LoadImageData(image, image_idx, err, warn, req_width, req_height, bytes, size, nullptr);
}
#endif

inline std::string trim(std::string s)
{
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    return s;
}

}  // namespace detail::gltf

/// svo_mesh_from_gltf: converts an already loaded tinygltf::Model (see the file comment for what
/// is read and how). On success `out` is replaced; on failure it is left empty and `st` names the
/// mesh / primitive / accessor at fault. Cost: O(output vertices + triangles + texture texels).
inline bool svo_mesh_from_gltf(const tinygltf::Model& model, SvoMeshData& out, SvoStatus& st, SvoGltfStats* stats = nullptr,
                               const SvoGltfLimits& limits = SvoGltfLimits())
{
    SvoGltfStats local_stats;
    SvoGltfStats& s = stats ? *stats : local_stats;
    s = SvoGltfStats();
    out = SvoMeshData();
    st = SvoStatus();
    SvoMeshData mesh;
    detail::gltf::Loader L{model, st, s, limits};
    if (!L.convert(mesh)) return false;
    out = std::move(mesh);  // moving keeps the image buffers, so the texture views stay valid
    return true;
}

/// load_gltf_mesh_from_memory: parses a glTF from memory: a .glb when it starts with "glTF",
/// JSON text otherwise. External URIs (buffers, images) resolve against `base_dir` ("" = the
/// current directory); data URIs and GLB chunks need none. Errors as load_gltf_mesh.
inline bool load_gltf_mesh_from_memory(const void* data, size_t size, const std::string& base_dir, SvoMeshData& out,
                                       SvoStatus& st, SvoGltfStats* stats = nullptr,
                                       const SvoGltfLimits& limits = SvoGltfLimits())
{
    out = SvoMeshData();
    st = SvoStatus();
    if (stats) *stats = SvoGltfStats();
    if (!data && size) return st.fail(SvoError::invalid_argument, "glTF: null data");
    if (size > limits.max_file_bytes || size > 0xFFFFFFFFull)
        return st.fail(SvoError::too_large, "glTF: " + std::to_string(size) + " bytes (at most " +
                                                std::to_string(std::min<uint64_t>(limits.max_file_bytes, 0xFFFFFFFFull)) + ")");
    const unsigned char* bytes = static_cast<const unsigned char*>(data);
    const bool glb = size >= 4 && std::memcmp(bytes, "glTF", 4) == 0;
    if (glb && size >= 12) {
        const uint32_t version = detail::gltf::read_le(bytes + 4, 4);
        if (version != 2)
            return st.fail(SvoError::corrupt, "glTF: GLB version " + std::to_string(version) + " (only version 2 is glTF 2.0)");
    }
    // JSON nesting: the whole text, or a GLB's JSON chunk (when its length is in range; tinygltf
    // rejects the file otherwise).
    const unsigned char* json = bytes;
    size_t json_size = size;
    if (glb) {
        const uint64_t chunk = size >= 20 ? detail::gltf::read_le(bytes + 12, 4) : 0;
        json = bytes + (size >= 20 ? 20 : size);
        json_size = size >= 20 && chunk <= size - 20 ? size_t(chunk) : 0;
    }
    if (!detail::gltf::json_depth_ok(json, json_size, limits.max_json_depth))
        return st.fail(SvoError::too_large, "glTF: JSON nested deeper than " + std::to_string(limits.max_json_depth) + " levels");
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string err, warn;
#ifndef TINYGLTF_NO_STB_IMAGE
    uint64_t max_pixels = limits.max_image_pixels;
    loader.SetImageLoader(&detail::gltf::guarded_load_image, &max_pixels);
#endif
    const bool ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes, static_cast<unsigned>(size), base_dir)
                        : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes),
                                                     static_cast<unsigned>(size), base_dir);
    if (!ok) {
        err = detail::gltf::trim(err.empty() ? warn : err);
        const bool io = err.find("ailed to load external") != std::string::npos || err.find("File not found") != std::string::npos ||
                        err.find("File open error") != std::string::npos || err.find("File read error") != std::string::npos;
        const bool large = err.find(", over the limit of ") != std::string::npos;
        return st.fail(io ? SvoError::io : large ? SvoError::too_large : SvoError::corrupt,
                       std::string("glTF: cannot load the ") + (glb ? "GLB" : "JSON glTF") + ": " + err);
    }
    SvoGltfStats local_stats;
    SvoGltfStats& s = stats ? *stats : local_stats;
    if (!svo_mesh_from_gltf(model, out, st, &s, limits)) return false;
    warn = detail::gltf::trim(warn);
    if (!warn.empty() && s.warnings.size() < 64) s.warnings.push_back("tinygltf: " + warn);
    return true;
}

/// load_gltf_mesh: reads a .gltf (JSON, data URIs or files beside it) or .glb file into `out`
/// (positions, normals, uvs, indices, per-triangle material ids, materials, textures; see the
/// file comment for what is read and how). Returns false with `st` set: io when the file cannot be
/// read, corrupt / invalid_argument / too_large as described above; `out` is then empty. `stats`
/// (optional) receives counts and warnings. Cost: the file's size + O(output).
inline bool load_gltf_mesh(const std::string& path, SvoMeshData& out, SvoStatus& st, SvoGltfStats* stats = nullptr,
                           const SvoGltfLimits& limits = SvoGltfLimits())
{
    out = SvoMeshData();
    st = SvoStatus();
    if (stats) *stats = SvoGltfStats();
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return st.fail(SvoError::io, "glTF: cannot open '" + path + "': " + std::strerror(errno));
    std::vector<unsigned char> bytes;
    unsigned char chunk[1 << 16];
    bool read_error = false;
    for (;;) {
        const size_t got = std::fread(chunk, 1, sizeof chunk, f);
        if (got > 0) {
            if (bytes.size() + got > limits.max_file_bytes) {
                std::fclose(f);
                return st.fail(SvoError::too_large, "glTF: '" + path + "' is larger than " + std::to_string(limits.max_file_bytes) + " bytes");
            }
            bytes.insert(bytes.end(), chunk, chunk + got);
        }
        if (got < sizeof chunk) {
            read_error = std::ferror(f) != 0;
            break;
        }
    }
    std::fclose(f);
    if (read_error) return st.fail(SvoError::io, "glTF: error reading '" + path + "'");
    const size_t slash = path.find_last_of("/\\");
    const std::string base_dir = slash == std::string::npos ? std::string() : path.substr(0, slash);
    if (!load_gltf_mesh_from_memory(bytes.data(), bytes.size(), base_dir, out, st, stats, limits)) {
        st.message += " (file '" + path + "')";
        return false;
    }
    return true;
}

}  // namespace raykit
