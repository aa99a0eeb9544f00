// raykit consumer check: the CPU headers work from an installed/added raykit, and the shader
// compiled by raykit_compile_shaders() is SPIR-V with a depfile that lists raykit's include.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include <raykit/raykit.hpp>

static bool is_spirv(const char* path)
{
    std::ifstream f(path, std::ios::binary);
    std::uint32_t magic = 0;
    f.read(reinterpret_cast<char*>(&magic), sizeof magic);
    return f && magic == 0x07230203u;
}

int main(int argc, char** argv)
{
    if (argc < 4) return 2;
    const float f0 = raykit::rk_f0_from_eta(1.52f);
    std::printf("F0(1.52) = %.7f, two panes = %.7f\n", static_cast<double>(f0),
                static_cast<double>(raykit::rk_fresnel_glazing(f0, 2.0f)));
    if (f0 < 0.04257f || f0 > 0.04259f) return 1;
    if (!is_spirv(argv[1]) || !is_spirv(argv[3])) {
        std::printf("not SPIR-V: %s or %s\n", argv[1], argv[3]);
        return 1;
    }
    std::ifstream d(argv[2]);
    const std::string dep((std::istreambuf_iterator<char>(d)), std::istreambuf_iterator<char>());
    if (dep.find("raykit/fresnel.glsl") == std::string::npos || dep.find("raykit/common.glsl") == std::string::npos) {
        std::printf("depfile %s does not list raykit's includes:\n%s\n", argv[2], dep.c_str());
        return 1;
    }
    // raykit_compile_shaders with other DEFINES, FLAGS or a VARIANT: distinct files, distinct code.
    if (argc < 7) return 2;
    const std::string names[4] = {argv[1], argv[4], argv[5], argv[6]};
    std::string code[4];
    for (int i = 0; i < 4; ++i) {
        if (!is_spirv(names[i].c_str())) {
            std::printf("not SPIR-V: %s\n", names[i].c_str());
            return 1;
        }
        std::ifstream f(names[i], std::ios::binary);
        code[i].assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
        for (int j = 0; j < i; ++j) {
            if (names[i] == names[j] || code[i] == code[j]) {
                std::printf("variants %s and %s share a file or its code\n", names[j].c_str(), names[i].c_str());
                return 1;
            }
        }
    }
    if (names[3].find("window.comp.mode2.spv") == std::string::npos) {
        std::printf("VARIANT mode2 not in the output name: %s\n", names[3].c_str());
        return 1;
    }
    // The sample interior material (both stages, OpenGL and Vulkan).
    if (argc != 11) {
        std::printf("expected 4 material SPIR-V files, got %d arguments\n", argc - 7);
        return 1;
    }
    for (int i = 7; i < 11; ++i) {
        if (!is_spirv(argv[i])) {
            std::printf("not SPIR-V: %s\n", argv[i]);
            return 1;
        }
    }
    std::printf("consumer ok: SPIR-V for Vulkan and OpenGL, depfile lists raykit includes, 4 distinct variants, "
                "the interior material for both\n");
    return 0;
}
