// Built with -fno-exceptions -fno-rtti (tests/CMakeLists.txt), as engines build: every raykit
// header (raykit.hpp includes them all but the opt-in glTF loader, svo_gltf.hpp, which needs
// tinygltf) compiles, and errors reach the caller as statuses or documented empty results.
#include <cstdio>
#include <vector>

#include "raykit/raykit.hpp"

using namespace raykit;

int main()
{
    // A unit cube (12 triangles), voxelised solid at depth 5.
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const std::vector<uint32_t> idx = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                       1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7};
    SvoMesh mesh;
    mesh.positions = &p[0].x;
    mesh.vertex_count = p.size();
    mesh.indices = idx.data();
    mesh.triangle_count = idx.size() / 3;
    SvoBuildOptions opt;
    opt.depth = 5;
    opt.fill = SvoFill::solid;
    opt.attributes = RK_SVO_ATTR_COLOR | RK_SVO_ATTR_MATERIAL;
    SvoTree t;
    SvoStatus st;
    if (!build_svo(mesh, opt, t, st)) {
        std::printf("build failed: %s\n", st.message.c_str());
        return 1;
    }
    // Errors come back as statuses.
    SvoBuildOptions bad = opt;
    bad.depth = 99;
    SvoTree t2;
    SvoStatus st2;
    if (build_svo(mesh, bad, t2, st2) || st2.code != SvoError::invalid_argument) return 2;
    std::vector<uint8_t> bytes;
    SvoTree back;
    if (!svo_save(t, bytes, st) || !svo_load(bytes.data(), bytes.size(), back, st)) return 3;
    bytes.resize(bytes.size() / 2);
    SvoTree cut;
    if (svo_load(bytes.data(), bytes.size(), cut, st2)) return 4;
    // Trace through the middle; refract through the cube (index 1.5).
    const std::vector<uint32_t> words = back.gpu_words();
    const rk_svo_tree tree = svo_trace_tree(back);
    const rk_svo_trace_hit h = rk_svo_trace(words.data(), tree, glm::vec3(-1.0f, 0.5f, 0.5f), glm::vec3(1.0f, 0.0f, 0.0f),
                                            RK_FLT_MAX, glm::vec2(0.0f));
    if (!h.hit) return 5;
    const std::vector<vec4> media = svo_media_table(back);
    const rk_svo_refraction r = rk_svo_refract_through(words.data(), tree, rk_svo_media_ref{back.material.data(), media.data()},
                                                       glm::vec3(-1.0f, 0.5f, 0.5f), glm::vec3(1.0f, 0.1f, 0.0f), 1.0f, 4u);
    if (!r.hit || !r.complete) return 6;
    if (!bake_fresnel_lut_1d(1, 1.5f, FresnelLutMode::single_surface).empty()) return 7;
    if (tonemap_defines(ToneOperator::aces_hill).empty()) return 8;
    // The helpers that used to throw: broken preconditions give empty results and a status.
    Status s;
    if (!gaussian_weights(-1.0f, 3, &s).empty() || s.code != Error::invalid_argument) return 9;
    if (!bloom_chain(0, 0, 8, 4, &s).levels.empty() || s.ok()) return 10;
    if (validate_bloom_params(BloomParams{}, &s) == false || !s.ok()) return 11;
    if (!reduction_chain(5, 5, 1, &s).empty() || s.ok()) return 12;
    if (log_average_luminance(nullptr, 4, 4, 3, {}, &s).count != 0 || s.ok()) return 13;
    InteriorSceneDesc scene;
    scene.furniture_layers = 9;
    if (!interior_defines(scene, &s).empty() || s.ok()) return 14;
    if (interior_atlas_layout(60, 4, 3, &s).size() != 0 || s.ok()) return 15;
    if (generate_env_mips(EnvImage(6, 6), 3, &s).size() != 0 || s.ok()) return 16;
    if (bake_octahedral(EnvCubeMap{}, 16, 0, &s).size != 0 || s.ok()) return 17;
    ShaderSourceOptions so;
    so.include_dirs = {RAYKIT_SHADER_DIR};
    so.defines = {{"RK_TONEMAP_OPERATOR", "1"}};
    ShaderSource src;
    if (!resolve_shader("#version 450\n#include \"raykit/tonemap.glsl\"\n", "t.frag", ".", so, src, s)) return 18;
    if (resolve_shader("#include \"raykit/nope.glsl\"\n", "t.frag", ".", so, src, s) || s.code != Error::not_found) return 19;
    std::printf("raykit headers without exceptions or RTTI: built %llu voxels, traced t = %g, refracted out along (%g, %g, %g)\n",
                static_cast<unsigned long long>(back.voxel_count), double(h.t), double(r.dir.x), double(r.dir.y), double(r.dir.z));
    return 0;
}
