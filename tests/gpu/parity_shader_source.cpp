// raykit/shader_source.hpp on the driver: deliberately broken shaders, resolved with defines and
// includes (nested, in active, inactive and driver-dependent #if blocks, included twice), compiled
// by OpenGL; the driver's error message, passed through raykit::shader_log_with_files, must name
// the file and line where the error was written.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "parity.hpp"
#include "raykit/shader_source.hpp"
#include "shader_mem_files.hpp"

namespace {

// Compiles a fragment shader; returns the info log ("" when it compiled).
std::string compile_log(const std::string& src)
{
    GLuint sh = glCreateShader(GL_FRAGMENT_SHADER);
    const char* p = src.c_str();
    glShaderSource(sh, 1, &p, nullptr);
    glCompileShader(sh);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    std::string log;
    if (!ok) {
        GLint len = 0;
        glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
        log.resize(static_cast<size_t>(len > 1 ? len : 1));
        glGetShaderInfoLog(sh, len, nullptr, &log[0]);
        log.resize(std::strlen(log.c_str()));
        if (log.empty()) log = "(compile failed without a log)";
    }
    glDeleteShader(sh);
    return log;
}

// (file, line) of the first error in a log rewritten by shader_log_with_files: Mesa's
// "file:L(C): error", NVIDIA's "file(L) : error", glslang-style "ERROR: file:L:".
bool first_error(const std::string& log, std::string& file, int& line)
{
    static const std::regex mesa(R"(^(?:ERROR: )?([^\s:(]+):(\d+)(?:\(\d+\))?:\s*error)", std::regex::multiline);
    static const std::regex nv(R"(^([^\s:(]+)\((\d+)\)\s*:\s*error)", std::regex::multiline);
    std::smatch m;
    if (std::regex_search(log, m, mesa) || std::regex_search(log, m, nv)) {
        file = m.str(1);
        line = std::stoi(m.str(2));
        return true;
    }
    return false;
}

std::string filler(int n)
{
    std::string s;
    for (int i = 0; i < n; ++i) s += "float filler_" + std::to_string(i) + "(float x) { return x * " + std::to_string(i) + ".0; }\n";
    return s;
}

}  // namespace

TEST(GpuShaderSource, DriverErrorsNameTheRightFileAndLine)
{
    MemFiles fs;
    // A guarded library, a nested include, a long file only included where the #if is false, and
    // one behind a driver-dependent condition (llvmpipe and every GL 4.5 driver define
    // GL_ARB_compute_shader; nobody defines GL_RK_not_an_extension).
    fs.files["/s/lib.glsl"] = "#ifndef LIB_GLSL\n#define LIB_GLSL\n#include \"deep.glsl\"\nfloat lib(float x) { return deep(x); }\n#endif\n";
    fs.files["/s/deep.glsl"] = "#ifndef DEEP_GLSL\n#define DEEP_GLSL\nfloat deep(float x) { return x + 1.0; }\n#endif\n";
    fs.files["/s/big.glsl"] = filler(1200);
    fs.files["/s/ext.glsl"] = filler(40);
    const std::string main_head =
        "#version 450\n"                                    // 1
        "#extension GL_GOOGLE_include_directive : enable\n"  // 2
        "#include \"lib.glsl\"\n"                           // 3
        "#if RK_MODE == 1\n"                                // 4
        "#include \"big.glsl\"\n"                           // 5
        "#endif\n"                                          // 6
        "#ifdef GL_RK_not_an_extension\n"                   // 7
        "#include \"ext.glsl\"\n"                           // 8
        "#endif\n"                                          // 9
        "#include \"lib.glsl\"\n"                           // 10
        "layout(location = 0) out vec4 o;\n";               // 11
    const std::vector<raykit::ShaderDefine> defines = {{"RK_MODE", "0"}, {"RK_A", "1"}, {"RK_B", "2"},
                                                       {"RK_C", "3"}, {"RK_D", "4"}};
    struct Case {
        const char* what;
        std::string main;
        std::string broken_file;  // which file gets the error ("" = main)
        std::string broken_text;
        std::string want_file;
        int want_line;
    };
    const std::vector<Case> cases = {
        {"error in the main file after defines and includes", main_head + "void main() {\n  o = vec4(undefined_a);\n}\n",
         "", "", "/s/main.frag", 13},
        {"error in a nested include", main_head + "void main() { o = vec4(lib(1.0)); }\n", "/s/deep.glsl",
         "#ifndef DEEP_GLSL\n#define DEEP_GLSL\n\nfloat deep(float x) { return x + undefined_b; }\n#endif\n", "/s/deep.glsl", 4},
        {"error in an include behind a condition the driver takes",
         "#version 450\n#ifdef GL_ARB_compute_shader\n#include \"ext.glsl\"\n#endif\nlayout(location = 0) out vec4 o;\n"
         "void main() { o = vec4(tail(1.0)); }\n",
         "/s/ext.glsl", filler(20) + "float broken() { return undefined_c; }\nfloat tail(float x) { return x; }\n",
         "/s/ext.glsl", 21},
        {"error in the #else branch of a block the driver skips",
         "#version 450\n#ifdef GL_RK_not_an_extension\n#include \"ext.glsl\"\n#else\nfloat e = undefined_e;\n#endif\n"
         "layout(location = 0) out vec4 o;\nvoid main() { o = vec4(e); }\n",
         "", "", "/s/main.frag", 5},
    };
    for (const Case& c : cases) {
        for (const bool unique : {false, true}) {
            MemFiles f = fs;
            f.files["/s/main.frag"] = c.main;
            if (!c.broken_file.empty()) f.files[c.broken_file] = c.broken_text;
            raykit::ShaderSourceOptions opt;
            opt.loader = f.loader();
            opt.defines = defines;
            opt.unique_line_numbers = unique;
            raykit::ShaderSource src;
            raykit::Status st;
            ASSERT_TRUE(raykit::load_shader("/s/main.frag", opt, src, st)) << c.what << ": " << st.message;
            const std::string log = raykit::shader_log_with_files(compile_log(src.text), src.files);
            ASSERT_FALSE(log.empty()) << c.what << ": the broken shader compiled";
            std::string file;
            int line = 0;
            ASSERT_TRUE(first_error(log, file, line)) << c.what << ": no error location in\n" << log;
            EXPECT_EQ(line, c.want_line) << c.what << (unique ? " (unique line numbers)\n" : "\n") << log;
            // With standard numbering the file comes from the source-string number the driver
            // prints, which Mesa gets wrong for some errors (string 0 for an undeclared identifier
            // in any file); unique line numbers name the file on every driver.
            if (unique) {
                EXPECT_EQ(file, c.want_file) << c.what << "\n" << log;
            }
            EXPECT_EQ(src.text.find("filler_1199"), std::string::npos) << c.what << ": big.glsl was inlined";
        }
    }
    // `#line` means "the next line is N" from GLSL 3.30 and ES 3.00 on, "N + 1" before (and without
    // #version): the resolver numbers for the version it reads. An error in the main file after an
    // include and one inside the include, for old and new versions, with and without defines.
    for (const char* version : {"", "#version 150\n", "#version 330\n", "#version 300 es\nprecision highp float;\n"}) {
        for (const bool with_defines : {false, true}) {
            MemFiles f;
            f.files["/s/inc.glsl"] = "float inc_a(float x) { return x; }\nfloat inc_b(float x) { return x + undefined_in_inc; }\n";
            const std::string head = std::string(version) + "#include \"inc.glsl\"\n";
            const int head_lines = static_cast<int>(std::count(head.begin(), head.end(), '\n'));
            for (const bool error_in_include : {false, true}) {
                const bool es = std::string(version).find("es") != std::string::npos, legacy = std::string(version).empty();
                // GLSL 1.10 (no #version) has no `out`: gl_FragColor there.
                f.files["/s/main.frag"] = head + (legacy ? "// (1.10: gl_FragColor)\n" : es ? "out highp vec4 o;\n" : "out vec4 o;\n") +
                                         "\nvoid main() { " + (legacy ? "gl_FragColor" : "o") + " = vec4(" +
                                         (error_in_include ? "inc_a(1.0)" : "undefined_in_main") + "); }\n";
                if (!error_in_include) f.files["/s/inc.glsl"] = "float inc_a(float x) { return x; }\n";
                raykit::ShaderSourceOptions opt;
                opt.loader = f.loader();
                opt.unique_line_numbers = true;
                if (with_defines) opt.defines = {{"RK_A", "1"}, {"RK_B", "2"}};
                raykit::ShaderSource src;
                raykit::Status st;
                ASSERT_TRUE(raykit::load_shader("/s/main.frag", opt, src, st)) << st.message;
                const std::string log = raykit::shader_log_with_files(compile_log(src.text), src.files);
                std::string file;
                int line = 0;
                const std::string what = std::string("version '") + version + "'" + (with_defines ? " with defines" : "") +
                                         (error_in_include ? ", error in the include" : ", error in main");
                ASSERT_TRUE(first_error(log, file, line)) << what << ": no error location in\n" << log << "\n" << src.text;
                EXPECT_EQ(file, error_in_include ? "/s/inc.glsl" : "/s/main.frag") << what << "\n" << log;
                EXPECT_EQ(line, error_in_include ? 2 : head_lines + 3) << what << "\n" << log << "\n" << src.text;
                f.files["/s/inc.glsl"] = "float inc_a(float x) { return x; }\nfloat inc_b(float x) { return x + undefined_in_inc; }\n";
            }
        }
    }
    // The same main file without errors compiles (the resolver's output is valid GLSL).
    MemFiles f = fs;
    f.files["/s/main.frag"] = main_head + "void main() { o = vec4(lib(1.0)); }\n";
    raykit::ShaderSourceOptions opt;
    opt.loader = f.loader();
    opt.defines = defines;
    raykit::ShaderSource src;
    raykit::Status st;
    ASSERT_TRUE(raykit::load_shader("/s/main.frag", opt, src, st)) << st.message;
    EXPECT_EQ(compile_log(src.text), "");
}

TEST(GpuShaderSource, EveryRaykitIncludeCompilesResolved)
{
    // Each shaders/raykit/*.glsl, resolved at run time and compiled by the driver in an empty
    // fragment shader (glslang validates them offline; this checks the resolver's output).
    const std::string dir = parity::shader_dir();
    for (const char* inc : {"raykit/fresnel.glsl", "raykit/tonemap.glsl", "raykit/interior_shading.glsl",
                            "raykit/svo_traverse.glsl", "raykit/svo_secondary.glsl", "raykit/bloom.glsl"}) {
        const std::string main = std::string("#version 450\n#include \"") + inc +
                                 "\"\nlayout(location = 0) out vec4 o;\nvoid main() { o = vec4(1.0); }\n";
        raykit::ShaderSourceOptions opt;
        opt.include_dirs = {dir};
        raykit::ShaderSource src;
        raykit::Status st;
        ASSERT_TRUE(raykit::resolve_shader(main, "main.frag", dir, opt, src, st)) << inc << ": " << st.message;
        EXPECT_EQ(raykit::shader_log_with_files(compile_log(src.text), src.files), "") << inc;
    }
}
