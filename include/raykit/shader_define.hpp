// raykit — shader_define.hpp: ShaderDefine, the feature macro that C++ helpers derive for a shader
// (tonemap_defines(), interior_defines()) and shader_source.hpp or raykit_compile_shaders() inject.
// A header of its own so those helpers do not pull in the include resolver (and its exceptions).
#pragma once

#include <string>

namespace raykit {

/// A feature macro to inject: `#define name value`.
struct ShaderDefine {
    std::string name;
    std::string value = "1";
};

}  // namespace raykit
