// Tests of raykit/svo_file.hpp: the octree file and its validating loader.
// - Round trips save -> load of trees from an independent test packer (tests/svo_test_pack.hpp)
//   and, when raykit/svo_build.hpp is there, from build_svo on a sphere: every field and stream
//   identical, identical svo_for_each_voxel output, identical bytes when saved again.
// - The byte layout against an independent writer/reader of docs/svo-format.md's table (field
//   offsets written out here, CRC-32 computed bit by bit).
// - Corrupt files: every truncation, bad magic, versions, every header field at 0 / max / +-1,
//   every single-bit flip, structural corruptions with the CRCs recomputed so that they reach
//   svo_validate, counts whose 32/64-bit products wrap. The exact SvoError of each.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "raykit/svo_file.hpp"
#include "svo_test_pack.hpp"

#if __has_include("raykit/svo_build.hpp") && !defined(RAYKIT_TEST_NO_SVO_BUILD)
#include "raykit/svo_build.hpp"
#define RAYKIT_TEST_HAVE_SVO_BUILD 1
#endif

using namespace raykit;
using svotest::pack_cells;
using svotest::PackOptions;
using svotest::random_cells;

namespace {

using Bytes = std::vector<uint8_t>;

// ---- Independent little-endian helpers, CRC and file writer (docs/svo-format.md) ----

uint32_t crc32_bitwise(const uint8_t* p, size_t n)
{
    uint32_t c = 0xFFFFFFFFu;
    for (size_t i = 0; i < n; ++i) {
        c ^= p[i];
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return ~c;
}

uint32_t rd32(const Bytes& b, size_t o) { return uint32_t(b[o]) | uint32_t(b[o + 1]) << 8 | uint32_t(b[o + 2]) << 16 | uint32_t(b[o + 3]) << 24; }
uint64_t rd64(const Bytes& b, size_t o) { return uint64_t(rd32(b, o)) | uint64_t(rd32(b, o + 4)) << 32; }
void wr32(Bytes& b, size_t o, uint32_t v)
{
    for (int k = 0; k < 4; ++k) b[o + size_t(k)] = uint8_t(v >> (8 * k));
}
void wr64(Bytes& b, size_t o, uint64_t v)
{
    wr32(b, o, uint32_t(v));
    wr32(b, o + 4, uint32_t(v >> 32));
}
uint32_t fbits(float f)
{
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u;
}

// Field offsets of the documented header.
enum : size_t {
    kVersion = 8, kHeaderSize = 12, kDepth = 16, kBrickLevels = 20, kAttributes = 24, kPointerBits = 28, kRootMin = 32,
    kRootSize = 44, kDescWords = 48, kFarSlots = 52, kBrickCount = 56, kMaterialCount = 60, kVoxelCount = 64,
    kAttrCount = 72, kFileSize = 80, kSections = 88, kLevelNodes = 184
};
size_t header_bytes(uint32_t depth) { return 184 + 8 * (size_t(depth) + 1) + 8; }

/// Recomputes both CRCs of a file image whose header_size field is usable (else leaves it alone).
void fix_crcs(Bytes& f)
{
    if (f.size() < 16) return;
    const uint32_t hs = rd32(f, kHeaderSize);
    if (hs < 16 || hs > f.size()) return;
    wr32(f, hs - 8, crc32_bitwise(f.data() + hs, f.size() - hs));
    wr32(f, hs - 4, crc32_bitwise(f.data(), hs - 4));
}

/// Writes ANY tree (valid or not) the way the documentation lays a file out: counts from the
/// tree's fields, section sizes from its vectors' actual lengths.
Bytes raw_file(const SvoTree& t)
{
    const size_t hs = header_bytes(t.depth);
    Bytes f(hs, 0);
    const uint8_t magic[8] = {'R', 'K', 'S', 'V', 'O', 0x0D, 0x0A, 0x1A};
    std::memcpy(f.data(), magic, 8);
    wr32(f, kVersion, 1);
    wr32(f, kHeaderSize, uint32_t(hs));
    wr32(f, kDepth, t.depth);
    wr32(f, kBrickLevels, t.brick_levels);
    wr32(f, kAttributes, t.attributes);
    wr32(f, kPointerBits, t.pointer_bits);
    wr32(f, kRootMin, fbits(t.root_min.x));
    wr32(f, kRootMin + 4, fbits(t.root_min.y));
    wr32(f, kRootMin + 8, fbits(t.root_min.z));
    wr32(f, kRootSize, fbits(t.root_size));
    wr32(f, kDescWords, t.desc_words);
    wr32(f, kFarSlots, t.far_slots);
    wr32(f, kBrickCount, t.brick_count);
    wr32(f, kMaterialCount, uint32_t(t.materials.size()));
    wr64(f, kVoxelCount, t.voxel_count);
    wr64(f, kAttrCount, t.attr_count);
    for (size_t l = 0; l < t.level_nodes.size() && l <= t.depth; ++l) wr64(f, kLevelNodes + 8 * l, t.level_nodes[l]);
    const std::vector<uint32_t>* u32s[5] = {&t.words, &t.brick_base, &t.color, &t.normal, &t.material};
    for (int s = 0; s < 6; ++s) {
        const size_t start = f.size();
        if (s < 5) {
            for (uint32_t w : *u32s[s]) {
                f.resize(f.size() + 4);
                wr32(f, f.size() - 4, w);
            }
        } else {
            for (const SvoMaterial& m : t.materials) {
                const float v[9] = {m.base_color.x, m.base_color.y, m.base_color.z, m.base_color.w, m.reflectance,
                                    m.ior,          m.absorption.x, m.absorption.y, m.absorption.z};
                for (float x : v) {
                    f.resize(f.size() + 4);
                    wr32(f, f.size() - 4, fbits(x));
                }
            }
        }
        wr64(f, kSections + 16 * size_t(s), start);
        wr64(f, kSections + 16 * size_t(s) + 8, f.size() - start);
    }
    wr64(f, kFileSize, f.size());
    fix_crcs(f);
    return f;
}

// ---- Comparisons ----

void expect_same_tree(const SvoTree& a, const SvoTree& b)
{
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.brick_levels, b.brick_levels);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(fbits(a.root_min[k]), fbits(b.root_min[k])) << k;
    EXPECT_EQ(fbits(a.root_size), fbits(b.root_size));
    EXPECT_EQ(a.attributes, b.attributes);
    EXPECT_EQ(a.pointer_bits, b.pointer_bits);
    EXPECT_EQ(a.desc_words, b.desc_words);
    EXPECT_EQ(a.far_slots, b.far_slots);
    EXPECT_EQ(a.brick_count, b.brick_count);
    EXPECT_EQ(a.voxel_count, b.voxel_count);
    EXPECT_EQ(a.level_nodes, b.level_nodes);
    EXPECT_EQ(a.words, b.words);
    EXPECT_EQ(a.brick_base, b.brick_base);
    EXPECT_EQ(a.attr_count, b.attr_count);
    EXPECT_EQ(a.color, b.color);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(a.material, b.material);
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        const SvoMaterial &x = a.materials[i], &y = b.materials[i];
        const float u[9] = {x.base_color.x, x.base_color.y, x.base_color.z, x.base_color.w, x.reflectance, x.ior, x.absorption.x, x.absorption.y, x.absorption.z};
        const float v[9] = {y.base_color.x, y.base_color.y, y.base_color.z, y.base_color.w, y.reflectance, y.ior, y.absorption.x, y.absorption.y, y.absorption.z};
        for (int k = 0; k < 9; ++k) EXPECT_EQ(fbits(u[k]), fbits(v[k])) << "material " << i << " value " << k;
    }
}

using Voxels = std::vector<std::tuple<uint32_t, uint32_t, uint32_t, uint64_t>>;
Voxels voxels_of(const SvoTree& t)
{
    Voxels v;
    svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t a) { v.emplace_back(c.x, c.y, c.z, a); });
    return v;
}

Bytes save_ok(const SvoTree& t)
{
    Bytes b;
    SvoStatus st;
    EXPECT_TRUE(svo_save(t, b, st)) << st.message;
    return b;
}

/// Loads `f`; on failure checks the message is non-empty and `out` untouched.
SvoError load_code(const Bytes& f, SvoTree* loaded = nullptr, std::string* msg = nullptr)
{
    SvoTree out;
    out.depth = 77;  // sentinel: must survive a failed load
    SvoStatus st;
    const bool ok = svo_load(f.data(), f.size(), out, st);
    EXPECT_EQ(ok, st.ok());
    if (!ok) {
        EXPECT_FALSE(st.message.empty());
        EXPECT_EQ(out.depth, 77u) << "a failed load modified its output";
    }
    if (msg) *msg = st.message;
    if (loaded) *loaded = out;
    return st.code;
}


#define EXPECT_CODE(expected, actual, what) \
    EXPECT_EQ(svo_error_name(expected), std::string(svo_error_name(actual))) << what

/// A round trip in memory and through a file, plus the checks every loaded tree must pass.
void check_round_trip(const SvoTree& t, const std::string& what)
{
    SCOPED_TRACE(what);
    SvoStatus st;
    ASSERT_TRUE(svo_validate(t, st)) << st.message;
    Bytes b;
    ASSERT_TRUE(svo_save(t, b, st)) << st.message;
    EXPECT_EQ(b, raw_file(t)) << "svo_save differs from the documented layout";
    SvoTree u;
    ASSERT_TRUE(svo_load(b.data(), b.size(), u, st)) << st.message;
    EXPECT_TRUE(st.ok());
    expect_same_tree(t, u);
    EXPECT_EQ(voxels_of(t), voxels_of(u));
    Bytes b2;
    ASSERT_TRUE(svo_save(u, b2, st));
    EXPECT_EQ(b, b2);
}

std::string tmp_path(const std::string& name)
{
    return ::testing::TempDir() + "raykit_svo_file_" + name + "_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed());
}

// A depth-4 tree with far slots (pointer_bits 4), every attribute stream and 3 materials.
SvoTree rich_tree()
{
    PackOptions o;
    o.pointer_bits = 4;
    o.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;
    o.materials = 3;
    return pack_cells(4, random_cells(4, 300, 11), o);
}

}  // namespace

// ---- CRC ----

TEST(SvoCrc32, CheckValueAndBitwiseReference)
{
    const char* s = "123456789";
    EXPECT_EQ(svo_crc32(reinterpret_cast<const uint8_t*>(s), 9), 0xCBF43926u);
    EXPECT_EQ(crc32_bitwise(reinterpret_cast<const uint8_t*>(s), 9), 0xCBF43926u);
    EXPECT_EQ(svo_crc32(nullptr, 0), 0u);
    Bytes r(1000);
    for (size_t i = 0; i < r.size(); ++i) r[i] = uint8_t(svotest::test_hash(i));
    for (size_t n : {size_t(1), size_t(3), size_t(64), size_t(999), size_t(1000)}) {
        EXPECT_EQ(svo_crc32(r.data(), n), crc32_bitwise(r.data(), n)) << n;
        // In pieces, continuing from the previous result.
        const size_t h = n / 3;
        EXPECT_EQ(svo_crc32(r.data() + h, n - h, svo_crc32(r.data(), h)), crc32_bitwise(r.data(), n)) << n;
    }
}

// ---- The test packer itself, against the cell sets it was given ----

TEST(SvoTestPacker, UnpacksToItsCellsAndLooksThemUp)
{
    int far_trees = 0;
    for (uint32_t depth = 1; depth <= 6; ++depth)
        for (uint32_t pb : {4u, 23u})
            for (size_t n : {size_t(1), size_t(7), size_t(150)}) {
                const auto cells = random_cells(depth, n, depth * 31 + n);
                PackOptions o;
                o.pointer_bits = pb;
                const SvoTree t = pack_cells(depth, cells, o);
                SvoStatus st;
                ASSERT_TRUE(svo_validate(t, st)) << "depth " << depth << " pb " << pb << " n " << n << ": " << st.message;
                std::set<std::tuple<uint32_t, uint32_t, uint32_t>> want, got;
                for (auto c : cells) want.emplace(c.x, c.y, c.z);
                std::set<uint64_t> attrs;
                svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t a) {
                    got.emplace(c.x, c.y, c.z);
                    attrs.insert(a);
                });
                EXPECT_EQ(got, want);
                EXPECT_EQ(attrs.size(), want.size());  // distinct attribute slots
                EXPECT_EQ(t.voxel_count, want.size());
                far_trees += t.far_slots > 0;
                if (pb == 4 && depth >= 5 && n == 150) {
                    EXPECT_GT(t.far_slots, 0u) << "pointer_bits 4 must force far pointers";
                }
                // rk_svo_lookup on every cell (depth <= 4) or a sample.
                const std::vector<uint32_t> g = t.gpu_words();
                const uint32_t side = 1u << depth, step = depth <= 4 ? 1u : 5u;
                for (uint32_t z = 0; z < side; z += step)
                    for (uint32_t y = 0; y < side; y += step)
                        for (uint32_t x = 0; x < side; x += step) {
                            const rk_svo_hit h = rk_svo_lookup(g.data(), t.desc_words, t.gpu_brick_base_word(), depth, uvec3(x, y, z), depth);
                            ASSERT_EQ(h.found, want.count({x, y, z}) == 1) << x << "," << y << "," << z << " depth " << depth;
                        }
            }
    EXPECT_GE(far_trees, 2);
}

// ---- Layout ----

TEST(SvoFile, LayoutMatchesTheDocumentedTable)
{
    const SvoTree t = rich_tree();
    ASSERT_GT(t.far_slots, 0u);
    const Bytes f = save_ok(t);
    const size_t hs = header_bytes(4);
    ASSERT_EQ(hs, 232u);
    const uint8_t magic[8] = {0x52, 0x4B, 0x53, 0x56, 0x4F, 0x0D, 0x0A, 0x1A};
    EXPECT_EQ(0, std::memcmp(f.data(), magic, 8));
    EXPECT_EQ(rd32(f, kVersion), 1u);
    EXPECT_EQ(rd32(f, kHeaderSize), hs);
    EXPECT_EQ(rd32(f, kDepth), 4u);
    EXPECT_EQ(rd32(f, kBrickLevels), 2u);
    EXPECT_EQ(rd32(f, kAttributes), 7u);
    EXPECT_EQ(rd32(f, kPointerBits), 4u);
    EXPECT_EQ(rd32(f, kRootMin), fbits(-1.0f));
    EXPECT_EQ(rd32(f, kRootMin + 4), fbits(0.5f));
    EXPECT_EQ(rd32(f, kRootMin + 8), fbits(2.0f));
    EXPECT_EQ(rd32(f, kRootSize), fbits(3.0f));
    EXPECT_EQ(rd32(f, kDescWords), t.desc_words);
    EXPECT_EQ(rd32(f, kFarSlots), t.far_slots);
    EXPECT_EQ(rd32(f, kBrickCount), t.brick_count);
    EXPECT_EQ(rd32(f, kMaterialCount), 3u);
    EXPECT_EQ(rd64(f, kVoxelCount), t.voxel_count);
    EXPECT_EQ(rd64(f, kAttrCount), t.attr_count);
    EXPECT_EQ(rd64(f, kFileSize), f.size());
    const uint64_t sizes[6] = {4 * t.words.size(), 4 * uint64_t(t.brick_count), 4 * t.attr_count, 4 * t.attr_count, 4 * t.attr_count, 36 * 3};
    uint64_t off = hs;
    for (int s = 0; s < 6; ++s) {
        EXPECT_EQ(rd64(f, kSections + 16 * size_t(s)), off) << s;
        EXPECT_EQ(rd64(f, kSections + 16 * size_t(s) + 8), sizes[s]) << s;
        off += sizes[s];
    }
    EXPECT_EQ(off, f.size());
    for (size_t l = 0; l <= 4; ++l) EXPECT_EQ(rd64(f, kLevelNodes + 8 * l), t.level_nodes[l]) << l;
    EXPECT_EQ(rd32(f, hs - 8), crc32_bitwise(f.data() + hs, f.size() - hs));
    EXPECT_EQ(rd32(f, hs - 4), crc32_bitwise(f.data(), hs - 4));
    // Payload words in order, little-endian; the material table as 9 floats each.
    for (size_t i = 0; i < t.words.size(); ++i) ASSERT_EQ(rd32(f, hs + 4 * i), t.words[i]) << i;
    const size_t mat = f.size() - 36 * 3;
    EXPECT_EQ(rd32(f, mat + 36 + 4 * 5), fbits(t.materials[1].ior));
    EXPECT_EQ(rd32(f, mat + 36 * 2 + 4 * 8), fbits(t.materials[2].absorption.z));
}

// ---- Round trips ----

TEST(SvoFile, RoundTripPackedTrees)
{
    int n_trees = 0;
    for (uint32_t depth = 1; depth <= 6; ++depth)
        for (uint32_t pb : {4u, 23u})
            for (uint32_t attrs : {0u, 1u, 2u, 4u, 7u})
                for (size_t n : {size_t(0), size_t(1), size_t(9), size_t(400)}) {
                    PackOptions o;
                    o.pointer_bits = pb;
                    o.attributes = attrs;
                    o.materials = 1 + uint32_t(n % 5);
                    const SvoTree t = pack_cells(depth, random_cells(depth, n, depth + n + attrs), o);
                    check_round_trip(t, "depth " + std::to_string(depth) + " pb " + std::to_string(pb) + " attrs " +
                                            std::to_string(attrs) + " voxels " + std::to_string(n));
                    ++n_trees;
                }
    EXPECT_EQ(n_trees, 6 * 2 * 5 * 4);
}

TEST(SvoFile, RoundTripThroughAFile)
{
    const SvoTree t = rich_tree();
    const std::string path = tmp_path("rt");
    SvoStatus st;
    ASSERT_TRUE(svo_save_file(t, path, st)) << st.message;
    SvoTree u;
    ASSERT_TRUE(svo_load_file(path, u, st)) << st.message;
    expect_same_tree(t, u);
    // The file holds exactly svo_save's bytes.
    std::FILE* fp = std::fopen(path.c_str(), "rb");
    ASSERT_NE(fp, nullptr);
    Bytes disk(100000);
    disk.resize(std::fread(disk.data(), 1, disk.size(), fp));
    std::fclose(fp);
    EXPECT_EQ(disk, save_ok(t));
    // A damaged file gives the same verdicts as the same bytes in memory.
    struct Case { size_t cut; size_t flip; SvoError want; };
    for (const Case& c : {Case{disk.size() - 1, 0, SvoError::truncated}, Case{100, 0, SvoError::truncated},
                          Case{disk.size(), disk.size() - 3, SvoError::checksum_mismatch}, Case{disk.size(), 20, SvoError::checksum_mismatch}}) {
        Bytes d(disk.begin(), disk.begin() + long(c.cut));
        if (c.flip) d[c.flip] ^= 0x10;
        fp = std::fopen(path.c_str(), "wb");
        ASSERT_NE(fp, nullptr);
        ASSERT_EQ(std::fwrite(d.data(), 1, d.size(), fp), d.size());
        std::fclose(fp);
        u.depth = 99;
        EXPECT_FALSE(svo_load_file(path, u, st));
        EXPECT_CODE(c.want, st.code, "cut " << c.cut << " flip " << c.flip << ": " << st.message);
        EXPECT_CODE(c.want, load_code(d), "same bytes in memory");
        EXPECT_NE(st.message.find(path), std::string::npos) << st.message;
        EXPECT_EQ(u.depth, 99u);
    }
    std::remove(path.c_str());
    EXPECT_FALSE(svo_load_file(path, u, st));
    EXPECT_EQ(st.code, SvoError::io);
    EXPECT_FALSE(svo_save_file(t, ::testing::TempDir() + "no_such_dir_raykit/x.svo", st));
    EXPECT_EQ(st.code, SvoError::io);
    // An invalid tree is not written.
    SvoTree bad = t;
    bad.words[0] &= ~RK_SVO_CHILD_MASK;
    EXPECT_FALSE(svo_save_file(bad, path, st));
    EXPECT_EQ(st.code, SvoError::corrupt);
    EXPECT_EQ(std::fopen(path.c_str(), "rb"), nullptr);
    Bytes out;
    EXPECT_FALSE(svo_save(bad, out, st));
    EXPECT_EQ(st.code, SvoError::corrupt);
    EXPECT_NE(st.message.find("svo_save"), std::string::npos);
}

#ifdef RAYKIT_TEST_HAVE_SVO_BUILD
namespace {
SvoMeshData sphere_mesh(int rings, int segments)
{
    SvoMeshData m;
    const float pi = 3.14159265f;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const float th = pi * float(r) / float(rings), ph = 2 * pi * float(s) / float(segments);
            const glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
            m.positions.push_back(0.8f * n + glm::vec3(0.1f, -0.2f, 0.3f));
            m.normals.push_back(n);
            m.uvs.emplace_back(float(s) / float(segments), float(r) / float(rings));
        }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = uint32_t(r * (segments + 1) + s), b = a + uint32_t(segments + 1);
            for (uint32_t i : {a, b, a + 1, a + 1, b, b + 1}) m.indices.push_back(i);
            m.material_ids.push_back(uint16_t(s % 2));
            m.material_ids.push_back(uint16_t(r % 2));
        }
    SvoMeshMaterial red, glass;
    red.values.base_color = glm::vec4(0.9f, 0.1f, 0.1f, 1.0f);
    glass.values.reflectance = 0.25f;
    glass.values.ior = 1.33f;
    glass.values.absorption = glm::vec3(0.5f, 0.1f, 0.0f);
    m.materials = {red, glass};
    return m;
}
}  // namespace

TEST(SvoFile, RoundTripBuiltSpheres)
{
    const SvoMeshData mesh = sphere_mesh(12, 24);
    int far_trees = 0;
    for (int depth : {1, 2, 5})
        for (uint32_t pb : {4u, 23u})
            for (uint32_t attrs : {0u, 1u, 2u, 4u, 7u}) {
                SvoBuildOptions o;
                o.depth = depth;
                o.pointer_bits = pb;
                o.attributes = attrs;
                o.threads = 1;
                SvoTree t;
                SvoStatus st;
                ASSERT_TRUE(build_svo(mesh.view(), o, t, st)) << st.message;
                ASSERT_GT(t.voxel_count, 0u);
                far_trees += t.far_slots > 0;
                check_round_trip(t, "sphere depth " + std::to_string(depth) + " pb " + std::to_string(pb) + " attrs " +
                                        std::to_string(attrs));
            }
    EXPECT_GE(far_trees, 5);  // depth 5 with pointer_bits 4 needs far pointers
}
#endif

// ---- Corrupt files ----

TEST(SvoFileCorrupt, EveryTruncationIsTruncated)
{
    PackOptions o;
    o.attributes = 7;
    o.materials = 2;
    o.pointer_bits = 4;
    const Bytes f = save_ok(pack_cells(3, random_cells(3, 40, 5), o));
    ASSERT_GT(f.size(), header_bytes(3));
    for (size_t n = 0; n < f.size(); ++n) {
        const Bytes g(f.begin(), f.begin() + long(n));
        std::string msg;
        EXPECT_CODE(SvoError::truncated, load_code(g, nullptr, &msg), "length " << n << ": " << msg);
    }
    // Only the header: truncated, and the message names both sizes.
    const Bytes h(f.begin(), f.begin() + long(header_bytes(3)));
    std::string msg;
    EXPECT_CODE(SvoError::truncated, load_code(h, nullptr, &msg), msg);
    EXPECT_NE(msg.find(std::to_string(f.size())), std::string::npos) << msg;
    // One byte more than announced: corrupt (trailing bytes).
    Bytes g = f;
    g.push_back(0);
    EXPECT_CODE(SvoError::corrupt, load_code(g, nullptr, &msg), msg);
    SvoTree t;
    SvoStatus st;
    EXPECT_FALSE(svo_load(nullptr, 10, t, st));
    EXPECT_EQ(st.code, SvoError::invalid_argument);
    EXPECT_FALSE(svo_load(nullptr, 0, t, st));
    EXPECT_EQ(st.code, SvoError::truncated);
}

TEST(SvoFileCorrupt, BadMagic)
{
    const Bytes f = save_ok(rich_tree());
    for (size_t i = 0; i < 8; ++i)
        for (uint8_t x : {uint8_t(0x00), uint8_t(0xFF), uint8_t(0x20)}) {
            Bytes g = f;
            if (g[i] == x) continue;
            g[i] = x;
            EXPECT_CODE(SvoError::bad_magic, load_code(g), "byte " << i);
            g.resize(i + 1);  // a short file with a wrong prefix is still bad_magic
            EXPECT_CODE(SvoError::bad_magic, load_code(g), "byte " << i << " short");
        }
    // Text-mode transfers: CR LF -> LF, and LF -> CR LF.
    Bytes a = f;
    a.erase(a.begin() + 5);
    std::string msg;
    EXPECT_CODE(SvoError::bad_magic, load_code(a, nullptr, &msg), msg);
    EXPECT_NE(msg.find("text-mode"), std::string::npos) << msg;
    Bytes b = f;
    b.insert(b.begin() + 6, 0x0D);
    EXPECT_CODE(SvoError::bad_magic, load_code(b, nullptr, &msg), msg);
    EXPECT_NE(msg.find("text-mode"), std::string::npos) << msg;
    const Bytes png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    EXPECT_CODE(SvoError::bad_magic, load_code(png), "png");
}

TEST(SvoFileCorrupt, EveryOtherVersionIsUnsupported)
{
    const Bytes f = save_ok(rich_tree());
    for (uint32_t v : {0u, 2u, 3u, 0x100u, 0x01000000u, 0x80000001u, 0xFFFFFFFFu}) {
        Bytes g = f;
        wr32(g, kVersion, v);
        std::string msg;
        EXPECT_CODE(SvoError::unsupported_version, load_code(g, nullptr, &msg), "version " << v);
        EXPECT_NE(msg.find(std::to_string(v)), std::string::npos) << msg;
        fix_crcs(g);
        EXPECT_CODE(SvoError::unsupported_version, load_code(g), "version " << v << " crc fixed");
    }
}

TEST(SvoFileCorrupt, HeaderSize)
{
    const Bytes f = save_ok(rich_tree());
    const uint32_t hs = rd32(f, kHeaderSize);
    for (uint32_t v : {0u, 16u, 207u, hs - 1, hs + 1, 361u, 368u, 0xFFFFFFFFu}) {
        Bytes g = f;
        wr32(g, kHeaderSize, v);
        EXPECT_CODE(SvoError::corrupt, load_code(g), "header_size " << v);
    }
    // Another well-formed size: its CRC slot is elsewhere -> checksum; CRCs fixed -> depth mismatch.
    for (uint32_t v : {hs - 8, hs + 8, 208u, 360u}) {
        Bytes g = f;
        wr32(g, kHeaderSize, v);
        EXPECT_CODE(SvoError::checksum_mismatch, load_code(g), "header_size " << v);
        fix_crcs(g);
        EXPECT_CODE(SvoError::corrupt, load_code(g), "header_size " << v << " crc fixed");
    }
    // Larger than the whole file.
    Bytes g(f.begin(), f.begin() + 300);
    wr32(g, kHeaderSize, 304);
    EXPECT_CODE(SvoError::truncated, load_code(g), "header_size past the end");
}

TEST(SvoFileCorrupt, EveryHeaderFieldAtZeroMaxAndOffByOne)
{
    const SvoTree t = rich_tree();
    const Bytes f = save_ok(t);
    const size_t hs = header_bytes(4);
    const SvoError C = SvoError::corrupt, L = SvoError::too_large, K = SvoError::checksum_mismatch, O = SvoError::ok;
    struct Field {
        const char* name;
        size_t off;
        int width;
        SvoError zero, max, minus, plus;
    };
    std::vector<Field> fields = {
        {"depth", kDepth, 4, C, C, C, C},
        {"brick_levels", kBrickLevels, 4, C, C, C, C},
        {"attributes", kAttributes, 4, C, C, C, C},
        {"pointer_bits", kPointerBits, 4, C, C, C, O},  // a looser claim (5) still holds
        {"root_min.x", kRootMin, 4, O, C, O, O},        // 0.0 and the neighbouring floats are fine; 0xFFFFFFFF is NaN
        {"root_size", kRootSize, 4, C, C, O, O},
        {"desc_words", kDescWords, 4, C, L, C, C},
        {"far_slots", kFarSlots, 4, C, C, C, C},
        {"brick_count", kBrickCount, 4, C, L, C, C},
        {"material_count", kMaterialCount, 4, C, L, C, C},
        {"voxel_count", kVoxelCount, 8, C, C, C, C},
        {"attr_count", kAttrCount, 8, C, L, C, C},
        {"file_size", kFileSize, 8, C, C, C, C},
        {"payload_crc", hs - 8, 4, K, K, K, K},
    };
    const char* sec[6] = {"words", "brick_base", "color", "normal", "material", "materials"};
    std::vector<std::string> names;
    for (int s = 0; s < 6; ++s) {
        names.push_back(std::string(sec[s]) + ".offset");
        names.push_back(std::string(sec[s]) + ".size");
    }
    for (int s = 0; s < 12; ++s) fields.push_back({names[size_t(s)].c_str(), kSections + 8 * size_t(s), 8, C, C, C, C});
    std::vector<std::string> lnames;
    for (int l = 0; l <= 4; ++l) lnames.push_back("level_nodes[" + std::to_string(l) + "]");
    for (int l = 0; l <= 4; ++l) fields.push_back({lnames[size_t(l)].c_str(), kLevelNodes + 8 * size_t(l), 8, C, C, C, C});
    for (const Field& fd : fields) {
        const uint64_t v = fd.width == 4 ? rd32(f, fd.off) : rd64(f, fd.off);
        const uint64_t mx = fd.width == 4 ? 0xFFFFFFFFull : ~0ull;
        const uint64_t vals[4] = {0, mx, v - 1, v + 1};
        const SvoError want[4] = {fd.zero, fd.max, fd.minus, fd.plus};
        for (int k = 0; k < 4; ++k) {
            if (vals[k] == v) continue;
            Bytes g = f;
            if (fd.width == 4)
                wr32(g, fd.off, uint32_t(vals[k]));
            else
                wr64(g, fd.off, vals[k]);
            // Without the CRC recomputed the header checksum catches it.
            EXPECT_CODE(SvoError::checksum_mismatch, load_code(g), fd.name << " = " << vals[k] << " (CRC stale)");
            if (fd.off == hs - 8)
                wr32(g, hs - 4, crc32_bitwise(g.data(), hs - 4));  // header CRC only: keep the wrong payload CRC
            else
                fix_crcs(g);
            SvoTree u;
            std::string msg;
            EXPECT_CODE(want[k], load_code(g, &u, &msg), fd.name << " = " << vals[k] << ": " << msg);
            if (want[k] == SvoError::ok) {
                SvoTree e = t;
                if (fd.off == kPointerBits) e.pointer_bits = uint32_t(vals[k]);
                const uint32_t bits = uint32_t(vals[k]);
                if (fd.off == kRootMin) std::memcpy(&e.root_min.x, &bits, 4);
                if (fd.off == kRootSize) std::memcpy(&e.root_size, &bits, 4);
                expect_same_tree(e, u);
            }
        }
    }
    // The header CRC itself.
    for (uint32_t v : {0u, 0xFFFFFFFFu, rd32(f, hs - 4) ^ 1u}) {
        Bytes g = f;
        wr32(g, hs - 4, v);
        EXPECT_CODE(K, load_code(g), "header_crc " << v);
    }
    // Special floats in the root cube.
    for (float x : {std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                    std::numeric_limits<float>::quiet_NaN(), -0.0f, -1.0f, std::numeric_limits<float>::max()}) {
        Bytes g = f;
        wr32(g, kRootSize, fbits(x));
        fix_crcs(g);
        // max is finite, but root_min + root_size (-1 + FLT_MAX ... fine) stays finite: accepted.
        const SvoError want = x == std::numeric_limits<float>::max() ? O : C;
        EXPECT_CODE(want, load_code(g), "root_size " << x);
        g = f;
        wr32(g, kRootMin + 8, fbits(x));
        fix_crcs(g);
        // root_min.z = FLT_MAX: FLT_MAX + 3 rounds to FLT_MAX, finite: accepted. -0 and -1: accepted.
        const bool finite = x == x && x != std::numeric_limits<float>::infinity() && x != -std::numeric_limits<float>::infinity();
        EXPECT_CODE(finite ? O : C, load_code(g), "root_min.z " << x);
    }
}

TEST(SvoFileCorrupt, EverySingleBitFlip)
{
    PackOptions o;
    o.attributes = 7;
    o.materials = 2;
    o.pointer_bits = 4;
    const Bytes f = save_ok(pack_cells(3, random_cells(3, 60, 9), o));
    const size_t hs = header_bytes(3);
    const uint32_t size = uint32_t(f.size());
    int counts[16] = {};
    for (size_t i = 0; i < f.size(); ++i)
        for (int bit = 0; bit < 8; ++bit) {
            Bytes g = f;
            g[i] ^= uint8_t(1u << bit);
            const SvoError e = load_code(g);
            ++counts[int(e)];
            SvoError want = SvoError::checksum_mismatch;
            if (i < 8) want = SvoError::bad_magic;
            else if (i < 12) want = SvoError::unsupported_version;
            else if (i < 16) {
                // header_size flipped: malformed -> corrupt; past the end -> truncated; another
                // well-formed size -> its CRC slot holds other bytes -> checksum_mismatch.
                const uint32_t v = rd32(g, kHeaderSize);
                const bool well_formed = v >= 208 && v <= 360 && (v - 208) % 8 == 0;
                want = !well_formed ? SvoError::corrupt : v > size ? SvoError::truncated : SvoError::checksum_mismatch;
            }
            ASSERT_EQ(svo_error_name(want), std::string(svo_error_name(e))) << "byte " << i << " bit " << bit << " (header " << hs << ")";
        }
    EXPECT_EQ(counts[int(SvoError::ok)], 0);
    EXPECT_GT(counts[int(SvoError::checksum_mismatch)], int(8 * (f.size() - 16)) - 1);
}

namespace {
// Structural corruption: mutate a copy of `t`, write it with the documented layout (CRCs right),
// expect `want` from both svo_validate (in memory) and svo_load (the file).
template <class F>
void expect_structural(const SvoTree& t, SvoError want, const std::string& what, F mutate, const char* needle = nullptr)
{
    SvoTree u = t;
    mutate(u);
    SvoStatus st;
    EXPECT_FALSE(svo_validate(u, st)) << what;
    EXPECT_CODE(want, st.code, what << ": " << st.message);
    if (needle) {
        EXPECT_NE(st.message.find(needle), std::string::npos) << what << ": " << st.message;
    }
    std::string msg;
    EXPECT_CODE(want, load_code(raw_file(u), nullptr, &msg), what << " (file): " << msg);
    Bytes b;
    EXPECT_FALSE(svo_save(u, b, st)) << what;
}

// Ordinals of the descriptors of a valid tree, breadth-first (far slots excluded).
std::vector<uint32_t> descriptor_ordinals(const SvoTree& t)
{
    std::vector<uint32_t> out, cur{0u}, next;
    const uint32_t top = t.depth - t.brick_levels;
    for (uint32_t level = 0; level < top; ++level) {
        next.clear();
        for (uint32_t o : cur) {
            out.push_back(o);
            const uint32_t d = t.words[o];
            const uint32_t first = o + (rk_svo_is_far(d) ? t.words[o + rk_svo_rel_ptr(d)] : rk_svo_rel_ptr(d));
            for (uint32_t k = 0; k < uint32_t(__builtin_popcount(rk_svo_child_mask(d))); ++k) next.push_back(first + k);
        }
        cur.swap(next);
    }
    return out;
}

uint32_t find_far_desc(const SvoTree& t, uint32_t from = 0)
{
    for (uint32_t o : descriptor_ordinals(t))
        if (o >= from && rk_svo_is_far(t.words[o])) return o;
    return ~0u;
}
}  // namespace

TEST(SvoFileCorrupt, StructuralCorruptionsReachTheValidator)
{
    const SvoTree t = rich_tree();  // depth 4, pointer_bits 4, far slots
    PackOptions o23;
    o23.attributes = 7;
    o23.materials = 2;
    const SvoTree n = pack_cells(5, random_cells(5, 500, 3), o23);  // near pointers only
    ASSERT_EQ(n.far_slots, 0u);
    ASSERT_GT(t.far_slots, 0u);
    const SvoError C = SvoError::corrupt;
    const uint32_t D = n.desc_words;
    const uint32_t fd = find_far_desc(t);
    ASSERT_NE(fd, ~0u);
    const uint32_t fslot = fd + rk_svo_rel_ptr(t.words[fd]);

    // The pristine trees load (the file writer here agrees with svo_save).
    EXPECT_EQ(raw_file(t), save_ok(t));
    EXPECT_CODE(SvoError::ok, load_code(raw_file(n)), "pristine");

    auto set_ptr = [](uint32_t& w, uint32_t p) { w = (w & 0x1FFu) | (p << RK_SVO_PTR_SHIFT); };
    expect_structural(n, C, "root pointer past the end", [&](SvoTree& u) { set_ptr(u.words[0], D + 2 * u.brick_count + 100); }, "ordinal 0");
    expect_structural(n, C, "root pointer at the max", [&](SvoTree& u) { set_ptr(u.words[0], RK_SVO_PTR_MAX); });
    expect_structural(n, C, "pointer 0 (self loop)", [&](SvoTree& u) { set_ptr(u.words[1], 0); }, "zero pointer");
    expect_structural(n, C, "pointer one short", [&](SvoTree& u) { set_ptr(u.words[1], rk_svo_rel_ptr(u.words[1]) - 1); });
    expect_structural(n, C, "pointer one long", [&](SvoTree& u) { set_ptr(u.words[1], rk_svo_rel_ptr(u.words[1]) + 1); });
    expect_structural(n, C, "last level-1 descriptor points at its sibling", [&](SvoTree& u) { set_ptr(u.words[2], 1); });
    expect_structural(t, C, "near pointer over pointer_bits", [&](SvoTree& u) { u.pointer_bits = 4; set_ptr(u.words[0], 16); },
                      "pointer_bits");
    // Far pointers.
    expect_structural(t, C, "far slot offset wraps backwards", [&](SvoTree& u) { u.words[fslot] = 0xFFFFFFFFu; });
    expect_structural(t, C, "far slot offset 0 (self loop)", [&](SvoTree& u) { u.words[fslot] = 0; }, "offset 0");
    expect_structural(t, C, "far slot offset +1", [&](SvoTree& u) { u.words[fslot] += 1; });
    expect_structural(t, C, "far slot index past its group's slots", [&](SvoTree& u) { set_ptr(u.words[fd], rk_svo_rel_ptr(u.words[fd]) + 8); },
                      "far slot");
    expect_structural(t, C, "far slot index past the region", [&](SvoTree& u) { set_ptr(u.words[fd], 15); });
    expect_structural(t, C, "far bit cleared", [&](SvoTree& u) { u.words[fd] &= ~RK_SVO_FAR_BIT; });
    expect_structural(t, C, "far bit set on a near descriptor", [&](SvoTree& u) {
        for (uint32_t o = 0; o < u.desc_words; ++o)
            if (rk_svo_child_mask(u.words[o]) && !rk_svo_is_far(u.words[o]) && o != fslot) {
                bool is_slot = false;
                for (uint32_t q = 0; q < u.desc_words; ++q)
                    if (rk_svo_is_far(u.words[q]) && q + rk_svo_rel_ptr(u.words[q]) == o) is_slot = true;
                if (!is_slot) { u.words[o] |= RK_SVO_FAR_BIT; return; }
            }
    });
    expect_structural(t, C, "far_slots count off by one", [&](SvoTree& u) { u.far_slots += 1; }, "far_slots");
    // Two far descriptors of one sibling group sharing a slot: find a group with two far members
    // (pointer_bits 4 at depth 6 has plenty).
    {
        PackOptions o4;
        o4.pointer_bits = 4;
        const SvoTree t6 = pack_cells(6, random_cells(6, 3000, 8), o4);
        const std::vector<uint32_t> ds = descriptor_ordinals(t6);
        uint32_t a = ~0u, b = ~0u;
        for (size_t i = 0; i + 1 < ds.size() && a == ~0u; ++i) {
            const uint32_t x = ds[i], y = ds[i + 1];
            if (rk_svo_is_far(t6.words[x]) && rk_svo_is_far(t6.words[y]) && y < x + rk_svo_rel_ptr(t6.words[x])) a = x, b = y;
        }
        ASSERT_NE(a, ~0u) << "no sibling group with two far descriptors";
        const uint32_t sa = a + rk_svo_rel_ptr(t6.words[a]);
        expect_structural(t6, C, "far slot used twice", [&](SvoTree& u) { set_ptr(u.words[b], sa - b); }, "used twice");
        expect_structural(t6, C, "far slots swapped between two descriptors", [&](SvoTree& u) {
            const uint32_t sb = b + rk_svo_rel_ptr(u.words[b]);
            set_ptr(u.words[a], sb - a);
            set_ptr(u.words[b], sa - b);
        });
    }
    // Masks.
    expect_structural(n, C, "child mask zero", [&](SvoTree& u) { u.words[1] &= ~RK_SVO_CHILD_MASK; }, "empty child mask");
    expect_structural(n, C, "root child mask zero (not an empty tree)", [&](SvoTree& u) { u.words[0] &= ~RK_SVO_CHILD_MASK; });
    expect_structural(n, C, "extra child bit", [&](SvoTree& u) {
        uint32_t o = 1;
        while (rk_svo_child_mask(u.words[o]) == 0xFFu) ++o;
        const uint32_t m = rk_svo_child_mask(u.words[o]);
        u.words[o] |= ~m & (m + 1);  // its lowest clear bit
    });
    expect_structural(n, C, "brick mask zero", [&](SvoTree& u) { u.words[D + 4] = u.words[D + 5] = 0; }, "empty mask");
    expect_structural(n, C, "brick mask extra bit", [&](SvoTree& u) {
        uint32_t& lo = u.words[D + 2];
        lo |= ~lo & (lo + 1);  // brick 1 gains a voxel: brick_base[2] no longer matches
    }, "brick_base[2]");
    {
        const SvoTree d1 = pack_cells(1, random_cells(1, 3, 2));
        expect_structural(d1, C, "2^3 brick with bit 8", [&](SvoTree& u) { u.words[0] |= 0x100u; }, "bits above 7");
        expect_structural(d1, C, "2^3 brick with a high word", [&](SvoTree& u) { u.words[1] = 1u; });
    }
    // Bricks and attributes.
    expect_structural(n, C, "brick_base off by one", [&](SvoTree& u) { u.brick_base[3] += 1; }, "brick_base[3]");
    expect_structural(n, C, "brick_base first off by one", [&](SvoTree& u) { u.brick_base[0] -= 1; }, "brick_base[0]");
    expect_structural(n, C, "level_nodes wrong", [&](SvoTree& u) { u.level_nodes[2] += 1; }, "level_nodes[2]");
    expect_structural(n, C, "level_nodes of the voxels wrong", [&](SvoTree& u) { u.level_nodes[5] -= 1; });
    expect_structural(n, C, "voxel_count wrong", [&](SvoTree& u) { u.voxel_count += 1; }, "voxel_count");
    expect_structural(n, C, "material id out of range", [&](SvoTree& u) { u.material[7] = uint32_t(u.materials.size()); }, "material[7]");
    expect_structural(n, C, "material word with reserved bits", [&](SvoTree& u) { u.material[8] = 0x10000u; });
    expect_structural(n, C, "material NaN", [&](SvoTree& u) { u.materials[1].absorption.y = std::numeric_limits<float>::quiet_NaN(); });
    expect_structural(n, C, "material ior 0", [&](SvoTree& u) { u.materials[0].ior = 0.0f; }, "ior");
    expect_structural(n, C, "attr_count +1 (streams too)", [&](SvoTree& u) {
        u.attr_count += 1;
        u.color.push_back(0);
        u.normal.push_back(0);
        u.material.push_back(0);
    }, "attr_count");
    expect_structural(n, C, "attr_count -1 (streams too)", [&](SvoTree& u) {
        u.attr_count -= 1;
        u.color.pop_back();
        u.normal.pop_back();
        u.material.pop_back();
    });
    expect_structural(n, C, "one stream longer", [&](SvoTree& u) { u.normal.push_back(0); }, "normal");
    expect_structural(n, C, "absent stream present", [&](SvoTree& u) { u.attributes &= ~RK_SVO_ATTR_COLOR; });
    expect_structural(n, C, "materials without the attribute", [&](SvoTree& u) {
        u.attributes &= ~RK_SVO_ATTR_MATERIAL;
        u.material.clear();
    });
    expect_structural(n, C, "material attribute with an empty table", [&](SvoTree& u) { u.materials.clear(); });
    // Region sizes.
    expect_structural(n, C, "an unreachable word in the descriptor region", [&](SvoTree& u) {
        for (uint32_t o = 0; o < u.desc_words; ++o)  // keep the (near) brick pointers right
            if (o + rk_svo_rel_ptr(u.words[o]) >= u.desc_words) set_ptr(u.words[o], rk_svo_rel_ptr(u.words[o]) + 1);
        u.words.insert(u.words.begin() + u.desc_words, 0u);
        u.desc_words += 1;
        for (uint32_t& b : u.brick_base) b += 1;
        u.attr_count += 1;
        u.color.insert(u.color.begin(), 0u);
        u.normal.insert(u.normal.begin(), 0u);
        u.material.insert(u.material.begin(), 0u);
    }, "desc_words");
    expect_structural(n, C, "a brick no descriptor reaches", [&](SvoTree& u) {
        u.words.push_back(1u);
        u.words.push_back(0u);
        u.brick_count += 1;
        u.brick_base.push_back(uint32_t(u.attr_count));
    });
    expect_structural(n, C, "words shorter than its counts", [&](SvoTree& u) { u.words.pop_back(); });
    expect_structural(n, C, "brick_base shorter than brick_count", [&](SvoTree& u) { u.brick_base.pop_back(); });
    expect_structural(n, C, "depth 0", [&](SvoTree& u) { u.depth = 0; });
    expect_structural(n, C, "depth 21", [&](SvoTree& u) { u.depth = 21; u.level_nodes.resize(22); });
    expect_structural(n, C, "brick_levels 1 at depth 5", [&](SvoTree& u) { u.brick_levels = 1; });
    expect_structural(n, C, "pointer_bits 24", [&](SvoTree& u) { u.pointer_bits = 24; });
    expect_structural(n, C, "pointer_bits 3", [&](SvoTree& u) { u.pointer_bits = 3; });
    expect_structural(n, C, "attribute bit 3", [&](SvoTree& u) { u.attributes |= 8u; });
    expect_structural(n, C, "root_size -0", [&](SvoTree& u) { u.root_size = -0.0f; });
    expect_structural(n, C, "root_min + root_size overflows", [&](SvoTree& u) { u.root_min.y = 3.4e38f; u.root_size = 1e38f; });
    expect_structural(n, C, "level_nodes one short", [&](SvoTree& u) { u.level_nodes.pop_back(); });
    expect_structural(n, C, "empty words", [&](SvoTree& u) {
        u.words.clear();
        u.desc_words = 0;
        u.brick_count = 0;
        u.brick_base.clear();
    });
    // Empty trees: only a zero root is accepted.
    const SvoTree e5 = pack_cells(5, {});
    const SvoTree e2 = pack_cells(2, {});
    check_round_trip(e5, "empty depth 5");
    check_round_trip(e2, "empty depth 2");
    check_round_trip(pack_cells(1, {}), "empty depth 1");
    expect_structural(e5, C, "empty root with a pointer", [&](SvoTree& u) { u.words[0] = 1u << RK_SVO_PTR_SHIFT; });
    expect_structural(e5, C, "empty root with a far bit", [&](SvoTree& u) { u.words[0] = RK_SVO_FAR_BIT; });
    expect_structural(e5, C, "empty tree with level_nodes[0] = 0", [&](SvoTree& u) { u.level_nodes[0] = 0; });
    expect_structural(e5, C, "empty tree with level_nodes[1] = 1", [&](SvoTree& u) { u.level_nodes[1] = 1; });
    expect_structural(e2, C, "empty brick root with voxel_count 1", [&](SvoTree& u) { u.voxel_count = 1; u.level_nodes[2] = 1; });
    expect_structural(e2, C, "empty root brick with no brick", [&](SvoTree& u) {
        u.words.clear();
        u.brick_count = 0;
        u.brick_base.clear();
        u.attr_count = 0;
    });
    expect_structural(e2, C, "root brick with a descriptor region", [&](SvoTree& u) {
        u.words.insert(u.words.begin(), 0u);
        u.desc_words = 1;
    });
}

TEST(SvoFileCorrupt, CountsThatWrap32Or64BitArithmetic)
{
    const SvoTree t = rich_tree();
    const Bytes f = save_ok(t);
    struct Case {
        const char* what;
        size_t off;
        int width;
        uint64_t value;
        SvoError want;
    };
    const uint64_t bc = t.brick_count, D = t.desc_words, A = t.attr_count;
    const Case cases[] = {
        // 2 * brick_count wraps 32 bits back to the real value: a 32-bit check would accept it.
        {"brick_count + 2^31", kBrickCount, 4, bc + (1ull << 31), SvoError::too_large},
        {"desc_words + 2^32 - 2 * 2^31 ...", kDescWords, 4, 0xFFFFFFFFull, SvoError::too_large},
        // 4 * attr_count wraps 64 bits back to the real size.
        {"attr_count + 2^62", kAttrCount, 8, A + (1ull << 62), SvoError::too_large},
        {"attr_count 2^32 + 1", kAttrCount, 8, (1ull << 32) + 1, SvoError::too_large},
        {"attr_count 2^32 (absent streams would be fine; present ones do not fit)", kAttrCount, 8, 1ull << 32, SvoError::corrupt},
        // 36 * material_count wraps 32 bits: 36 * (3 + 2^32/4) = 108 + 9 * 2^32.
        {"material_count + 2^30", kMaterialCount, 4, 3 + (1ull << 30), SvoError::too_large},
        {"voxel_count 2^64 - 1", kVoxelCount, 8, ~0ull, SvoError::corrupt},
        {"level_nodes[4] 2^63", kLevelNodes + 32, 8, 1ull << 63, SvoError::corrupt},
        {"file_size 2^64 - 1", kFileSize, 8, ~0ull, SvoError::corrupt},
        // A section size that would wrap the offset sum to the right file size.
        {"color size 2^64 - 4", kSections + 16 * 2 + 8, 8, ~0ull - 3, SvoError::corrupt},
        {"words offset 2^64 - 8", kSections, 8, ~0ull - 7, SvoError::corrupt},
    };
    (void)D;
    for (const Case& c : cases) {
        Bytes g = f;
        if (c.width == 4)
            wr32(g, c.off, uint32_t(c.value));
        else
            wr64(g, c.off, c.value);
        fix_crcs(g);
        std::string msg;
        EXPECT_CODE(c.want, load_code(g, nullptr, &msg), c.what << ": " << msg);
    }
    // The same in memory: svo_validate refuses counts past the format's limits before touching
    // the vectors.
    SvoTree u = t;
    u.brick_count += 1u << 31;
    SvoStatus st;
    EXPECT_FALSE(svo_validate(u, st));
    EXPECT_EQ(st.code, SvoError::too_large) << st.message;
    u = t;
    u.attr_count = (1ull << 32) + 1;
    EXPECT_FALSE(svo_validate(u, st));
    EXPECT_EQ(st.code, SvoError::too_large) << st.message;
}

TEST(SvoFileCorrupt, MessagesNameTheFieldAndOffset)
{
    const Bytes f = save_ok(rich_tree());
    std::string msg;
    Bytes g = f;
    g.resize(g.size() - 10);
    load_code(g, nullptr, &msg);
    EXPECT_NE(msg.find(std::to_string(f.size())), std::string::npos) << msg;  // announced size
    g = f;
    g[f.size() - 5] ^= 1;
    load_code(g, nullptr, &msg);
    EXPECT_NE(msg.find("payload checksum"), std::string::npos) << msg;
    g = f;
    wr32(g, kBrickCount, rd32(f, kBrickCount) + 1);
    fix_crcs(g);
    load_code(g, nullptr, &msg);
    EXPECT_NE(msg.find("section words size (byte 96)"), std::string::npos) << msg;
    g = f;
    wr32(g, kDepth, 9);
    fix_crcs(g);
    load_code(g, nullptr, &msg);
    EXPECT_NE(msg.find("depth 9"), std::string::npos) << msg;
}
