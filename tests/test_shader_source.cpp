// Tests of raykit/shader_source.hpp (run-time include resolution and macro injection) and a lint
// of the shared dialect over every shaders/raykit/*.glsl (docs/dialect.md).
#include <gtest/gtest.h>

#include <dirent.h>

#include <regex>
#include <string>
#include <vector>

#include "raykit/shader_source.hpp"

using raykit::ShaderDefine;

namespace {
const std::string kData = RAYKIT_TEST_DATA_DIR;
const std::string kShaders = RAYKIT_SHADER_DIR;

size_t count(const std::string& s, const std::string& what)
{
    size_t n = 0;
    for (size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
    return n;
}
}  // namespace

TEST(ShaderSource, ResolvesNestedRelativeIncludes)
{
    std::vector<std::string> files;
    const std::string src = "#version 450\n#extension GL_GOOGLE_include_directive : require\n#include \"a.glsl\"\n"
                            "#include \"inc/c.glsl\"\nvoid main() {}\n";
    const std::string out = raykit::resolve_shader_includes(src, "main.comp", kData, {kData + "/inc"}, &files);
    EXPECT_EQ(count(out, "float a()"), 1u);
    EXPECT_EQ(count(out, "float b()"), 1u);
    EXPECT_EQ(count(out, "const float C"), 2u);  // included twice textually; the guard skips one
    EXPECT_EQ(count(out, "#include"), 0u);
    EXPECT_EQ(count(out, "GL_GOOGLE_include_directive"), 0u);
    ASSERT_EQ(files.size(), 5u);  // main, a, b, c (via b), c (via main)
    EXPECT_NE(files[2].find("sub/b.glsl"), std::string::npos);
    // After an include, line numbering resumes at the including file's next line.
    EXPECT_NE(out.find("#line 4 0\n"), std::string::npos);
}

TEST(ShaderSource, MissingIncludeAndRecursionAreClearErrors)
{
    try {
        raykit::resolve_shader_includes("#include \"nope.glsl\"\n", "x.frag", kData, {});
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("x.frag:1: cannot find #include \"nope.glsl\""), std::string::npos) << e.what();
    }
    EXPECT_THROW(raykit::load_shader_file(kData + "/inc/self.glsl", {}), std::runtime_error);
    EXPECT_THROW(raykit::load_shader_file(kData + "/does_not_exist.glsl", {}), std::runtime_error);
}

TEST(ShaderSource, InjectsDefinesAfterVersion)
{
    const std::string out = raykit::inject_shader_defines("// c\n#version 310 es\nvoid main(){}\n",
                                                          {{"RK_A", "3"}, ShaderDefine{"RK_B"}});
    EXPECT_EQ(out, "// c\n#version 310 es\n#define RK_A 3\n#define RK_B 1\n#line 3 0\nvoid main(){}\n");
    EXPECT_EQ(raykit::inject_shader_defines("void main(){}\n", {{"X", "1"}}), "#define X 1\n#line 1 0\nvoid main(){}\n");
    EXPECT_THROW(raykit::inject_shader_defines("#version 450\n", {{"1X", "1"}}), std::invalid_argument);
    EXPECT_THROW(raykit::inject_shader_defines("#version 450\n", {{"A B", "1"}}), std::invalid_argument);
}

TEST(ShaderSource, LoadsRaykitShader)
{
    const std::string out = raykit::load_shader_file(kShaders + "/raykit/fresnel.glsl", {kShaders});
    EXPECT_NE(out.find("rk_fresnel_dielectric_sp"), std::string::npos);
    EXPECT_NE(out.find("rk_saturate"), std::string::npos);  // from common.glsl
}

// The dialect lint: patterns that compile in one language but mean something else (or nothing) in
// the other. Comments are stripped first.
TEST(Dialect, SharedFilesFollowTheRules)
{
    std::vector<std::string> names;
    DIR* d = opendir((kShaders + "/raykit").c_str());
    ASSERT_NE(d, nullptr);
    while (dirent* e = readdir(d)) {
        const std::string n = e->d_name;
        if (n.size() > 5 && n.compare(n.size() - 5, 5, ".glsl") == 0) names.push_back(n);
    }
    closedir(d);
    ASSERT_FALSE(names.empty());
    const std::regex comment(R"(//[^\n]*)");
    const std::regex unsuffixed_float(R"((^|[^\w.])(\d+\.\d*|\.\d+|\d+(?=[eE][-+]?\d))([eE][-+]?\d+)?(?![\w.]))");
    const std::regex swizzle(R"(\.\s*[xyzwrgba]{2,4}\b)");
    const std::regex no_inline(R"(^(float|vec[234]|bool|int|uint|void|mat[234]|ivec[234]|uvec[234]|rk_\w+)\s+rk_\w+\s*\()");
    for (const std::string& n : names) {
        std::string text;
        ASSERT_TRUE(raykit::detail::read_text_file(kShaders + "/raykit/" + n, text));
        std::string base = n.substr(0, n.size() - 5);
        for (char& ch : base) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
        EXPECT_NE(text.find("#ifndef RK_" + base + "_GLSL"), std::string::npos) << n << ": missing include guard";
        const std::string code = std::regex_replace(text, comment, "");
        std::smatch m;
        std::string rest = code;
        int line_scan = 0;
        while (std::regex_search(rest, m, unsuffixed_float)) {
            ADD_FAILURE() << n << ": float literal without f suffix: '" << m.str(2) << "'";
            rest = m.suffix();
            if (++line_scan > 5) break;
        }
        EXPECT_FALSE(std::regex_search(code, m, swizzle)) << n << ": swizzle '" << m.str() << "'";
        std::istringstream lines(code);
        std::string line;
        while (std::getline(lines, line)) {
            EXPECT_FALSE(std::regex_search(line, no_inline)) << n << ": function without RK_INLINE: " << line;
        }
    }
}
