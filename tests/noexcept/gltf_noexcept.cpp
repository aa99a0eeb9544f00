// The opt-in glTF loader as an engine built with -fno-exceptions -fno-rtti compiles it: tinygltf's
// implementation in this translation unit (it and nlohmann::json detect -fno-exceptions), the
// shipped test glTF loaded and voxelised, a missing file and a corrupt one reported as statuses.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "raykit/svo_gltf.hpp"

#include <cstdio>
#include <string>

#include "raykit/svo_build.hpp"

int main()
{
    using namespace raykit;
    SvoMeshData data;
    SvoStatus st;
    if (!load_gltf_mesh(std::string(RAYKIT_TEST_DATA_DIR) + "/svo/textured_box.gltf", data, st)) {
        std::printf("load failed: %s\n", st.message.c_str());
        return 1;
    }
    SvoBuildOptions opt;
    opt.depth = 5;
    SvoTree tree;
    if (!build_svo(data.view(), opt, tree, st) || tree.voxel_count == 0) {
        std::printf("build failed: %s\n", st.message.c_str());
        return 2;
    }
    SvoMeshData none;
    if (load_gltf_mesh(std::string(RAYKIT_TEST_DATA_DIR) + "/svo/does_not_exist.gltf", none, st) || st.ok()) return 3;
    const std::string garbage = "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ {";
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    const bool parsed = loader.LoadASCIIFromString(&model, &err, &warn, garbage.c_str(),
                                                   static_cast<unsigned>(garbage.size()), "");
    if (parsed) return 4;
    std::printf("glTF without exceptions: %llu voxels from the test glTF; a missing file: %s\n",
                static_cast<unsigned long long>(tree.voxel_count), st.message.c_str());
    return 0;
}
