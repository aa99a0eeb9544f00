// raykit — svo_file.hpp: the octree file (docs/svo-format.md, "File format"): a structural
// validator for SvoTree, and a saver and a validating loader for a portable little-endian file.
//
// - svo_validate(tree, st): a tree that passes can be walked by svo_for_each_voxel, rk_svo_lookup
//   or a shader (svo_traverse.glsl) without an out-of-bounds read or a loop.
// - svo_save / svo_save_file: validate, then write. svo_load / svo_load_file: check the header's
//   counts and offsets against the byte size before allocating or reading anything, then the
//   CRC-32 of the header and of the payload, then svo_validate.
//
// C++17 and GLM only; no exceptions (SvoStatus reports errors), no RTTI. Every public function
// resets `st` on entry, so `st` describes the last call.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "raykit/svo_format.hpp"

namespace raykit {

namespace detail::svo_file {

// Slicing-by-8 tables: t[0] is the byte-wise table, t[k][i] the CRC of byte i followed by k zero
// bytes.
struct Crc32Table {
    uint32_t t[8][256];
};

constexpr Crc32Table make_crc32_table()
{
    Crc32Table r{};
    for (uint32_t i = 0; i < 256u; ++i) {
        uint32_t c = i;
        for (int k = 0; k < 8; ++k) c = (c & 1u) ? (0xEDB88320u ^ (c >> 1)) : (c >> 1);
        r.t[0][i] = c;
    }
    for (int k = 1; k < 8; ++k)
        for (uint32_t i = 0; i < 256u; ++i) r.t[k][i] = (r.t[k - 1][i] >> 8) ^ r.t[0][r.t[k - 1][i] & 0xFFu];
    return r;
}

inline constexpr Crc32Table kCrc32 = make_crc32_table();

}  // namespace detail::svo_file

/// svo_crc32: CRC-32/ISO-HDLC (the CRC of zlib, PNG and gzip: reflected polynomial 0xEDB88320,
/// initial value and final xor 0xFFFFFFFF); svo_crc32("123456789", 9) = 0xCBF43926. `crc` is the
/// result over the preceding bytes, so a checksum can be computed in pieces (0 to start). Byte
/// order independent. Cost: slicing-by-8, 8 table lookups per 8 bytes (8 KiB of tables).
inline uint32_t svo_crc32(const uint8_t* data, size_t size, uint32_t crc = 0)
{
    const auto& T = detail::svo_file::kCrc32.t;
    uint32_t c = ~crc;
    const uint8_t* p = data;
    for (; size >= 8; size -= 8, p += 8) {
        const uint32_t a = c ^ (uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24);
        const uint32_t b = uint32_t(p[4]) | uint32_t(p[5]) << 8 | uint32_t(p[6]) << 16 | uint32_t(p[7]) << 24;
        c = T[7][a & 0xFFu] ^ T[6][(a >> 8) & 0xFFu] ^ T[5][(a >> 16) & 0xFFu] ^ T[4][a >> 24] ^ T[3][b & 0xFFu] ^
            T[2][(b >> 8) & 0xFFu] ^ T[1][(b >> 16) & 0xFFu] ^ T[0][b >> 24];
    }
    for (; size > 0; --size, ++p) c = T[0][(c ^ *p) & 0xFFu] ^ (c >> 8);
    return ~c;
}

namespace detail::svo_file {

// Byte layout of the header (docs/svo-format.md). All fields little-endian.
inline constexpr uint8_t kMagic[8] = {'R', 'K', 'S', 'V', 'O', 0x0D, 0x0A, 0x1A};
inline constexpr size_t kOffVersion = 8, kOffHeaderSize = 12, kOffDepth = 16, kOffBrickLevels = 20, kOffAttributes = 24,
                 kOffPointerBits = 28, kOffRootMin = 32, kOffRootSize = 44, kOffDescWords = 48, kOffFarSlots = 52,
                 kOffBrickCount = 56, kOffMaterialCount = 60, kOffVoxelCount = 64, kOffAttrCount = 72,
                 kOffFileSize = 80, kOffSections = 88, kOffLevelNodes = 184;
inline constexpr uint32_t kSections = 6;  // words, brick_base, color, normal, material, materials
inline constexpr const char* kSectionName[kSections] = {"words", "brick_base", "color", "normal", "material", "materials"};
inline constexpr uint64_t kMaterialBytes = 36;  // 9 floats
inline constexpr uint64_t kMaxMaterials = 65536;  // rk_svo_material_id is 16 bits
inline constexpr uint64_t k2p32 = uint64_t(1) << 32;
/// Header bytes for a depth: fixed part, level_nodes[depth + 1], payload CRC, header CRC.
constexpr uint64_t header_size_for(uint64_t depth) { return kOffLevelNodes + 8u * (depth + 1u) + 8u; }
inline constexpr uint64_t kMinHeader = header_size_for(1), kMaxHeader = header_size_for(RK_SVO_MAX_DEPTH);
inline constexpr size_t kChunk = 1u << 16;

inline void put_u32(uint8_t* p, uint32_t v)
{
    p[0] = uint8_t(v);
    p[1] = uint8_t(v >> 8);
    p[2] = uint8_t(v >> 16);
    p[3] = uint8_t(v >> 24);
}
inline void put_u64(uint8_t* p, uint64_t v)
{
    put_u32(p, uint32_t(v));
    put_u32(p + 4, uint32_t(v >> 32));
}
inline uint32_t get_u32(const uint8_t* p)
{
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
inline uint64_t get_u64(const uint8_t* p) { return uint64_t(get_u32(p)) | (uint64_t(get_u32(p + 4)) << 32); }
inline uint32_t float_bits(float f)
{
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}
inline float bits_float(uint32_t u)
{
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}
// Whether uint32_t is stored little-endian here (then words are copied, not assembled bytewise).
inline bool host_little_endian()
{
    const uint32_t one = 1;
    uint8_t b;
    std::memcpy(&b, &one, 1);
    return b == 1;
}
inline uint32_t popcount32(uint32_t v)
{
    v = v - ((v >> 1) & 0x55555555u);
    v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
    return (((v + (v >> 4)) & 0x0F0F0F0Fu) * 0x01010101u) >> 24;
}
inline std::string hex(uint64_t v)
{
    char b[24];
    std::snprintf(b, sizeof b, "0x%llx", static_cast<unsigned long long>(v));
    return b;
}
inline std::string num(uint64_t v) { return std::to_string(v); }

// A tree's material as the file's 9 floats.
inline void material_floats(const SvoMaterial& m, float f[9])
{
    f[0] = m.base_color.x;
    f[1] = m.base_color.y;
    f[2] = m.base_color.z;
    f[3] = m.base_color.w;
    f[4] = m.reflectance;
    f[5] = m.ior;
    f[6] = m.absorption.x;
    f[7] = m.absorption.y;
    f[8] = m.absorption.z;
}

// Expected byte sizes of the six payload sections from a tree's (or a header's) counts. Counts are
// at most 2^32 (checked by the callers), so no product overflows.
inline void section_sizes(uint64_t words, uint64_t bricks, uint32_t attributes, uint64_t attr_count,
                          uint64_t materials, uint64_t out[kSections])
{
    out[0] = 4u * words;
    out[1] = 4u * bricks;
    out[2] = (attributes & RK_SVO_ATTR_COLOR) ? 4u * attr_count : 0u;
    out[3] = (attributes & RK_SVO_ATTR_NORMAL) ? 4u * attr_count : 0u;
    out[4] = (attributes & RK_SVO_ATTR_MATERIAL) ? 4u * attr_count : 0u;
    out[5] = kMaterialBytes * materials;
}

// Serialises the payload of a valid tree in chunks of at most kChunk bytes: sink(ptr, n).
template <class Sink>
void emit_u32s(const std::vector<uint32_t>& v, std::vector<uint8_t>& buf, Sink& sink)
{
    const size_t per = kChunk / 4;
    const bool le = host_little_endian();
    for (size_t i = 0; i < v.size(); i += per) {
        const size_t m = v.size() - i < per ? v.size() - i : per;
        if (le) {
            sink(reinterpret_cast<const uint8_t*>(v.data() + i), 4 * m);
        } else {
            for (size_t k = 0; k < m; ++k) put_u32(&buf[4 * k], v[i + k]);
            sink(buf.data(), 4 * m);
        }
    }
}

template <class Sink>
void emit_payload(const SvoTree& t, Sink& sink)
{
    std::vector<uint8_t> buf(kChunk);
    emit_u32s(t.words, buf, sink);
    emit_u32s(t.brick_base, buf, sink);
    emit_u32s(t.color, buf, sink);
    emit_u32s(t.normal, buf, sink);
    emit_u32s(t.material, buf, sink);
    for (const SvoMaterial& m : t.materials) {
        float f[9];
        material_floats(m, f);
        for (int k = 0; k < 9; ++k) put_u32(&buf[4 * size_t(k)], float_bits(f[k]));
        sink(buf.data(), size_t(kMaterialBytes));
    }
}

// The header of a valid tree (header_size_for(depth) bytes) given its payload's CRC.
inline std::vector<uint8_t> make_header(const SvoTree& t, uint32_t payload_crc)
{
    const uint64_t hs = header_size_for(t.depth);
    std::vector<uint8_t> h(size_t(hs), 0);
    uint8_t* p = h.data();
    std::memcpy(p, kMagic, 8);
    put_u32(p + kOffVersion, RK_SVO_VERSION);
    put_u32(p + kOffHeaderSize, uint32_t(hs));
    put_u32(p + kOffDepth, t.depth);
    put_u32(p + kOffBrickLevels, t.brick_levels);
    put_u32(p + kOffAttributes, t.attributes);
    put_u32(p + kOffPointerBits, t.pointer_bits);
    put_u32(p + kOffRootMin + 0, float_bits(t.root_min.x));
    put_u32(p + kOffRootMin + 4, float_bits(t.root_min.y));
    put_u32(p + kOffRootMin + 8, float_bits(t.root_min.z));
    put_u32(p + kOffRootSize, float_bits(t.root_size));
    put_u32(p + kOffDescWords, t.desc_words);
    put_u32(p + kOffFarSlots, t.far_slots);
    put_u32(p + kOffBrickCount, t.brick_count);
    put_u32(p + kOffMaterialCount, uint32_t(t.materials.size()));
    put_u64(p + kOffVoxelCount, t.voxel_count);
    put_u64(p + kOffAttrCount, t.attr_count);
    uint64_t sz[kSections];
    section_sizes(t.words.size(), t.brick_base.size(), t.attributes, t.attr_count, t.materials.size(), sz);
    uint64_t off = hs;
    for (uint32_t s = 0; s < kSections; ++s) {
        put_u64(p + kOffSections + 16 * s, off);
        put_u64(p + kOffSections + 16 * s + 8, sz[s]);
        off += sz[s];
    }
    put_u64(p + kOffFileSize, off);
    for (uint32_t l = 0; l <= t.depth; ++l) put_u64(p + kOffLevelNodes + 8 * l, t.level_nodes[l]);
    put_u32(p + hs - 8, payload_crc);
    put_u32(p + hs - 4, svo_crc32(p, size_t(hs - 4)));
    return h;
}

// What the header says, after parse_header checked it.
struct Header {
    uint32_t header_size = 0, depth = 0, brick_levels = 0, attributes = 0, pointer_bits = 0;
    float root_min[3] = {0, 0, 0}, root_size = 0;
    uint32_t desc_words = 0, far_slots = 0, brick_count = 0, material_count = 0;
    uint64_t voxel_count = 0, attr_count = 0, file_size = 0;
    uint64_t level_nodes[RK_SVO_MAX_DEPTH + 1] = {};
    uint32_t payload_crc = 0;
};

// Checks a file's header: `data` holds the first `avail` bytes of a file of `size` bytes, avail >=
// min(size, kMaxHeader). Magic, version, header size and CRC, then every count and section offset
// against `size` with 64-bit arithmetic that cannot overflow. Nothing is allocated.
inline bool parse_header(const uint8_t* data, size_t avail, uint64_t size, Header& h, SvoStatus& st)
{
    const size_t nm = avail < 8 ? avail : 8;
    if (std::memcmp(data, kMagic, nm) != 0) {
        if ((nm >= 7 && std::memcmp(data, "RKSVO\n\x1a", 7) == 0) || (nm >= 8 && std::memcmp(data, "RKSVO\r\r\n", 8) == 0))
            return st.fail(SvoError::bad_magic, "svo_load: bad magic: the CR LF at bytes 5..6 was changed: the file went "
                                                "through a text-mode (line-ending) conversion");
        std::string got;
        for (size_t i = 0; i < nm; ++i) got += (i ? " " : "") + hex(data[i]);
        return st.fail(SvoError::bad_magic, "svo_load: bad magic: not a raykit octree file (bytes 0.." + num(nm ? nm - 1 : 0) +
                                                " are [" + got + "], expected \"RKSVO\" 0x0d 0x0a 0x1a)");
    }
    if (size < 16)
        return st.fail(SvoError::truncated, "svo_load: truncated: the file has " + num(size) +
                                                " bytes, less than the 16 bytes of magic, version and header_size");
    const uint32_t version = get_u32(data + kOffVersion);
    if (version != RK_SVO_VERSION)
        return st.fail(SvoError::unsupported_version, "svo_load: version (byte 8) is " + num(version) +
                                                          ", this build reads version " + num(RK_SVO_VERSION));
    const uint32_t hs = get_u32(data + kOffHeaderSize);
    if (hs < kMinHeader || hs > kMaxHeader || (hs - kMinHeader) % 8u != 0)
        return st.fail(SvoError::corrupt, "svo_load: header_size (byte 12) is " + num(hs) + ", not 200 + 8 * depth for a depth 1.." +
                                              num(RK_SVO_MAX_DEPTH));
    if (size < hs)
        return st.fail(SvoError::truncated, "svo_load: truncated: the file has " + num(size) + " bytes, its header alone " + num(hs));
    const uint32_t hcrc = get_u32(data + hs - 4), hcalc = svo_crc32(data, hs - 4);
    if (hcrc != hcalc)
        return st.fail(SvoError::checksum_mismatch, "svo_load: header checksum mismatch: CRC-32 of bytes 0.." + num(hs - 5) + " is " +
                                                        hex(hcalc) + ", the header stores " + hex(hcrc) + " (byte " + num(hs - 4) + ")");
    h.header_size = hs;
    h.depth = get_u32(data + kOffDepth);
    if (h.depth < 1 || h.depth > RK_SVO_MAX_DEPTH)
        return st.fail(SvoError::corrupt, "svo_load: depth (byte 16) is " + num(h.depth) + ", outside 1.." + num(RK_SVO_MAX_DEPTH));
    if (hs != header_size_for(h.depth))
        return st.fail(SvoError::corrupt, "svo_load: header_size (byte 12) is " + num(hs) + " but depth " + num(h.depth) + " needs " +
                                              num(header_size_for(h.depth)));
    h.brick_levels = get_u32(data + kOffBrickLevels);
    h.attributes = get_u32(data + kOffAttributes);
    h.pointer_bits = get_u32(data + kOffPointerBits);
    for (int k = 0; k < 3; ++k) h.root_min[k] = bits_float(get_u32(data + kOffRootMin + 4 * size_t(k)));
    h.root_size = bits_float(get_u32(data + kOffRootSize));
    h.desc_words = get_u32(data + kOffDescWords);
    h.far_slots = get_u32(data + kOffFarSlots);
    h.brick_count = get_u32(data + kOffBrickCount);
    h.material_count = get_u32(data + kOffMaterialCount);
    h.voxel_count = get_u64(data + kOffVoxelCount);
    h.attr_count = get_u64(data + kOffAttrCount);
    h.file_size = get_u64(data + kOffFileSize);
    for (uint32_t l = 0; l <= h.depth; ++l) h.level_nodes[l] = get_u64(data + kOffLevelNodes + 8 * l);
    h.payload_crc = get_u32(data + hs - 8);
    if (h.attributes & ~uint32_t(RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL | RK_SVO_ATTR_SHARED_SUB))
        return st.fail(SvoError::corrupt, "svo_load: attributes (byte 24) is " + hex(h.attributes) + ", only bits 0..3 are defined");
    // Counts: all u32 or range-checked u64, so the sums and products below stay far from 2^64.
    const uint64_t words = uint64_t(h.desc_words) + 2u * uint64_t(h.brick_count);
    if (words + h.brick_count > k2p32)
        return st.fail(SvoError::too_large, "svo_load: desc_words (byte 48) " + num(h.desc_words) + " + 3 * brick_count (byte 56) " +
                                                num(h.brick_count) + " exceeds 2^32 words");
    if (h.attr_count > k2p32)
        return st.fail(SvoError::too_large, "svo_load: attr_count (byte 72) is " + num(h.attr_count) + ", above 2^32");
    if (h.material_count > kMaxMaterials)
        return st.fail(SvoError::too_large, "svo_load: material count (byte 60) is " + num(h.material_count) + ", above 65536");
    uint64_t expect[kSections];
    section_sizes(words, h.brick_count, h.attributes, h.attr_count, h.material_count, expect);
    uint64_t off = hs;
    for (uint32_t s = 0; s < kSections; ++s) {
        const size_t at = kOffSections + 16 * s;
        const uint64_t so = get_u64(data + at), sz = get_u64(data + at + 8);
        if (sz != expect[s])
            return st.fail(SvoError::corrupt, std::string("svo_load: section ") + kSectionName[s] + " size (byte " + num(at + 8) +
                                                  ") is " + num(sz) + ", the header's counts give " + num(expect[s]));
        if (so != off)
            return st.fail(SvoError::corrupt, std::string("svo_load: section ") + kSectionName[s] + " offset (byte " + num(at) +
                                                  ") is " + num(so) + ", expected " + num(off) + " (sections are consecutive)");
        off += sz;
    }
    if (h.file_size != off)
        return st.fail(SvoError::corrupt, "svo_load: file_size (byte 80) is " + num(h.file_size) + ", the header's sections end at " +
                                              num(off));
    if (size < h.file_size)
        return st.fail(SvoError::truncated, "svo_load: truncated: the file has " + num(size) + " bytes, its header announces " +
                                                num(h.file_size));
    if (size > h.file_size)
        return st.fail(SvoError::corrupt, "svo_load: " + num(size - h.file_size) + " unexpected bytes after the end (byte " +
                                              num(h.file_size) + ") the header announces");
    if (h.file_size > static_cast<uint64_t>(SIZE_MAX))
        return st.fail(SvoError::too_large, "svo_load: the file's " + num(h.file_size) + " bytes exceed this platform's size_t");
    return true;
}

// Payload sources for decode_payload: next(n) returns n (<= kChunk) more bytes, or null on a read
// error. The memory source relies on parse_header having matched the byte size.
struct MemorySource {
    const uint8_t* p;
    const uint8_t* next(size_t n)
    {
        const uint8_t* r = p;
        p += n;
        return r;
    }
};

struct FileSource {
    std::FILE* f;
    std::vector<uint8_t> buf = std::vector<uint8_t>(kChunk);
    uint32_t crc = 0;
    const uint8_t* next(size_t n)
    {
        if (std::fread(buf.data(), 1, n, f) != n) return nullptr;
        crc = svo_crc32(buf.data(), n, crc);
        return buf.data();
    }
};

template <class Source>
bool read_u32s(Source& src, std::vector<uint32_t>& v, uint64_t count)
{
    v.resize(size_t(count));
    const size_t per = kChunk / 4;
    const bool le = host_little_endian();
    for (size_t i = 0; i < v.size(); i += per) {
        const size_t m = v.size() - i < per ? v.size() - i : per;
        const uint8_t* p = src.next(4 * m);
        if (!p) return false;
        if (le)
            std::memcpy(v.data() + i, p, 4 * m);
        else
            for (size_t k = 0; k < m; ++k) v[i + k] = get_u32(p + 4 * k);
    }
    return true;
}

// Reads the payload that `h` describes into `t` (sizes already checked against the byte size).
template <class Source>
bool decode_payload(const Header& h, Source& src, SvoTree& t)
{
    t.depth = h.depth;
    t.brick_levels = h.brick_levels;
    t.root_min = glm::vec3(h.root_min[0], h.root_min[1], h.root_min[2]);
    t.root_size = h.root_size;
    t.attributes = h.attributes;
    t.pointer_bits = h.pointer_bits;
    t.desc_words = h.desc_words;
    t.far_slots = h.far_slots;
    t.brick_count = h.brick_count;
    t.voxel_count = h.voxel_count;
    t.attr_count = h.attr_count;
    t.level_nodes.assign(h.level_nodes, h.level_nodes + h.depth + 1);
    const uint64_t a = h.attr_count;
    if (!read_u32s(src, t.words, uint64_t(h.desc_words) + 2u * uint64_t(h.brick_count))) return false;
    if (!read_u32s(src, t.brick_base, h.brick_count)) return false;
    if (!read_u32s(src, t.color, (h.attributes & RK_SVO_ATTR_COLOR) ? a : 0u)) return false;
    if (!read_u32s(src, t.normal, (h.attributes & RK_SVO_ATTR_NORMAL) ? a : 0u)) return false;
    if (!read_u32s(src, t.material, (h.attributes & RK_SVO_ATTR_MATERIAL) ? a : 0u)) return false;
    t.materials.resize(h.material_count);
    for (SvoMaterial& m : t.materials) {
        const uint8_t* p = src.next(size_t(kMaterialBytes));
        if (!p) return false;
        float f[9];
        for (int k = 0; k < 9; ++k) f[k] = bits_float(get_u32(p + 4 * size_t(k)));
        m.base_color = glm::vec4(f[0], f[1], f[2], f[3]);
        m.reflectance = f[4];
        m.ior = f[5];
        m.absorption = glm::vec3(f[6], f[7], f[8]);
    }
    return true;
}

// 64-bit file positioning (long is 32 bits on Windows).
inline int seek(std::FILE* f, int64_t off, int whence)
{
#if defined(_WIN32)
    return _fseeki64(f, off, whence);
#else
    return fseeko(f, static_cast<off_t>(off), whence);
#endif
}
inline int64_t tell(std::FILE* f)
{
#if defined(_WIN32)
    return _ftelli64(f);
#else
    return static_cast<int64_t>(ftello(f));
#endif
}

}  // namespace detail::svo_file

/// svo_validate: checks that `t` is a well-formed packed octree (docs/svo-format.md), so that
/// svo_for_each_voxel, rk_svo_lookup (any cell, any level) and a shader walking t.gpu_words() stay
/// inside t.words / t.brick_base / the attribute streams and terminate. Checked: depth 1..20,
/// brick_levels, pointer_bits 4..23, attribute bits, root_min / root_size finite (size > 0);
/// every vector's length; a breadth-first walk in which each descriptor's (near or far) pointer
/// lands on the next child group in breadth-first order, descriptor pointer fields are in
/// 1..2^pointer_bits - 1 and far-slot offsets > 0, each far slot lies in the slots right after its
/// descriptor's sibling group and is used exactly once, and the groups and far slots tile
/// [0, desc_words) and the bricks [desc_words, desc_words + brick_count); non-zero child and brick
/// masks (only the root of an empty tree may be empty; 2^3 bricks set bits 0..7 only); far_slots,
/// level_nodes (level_nodes[0] = 1, also for an empty tree), voxel_count, brick_base (running sum
/// from desc_words + brick_count of sub-nodes + voxels, or of voxels only with the shared-sub flag
/// in its top bit when RK_SVO_ATTR_SHARED_SUB is set) and attr_count equal what the walk counts;
/// material words < material count; materials (only with RK_SVO_ATTR_MATERIAL, 1..65536) finite
/// with ior > 0. Limits (too_large): desc_words + 3 * brick_count <= 2^32 (t.gpu_words() indices
/// fit 32 bits), attr_count <= 2^32 and brick attribute indices <= 2^31 (brick_base's top bit is
/// the shared-sub flag). Other failures: SvoError::corrupt, with a message naming the
/// field and the ordinal / word / level. Cost: O(words + attributes) time, at most desc_words
/// bytes of scratch (one per child group).
inline bool svo_validate(const SvoTree& t, SvoStatus& st)
{
    using namespace detail::svo_file;
    st = SvoStatus{};
    auto bad = [&](const std::string& m) { return st.fail(SvoError::corrupt, "svo_validate: " + m); };
    const uint32_t depth = t.depth;
    if (depth < 1 || depth > RK_SVO_MAX_DEPTH) return bad("depth is " + num(depth) + ", outside 1.." + num(RK_SVO_MAX_DEPTH));
    const uint32_t b = rk_svo_brick_levels(depth), top = depth - b;
    if (t.brick_levels != b)
        return bad("brick_levels is " + num(t.brick_levels) + ", depth " + num(depth) + " needs " + num(b));
    if (t.pointer_bits < 4 || t.pointer_bits > 23) return bad("pointer_bits is " + num(t.pointer_bits) + ", outside 4..23");
    if (t.attributes & ~uint32_t(RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL | RK_SVO_ATTR_SHARED_SUB))
        return bad("attributes is " + hex(t.attributes) + ", only bits 0..3 are defined");
    const bool shared = (t.attributes & RK_SVO_ATTR_SHARED_SUB) != 0;
    if (shared && b != 2u) return bad("RK_SVO_ATTR_SHARED_SUB is set but depth " + num(depth) + " has no sub-node level in its bricks");
    if (!std::isfinite(t.root_size) || !(t.root_size > 0.0f))
        return bad("root_size is " + std::to_string(t.root_size) + ", must be finite and > 0");
    for (int k = 0; k < 3; ++k)
        if (!std::isfinite(t.root_min[k]) || !std::isfinite(t.root_min[k] + t.root_size))
            return bad("root_min[" + num(uint64_t(k)) + "] is " + std::to_string(t.root_min[k]) +
                       ", the root cube must be finite");
    if (t.level_nodes.size() != uint64_t(depth) + 1u)
        return bad("level_nodes has " + num(t.level_nodes.size()) + " entries, depth " + num(depth) + " needs " + num(depth + 1u));
    const uint64_t D = t.desc_words, bc = t.brick_count;
    if (D + 3u * bc > k2p32)
        return st.fail(SvoError::too_large, "svo_validate: desc_words " + num(D) + " + 3 * brick_count " + num(bc) +
                                                " exceeds 2^32 (word indices of gpu_words() are 32-bit)");
    if (t.words.size() != D + 2u * bc)
        return bad("words has " + num(t.words.size()) + " entries, desc_words + 2 * brick_count = " + num(D + 2u * bc));
    if (t.brick_base.size() != bc)
        return bad("brick_base has " + num(t.brick_base.size()) + " entries, brick_count is " + num(bc));
    if (t.attr_count > k2p32)
        return st.fail(SvoError::too_large, "svo_validate: attr_count " + num(t.attr_count) + " exceeds 2^32");
    const std::vector<uint32_t>* streams[3] = {&t.color, &t.normal, &t.material};
    const char* names[3] = {"color", "normal", "material"};
    for (uint32_t s = 0; s < 3; ++s) {
        const bool present = (t.attributes >> s) & 1u;
        if (streams[s]->size() != (present ? t.attr_count : 0u))
            return bad(std::string(names[s]) + " stream has " + num(streams[s]->size()) + " entries, expected " +
                       num(present ? t.attr_count : 0u) + (present ? " (attr_count)" : " (attribute bit not set)"));
    }
    const bool has_mat = (t.attributes & RK_SVO_ATTR_MATERIAL) != 0;
    if (has_mat && (t.materials.empty() || t.materials.size() > kMaxMaterials))
        return bad("materials has " + num(t.materials.size()) + " entries, RK_SVO_ATTR_MATERIAL needs 1..65536");
    if (!has_mat && !t.materials.empty())
        return bad("materials has " + num(t.materials.size()) + " entries without RK_SVO_ATTR_MATERIAL");

    const uint32_t* w = t.words.data();
    std::vector<uint64_t> found(size_t(depth) + 1u, 0u);
    uint64_t far_used = 0;
    bool empty = false;
    const uint32_t near_lim = 1u << t.pointer_bits;
    if (top == 0) {
        if (D != 0 || t.far_slots != 0 || bc != 1)
            return bad("depth " + num(depth) + " has a brick root: desc_words (" + num(D) + ") and far_slots (" + num(t.far_slots) +
                       ") must be 0, brick_count (" + num(bc) + ") 1");
    } else if (D == 0) {
        return bad("desc_words is 0, depth " + num(depth) + " needs a root descriptor");
    } else if (rk_svo_child_mask(w[0]) == 0) {
        if (w[0] != 0 || D != 1 || bc != 0)
            return bad("the root descriptor (word 0 = " + hex(w[0]) + ") has an empty child mask: an empty tree's root must be 0 with "
                       "desc_words 1 (is " + num(D) + ") and brick_count 0 (is " + num(bc) + ")");
        empty = true;
    } else {
        // Child groups in breadth-first order, one byte each: member count - 1 (bits 0..2), far
        // slots (bits 3..6). A group's members are consecutive, its far slots follow them, and the
        // next group starts right after: group starts are the running sum, so not stored.
        std::vector<uint8_t> groups;
        groups.reserve(size_t(D / 4u + 1u));
        const uint32_t fs0 = rk_svo_is_far(w[0]) ? 1u : 0u;
        if (1u + fs0 > D) return bad("the root descriptor is far but desc_words is 1: no room for its far slot");
        groups.push_back(uint8_t(fs0 << 3));
        uint64_t cursor = 1u + fs0;  // first descriptor-region ordinal after the groups placed so far
        uint64_t brick_cursor = D;   // next brick ordinal
        uint64_t start = 0;          // first ordinal of the group being checked
        size_t level_end = 1;        // groups[0, level_end) are of level <= `level`
        uint32_t level = 0;
        for (size_t gi = 0; gi < groups.size(); ++gi) {
            if (gi == level_end) {
                ++level;
                level_end = groups.size();
            }
            const uint32_t n = (groups[gi] & 7u) + 1u, fs = groups[gi] >> 3;
            found[level] += n;
            const uint64_t slot0 = start + n;
            uint32_t used = 0;
            for (uint32_t k = 0; k < n; ++k) {
                const uint64_t o = start + k;
                const uint32_t d = w[o], mask = rk_svo_child_mask(d), ptr = rk_svo_rel_ptr(d);
                auto where = [&] { return "descriptor at ordinal " + num(o) + " (level " + num(level) + ", word " + hex(d) + ")"; };
                if (mask == 0) return bad(where() + " has an empty child mask");
                if (ptr == 0) return bad(where() + " has a zero pointer");
                if (ptr >= near_lim) return bad(where() + ": pointer " + num(ptr) + " exceeds pointer_bits " + num(t.pointer_bits));
                uint64_t off = ptr;
                if (rk_svo_is_far(d)) {
                    const uint64_t slot = o + ptr;
                    if (slot < slot0 || slot >= slot0 + fs)
                        return bad(where() + ": far slot at ordinal " + num(slot) + ", outside its sibling group's far slots [" +
                                   num(slot0) + ", " + num(slot0 + fs) + ")");
                    const uint32_t bit = 1u << (slot - slot0);
                    if (used & bit) return bad(where() + ": far slot at ordinal " + num(slot) + " is used twice");
                    used |= bit;
                    ++far_used;
                    off = w[slot];
                    if (off == 0) return bad(where() + ": far slot at ordinal " + num(slot) + " holds offset 0");
                }
                const uint64_t first = o + off;
                const uint32_t nc = popcount32(mask);
                if (level + 1u < top) {
                    if (first != cursor)
                        return bad(where() + ": children at ordinal " + num(first) + ", the next child group in breadth-first order "
                                   "starts at " + num(cursor));
                    if (cursor + nc > D)
                        return bad(where() + ": child group [" + num(cursor) + ", " + num(cursor + nc) +
                                   ") runs past the descriptor region (desc_words " + num(D) + ")");
                    uint32_t nfs = 0;
                    for (uint32_t c = 0; c < nc; ++c) nfs += rk_svo_is_far(w[cursor + c]) ? 1u : 0u;
                    if (cursor + nc + nfs > D)
                        return bad(where() + ": the far slots of child group [" + num(cursor) + ", " + num(cursor + nc) +
                                   ") run past the descriptor region (desc_words " + num(D) + ")");
                    groups.push_back(uint8_t((nc - 1u) | (nfs << 3)));
                    cursor += nc + nfs;
                } else {
                    if (first != brick_cursor)
                        return bad(where() + ": child bricks at ordinal " + num(first) + ", the next brick in breadth-first order is " +
                                   num(brick_cursor));
                    if (brick_cursor + nc > D + bc)
                        return bad(where() + ": child bricks [" + num(first) + ", " + num(first + nc) + ") run past brick_count " + num(bc));
                    brick_cursor += nc;
                }
            }
            start = slot0 + fs;
        }
        if (cursor != D)
            return bad("descriptors and far slots fill ordinals [0, " + num(cursor) + ") but desc_words is " + num(D));
        if (brick_cursor != D + bc)
            return bad("descriptors reach " + num(brick_cursor - D) + " bricks but brick_count is " + num(bc));
    }
    if (far_used != t.far_slots) return bad("far_slots is " + num(t.far_slots) + ", the descriptors use " + num(far_used));
    // Bricks: masks, brick_base running sum, sub-node and voxel counts.
    uint64_t run = D + bc;
    for (uint64_t j = 0; j < bc; ++j) {
        const uint32_t lo = w[D + 2u * j], hi = w[D + 2u * j + 1u];
        auto where = [&] { return "brick " + num(j) + " (ordinal " + num(D + j) + ", word " + num(D + 2u * j) + ")"; };
        if ((lo | hi) == 0) {
            if (top != 0) return bad(where() + " has an empty mask");
            empty = true;
        }
        if (b == 1u && (hi != 0 || lo > 0xFFu))
            return bad(where() + ": mask " + hex((uint64_t(hi) << 32) | lo) + " sets bits above 7 in a 2^3 brick (depth 1)");
        const uint32_t subs = b == 2u ? popcount32(rk_svo_brick_submask(uvec2(lo, hi))) : 0u;
        const uint32_t vox = popcount32(lo) + popcount32(hi);
        // Shared sub-node attributes: every entry carries the flag, runs over voxels only, < 2^31.
        const uint64_t want = run | (shared ? uint64_t(RK_SVO_BRICK_SHARED_SUB) : 0u);
        if (t.brick_base[j] != want)
            return bad("brick_base[" + num(j) + "] is " + hex(t.brick_base[j]) + ", expected " + hex(want) +
                       (shared ? " (the shared-sub flag | desc_words + brick_count + the voxels of the bricks before)"
                               : " (desc_words + brick_count + the sub-nodes and voxels of the bricks before)"));
        run += (shared ? 0u : subs) + vox;
        // brick_base's top bit is the shared-sub flag: indices stay below 2^31 in every tree.
        if (run > (k2p32 >> 1))
            return st.fail(SvoError::too_large, "svo_validate: attribute indices exceed 2^31 at brick " + num(j));
        if (b == 2u) found[top + 1u] += subs;
        found[depth] += vox;
    }
    found[top] = empty ? 0u : bc;
    found[0] = 1;  // the root, also when it is empty
    for (uint32_t l = 0; l <= depth; ++l)
        if (t.level_nodes[l] != found[l])
            return bad("level_nodes[" + num(l) + "] is " + num(t.level_nodes[l]) + ", the tree has " + num(found[l]) +
                       " occupied nodes at level " + num(l));
    if (t.voxel_count != found[depth]) return bad("voxel_count is " + num(t.voxel_count) + ", the bricks hold " + num(found[depth]));
    if (t.attr_count != run) return bad("attr_count is " + num(t.attr_count) + ", the tree indexes " + num(run) + " attributes");
    for (size_t i = 0; i < t.material.size(); ++i)
        if (t.material[i] >= t.materials.size())
            return bad("material[" + num(i) + "] is " + hex(t.material[i]) + ", the table has " + num(t.materials.size()) +
                       " materials (the word must be a material index, bits 16..31 zero)");
    for (size_t i = 0; i < t.materials.size(); ++i) {
        float f[9];
        material_floats(t.materials[i], f);
        for (int k = 0; k < 9; ++k)
            if (!std::isfinite(f[k])) return bad("materials[" + num(i) + "] value " + num(uint64_t(k)) + " is not finite");
        if (!(t.materials[i].ior > 0.0f)) return bad("materials[" + num(i) + "].ior is " + std::to_string(t.materials[i].ior) + ", must be > 0");
    }
    return true;
}

/// svo_save: validates `t` (svo_validate's errors) and writes the file into `bytes` (replaced):
/// header_size_for(depth) = 200 + 8 * depth header bytes, then the payload. Deterministic: equal
/// trees give equal bytes. Cost: O(size), one pass.
inline bool svo_save(const SvoTree& t, std::vector<uint8_t>& bytes, SvoStatus& st)
{
    using namespace detail::svo_file;
    if (!svo_validate(t, st)) return st.fail(st.code, "svo_save: " + st.message);
    uint64_t sz[kSections];
    section_sizes(t.words.size(), t.brick_base.size(), t.attributes, t.attr_count, t.materials.size(), sz);
    uint64_t total = header_size_for(t.depth);
    for (uint64_t s : sz) total += s;
    if (total > static_cast<uint64_t>(SIZE_MAX))
        return st.fail(SvoError::too_large, "svo_save: the file's " + num(total) + " bytes exceed this platform's size_t");
    bytes.clear();
    bytes.reserve(size_t(total));
    bytes.resize(size_t(header_size_for(t.depth)));
    uint32_t crc = 0;
    auto sink = [&](const uint8_t* p, size_t n) {
        crc = svo_crc32(p, n, crc);
        bytes.insert(bytes.end(), p, p + n);
    };
    emit_payload(t, sink);
    const std::vector<uint8_t> h = make_header(t, crc);
    std::memcpy(bytes.data(), h.data(), h.size());
    return true;
}

/// svo_save_file: svo_save into a file (created or truncated), streamed in 64 KiB chunks (no copy
/// of the tree in memory). Errors: svo_validate's; io when the file cannot be opened or written (a
/// partly written file is removed). Cost: O(size).
inline bool svo_save_file(const SvoTree& t, const std::string& path, SvoStatus& st)
{
    using namespace detail::svo_file;
    if (!svo_validate(t, st)) return st.fail(st.code, "svo_save_file: " + st.message);
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return st.fail(SvoError::io, "svo_save_file: cannot open '" + path + "' for writing");
    const std::vector<uint8_t> placeholder(size_t(header_size_for(t.depth)), 0);
    bool ok = std::fwrite(placeholder.data(), 1, placeholder.size(), f) == placeholder.size();
    uint32_t crc = 0;
    auto sink = [&](const uint8_t* p, size_t n) {
        crc = svo_crc32(p, n, crc);
        ok = ok && std::fwrite(p, 1, n, f) == n;
    };
    emit_payload(t, sink);
    if (ok) {
        const std::vector<uint8_t> h = make_header(t, crc);
        ok = seek(f, 0, SEEK_SET) == 0 && std::fwrite(h.data(), 1, h.size(), f) == h.size();
    }
    ok = (std::fclose(f) == 0) && ok;
    if (!ok) {
        std::remove(path.c_str());
        return st.fail(SvoError::io, "svo_save_file: writing '" + path + "' failed (disk full or I/O error); file removed");
    }
    return true;
}

/// svo_load: reads a file image of `size` bytes into `out` (replaced only on success). Checks, in
/// order: the magic (bad_magic; a text-mode line-ending conversion is named), the version
/// (unsupported_version), header_size and the header CRC-32 (truncated, corrupt,
/// checksum_mismatch), every count against the format's limits (too_large) and every section size
/// and offset against the counts and `size` (corrupt; truncated when the bytes end early), the
/// payload CRC-32 (checksum_mismatch) - all before allocating anything - then decodes and runs
/// svo_validate (corrupt, too_large). Memory: at most the tree's size, which is bounded by `size`
/// (a corrupt count cannot make it allocate more). Never reads outside [data, data + size).
/// Cost: O(size).
inline bool svo_load(const uint8_t* data, size_t size, SvoTree& out, SvoStatus& st)
{
    using namespace detail::svo_file;
    st = SvoStatus{};
    if (!data && size != 0) return st.fail(SvoError::invalid_argument, "svo_load: data is null");
    static const uint8_t kNone = 0;
    Header h;
    if (!parse_header(size ? data : &kNone, size, size, h, st)) return false;
    const uint32_t crc = svo_crc32(data + h.header_size, size - h.header_size);
    if (crc != h.payload_crc)
        return st.fail(SvoError::checksum_mismatch, "svo_load: payload checksum mismatch: CRC-32 of bytes " + num(h.header_size) + ".." +
                                                        num(size - 1) + " is " + hex(crc) + ", the header stores " + hex(h.payload_crc) +
                                                        " (byte " + num(h.header_size - 8) + ")");
    SvoTree t;
    MemorySource src{data + h.header_size};
    decode_payload(h, src, t);
    if (!svo_validate(t, st)) return st.fail(st.code, "svo_load: " + st.message);
    out = std::move(t);
    return true;
}

/// svo_load_file: svo_load from a file, streamed: the header is checked against the file's size
/// before the payload is read (in 64 KiB chunks, CRC computed on the way), so memory stays at the
/// tree's size. Errors: svo_load's, and io when the file cannot be opened, sized or read.
inline bool svo_load_file(const std::string& path, SvoTree& out, SvoStatus& st)
{
    using namespace detail::svo_file;
    st = SvoStatus{};
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return st.fail(SvoError::io, "svo_load_file: cannot open '" + path + "'");
    struct Closer {
        std::FILE* f;
        ~Closer() { std::fclose(f); }
    } closer{f};
    int64_t size = -1;
    if (seek(f, 0, SEEK_END) == 0) size = tell(f);
    if (size < 0 || seek(f, 0, SEEK_SET) != 0) return st.fail(SvoError::io, "svo_load_file: cannot determine the size of '" + path + "'");
    uint8_t head[kMaxHeader];
    const size_t want = uint64_t(size) < kMaxHeader ? size_t(size) : size_t(kMaxHeader);
    if (std::fread(head, 1, want, f) != want) return st.fail(SvoError::io, "svo_load_file: cannot read '" + path + "'");
    Header h;
    if (!parse_header(head, want, uint64_t(size), h, st)) return st.fail(st.code, st.message + " ('" + path + "')");
    if (seek(f, int64_t(h.header_size), SEEK_SET) != 0) return st.fail(SvoError::io, "svo_load_file: cannot seek in '" + path + "'");
    SvoTree t;
    FileSource src{f};
    if (!decode_payload(h, src, t))
        return st.fail(SvoError::io, "svo_load_file: reading '" + path + "' failed (I/O error, or the file shrank while read)");
    if (src.crc != h.payload_crc)
        return st.fail(SvoError::checksum_mismatch, "svo_load: payload checksum mismatch: CRC-32 of bytes " + num(h.header_size) + ".." +
                                                        num(h.file_size - 1) + " is " + hex(src.crc) + ", the header stores " +
                                                        hex(h.payload_crc) + " (byte " + num(h.header_size - 8) + ") ('" + path + "')");
    if (!svo_validate(t, st)) return st.fail(st.code, "svo_load: " + st.message + " ('" + path + "')");
    out = std::move(t);
    return true;
}

}  // namespace raykit
