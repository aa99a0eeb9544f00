// raykit samples — rk_png.hpp: PNG output shared by the samples and the GL benchmark
// (stb_image_write). It compiles stb's implementation, so include it from exactly one translation
// unit per executable (every sample is one).
#pragma once

#include <string>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wcast-qual"
#pragma GCC diagnostic ignored "-Wpedantic"
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace rkgl {

/// Writes a width x height RGBA8 image (tightly packed, top row first) to path as PNG.
/// Returns false when the file cannot be written.
inline bool write_png_rgba8(const std::string& path, int width, int height, const void* rgba)
{
    return stbi_write_png(path.c_str(), width, height, 4, rgba, width * 4) != 0;
}

}  // namespace rkgl
