// Tests of raykit/shader_source.hpp (run-time include resolution and macro injection) and a lint
// of the shared dialect over every shaders/raykit/*.glsl (docs/dialect.md).
#include <gtest/gtest.h>

#include <dirent.h>

#include <algorithm>
#include <cstdio>
#include <cctype>
#include <map>
#include <set>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "raykit/shader_source.hpp"
#include "glsl_scan.hpp"
#include "shader_mem_files.hpp"

using raykit::Error;
using raykit::ShaderDefine;
using raykit::ShaderSource;
using raykit::ShaderSourceOptions;
using raykit::Status;

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
    Status st;
    const std::string out = raykit::resolve_shader_includes(src, "main.comp", kData, {kData + "/inc"}, &files, &st);
    ASSERT_TRUE(st.ok()) << st.message;
    EXPECT_EQ(count(out, "float a()"), 1u);
    EXPECT_EQ(count(out, "float b()"), 1u);
    // c.glsl is reached twice (through b.glsl as "../c.glsl" and from main as "inc/c.glsl"): one
    // file, guarded, so it is inlined once.
    EXPECT_EQ(count(out, "const float C"), 1u);
    EXPECT_EQ(count(out, "#include"), 0u);
    EXPECT_EQ(count(out, "GL_GOOGLE_include_directive"), 0u);
    ASSERT_EQ(files.size(), 4u);  // main, a, b, c
    EXPECT_NE(files[2].find("sub/b.glsl"), std::string::npos);
    EXPECT_EQ(files[3], kData + "/inc/c.glsl");  // normalised: no "sub/.."
    // After an include, line numbering resumes at the including file's next line.
    EXPECT_NE(out.find("#line 4 0\n"), std::string::npos);
}

namespace {
// What a driver's preprocessor reports for each output line when every region is active: `#line L
// F` makes the next line L of string F (GLSL >= 3.30 and ES 3.00, as C). Returns, for each marker
// "@name:k" found in the output, the (string, line) the driver gives it.
std::map<std::string, std::pair<int, int>> driver_lines(const std::string& text)
{
    std::map<std::string, std::pair<int, int>> at;
    std::istringstream in(text);
    std::string line;
    int f = 0, l = 1;
    while (std::getline(in, line)) {
        int L = 0, F = 0;
        if (std::sscanf(line.c_str(), "#line %d %d", &L, &F) == 2) {
            l = L;
            f = F;
            continue;
        }
        const size_t m = line.find("@");
        if (m != std::string::npos) at[line.substr(m + 1)] = {f, l};
        ++l;
    }
    return at;
}
}  // namespace

TEST(ShaderSource, LineNumbersSurviveDefinesAndIncludes)
{
    MemFiles mem;
    mem.files["/s/lib.glsl"] = "#ifndef LIB\n#define LIB\n@lib:3\n#include \"deep.glsl\"\n@lib:5\n#endif\n";
    mem.files["/s/deep.glsl"] = "@deep:1\n\n@deep:3\n";
    mem.files["/s/main.frag"] = "// header comment naming #version 100 in prose\n#version 450\n@main:3\n"
                                "#include \"lib.glsl\"\n@main:5\n#include \"lib.glsl\"\n@main:7\n";
    ShaderSourceOptions opt;
    opt.loader = mem.loader();
    opt.defines = {{"RK_A", "1"}, {"RK_B", "2"}, {"RK_C", "3"}, {"RK_D", "4"}, {"RK_E", "5"}};
    ShaderSource out;
    Status st;
    ASSERT_TRUE(load_shader("/s/main.frag", opt, out, st)) << st.message;
    // The defines follow the #version directive, not the mention of #version in the comment.
    EXPECT_LT(out.text.find("#version 450"), out.text.find("#define RK_A 1"));
    ASSERT_EQ(out.files.size(), 3u);  // main, lib (once: its guard is defined the second time), deep
    const auto at = driver_lines(out.text);
    for (const auto& want : std::vector<std::pair<std::string, std::pair<int, int>>>{
             {"main:3", {0, 3}}, {"main:5", {0, 5}}, {"main:7", {0, 7}}, {"lib:3", {1, 3}}, {"lib:5", {1, 5}},
             {"deep:1", {2, 1}}, {"deep:3", {2, 3}}}) {
        ASSERT_TRUE(at.count(want.first)) << want.first;
        EXPECT_EQ(at.at(want.first), want.second) << want.first;
    }
    EXPECT_EQ(out.files[1], "/s/lib.glsl");
    // Unique numbering: string F's lines start at F * RK_SHADER_LINE_STRIDE + 1.
    opt.unique_line_numbers = true;
    ASSERT_TRUE(load_shader("/s/main.frag", opt, out, st)) << st.message;
    const auto uat = driver_lines(out.text);
    EXPECT_EQ(uat.at("main:7"), (std::pair<int, int>{0, 7}));
    EXPECT_EQ(uat.at("lib:5"), (std::pair<int, int>{1, 100005}));
    EXPECT_EQ(uat.at("deep:3"), (std::pair<int, int>{2, 200003}));
    opt.unique_line_numbers = false;
    // The same through inject_shader_defines first (its #line is honoured by the resolver).
    const std::string injected = raykit::inject_shader_defines(mem.files["/s/main.frag"], opt.defines);
    ShaderSourceOptions no_defines;
    no_defines.loader = opt.loader;
    ASSERT_TRUE(resolve_shader(injected, "/s/main.frag", "/s", no_defines, out, st)) << st.message;
    EXPECT_EQ(driver_lines(out.text).at("main:7"), (std::pair<int, int>{0, 7}));
    EXPECT_EQ(driver_lines(out.text).at("lib:5"), (std::pair<int, int>{1, 5}));
}

TEST(ShaderSource, IncludesOnlyInActiveBlocks)
{
    // Each expression picks yes.glsl or no.glsl; the expected branch is C's (and glslang's).
    struct Case {
        const char* expr;
        bool yes;
    };
    const Case cases[] = {
        {"1", true},
        {"0", false},
        {"RK_MODE == 2", true},
        {"RK_MODE == 1", false},
        {"RK_MODE * 3 + 1 == 7 && !defined(RK_NOPE)", true},
        {"defined RK_MODE && RK_MODE > 1", true},
        {"(RK_MODE << 4) == 0x20", true},
        {"RK_UNDEFINED_NAME", false},  // an undefined identifier is 0
        {"RK_ALIAS == 2", true},       // RK_ALIAS -> RK_MODE -> 2
        {"-1 < 0", true},
        {"~0 == -1", true},
        {"10 / 3 == 3 && 10 % 3 == 1", true},
        {"(1 || RK_UNDEFINED_NAME) && !(0 && 1)", true},
        {"RK_MODE != 2 || 0", false},
        {"017 == 15", true},
        {"4u == 4", true},
    };
    for (const Case& c : cases) {
        MemFiles mem;
        mem.files["/s/yes.glsl"] = "float yes;\n";
        mem.files["/s/no.glsl"] = "float no;\n";
        const std::string src = std::string("#version 450\n#define RK_ALIAS RK_MODE\n#if ") + c.expr +
                                "\n#include \"yes.glsl\"\n#else\n#include \"no.glsl\"\n#endif\n";
        ShaderSourceOptions opt;
        opt.loader = mem.loader();
        opt.defines = {{"RK_MODE", "2"}};
        ShaderSource out;
        Status st;
        ASSERT_TRUE(resolve_shader(src, "m.frag", "/s", opt, out, st)) << c.expr << ": " << st.message;
        EXPECT_EQ(mem.was_read("/s/yes.glsl"), c.yes) << c.expr;
        EXPECT_EQ(mem.was_read("/s/no.glsl"), !c.yes) << c.expr;
    }
    // An include in an inactive block is neither read nor required (glslang's behaviour).
    MemFiles mem;
    ShaderSourceOptions opt;
    opt.loader = mem.loader();
    ShaderSource out;
    Status st;
    EXPECT_TRUE(resolve_shader("#version 450\n#if 0\n#include \"missing.glsl\"\n#endif\n#ifdef RK_OFF\n"
                               "#include \"missing.glsl\"\n#elif 1\nfloat x;\n#else\n#include \"missing.glsl\"\n#endif\n",
                               "m.frag", "/s", opt, out, st))
        << st.message;
    EXPECT_TRUE(mem.read.empty());
    // #undef and nested blocks are followed.
    mem.files["/s/yes.glsl"] = "float yes;\n";
    EXPECT_TRUE(resolve_shader("#define X 1\n#undef X\n#ifdef X\n#include \"missing.glsl\"\n#endif\n#if 1\n#if 0\n"
                               "#include \"missing.glsl\"\n#endif\n#include \"yes.glsl\"\n#endif\n",
                               "m.frag", "/s", opt, out, st))
        << st.message;
    EXPECT_TRUE(mem.was_read("/s/yes.glsl"));
}

TEST(ShaderSource, UndecidableConditionsKeepLineNumbers)
{
    // GL_ARB_* macros depend on the driver: the include is inlined ("maybe"), and after the block
    // a #line puts the including file back on its own numbering whichever branch the driver took.
    MemFiles mem;
    mem.files["/s/ext.glsl"] = "float e0;\nfloat e1;\nfloat e2;\n";
    const std::string src = "#version 450\n#ifdef GL_ARB_gpu_shader_int64\n#include \"ext.glsl\"\n#else\n"
                            "float fallback;\n#endif\n@main:7\n";
    ShaderSourceOptions opt;
    opt.loader = mem.loader();
    ShaderSource out;
    Status st;
    ASSERT_TRUE(resolve_shader(src, "m.frag", "/s", opt, out, st)) << st.message;
    EXPECT_TRUE(mem.was_read("/s/ext.glsl"));
    EXPECT_NE(out.text.find("#endif\n#line 7 0\n@main:7"), std::string::npos) << out.text;
    EXPECT_NE(out.text.find("#else\n#line 5 0\nfloat fallback;"), std::string::npos) << out.text;
    // A guard defined only inside an undecidable block does not make a later include skip.
    mem.files["/s/g.glsl"] = "#ifndef G\n#define G\nfloat g;\n#endif\n";
    ASSERT_TRUE(resolve_shader("#if defined(GL_EXT_x)\n#include \"g.glsl\"\n#endif\n#include \"g.glsl\"\n", "m.frag",
                               "/s", opt, out, st))
        << st.message;
    EXPECT_EQ(count(out.text, "float g;"), 2u);
}

// Cases an independent review found: a backslash-continued #include, a "guard" with an #else, the
// version's own predefined macros, __LINE__, and an empty source folder.
TEST(ShaderSource, ReviewFindings)
{
    MemFiles mem;
    mem.files["/s/a.glsl"] = "float a_fn;\n";
    mem.files["a.glsl"] = "float a_fn;\n";
    mem.files["/s/alt.glsl"] = "#ifndef ALT\n#define ALT\nfloat first;\n#else\nfloat second;\n#endif\n";
    ShaderSourceOptions opt;
    opt.loader = mem.loader();
    ShaderSource out;
    Status st;
    // The continuation line of an #include is consumed, not emitted as code.
    ASSERT_TRUE(resolve_shader("#version 450\n#include \\\n  \"a.glsl\"\n@main:4\n", "m.frag", "/s", opt, out, st)) << st.message;
    EXPECT_EQ(out.text.find("  \"a.glsl\""), std::string::npos) << out.text;
    EXPECT_EQ(count(out.text, "float a_fn;"), 1u);
    EXPECT_EQ(driver_lines(out.text).at("main:4"), (std::pair<int, int>{0, 4}));
    // An #ifndef ... #else ... #endif file is not a guard: included twice, both halves appear.
    ASSERT_TRUE(resolve_shader("#include \"alt.glsl\"\n#include \"alt.glsl\"\n", "m.frag", "/s", opt, out, st)) << st.message;
    EXPECT_EQ(std::count(out.files.begin(), out.files.end(), std::string("/s/alt.glsl")), 2);  // inlined both times
    // Under #version 450, GL_ES is known to be undefined: the include is not required.
    EXPECT_TRUE(resolve_shader("#version 450\n#ifdef GL_ES\n#include \"missing.glsl\"\n#endif\n", "m.frag", "/s", opt, out, st))
        << st.message;
    EXPECT_FALSE(resolve_shader("#version 300 es\n#ifdef GL_ES\n#include \"missing.glsl\"\n#endif\n", "m.frag", "/s", opt, out, st));
    // __LINE__ is undecidable (its value is not tracked), so the include is read; __VERSION__
    // without #version is 110.
    mem.read.clear();
    EXPECT_TRUE(resolve_shader("#if __LINE__ > 1\n#include \"a.glsl\"\n#endif\n", "m.frag", "/s", opt, out, st)) << st.message;
    EXPECT_TRUE(mem.was_read("/s/a.glsl"));
    mem.read.clear();
    EXPECT_TRUE(resolve_shader("#if __VERSION__ == 110\n#include \"a.glsl\"\n#endif\n", "m.frag", "/s", opt, out, st)) << st.message;
    EXPECT_TRUE(mem.was_read("/s/a.glsl"));
    // A `//` comment ending in a backslash continues on the next line (the preprocessor splices
    // it): the #include there is commented out. CR-only line endings count as lines.
    mem.read.clear();
    EXPECT_TRUE(resolve_shader("// note \\\n#include \"missing.glsl\"\nfloat x;\n", "m.frag", "/s", opt, out, st)) << st.message;
    EXPECT_TRUE(mem.read.empty());
    ASSERT_TRUE(resolve_shader("#version 450\r#include \"a.glsl\"\r@main:3\r", "m.frag", "/s", opt, out, st)) << st.message;
    EXPECT_EQ(count(out.text, "float a_fn;"), 1u);
    EXPECT_EQ(driver_lines(out.text).at("main:3"), (std::pair<int, int>{0, 3}));
    // An empty source folder searches the bare name, not the filesystem root.
    mem.read.clear();
    EXPECT_TRUE(resolve_shader("#include \"a.glsl\"\n", "m.frag", "", opt, out, st)) << st.message;
    ASSERT_FALSE(mem.read.empty());
    EXPECT_EQ(mem.read[0], "a.glsl");
}

TEST(ShaderSource, GuardedFilesOnceUnguardedEveryTime)
{
    MemFiles mem;
    mem.files["/s/guarded.glsl"] = "// leading comment\n#ifndef GUARDED_GLSL\n#define GUARDED_GLSL\nfloat g;\n#endif // trailing\n";
    mem.files["/s/plain.glsl"] = "p += 1.0;\n";
    // Not a whole-file guard: code after the #endif.
    mem.files["/s/partial.glsl"] = "#ifndef PARTIAL\n#define PARTIAL\nfloat q;\n#endif\nfloat r;\n";
    ShaderSourceOptions opt;
    opt.loader = mem.loader();
    ShaderSource out;
    Status st;
    ASSERT_TRUE(resolve_shader("#include \"guarded.glsl\"\n#include \"guarded.glsl\"\n#include \"plain.glsl\"\n"
                               "#include \"plain.glsl\"\n#include \"partial.glsl\"\n#include \"partial.glsl\"\n",
                               "m.frag", "/s", opt, out, st))
        << st.message;
    EXPECT_EQ(count(out.text, "float g;"), 1u);
    EXPECT_EQ(count(out.text, "p += 1.0;"), 2u);
    EXPECT_EQ(count(out.text, "float r;"), 2u);
    EXPECT_EQ(out.files.size(), 6u);  // main, guarded, plain, plain, partial, partial
    // Skipping a guarded file needs its guard defined: after an #undef it is inlined again.
    ASSERT_TRUE(resolve_shader("#include \"guarded.glsl\"\n#undef GUARDED_GLSL\n#include \"guarded.glsl\"\n", "m.frag",
                               "/s", opt, out, st))
        << st.message;
    EXPECT_EQ(count(out.text, "float g;"), 2u);
}

TEST(ShaderSource, SampleMaterialResolvesToItsPreprocessedSize)
{
    // The sample interior material, every feature on: each raykit file once, comments blanked
    // (it was 386 KB with common.glsl inlined 16 times; 61 KB now).
    const std::string samples = RAYKIT_SAMPLES_DIR;
    ShaderSourceOptions opt;
    opt.include_dirs = {kShaders};
    opt.defines = {{"RK_IM_SHADING", "1"}, {"RK_IM_ROOM_LIGHTS", "1"}, {"RK_IM_FURNITURE_LAYERS", "2"},
                   {"RK_IM_REFLECTION", "1"}, {"RK_IM_FADE", "1"}, {"RK_IM_BUILDING_OUTPUT", "1"}};
    ShaderSource out;
    Status st;
    ASSERT_TRUE(load_shader(samples + "/common/interior_building.frag", opt, out, st)) << st.message;
    std::map<std::string, int> seen;
    for (const std::string& f : out.files) ++seen[f];
    for (const auto& kv : seen) EXPECT_EQ(kv.second, 1) << kv.first << " inlined " << kv.second << " times";
    EXPECT_EQ(seen.count(kShaders + "/raykit/common.glsl"), 1u);
    EXPECT_LT(out.text.size(), 80u * 1024u) << out.text.size();
    EXPECT_EQ(out.text.find("//"), std::string::npos);  // comments are blanked
}

TEST(ShaderSource, ErrorsAreStatusesNamingFileAndLine)
{
    Status st;
    EXPECT_EQ(raykit::resolve_shader_includes("#version 450\n\n#include \"nope.glsl\"\n", "x.frag", kData, {}, nullptr, &st), "");
    EXPECT_EQ(st.code, Error::not_found);
    EXPECT_NE(st.message.find("x.frag:3: cannot find #include \"nope.glsl\""), std::string::npos) << st.message;
    EXPECT_EQ(raykit::load_shader_file(kData + "/inc/self.glsl", {}, {}, nullptr, &st), "");
    EXPECT_EQ(st.code, Error::syntax);
    EXPECT_NE(st.message.find("deeper than 32"), std::string::npos) << st.message;
    EXPECT_EQ(raykit::load_shader_file(kData + "/does_not_exist.glsl", {}, {}, nullptr, &st), "");
    EXPECT_EQ(st.code, Error::io);
    ShaderSourceOptions opt;
    ShaderSource out;
    EXPECT_FALSE(resolve_shader("#if 1\nfloat x;\n", "u.frag", ".", opt, out, st));
    EXPECT_EQ(st.code, Error::syntax);
    EXPECT_NE(st.message.find("u.frag: #if without #endif"), std::string::npos) << st.message;
    EXPECT_FALSE(resolve_shader("float x;\n#endif\n", "u.frag", ".", opt, out, st));
    EXPECT_NE(st.message.find("u.frag:2: #endif without"), std::string::npos) << st.message;
    EXPECT_FALSE(resolve_shader("#if 1\n#else\n#else\n#endif\n", "u.frag", ".", opt, out, st));
    EXPECT_FALSE(resolve_shader("#include nope.glsl\n", "u.frag", ".", opt, out, st));
    EXPECT_NE(st.message.find("u.frag:1: malformed #include"), std::string::npos) << st.message;
    opt.defines = {{"1X", "1"}};
    EXPECT_FALSE(resolve_shader("void main(){}\n", "u.frag", ".", opt, out, st));
    EXPECT_EQ(st.code, Error::invalid_argument);
    EXPECT_TRUE(out.text.empty());
    // A commented-out include is not an include.
    opt.defines.clear();
    EXPECT_TRUE(resolve_shader("// #include \"nope.glsl\"\n/* \n#include \"nope.glsl\"\n*/\n", "u.frag", ".", opt, out, st))
        << st.message;
}

TEST(ShaderSource, InjectsDefinesAfterVersion)
{
    const std::string out = raykit::inject_shader_defines("// c\n#version 310 es\nvoid main(){}\n",
                                                          {{"RK_A", "3"}, ShaderDefine{"RK_B"}});
    EXPECT_EQ(out, "// c\n#version 310 es\n#define RK_A 3\n#define RK_B 1\n#line 3 0\nvoid main(){}\n");
    // No #version is GLSL 1.10, where `#line N` makes the next line N + 1: "#line 0" for line 1.
    EXPECT_EQ(raykit::inject_shader_defines("void main(){}\n", {{"X", "1"}}), "#define X 1\n#line 0 0\nvoid main(){}\n");
    EXPECT_EQ(raykit::inject_shader_defines("#version 150\nvoid main(){}\n", {{"X", "1"}}),
              "#version 150\n#define X 1\n#line 1 0\nvoid main(){}\n");
    // "#version" inside a comment is not the directive.
    EXPECT_EQ(raykit::inject_shader_defines("/* #version 100 */\n#version 450\n", {{"X", "1"}}),
              "/* #version 100 */\n#version 450\n#define X 1\n#line 3 0\n");
    Status st;
    EXPECT_EQ(raykit::inject_shader_defines("#version 450\n", {{"1X", "1"}}, &st), "");
    EXPECT_EQ(st.code, Error::invalid_argument);
    EXPECT_EQ(raykit::inject_shader_defines("#version 450\n", {{"A B", "1"}}, &st), "");
    EXPECT_EQ(raykit::inject_shader_defines("#version 450\n", {{"A", "1\n#define B 2"}}, &st), "");
}

TEST(ShaderSource, LogsNameFiles)
{
    const std::vector<std::string> files = {"main.frag", "raykit/fresnel.glsl"};
    EXPECT_EQ(raykit::shader_log_with_files("1:12(5): error: `x' undeclared\n0:3(1): warning: w\n", files),
              "raykit/fresnel.glsl:12(5): error: `x' undeclared\nmain.frag:3(1): warning: w\n");  // Mesa
    EXPECT_EQ(raykit::shader_log_with_files("1(12) : error C1008: undefined variable \"x\"", files),
              "raykit/fresnel.glsl(12) : error C1008: undefined variable \"x\"");  // NVIDIA
    EXPECT_EQ(raykit::shader_log_with_files("ERROR: 1:12: 'x' : undeclared identifier\n", files),
              "ERROR: raykit/fresnel.glsl:12: 'x' : undeclared identifier\n");  // glslang, ANGLE
    // Unique line numbers (ShaderSourceOptions::unique_line_numbers) name the file whatever the
    // string number says.
    EXPECT_EQ(raykit::shader_log_with_files("0:100012(5): error: `x' undeclared\n0:7(1): error: e", files),
              "raykit/fresnel.glsl:12(5): error: `x' undeclared\nmain.frag:7(1): error: e");
    EXPECT_EQ(raykit::shader_log_with_files("0(100012) : error C1008", files), "raykit/fresnel.glsl(12) : error C1008");
    // Unknown string numbers and other text are left alone.
    EXPECT_EQ(raykit::shader_log_with_files("7:1(1): error\nlink failed\n", files), "7:1(1): error\nlink failed\n");
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

// The README's macro table lists every option macro (each `#ifndef RK_X / #define RK_X` default
// in shaders/raykit/*.glsl, include guards aside).
TEST(Dialect, ReadmeListsEveryOptionMacro)
{
    std::string readme;
    ASSERT_TRUE(raykit::detail::read_text_file(std::string(RAYKIT_SAMPLES_DIR) + "/../README.md", readme));
    DIR* d = opendir((kShaders + "/raykit").c_str());
    ASSERT_NE(d, nullptr);
    const std::regex option(R"(#ifndef (RK_[A-Z0-9_]+)\n#define \1)");
    int n = 0;
    while (dirent* e = readdir(d)) {
        const std::string name = e->d_name;
        if (name.size() < 6 || name.compare(name.size() - 5, 5, ".glsl") != 0) continue;
        std::string text;
        ASSERT_TRUE(raykit::detail::read_text_file(kShaders + "/raykit/" + name, text));
        for (std::sregex_iterator it(text.begin(), text.end(), option), end; it != end; ++it) {
            const std::string m = (*it)[1];
            if (m.size() > 5 && m.compare(m.size() - 5, 5, "_GLSL") == 0) continue;
            ++n;
            EXPECT_TRUE(readme.find("`" + m + "`") != std::string::npos || readme.find("`" + m + "(") != std::string::npos)
                << name << ": " << m << " is not in the README's macro table";
        }
    }
    closedir(d);
    EXPECT_GE(n, 29);
}

using rktest::cpp_view;

// The one-definition rule by construction: every function of a file that C++ compiles whose body
// depends on an option macro, directly or through a macro or function that does, sits between
// RK_CONFIGURED_BEGIN and RK_CONFIGURED_END (an inline namespace named after the values in C++).
// Files a header wraps whole in such a namespace (svo_traverse, svo_secondary) are exempt.
TEST(Dialect, MacroDependentFunctionsAreConfigured)
{
    const std::string inc = std::string(RAYKIT_SAMPLES_DIR) + "/../include/raykit";
    std::map<std::string, std::string> files;  // name -> text
    DIR* d = opendir((kShaders + "/raykit").c_str());
    ASSERT_NE(d, nullptr);
    while (dirent* e = readdir(d)) {
        const std::string n = e->d_name;
        if (n.size() > 5 && n.compare(n.size() - 5, 5, ".glsl") == 0) {
            ASSERT_TRUE(raykit::detail::read_text_file(kShaders + "/raykit/" + n, files[n]));
        }
    }
    closedir(d);
    // Which files C++ compiles (included by a header, or by such a file), and which are wrapped.
    std::set<std::string> cpp, wrapped;
    d = opendir(inc.c_str());
    ASSERT_NE(d, nullptr);
    const std::regex hpp_include(R"(#include "raykit/(\w+\.glsl)\")");
    while (dirent* e = readdir(d)) {
        const std::string n = e->d_name;
        if (n.size() < 5 || n.compare(n.size() - 4, 4, ".hpp") != 0) continue;
        std::string t;
        ASSERT_TRUE(raykit::detail::read_text_file(inc + "/" + n, t));
        for (std::sregex_iterator it(t.begin(), t.end(), hpp_include), end; it != end; ++it) {
            cpp.insert((*it)[1]);
            const std::string before = t.substr(0, static_cast<size_t>(it->position()));
            const size_t prev = before.find_last_of('\n', before.size() >= 2 ? before.size() - 2 : 0);
            if (before.find("inline namespace", prev == std::string::npos ? 0 : prev) != std::string::npos) wrapped.insert((*it)[1]);
        }
    }
    closedir(d);
    const std::regex glsl_include(R"(#include "(\w+\.glsl)\")");
    for (bool grew = true; grew;) {
        grew = false;
        for (const std::string& f : std::set<std::string>(cpp)) {
            for (std::sregex_iterator it(files[f].begin(), files[f].end(), glsl_include), end; it != end; ++it) {
                grew = cpp.insert((*it)[1]).second || grew;
            }
        }
    }
    EXPECT_TRUE(cpp.count("tonemap.glsl") && cpp.count("interior_mapping.glsl") && wrapped.count("svo_traverse.glsl"));
    // Option macros, and macros defined from them.
    std::set<std::string> macros;
    const std::regex option(R"(#ifndef (RK_[A-Z0-9_]+)\n#define \1)");
    const std::regex define(R"(#define (RK_[A-Z0-9_]+)[ (]([^\n]*))");
    for (const auto& kv : files) {
        for (std::sregex_iterator it(kv.second.begin(), kv.second.end(), option), end; it != end; ++it) {
            const std::string m = (*it)[1];
            if (m.size() < 5 || m.compare(m.size() - 5, 5, "_GLSL") != 0) macros.insert(m);
        }
    }
    auto mentions = [](const std::string& text, const std::string& word) {
        for (size_t p = text.find(word); p != std::string::npos; p = text.find(word, p + 1)) {
            const bool l = p == 0 || !(std::isalnum(static_cast<unsigned char>(text[p - 1])) || text[p - 1] == '_');
            const size_t q = p + word.size();
            const bool r = q >= text.size() || !(std::isalnum(static_cast<unsigned char>(text[q])) || text[q] == '_');
            if (l && r) return true;
        }
        return false;
    };
    for (bool grew = true; grew;) {
        grew = false;
        for (const std::string& f : cpp) {
            const std::string code = cpp_view(std::regex_replace(files[f], std::regex(R"(//[^\n]*)"), ""));
            for (std::sregex_iterator it(code.begin(), code.end(), define), end; it != end; ++it) {
                const std::string name = (*it)[1], body = (*it)[2];
                if (macros.count(name) || name.rfind("RK_NS_", 0) == 0) continue;
                for (const std::string& m : std::set<std::string>(macros)) {
                    if (mentions(body, m)) grew = macros.insert(name).second || grew;
                }
            }
        }
    }
    // Functions, their dependence, and whether each is configured.
    struct Fn {
        std::string file, body;
        bool configured;
        bool depends = false;
    };
    std::map<std::string, Fn> fns;
    const std::regex fn(R"(RK_INLINE\s+\w+\s+(\w+)\s*\()");
    for (const std::string& f : cpp) {
        if (wrapped.count(f)) continue;
        const std::string code = cpp_view(std::regex_replace(files[f], std::regex(R"(//[^\n]*)"), ""));
        for (std::sregex_iterator it(code.begin(), code.end(), fn), end; it != end; ++it) {
            const size_t at = static_cast<size_t>(it->position());
            const size_t open = code.find('{', at), semi = code.find(';', at);
            if (open == std::string::npos || semi < open) continue;  // a declaration
            int depth = 0;
            size_t close = open;
            for (; close < code.size(); ++close) {
                depth += code[close] == '{' ? 1 : (code[close] == '}' ? -1 : 0);
                if (depth == 0) break;
            }
            const std::string pre = code.substr(0, at);
            const size_t b = pre.rfind("RK_CONFIGURED_BEGIN"), e = pre.rfind("RK_CONFIGURED_END");
            const bool configured = b != std::string::npos && (e == std::string::npos || e < b);
            fns[(*it)[1]] = Fn{f, code.substr(at, close - at + 1), configured};
        }
    }
    for (auto& kv : fns) {
        for (const std::string& m : macros) kv.second.depends = kv.second.depends || mentions(kv.second.body, m);
    }
    for (bool grew = true; grew;) {
        grew = false;
        for (auto& kv : fns) {
            if (kv.second.depends) continue;
            for (const auto& other : fns) {
                if (other.second.depends && other.first != kv.first && mentions(kv.second.body, other.first)) {
                    kv.second.depends = grew = true;
                    break;
                }
            }
        }
    }
    int configured = 0;
    for (const auto& kv : fns) {
        if (kv.second.depends) {
            ++configured;
            EXPECT_TRUE(kv.second.configured) << kv.second.file << ": " << kv.first
                                              << " depends on an option macro but is outside RK_CONFIGURED_BEGIN/END";
        }
    }
    EXPECT_GE(configured, 14);
}
