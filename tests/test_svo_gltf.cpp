// raykit/svo_gltf.hpp: the shipped glTF (tests/data/svo/textured_box.gltf, written by
// scripts/make_test_gltf.py) against values derived by hand from its node transforms, geometry,
// texture and materials; the same scene as .glb; hostile variants (each must fail with a clear
// error, never crash); and a depth-5 voxelisation whose box-face colours are the checker's area
// averages.
//
// tinygltf's implementation is compiled here (as svo_gltf.hpp documents); Debian puts stb in
// /usr/include/stb, so stb is included from there and tinygltf told not to include it itself.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "raykit/svo_gltf.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "raykit/svo_build.hpp"

namespace {

using raykit::SvoError;

const std::string kBox = std::string(RAYKIT_TEST_DATA_DIR) + "/svo/textured_box.gltf";

// What scripts/make_test_gltf.py writes, restated.
const uint8_t kColorA[3] = {200, 40, 30};
const uint8_t kColorB[3] = {240, 220, 110};
bool texel_is_a(int i, int j) { return (i / 4 + j / 4) % 2 == 0; }
struct Face {
    glm::vec3 n, a, b;  // outward normal, in-plane axes (a x b = n)
};
const Face kFaces[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
    {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}, {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
};
const glm::vec3 kBoxCentre(1.0f, 0.5f, -2.0f);  // node 0's translation

double srgb_to_linear(double c)  // IEC 61966-2-1
{
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

std::string read_text(const std::string& path)
{
    std::ifstream f(path, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void write_bytes(const std::string& path, const void* data, size_t size)
{
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(static_cast<const char*>(data), std::streamsize(size));
}

/// A folder for this run's files, removed when the program ends.
std::string temp_dir()
{
    struct Dir {
        std::string path;
        Dir()
        {
            const std::filesystem::path p = std::filesystem::temp_directory_path() /
                                            ("raykit_test_svo_gltf_" + std::to_string(static_cast<long>(::getpid())));
            std::filesystem::create_directories(p);
            path = p.string();
        }
        ~Dir()
        {
            std::error_code ec;
            std::filesystem::remove_all(path, ec);
        }
    };
    static const Dir dir;
    return dir.path;
}

std::string base64(const std::vector<uint8_t>& in)
{
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < in.size(); i += 3) {
        const uint32_t v = uint32_t(in[i]) << 16 | (i + 1 < in.size() ? uint32_t(in[i + 1]) << 8 : 0u) |
                           (i + 2 < in.size() ? uint32_t(in[i + 2]) : 0u);
        out += t[(v >> 18) & 63];
        out += t[(v >> 12) & 63];
        out += i + 1 < in.size() ? t[(v >> 6) & 63] : '=';
        out += i + 2 < in.size() ? t[v & 63] : '=';
    }
    return out;
}

void put_f32(std::vector<uint8_t>& b, float f)
{
    uint32_t u;
    std::memcpy(&u, &f, 4);
    for (int k = 0; k < 4; ++k) b.push_back(uint8_t(u >> (8 * k)));
}

/// A small glTF with one mesh of two triangles: POSITION (3 floats x 3 vertices, bufferView 0)
/// and u16 indices (6, bufferView 1) in one data-URI buffer; every field a test breaks is a string.
struct Doc {
    std::vector<float> positions{0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<uint16_t> indices{0, 1, 2, 0, 2, 1};
    std::vector<uint8_t> extra_bytes;  ///< appended to the buffer (4-aligned), for extra views
    std::string pos_count = "3", pos_extra, view0_len = "36", view0_extra, buffer_len;
    std::string buffer_uri;  ///< default: the data URI of the bytes above
    std::string extra_views;  ///< ",{...}" bufferViews 2.. (extra bytes start at 48)
    std::string nodes = R"([{"mesh":0}])";
    std::string scene = R"("scene":0,"scenes":[{"nodes":[0]}],)";
    std::string prim_extra, top_extra;

    std::string json() const
    {
        std::vector<uint8_t> buf;
        for (float f : positions) put_f32(buf, f);
        for (uint16_t i : indices) buf.push_back(uint8_t(i)), buf.push_back(uint8_t(i >> 8));
        buf.insert(buf.end(), extra_bytes.begin(), extra_bytes.end());
        const std::string uri = buffer_uri.empty() ? "data:application/octet-stream;base64," + base64(buf) : buffer_uri;
        const std::string len = buffer_len.empty() ? std::to_string(buf.size()) : buffer_len;
        return R"({"asset":{"version":"2.0"},)" + scene + R"("nodes":)" + nodes +
               R"(,"meshes":[{"name":"tri","primitives":[{"attributes":{"POSITION":0},"indices":1)" + prim_extra +
               R"(}]}],"buffers":[{"byteLength":)" + len + R"(,"uri":")" + uri +
               R"("}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" + view0_len + view0_extra +
               R"(},{"buffer":0,"byteOffset":36,"byteLength":12})" + extra_views +
               R"(],"accessors":[{"bufferView":0,"componentType":5126,"count":)" + pos_count + R"(,"type":"VEC3")" +
               pos_extra + R"(},{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}])" + top_extra + "}";
    }
};

struct Result {
    bool ok;
    raykit::SvoStatus st;
    raykit::SvoMeshData mesh;
    raykit::SvoGltfStats stats;
};

Result load_file(const std::string& path, const raykit::SvoGltfLimits& lim = raykit::SvoGltfLimits())
{
    Result r;
    r.ok = raykit::load_gltf_mesh(path, r.mesh, r.st, &r.stats, lim);
    return r;
}

Result load_text(const std::string& name, const std::string& text, const raykit::SvoGltfLimits& lim = raykit::SvoGltfLimits())
{
    const std::string path = temp_dir() + "/" + name;
    write_bytes(path, text.data(), text.size());
    return load_file(path, lim);
}

void expect_vec3(glm::vec3 got, glm::vec3 want, float tol, const std::string& what)
{
    EXPECT_NEAR(got.x, want.x, tol) << what;
    EXPECT_NEAR(got.y, want.y, tol) << what;
    EXPECT_NEAR(got.z, want.z, tol) << what;
}

// ---------------------------------------------------------------------------------------------
// The shipped file.

TEST(SvoGltf, ShippedFileCountsAndStats)
{
    const Result r = load_file(kBox);
    ASSERT_TRUE(r.ok) << r.st.message;
    EXPECT_EQ(r.st.code, SvoError::ok);
    // Default scene: node 0 (box + lid) and its child node 1 (fan, points, lines, triangle);
    // node 2 is only in scene 1.
    EXPECT_EQ(r.stats.nodes, 2u);
    EXPECT_EQ(r.stats.mesh_instances, 2u);
    EXPECT_EQ(r.stats.primitives, 4u);
    EXPECT_EQ(r.stats.skipped_points, 1u);
    EXPECT_EQ(r.stats.skipped_lines, 1u);
    EXPECT_EQ(r.stats.skipped_no_position, 0u);
    EXPECT_EQ(r.stats.dropped_bad_index, 0u);
    // box 12 + lid strip 2 + fan 3 + triangle 1; vertices 24 + 4 + 5 + 3 (the normal-less triangle
    // is de-indexed with flat normals).
    EXPECT_EQ(r.stats.triangles, 18u);
    EXPECT_EQ(r.stats.vertices, 36u);
    EXPECT_EQ(r.mesh.indices.size(), 54u);
    EXPECT_EQ(r.mesh.positions.size(), 36u);
    EXPECT_EQ(r.mesh.normals.size(), 36u);
    EXPECT_EQ(r.mesh.uvs.size(), 36u);
    EXPECT_EQ(r.mesh.material_ids.size(), 18u);
    EXPECT_EQ(r.stats.materials, 3u);
    EXPECT_EQ(r.stats.textures, 1u);
    for (const glm::vec3& p : r.mesh.positions) EXPECT_LT(p.x, 50.0f) << "node 2 (x = 100) must not be loaded";
    const raykit::SvoMesh v = r.mesh.view();
    EXPECT_EQ(v.triangle_count, 18u);
    EXPECT_NE(v.normals, nullptr);
    EXPECT_NE(v.uvs, nullptr);
    EXPECT_NE(v.material_ids, nullptr);
}

TEST(SvoGltf, BoxPositionsNormalsUvsIndices)
{
    const Result r = load_file(kBox);
    ASSERT_TRUE(r.ok) << r.st.message;
    // Node 0: translation only, so world = local + (1, 0.5, -2) and normals unchanged.
    for (int f = 0; f < 6; ++f) {
        const Face& F = kFaces[f];
        const float st[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int k = 0; k < 4; ++k) {
            const size_t v = size_t(4 * f + k);
            const glm::vec3 local = 0.5f * F.n + (st[k][0] - 0.5f) * F.a + (st[k][1] - 0.5f) * F.b;
            const std::string what = "face " + std::to_string(f) + " vertex " + std::to_string(k);
            expect_vec3(r.mesh.positions[v], local + kBoxCentre, 1e-6f, what);
            expect_vec3(r.mesh.normals[v], F.n, 1e-6f, what);
            EXPECT_FLOAT_EQ(r.mesh.uvs[v].x, st[k][0]) << what;
            EXPECT_FLOAT_EQ(r.mesh.uvs[v].y, 1.0f - st[k][1]) << what;
        }
        const uint32_t b = uint32_t(4 * f);
        const uint32_t want[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
        for (int k = 0; k < 6; ++k) EXPECT_EQ(r.mesh.indices[size_t(6 * f + k)], want[k]) << "face " << f;
        // Winding: the geometric normal of both triangles is the outward normal.
        for (int t = 0; t < 2; ++t) {
            const uint32_t* tri = &r.mesh.indices[size_t(6 * f + 3 * t)];
            const glm::vec3 g = glm::cross(r.mesh.positions[tri[1]] - r.mesh.positions[tri[0]],
                                           r.mesh.positions[tri[2]] - r.mesh.positions[tri[0]]);
            expect_vec3(glm::normalize(g), F.n, 1e-6f, "winding of face " + std::to_string(f));
        }
    }
    for (size_t t = 0; t < 12; ++t) EXPECT_EQ(r.mesh.material_ids[t], 0u);
}

TEST(SvoGltf, LidStripWithNormalizedU16Texcoords)
{
    const Result r = load_file(kBox);
    ASSERT_TRUE(r.ok) << r.st.message;
    // Local square y = 1.25 -> world y = 1.75; vertices (-0.5, 0.5), (0.5, 0.5), (-0.5, -0.5), (0.5, -0.5) in (x, z).
    const glm::vec3 want[4] = {{0.5f, 1.75f, -1.5f}, {1.5f, 1.75f, -1.5f}, {0.5f, 1.75f, -2.5f}, {1.5f, 1.75f, -2.5f}};
    const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {0, 1}, {1, 32768.0f / 65535.0f}};
    for (size_t k = 0; k < 4; ++k) {
        expect_vec3(r.mesh.positions[24 + k], want[k], 1e-6f, "lid vertex " + std::to_string(k));
        expect_vec3(r.mesh.normals[24 + k], {0, 1, 0}, 1e-6f, "lid normal");
        EXPECT_FLOAT_EQ(r.mesh.uvs[24 + k].x, uv[k].x);
        EXPECT_FLOAT_EQ(r.mesh.uvs[24 + k].y, uv[k].y);
    }
    // Strip 0 1 2 3 -> (0, 1, 2), (1, 3, 2): both facing +y.
    const uint32_t tri[6] = {24, 25, 26, 25, 27, 26};
    for (size_t k = 0; k < 6; ++k) EXPECT_EQ(r.mesh.indices[36 + k], tri[k]);
    EXPECT_EQ(r.mesh.material_ids[12], 1u);
    EXPECT_EQ(r.mesh.material_ids[13], 1u);
}

TEST(SvoGltf, ChildNodeTrsFanNormalsAndFlatTriangle)
{
    const Result r = load_file(kBox);
    ASSERT_TRUE(r.ok) << r.st.message;
    // Node 1 in node 0: world = T(1, 0.5, -2) T(0, 0, 2) R_y(90) S(2, 1, 0.5):
    // local p -> (1 + 0.5 p.z, 0.5 + p.y, -2 p.x).
    auto world = [](glm::vec3 p) { return glm::vec3(1.0f + 0.5f * p.z, 0.5f + p.y, -2.0f * p.x); };
    const glm::vec3 fan[5] = {{0, 0, 0}, {0.4f, -0.4f, 0.2f}, {0.4f, 0.4f, 0.2f}, {-0.4f, 0.4f, -0.2f}, {-0.4f, -0.4f, -0.2f}};
    // Hand-computed world positions, and the formula, must agree with the loader.
    const glm::vec3 hand[5] = {{1, 0.5f, 0}, {1.1f, 0.1f, -0.8f}, {1.1f, 0.9f, -0.8f}, {0.9f, 0.9f, 0.8f}, {0.9f, 0.1f, 0.8f}};
    // Plane z = 0.5 x maps to 8 (x - 1) + z = 0: normal (8, 0, 1) / sqrt(65) (inverse transpose).
    const glm::vec3 n_world = glm::vec3(8, 0, 1) / std::sqrt(65.0f);
    const glm::vec2 uv[5] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {51.0f / 255.0f, 102.0f / 255.0f}};
    for (size_t k = 0; k < 5; ++k) {
        expect_vec3(world(fan[k]), hand[k], 1e-6f, "hand arithmetic");
        expect_vec3(r.mesh.positions[28 + k], hand[k], 1e-6f, "fan vertex " + std::to_string(k));
        expect_vec3(r.mesh.normals[28 + k], n_world, 1e-6f, "fan normal");
        EXPECT_FLOAT_EQ(r.mesh.uvs[28 + k].x, uv[k].x);
        EXPECT_FLOAT_EQ(r.mesh.uvs[28 + k].y, uv[k].y);
    }
    // Fan 0..4 -> (1, 2, 0), (2, 3, 0), (3, 4, 0); geometric normals agree with the vertex normal.
    const uint32_t tri[9] = {29, 30, 28, 30, 31, 28, 31, 32, 28};
    for (size_t k = 0; k < 9; ++k) EXPECT_EQ(r.mesh.indices[42 + k], tri[k]);
    for (size_t t = 0; t < 3; ++t) {
        const uint32_t* i = &r.mesh.indices[42 + 3 * t];
        const glm::vec3 g = glm::normalize(
            glm::cross(r.mesh.positions[i[1]] - r.mesh.positions[i[0]], r.mesh.positions[i[2]] - r.mesh.positions[i[0]]));
        expect_vec3(g, n_world, 1e-5f, "fan triangle " + std::to_string(t));
    }
    for (size_t t = 14; t < 17; ++t) EXPECT_EQ(r.mesh.material_ids[t], 2u) << "no material -> the default one";
    // The normal-less triangle (local z = 0 plane): de-indexed, flat normal +x, zero texcoords.
    const glm::vec3 tri_local[3] = {{-0.3f, 0.6f, 0}, {0.3f, 0.6f, 0}, {0, 0.9f, 0}};
    for (size_t k = 0; k < 3; ++k) {
        expect_vec3(r.mesh.positions[33 + k], world(tri_local[k]), 1e-6f, "triangle vertex");
        expect_vec3(r.mesh.normals[33 + k], {1, 0, 0}, 1e-6f, "flat normal");
        EXPECT_EQ(r.mesh.uvs[33 + k], glm::vec2(0.0f));
        EXPECT_EQ(r.mesh.indices[51 + k], uint32_t(33 + k));
    }
    EXPECT_EQ(r.mesh.material_ids[17], 1u);
}

TEST(SvoGltf, MaterialsAndTexture)
{
    const Result r = load_file(kBox);
    ASSERT_TRUE(r.ok) << r.st.message;
    ASSERT_EQ(r.mesh.materials.size(), 3u);
    const raykit::SvoMeshMaterial& m0 = r.mesh.materials[0];
    EXPECT_EQ(m0.values.base_color, glm::vec4(1.0f));
    EXPECT_EQ(m0.base_color_texture, 0);
    EXPECT_FLOAT_EQ(m0.values.reflectance, 0.0f);  // metallic 0
    EXPECT_FLOAT_EQ(m0.values.ior, 1.5f);
    EXPECT_EQ(m0.values.absorption, glm::vec3(0.0f));
    const raykit::SvoMeshMaterial& m1 = r.mesh.materials[1];
    EXPECT_FLOAT_EQ(m1.values.base_color.r, 0.1f);
    EXPECT_FLOAT_EQ(m1.values.base_color.g, 0.4f);
    EXPECT_FLOAT_EQ(m1.values.base_color.b, 0.8f);
    EXPECT_FLOAT_EQ(m1.values.base_color.a, 0.5f);
    EXPECT_EQ(m1.base_color_texture, -1);
    EXPECT_NEAR(m1.values.reflectance, 0.5 * (1.0 - 0.2), 1e-6);  // metallic x (1 - roughness)
    EXPECT_FLOAT_EQ(m1.values.ior, 1.33f);
    EXPECT_NEAR(m1.values.absorption.x, std::log(2.0) / 2.0, 1e-6);  // -ln(0.5) / 2
    EXPECT_NEAR(m1.values.absorption.y, std::log(4.0) / 2.0, 1e-6);  // -ln(0.25) / 2
    EXPECT_NEAR(m1.values.absorption.z, 0.0, 1e-7);
    const raykit::SvoMeshMaterial& m2 = r.mesh.materials[2];  // default: white, untextured
    EXPECT_EQ(m2.values.base_color, glm::vec4(1.0f));
    EXPECT_EQ(m2.base_color_texture, -1);
    EXPECT_FLOAT_EQ(m2.values.reflectance, 0.0f);
    EXPECT_FLOAT_EQ(m2.values.ior, 1.5f);

    ASSERT_EQ(r.mesh.textures.size(), 1u);
    const raykit::SvoImageView& t = r.mesh.textures[0];
    ASSERT_EQ(t.width, 8);
    ASSERT_EQ(t.height, 8);
    ASSERT_EQ(t.channels, 4);  // tinygltf expands RGB to RGBA
    EXPECT_TRUE(t.srgb);
    EXPECT_EQ(t.wrap_s, raykit::SvoWrap::clamp);
    EXPECT_EQ(t.wrap_t, raykit::SvoWrap::mirror);
    const size_t stride = t.row_stride ? t.row_stride : size_t(t.width * t.channels);
    int a_count = 0;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            const uint8_t* px = t.pixels + size_t(j) * stride + size_t(i * 4);
            const uint8_t* want = texel_is_a(i, j) ? kColorA : kColorB;
            for (int c = 0; c < 3; ++c) EXPECT_EQ(px[c], want[c]) << "texel " << i << "," << j;
            EXPECT_EQ(px[3], 255);
            a_count += texel_is_a(i, j);
        }
    EXPECT_EQ(a_count, 32);
}

// The same scene as .glb (written by tinygltf's own writer) loads to identical arrays.
std::vector<uint8_t> shipped_as_glb()
{
    tinygltf::TinyGLTF io;
    tinygltf::Model model;
    std::string err, warn;
    EXPECT_TRUE(io.LoadASCIIFromFile(&model, &err, &warn, kBox)) << err;
    EXPECT_EQ(model.buffers.size(), 1u);
    if (!model.buffers.empty()) model.buffers[0].uri.clear();  // buffer 0 goes to the BIN chunk
    std::ostringstream out;
    EXPECT_TRUE(io.WriteGltfSceneToStream(&model, out, false, true));
    const std::string s = out.str();
    return std::vector<uint8_t>(s.begin(), s.end());
}

TEST(SvoGltf, GlbLoadsTheSameMesh)
{
    const std::vector<uint8_t> glb = shipped_as_glb();
    ASSERT_GT(glb.size(), 20u);
    ASSERT_EQ(std::memcmp(glb.data(), "glTF", 4), 0);
    const std::string text(glb.begin(), glb.end());
    ASSERT_NE(text.find("BIN"), std::string::npos) << "a BIN chunk";
    ASSERT_EQ(text.find("application/octet-stream"), std::string::npos) << "no data-URI buffer";
    const std::string path = temp_dir() + "/box.glb";
    write_bytes(path, glb.data(), glb.size());
    const Result a = load_file(kBox), b = load_file(path);
    ASSERT_TRUE(a.ok) << a.st.message;
    ASSERT_TRUE(b.ok) << b.st.message;
    EXPECT_EQ(a.mesh.positions, b.mesh.positions);
    EXPECT_EQ(a.mesh.normals, b.mesh.normals);
    EXPECT_EQ(a.mesh.uvs, b.mesh.uvs);
    EXPECT_EQ(a.mesh.indices, b.mesh.indices);
    EXPECT_EQ(a.mesh.material_ids, b.mesh.material_ids);
    EXPECT_EQ(a.mesh.images, b.mesh.images);
    ASSERT_EQ(b.mesh.materials.size(), 3u);
    EXPECT_FLOAT_EQ(b.mesh.materials[1].values.ior, 1.33f);
    // From memory, too.
    raykit::SvoMeshData m;
    raykit::SvoStatus st;
    ASSERT_TRUE(raykit::load_gltf_mesh_from_memory(glb.data(), glb.size(), "", m, st)) << st.message;
    EXPECT_EQ(m.positions, a.mesh.positions);
}

// ---------------------------------------------------------------------------------------------
// Small documents: features and hostile variants.

TEST(SvoGltf, ReferenceDocumentLoads)
{
    const Result r = load_text("ok.gltf", Doc().json());
    ASSERT_TRUE(r.ok) << r.st.message;
    EXPECT_EQ(r.stats.triangles, 2u);
    EXPECT_TRUE(r.mesh.normals.empty()) << "no primitive has normals: the builder uses face normals";
    EXPECT_TRUE(r.mesh.uvs.empty());
    ASSERT_EQ(r.mesh.materials.size(), 1u);  // just the default one
    EXPECT_EQ(r.mesh.material_ids, std::vector<uint16_t>(2, 0));
}

TEST(SvoGltf, IndexOutOfRangeDropsTheTriangle)
{
    Doc d;
    d.indices = {0, 1, 2, 0, 2, 9};
    const Result r = load_text("bad_index.gltf", d.json());
    ASSERT_TRUE(r.ok) << r.st.message;
    EXPECT_EQ(r.stats.dropped_bad_index, 1u);
    EXPECT_EQ(r.stats.triangles, 1u);
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_EQ(r.mesh.material_ids.size(), 1u);
}

TEST(SvoGltf, MirroringTransformFlipsWinding)
{
    Doc d;
    d.nodes = R"([{"mesh":0,"scale":[-1,1,1]}])";
    const Result r = load_text("mirror.gltf", d.json());
    ASSERT_TRUE(r.ok) << r.st.message;
    EXPECT_EQ(r.mesh.indices, (std::vector<uint32_t>{0, 2, 1, 0, 1, 2}));
    // Triangle (0, 1, 2) faces +z in the file; mirrored in x it must still face +z.
    const glm::vec3 g = glm::cross(r.mesh.positions[r.mesh.indices[1]] - r.mesh.positions[r.mesh.indices[0]],
                                   r.mesh.positions[r.mesh.indices[2]] - r.mesh.positions[r.mesh.indices[0]]);
    EXPECT_GT(g.z, 0.0f);
    expect_vec3(r.mesh.positions[1], {-1, 0, 0}, 0.0f, "mirrored vertex");
}

TEST(SvoGltf, MatrixTransformAndDeepChainCompose)
{
    Doc d;
    // Column-major matrix: scale 2, translation (1, 2, 3).
    d.nodes = R"([{"mesh":0,"matrix":[2,0,0,0, 0,2,0,0, 0,0,2,0, 1,2,3,1]}])";
    Result r = load_text("matrix.gltf", d.json());
    ASSERT_TRUE(r.ok) << r.st.message;
    expect_vec3(r.mesh.positions[1], {3, 2, 3}, 0.0f, "matrix");
    expect_vec3(r.mesh.positions[2], {1, 4, 3}, 0.0f, "matrix");
    // A 300-deep chain of translations by 0.01 in x: the mesh at the leaf is moved by 3.
    std::string nodes = "[";
    const int depth = 300;
    for (int i = 0; i < depth; ++i) {
        nodes += std::string(i ? "," : "") + R"({"translation":[0.01,0,0])";
        nodes += i + 1 < depth ? R"(,"children":[)" + std::to_string(i + 1) + "]}" : R"(,"mesh":0})";
    }
    d.nodes = nodes + "]";
    r = load_text("chain.gltf", d.json());
    ASSERT_TRUE(r.ok) << r.st.message;
    EXPECT_EQ(r.stats.nodes, size_t(depth));
    EXPECT_NEAR(r.mesh.positions[0].x, 3.0f, 1e-5f);
    EXPECT_NEAR(r.mesh.positions[1].x, 4.0f, 1e-5f);
}

TEST(SvoGltf, NoSceneUsesRootNodes)
{
    Doc d;
    d.scene = "";
    d.nodes = R"([{"translation":[5,0,0],"children":[1]},{"mesh":0},{"mesh":0,"translation":[0,7,0]}])";
    const Result r = load_text("noscene.gltf", d.json());
    ASSERT_TRUE(r.ok) << r.st.message;
    EXPECT_EQ(r.stats.nodes, 3u);
    EXPECT_EQ(r.stats.mesh_instances, 2u);
    ASSERT_EQ(r.mesh.positions.size(), 6u);
    expect_vec3(r.mesh.positions[0], {5, 0, 0}, 0.0f, "root 0's child");
    expect_vec3(r.mesh.positions[3], {0, 7, 0}, 0.0f, "root 2");
}

TEST(SvoGltf, SparseAccessorIsApplied)
{
    Doc d;
    d.extra_bytes = {2, 0, 0, 0};  // sparse index 2 (u8) + padding, at byte 48
    put_f32(d.extra_bytes, 5.0f);
    put_f32(d.extra_bytes, 6.0f);
    put_f32(d.extra_bytes, 7.0f);  // value at byte 52
    d.extra_views = R"(,{"buffer":0,"byteOffset":48,"byteLength":1},{"buffer":0,"byteOffset":52,"byteLength":12})";
    d.pos_extra = R"(,"sparse":{"count":1,"indices":{"bufferView":2,"componentType":5121},"values":{"bufferView":3}})";
    Result r = load_text("sparse.gltf", d.json());
    ASSERT_TRUE(r.ok) << r.st.message;
    expect_vec3(r.mesh.positions[1], {1, 0, 0}, 0.0f, "untouched");
    expect_vec3(r.mesh.positions[2], {5, 6, 7}, 0.0f, "replaced");
    // A sparse index beyond the accessor's count.
    d.extra_bytes[0] = 3;
    r = load_text("sparse_bad.gltf", d.json());
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.st.code, SvoError::corrupt);
    EXPECT_NE(r.st.message.find("index 3 >= count 3"), std::string::npos) << r.st.message;
}

/// Expects failure with `code` and a message containing every one of `needles`.
void expect_fail(const Result& r, SvoError code, std::initializer_list<const char*> needles)
{
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(int(r.st.code), int(code)) << r.st.message;
    for (const char* n : needles) EXPECT_NE(r.st.message.find(n), std::string::npos) << "'" << n << "' not in: " << r.st.message;
    EXPECT_TRUE(r.mesh.positions.empty() && r.mesh.indices.empty()) << "a failed load leaves the mesh empty";
}

TEST(SvoGltf, HostileInvalidJson)
{
    expect_fail(load_text("bad.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [ {"), SvoError::corrupt, {"JSON"});
    expect_fail(load_text("empty.gltf", ""), SvoError::corrupt, {"glTF"});
    expect_fail(load_text("array.gltf", "[1, 2, 3]"), SvoError::corrupt, {"glTF"});
}

TEST(SvoGltf, HostileAccessorCountBeyondBuffer)
{
    Doc d;
    d.pos_count = "4";
    expect_fail(load_text("count4.gltf", d.json()), SvoError::corrupt,
                {"mesh 0 'tri' primitive 0", "POSITION accessor 0", "count 4", "exceeds bufferView 0 (36 bytes)"});
}

TEST(SvoGltf, HostileByteStrideTooSmall)
{
    Doc d;
    d.view0_extra = R"(,"byteStride":8)";
    expect_fail(load_text("stride.gltf", d.json()), SvoError::corrupt,
                {"POSITION accessor 0", "byteStride 8", "smaller than the element size 12"});
}

TEST(SvoGltf, HostileBufferViewBeyondBuffer)
{
    Doc d;
    d.view0_len = "400";
    const Result r = load_text("view.gltf", d.json());
    EXPECT_FALSE(r.ok);
    EXPECT_EQ(r.st.code, SvoError::corrupt) << r.st.message;
    EXPECT_NE(r.st.message.find("bufferView"), std::string::npos) << r.st.message;
    // A view into a buffer that does not exist.
    d.view0_len = "36";
    d.view0_extra = R"(,"buffer":7)";
    const Result r2 = load_text("view_buffer.gltf", d.json());
    EXPECT_FALSE(r2.ok);
    EXPECT_NE(r2.st.message.find("buffer"), std::string::npos) << r2.st.message;
}

TEST(SvoGltf, HostileNegativeAndHugeCounts)
{
    for (const char* count : {"-1", "0", "4294967296", "1e12", "18446744073709551615", "3.5", "\"3\""}) {
        Doc d;
        d.pos_count = count;
        const Result r = load_text("count.gltf", d.json());
        EXPECT_FALSE(r.ok) << "count " << count;
        EXPECT_EQ(r.st.code == SvoError::corrupt || r.st.code == SvoError::too_large, true)
            << "count " << count << ": " << r.st.message;
        EXPECT_FALSE(r.st.message.empty());
    }
    // A huge byteOffset must not wrap around the 64-bit range check.
    Doc d;
    d.pos_extra = R"(,"byteOffset":18446744073709551600)";
    const Result r = load_text("offset.gltf", d.json());
    EXPECT_FALSE(r.ok);
    EXPECT_FALSE(r.st.message.empty());
}

TEST(SvoGltf, HostileMissingImageAndBadDataUri)
{
    Doc d;
    d.prim_extra = R"(,"material":0)";
    d.top_extra = R"(,"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
                  R"("textures":[{"source":0}],"images":[{"uri":"no_such_image.png"}])";
    const Result r = load_text("missing_image.gltf", d.json());
    EXPECT_FALSE(r.ok);
    EXPECT_NE(r.st.message.find("no_such_image.png"), std::string::npos) << r.st.message;
    EXPECT_TRUE(r.st.code == SvoError::io || r.st.code == SvoError::corrupt) << r.st.message;

    Doc bad;
    bad.buffer_uri = "data:application/octet-stream;base64,@@@@not*base64";
    const Result r2 = load_text("bad_uri.gltf", bad.json());
    EXPECT_FALSE(r2.ok);
    EXPECT_EQ(r2.st.code, SvoError::corrupt) << r2.st.message;
    EXPECT_FALSE(r2.st.message.empty());

    Doc missing;
    missing.buffer_uri = "no_such_buffer.bin";
    const Result r3 = load_text("missing_buffer.gltf", missing.json());
    EXPECT_FALSE(r3.ok);
    EXPECT_EQ(r3.st.code, SvoError::io) << r3.st.message;
    EXPECT_NE(r3.st.message.find("no_such_buffer.bin"), std::string::npos) << r3.st.message;

    // A data URI shorter than byteLength.
    Doc shortb;
    shortb.buffer_len = "4000";
    const Result r4 = load_text("short_buffer.gltf", shortb.json());
    EXPECT_FALSE(r4.ok);
    EXPECT_FALSE(r4.st.message.empty());
}

TEST(SvoGltf, HostileNodeCycleAndDeepHierarchy)
{
    Doc d;
    d.nodes = R"([{"mesh":0,"children":[1]},{"children":[0]}])";
    expect_fail(load_text("cycle.gltf", d.json()), SvoError::corrupt, {"reached twice"});
    d.nodes = R"([{"mesh":0,"children":[0]}])";
    expect_fail(load_text("self.gltf", d.json()), SvoError::corrupt, {"node 0 is reached twice"});
    d.nodes = R"([{"mesh":0,"children":[5]}])";
    expect_fail(load_text("child.gltf", d.json()), SvoError::corrupt, {"node 5 does not exist"});
    // 5000 levels: over the default limit of 1024, a clear error rather than a deep recursion.
    std::string nodes = "[";
    for (int i = 0; i < 5000; ++i)
        nodes += std::string(i ? "," : "") + (i + 1 < 5000 ? R"({"children":[)" + std::to_string(i + 1) + "]}" : R"({"mesh":0})");
    d.nodes = nodes + "]";
    expect_fail(load_text("deep.gltf", d.json()), SvoError::too_large, {"deeper than 1024 levels"});
}

TEST(SvoGltf, HostileTypesModesAndReferences)
{
    Doc d;
    d.pos_extra = "";
    std::string j = d.json();
    // POSITION as VEC2.
    std::string v2 = j;
    v2.replace(v2.find(R"("type":"VEC3")"), 13, R"("type":"VEC2")");
    expect_fail(load_text("vec2.gltf", v2), SvoError::corrupt, {"POSITION accessor 0 holds VEC2 of float"});
    // Float indices.
    std::string fi = j;
    fi.replace(fi.find(R"("componentType":5123)"), 20, R"("componentType":5126)");
    expect_fail(load_text("float_idx.gltf", fi), SvoError::corrupt, {"indices accessor 1"});
    // Unknown primitive mode.
    Doc m;
    m.prim_extra = R"(,"mode":9)";
    const Result rm = load_text("mode.gltf", m.json());
    EXPECT_FALSE(rm.ok);
    EXPECT_FALSE(rm.st.message.empty());
    // Material index out of range.
    Doc mat;
    mat.prim_extra = R"(,"material":3)";
    const Result rmat = load_text("material.gltf", mat.json());
    EXPECT_FALSE(rmat.ok);
    EXPECT_NE(rmat.st.message.find("material 3"), std::string::npos) << rmat.st.message;
    // Draco is required but not supported.
    Doc draco;
    draco.top_extra = R"(,"extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"])";
    expect_fail(load_text("draco.gltf", draco.json()), SvoError::invalid_argument, {"KHR_draco_mesh_compression"});
    // Missing file.
    expect_fail(load_file(temp_dir() + "/does_not_exist.gltf"), SvoError::io, {"cannot open", "does_not_exist.gltf"});
}

TEST(SvoGltf, HostileHugeImageDeepJsonAndMismatchedCounts)
{
    // A PNG whose header announces 100000 x 100000 RGBA pixels (40 GB): refused from the header.
    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    for (uint32_t v : {100000u, 100000u})
        for (int k = 3; k >= 0; --k) png.push_back(uint8_t(v >> (8 * k)));
    for (int b : {8, 6, 0, 0, 0, 0, 0, 0, 0}) png.push_back(uint8_t(b));
    Doc d;
    d.prim_extra = R"(,"material":0)";
    d.top_extra = R"(,"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
                  R"("textures":[{"source":0}],"images":[{"uri":"data:image/png;base64,)" + base64(png) + R"("}])";
    expect_fail(load_text("huge_image.gltf", d.json()), SvoError::too_large, {"100000x100000", "over the limit"});
    // An 8x8 PNG whose IDAT chunk announces 2 GB that are not there (stb would grow its buffer
    // to that size first), and an image in a format glTF does not allow.
    auto image_doc = [](const std::vector<uint8_t>& bytes) {
        Doc doc;
        doc.prim_extra = R"(,"material":0)";
        doc.top_extra = R"(,"materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
                        R"("textures":[{"source":0}],"images":[{"uri":"data:image/png;base64,)" + base64(bytes) + R"("}])";
        return doc.json();
    };
    std::vector<uint8_t> idat(png.begin(), png.begin() + 16);
    for (uint32_t v : {8u, 8u})
        for (int k = 3; k >= 0; --k) idat.push_back(uint8_t(v >> (8 * k)));
    for (int b : {8, 6, 0, 0, 0, 0, 0, 0, 0, 0x7F, 0xFF, 0xFF, 0xF0, int('I'), int('D'), int('A'), int('T'), 0x78, 0x9C})
        idat.push_back(uint8_t(b));
    expect_fail(load_text("idat.gltf", image_doc(idat)), SvoError::corrupt, {"image[0]", "not a (complete) PNG"});
    const std::vector<uint8_t> tga = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xFF, 0x7F, 0xFF, 0x7F, 32, 0};
    expect_fail(load_text("tga.gltf", image_doc(tga)), SvoError::corrupt, {"image[0]", "not a (complete) PNG"});

    // 100000 levels of nested arrays in "extras".
    Doc deep;
    deep.top_extra = R"(,"extras":)" + std::string(100000, '[') + std::string(100000, ']');
    expect_fail(load_text("deep_json.gltf", deep.json()), SvoError::too_large, {"nested deeper than 128"});

    // A NORMAL accessor (sparse, no bufferView) announcing far more elements than POSITION.
    Doc n;
    n.extra_bytes = {0, 0, 0, 0};
    for (int k = 0; k < 3; ++k) put_f32(n.extra_bytes, 1.0f);
    n.extra_views = R"(,{"buffer":0,"byteOffset":48,"byteLength":1},{"buffer":0,"byteOffset":52,"byteLength":12})";
    std::string j = n.json();
    const std::string attrs = R"("attributes":{"POSITION":0})";
    j.replace(j.find(attrs), attrs.size(), R"("attributes":{"POSITION":0,"NORMAL":2})");
    j.insert(j.rfind("]}"), R"(,{"componentType":5126,"count":200000000,"type":"VEC3",)"
                            R"("sparse":{"count":1,"indices":{"bufferView":2,"componentType":5121},"values":{"bufferView":3}}})");
    expect_fail(load_text("normal_count.gltf", j), SvoError::corrupt, {"NORMAL accessor 2 has count 200000000, POSITION 3"});
}

TEST(SvoGltf, LimitsBoundInstancing)
{
    // 200 nodes instancing one mesh: fine by default, too_large with a 100-triangle limit.
    Doc d;
    std::string nodes = "[", roots;
    for (int i = 0; i < 200; ++i) {
        nodes += std::string(i ? "," : "") + R"({"mesh":0})";
        roots += std::string(i ? "," : "") + std::to_string(i);
    }
    d.nodes = nodes + "]";
    d.scene = R"("scene":0,"scenes":[{"nodes":[)" + roots + "]}],";
    const std::string j = d.json();
    Result r = load_text("many.gltf", j);
    ASSERT_TRUE(r.ok) << r.st.message;
    EXPECT_EQ(r.stats.triangles, 400u);
    raykit::SvoGltfLimits lim;
    lim.max_triangles = 100;
    expect_fail(load_text("many.gltf", j, lim), SvoError::too_large, {"more than 100 triangles"});
}

TEST(SvoGltf, HostileGlbChunks)
{
    const std::vector<uint8_t> glb = shipped_as_glb();
    ASSERT_GT(glb.size(), 28u);
    auto put32 = [](std::vector<uint8_t>& b, size_t at, uint32_t v) {
        for (int k = 0; k < 4; ++k) b[at + size_t(k)] = uint8_t(v >> (8 * k));
    };
    auto get32 = [](const std::vector<uint8_t>& b, size_t at) {
        return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
    };
    const uint32_t json_len = get32(glb, 12);
    const size_t bin_at = 20 + json_len;
    ASSERT_LT(bin_at + 8, glb.size());
    struct Case {
        const char* name;
        size_t at;
        uint32_t value;
    };
    const Case cases[] = {
        {"json chunk length huge", 12, 0xFFFFFFF0u},
        {"json chunk length beyond file", 12, uint32_t(glb.size())},
        {"json chunk length zero", 12, 0u},
        {"bin chunk length huge", bin_at, 0xFFFFFFF0u},
        {"bin chunk length beyond file", bin_at, uint32_t(glb.size())},
        {"total length huge", 8, 0xFFFFFFF0u},
        {"total length tiny", 8, 12u},
        {"version 1", 4, 1u},
    };
    for (const Case& c : cases) {
        std::vector<uint8_t> b = glb;
        put32(b, c.at, c.value);
        raykit::SvoMeshData m;
        raykit::SvoStatus st;
        EXPECT_FALSE(raykit::load_gltf_mesh_from_memory(b.data(), b.size(), "", m, st)) << c.name;
        EXPECT_EQ(st.code, SvoError::corrupt) << c.name << ": " << st.message;
        EXPECT_NE(st.message.find("GLB"), std::string::npos) << c.name << ": " << st.message;
    }
    // Every truncation of the first 64 bytes, and of the last bytes, fails cleanly.
    for (size_t n = 0; n < glb.size(); n += (n < 64 || n + 64 > glb.size()) ? 1 : 97) {
        raykit::SvoMeshData m;
        raykit::SvoStatus st;
        const bool ok = raykit::load_gltf_mesh_from_memory(glb.data(), n, "", m, st);
        EXPECT_FALSE(ok) << "truncated to " << n << " bytes";
        EXPECT_FALSE(st.message.empty());
    }
}

TEST(SvoGltf, ByteFlipsNeverCrash)
{
    // Deterministic single-byte corruptions of the JSON text and of the .glb: whatever the
    // outcome, a failure has a message and a success has consistent arrays.
    const std::string text = read_text(kBox);
    const std::vector<uint8_t> glb = shipped_as_glb();
    uint32_t seed = 12345u;
    auto next = [&seed] { return seed = seed * 1664525u + 1013904223u; };
    int failures = 0, successes = 0;
    for (int k = 0; k < 300; ++k) {
        const bool use_glb = k % 2 == 1;
        std::vector<uint8_t> b = use_glb ? glb : std::vector<uint8_t>(text.begin(), text.end());
        const size_t at = next() % b.size();
        const uint8_t chars[] = {'0', '9', '-', '"', '{', ']', 0xFF, 0x00};
        b[at] = use_glb ? uint8_t(next()) : chars[next() % sizeof chars];
        raykit::SvoMeshData m;
        raykit::SvoStatus st;
        raykit::SvoGltfStats s;
        if (raykit::load_gltf_mesh_from_memory(b.data(), b.size(), temp_dir(), m, st, &s)) {
            ++successes;
            EXPECT_EQ(m.indices.size() % 3, 0u);
            for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
            EXPECT_TRUE(m.normals.empty() || m.normals.size() == m.positions.size());
            EXPECT_TRUE(m.uvs.empty() || m.uvs.size() == m.positions.size());
            EXPECT_EQ(m.material_ids.size(), m.indices.size() / 3);
            for (uint16_t id : m.material_ids) ASSERT_LT(id, m.materials.size());
            for (const raykit::SvoMeshMaterial& mm : m.materials) EXPECT_LT(mm.base_color_texture, int(m.textures.size()));
        } else {
            ++failures;
            EXPECT_FALSE(st.message.empty());
        }
    }
    EXPECT_GT(failures, 0);
    EXPECT_GT(successes, 0);
}

// ---------------------------------------------------------------------------------------------
// Voxelisation of the shipped file: box-face voxels carry the checker's area averages.

TEST(SvoGltf, VoxelisedBoxFacesShowTheChecker)
{
    const Result r = load_file(kBox);
    ASSERT_TRUE(r.ok) << r.st.message;
    // Root cube aligned with the box: 4 units, voxels of 1/8 at depth 5, so the box [0.5, 1.5] x
    // [0, 1] x [-2.5, -1.5] spans cells 12..20 per axis and each face maps 8x8 voxels to 8x8 texels.
    raykit::SvoBuildOptions opt;
    opt.depth = 5;
    opt.fixed_bounds = true;
    opt.bounds_min = kBoxCentre - glm::vec3(2.0f);
    opt.bounds_size = 4.0f;
    opt.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_NORMAL | RK_SVO_ATTR_MATERIAL;
    opt.threads = 1;
    raykit::SvoTree tree;
    raykit::SvoStatus st;
    ASSERT_TRUE(raykit::build_svo(r.mesh.view(), opt, tree, st)) << st.message;
    ASSERT_EQ(tree.depth, 5u);
    std::map<uint64_t, uint64_t> attr;  // cell key -> attribute index
    auto key = [](glm::uvec3 c) { return uint64_t(c.x) | uint64_t(c.y) << 16 | uint64_t(c.z) << 32; };
    raykit::svo_for_each_voxel(tree, [&](glm::uvec3 cell, uint64_t a) { attr[key(cell)] = a; });

    double lin_a[3], lin_b[3];
    for (int c = 0; c < 3; ++c) lin_a[c] = srgb_to_linear(kColorA[c] / 255.0), lin_b[c] = srgb_to_linear(kColorB[c] / 255.0);
    int pure_checked = 0, mixed_checked = 0;
    for (int f = 0; f < 6; ++f) {
        const Face& F = kFaces[f];
        const int ax = F.n.x != 0 ? 0 : F.n.y != 0 ? 1 : 2;
        const int pa = (ax + 1) % 3, pb = (ax + 2) % 3;  // in-plane axes
        const bool positive = F.n[ax] > 0;
        // The voxel layer just outside the face: it touches this face with its whole side and the
        // neighbouring faces only along lines, so its colour is this face's alone.
        const uint32_t layer = positive ? 20u : 11u;
        for (uint32_t p = 12; p < 20; ++p)
            for (uint32_t q = 12; q < 20; ++q) {
                glm::uvec3 cell;
                cell[ax] = layer, cell[pa] = p, cell[pb] = q;
                const auto it = attr.find(key(cell));
                ASSERT_NE(it, attr.end()) << "face " << f << " cell " << p << "," << q << " empty";
                // The voxel's footprint on the face in texture space: corners in world space ->
                // (s, t) = 0.5 + dot(P - centre, a or b), uv = (s, 1 - t).
                double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
                for (int corner = 0; corner < 4; ++corner) {
                    glm::vec3 P;
                    P[ax] = kBoxCentre[ax] + 0.5f * F.n[ax];
                    P[pa] = opt.bounds_min[pa] + 0.125f * float(p + uint32_t(corner & 1));
                    P[pb] = opt.bounds_min[pb] + 0.125f * float(q + uint32_t(corner >> 1));
                    const double s = 0.5 + double(glm::dot(P - kBoxCentre, F.a));
                    const double t = 0.5 + double(glm::dot(P - kBoxCentre, F.b));
                    u0 = std::min(u0, s), u1 = std::max(u1, s), v0 = std::min(v0, 1.0 - t), v1 = std::max(v1, 1.0 - t);
                }
                // Area average of the (nearest-texel) checker over the footprint, in linear RGB.
                double avg[3] = {0, 0, 0}, area = 0;
                int a_texels = 0, b_texels = 0;
                for (int j = 0; j < 8; ++j)
                    for (int i = 0; i < 8; ++i) {
                        const double w = std::max(0.0, std::min(u1, (i + 1) / 8.0) - std::max(u0, i / 8.0)) *
                                         std::max(0.0, std::min(v1, (j + 1) / 8.0) - std::max(v0, j / 8.0));
                        if (w <= 0) continue;
                        const bool is_a = texel_is_a(i, j);
                        (is_a ? a_texels : b_texels) += 1;
                        for (int c = 0; c < 3; ++c) avg[c] += w * (is_a ? lin_a[c] : lin_b[c]);
                        area += w;
                    }
                ASSERT_NEAR(area, 1.0 / 64.0, 1e-9) << "footprint of face " << f;
                const glm::vec4 got = raykit::rk_svo_unpack_color(tree.color[size_t(it->second)]);
                const std::string where = "face " + std::to_string(f) + " cell (" + std::to_string(cell.x) + "," +
                                          std::to_string(cell.y) + "," + std::to_string(cell.z) + ")";
                // A voxel whose texel and neighbours (one texel around, what bilinear filtering
                // reaches) are all one colour must be that colour; others lie between A and B.
                const int ti = int(std::floor((u0 + u1) * 4.0)), tj = int(std::floor((v0 + v1) * 4.0));
                bool pure = true;
                for (int dj = -1; dj <= 1; ++dj)
                    for (int di = -1; di <= 1; ++di) {
                        const int ii = std::min(7, std::max(0, ti + di)), jj = std::min(7, std::max(0, tj + dj));
                        pure = pure && texel_is_a(ii, jj) == texel_is_a(ti, tj);
                    }
                for (int c = 0; c < 3; ++c) {
                    const double want = avg[c] / area;
                    if (pure) {
                        // One 8-bit sRGB step of the stored colour, in linear terms.
                        EXPECT_NEAR(got[c], want, 0.01 * want + 0.002) << where << " channel " << c;
                    } else {
                        EXPECT_GE(got[c], std::min(lin_a[c], lin_b[c]) - 0.003) << where << " channel " << c;
                        EXPECT_LE(got[c], std::max(lin_a[c], lin_b[c]) + 0.003) << where << " channel " << c;
                    }
                }
                (pure ? pure_checked : mixed_checked) += 1;
                EXPECT_NEAR(got.a, 1.0, 1.0 / 255.0) << where;
                const glm::vec3 n = raykit::rk_svo_unpack_normal(tree.normal[size_t(it->second)]);
                EXPECT_GT(glm::dot(n, F.n), 0.999f) << where;
                EXPECT_EQ(raykit::rk_svo_material_id(tree.material[size_t(it->second)]), 0u) << where;
            }
    }
    EXPECT_EQ(pure_checked + mixed_checked, 6 * 64);
    // Texels 0, 1, 2, 5, 6, 7 of each axis are one colour with their neighbours: 6 x 6 per face.
    EXPECT_EQ(pure_checked, 6 * 36);
    // The lid (material 1) is at y = 1.75: cell boundary 26, so layers 25 and 26 hold it.
    const auto lid = attr.find(key(glm::uvec3(15, 26, 15)));
    ASSERT_NE(lid, attr.end());
    EXPECT_EQ(raykit::rk_svo_material_id(tree.material[size_t(lid->second)]), 1u);
    const glm::vec4 lid_colour = raykit::rk_svo_unpack_color(tree.color[size_t(lid->second)]);
    EXPECT_NEAR(lid_colour.r, 0.1, 0.005);
    EXPECT_NEAR(lid_colour.g, 0.4, 0.005);
    EXPECT_NEAR(lid_colour.b, 0.8, 0.005);
}

}  // namespace
