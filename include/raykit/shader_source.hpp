// raykit — shader_source.hpp: load GLSL that #includes raykit for drivers that cannot.
//
// glslang/glslc resolve `#include "raykit/fresnel.glsl"` offline (GL_GOOGLE_include_directive, see
// raykit_compile_shaders() in CMake). An OpenGL driver compiling GLSL at run time does not, so this
// header inlines the includes on the CPU and injects feature macros after #version. Pure C++17,
// no GL dependency.
#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "raykit/shader_define.hpp"

namespace raykit {

namespace detail {

inline bool read_text_file(const std::string& path, std::string& out)
{
    std::ifstream f(path, std::ios::binary);
    if (!f) return false;
    std::ostringstream ss;
    ss << f.rdbuf();
    out = ss.str();
    return true;
}

inline std::string dir_of(const std::string& path)
{
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

inline std::string trim_left(const std::string& s)
{
    size_t i = 0;
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    return s.substr(i);
}

// Parses `#include "name"` (spaces allowed after '#'); returns false for any other line.
inline bool parse_include(const std::string& line, std::string& name)
{
    std::string t = trim_left(line);
    if (t.empty() || t[0] != '#') return false;
    t = trim_left(t.substr(1));
    if (t.compare(0, 7, "include") != 0) return false;
    t = trim_left(t.substr(7));
    if (t.size() < 2 || t[0] != '"') return false;
    const size_t close = t.find('"', 1);
    if (close == std::string::npos) return false;
    name = t.substr(1, close - 1);
    return true;
}

inline void resolve_into(const std::string& text, const std::string& file, const std::string& dir,
                         const std::vector<std::string>& include_dirs, int depth, std::string& out,
                         std::vector<std::string>& files)
{
    if (depth > 32) {
        throw std::runtime_error("raykit: #include nesting deeper than 32 at " + file +
                                 " (an include without a guard including itself?)");
    }
    const int file_index = static_cast<int>(files.size());
    files.push_back(file);
    std::istringstream in(text);
    std::string line;
    int line_no = 0;
    while (std::getline(in, line)) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::string name;
        if (parse_include(line, name)) {
            std::vector<std::string> candidates;
            candidates.push_back(dir + "/" + name);
            for (const std::string& d : include_dirs) candidates.push_back(d + "/" + name);
            std::string body;
            std::string found;
            for (const std::string& c : candidates) {
                if (read_text_file(c, body)) {
                    found = c;
                    break;
                }
            }
            if (found.empty()) {
                throw std::runtime_error(file + ":" + std::to_string(line_no) + ": cannot find #include \"" +
                                         name + "\" (searched the including file's folder and " +
                                         std::to_string(include_dirs.size()) + " include dirs)");
            }
            out += "#line 1 " + std::to_string(files.size()) + "\n";
            resolve_into(body, found, dir_of(found), include_dirs, depth + 1, out, files);
            out += "#line " + std::to_string(line_no + 1) + " " + std::to_string(file_index) + "\n";
            continue;
        }
        const std::string t = trim_left(line);
        if (t.rfind("#extension", 0) == 0 && t.find("GL_GOOGLE_include_directive") != std::string::npos) {
            out += "\n";  // the driver would reject the unknown extension; keep line numbers
            continue;
        }
        out += line;
        out += '\n';
    }
}

}  // namespace detail

/// resolve_shader_includes: returns `source` with every `#include "x"` replaced by the file's text,
/// searched in `source_dir` (the including file's folder, recursively for nested includes) and then
/// in `include_dirs` in order; `#extension GL_GOOGLE_include_directive` lines are dropped and
/// `#line L F` directives keep driver error messages pointing at the right line. `F` indexes
/// `files_out` (0 = the source itself), when given. Guards (#ifndef) in the included files handle
/// repeated includes, exactly as in glslang. Throws std::runtime_error naming file:line for a
/// missing include and for nesting deeper than 32.
inline std::string resolve_shader_includes(const std::string& source, const std::string& source_name,
                                           const std::string& source_dir,
                                           const std::vector<std::string>& include_dirs,
                                           std::vector<std::string>* files_out = nullptr)
{
    std::string out;
    std::vector<std::string> files;
    detail::resolve_into(source, source_name, source_dir, include_dirs, 0, out, files);
    if (files_out) *files_out = files;
    return out;
}

/// inject_shader_defines: inserts `#define name value` lines right after the `#version` line (or
/// at the top when there is none), followed by `#line` so driver line numbers stay those of the
/// file. Names must be identifiers; throws std::invalid_argument otherwise.
inline std::string inject_shader_defines(const std::string& source, const std::vector<ShaderDefine>& defines)
{
    if (defines.empty()) return source;
    std::string block;
    for (const ShaderDefine& d : defines) {
        bool ok = !d.name.empty() && !(d.name[0] >= '0' && d.name[0] <= '9');
        for (char ch : d.name) {
            ok = ok && ((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_');
        }
        if (!ok) throw std::invalid_argument("raykit: invalid shader macro name '" + d.name + "'");
        block += "#define " + d.name + " " + d.value + "\n";
    }
    const size_t v = source.find("#version");
    if (v == std::string::npos) return block + "#line 1 0\n" + source;
    const size_t eol = source.find('\n', v);
    const std::string head = eol == std::string::npos ? source + "\n" : source.substr(0, eol + 1);
    const std::string tail = eol == std::string::npos ? std::string() : source.substr(eol + 1);
    int version_line = 1;
    for (size_t i = 0; i < v; ++i) version_line += source[i] == '\n' ? 1 : 0;
    return head + block + "#line " + std::to_string(version_line + 1) + " 0\n" + tail;
}

/// load_shader_file: reads `path`, resolves its includes (see resolve_shader_includes) and injects
/// `defines`. Throws std::runtime_error when the file cannot be read.
inline std::string load_shader_file(const std::string& path, const std::vector<std::string>& include_dirs,
                                    const std::vector<ShaderDefine>& defines = {},
                                    std::vector<std::string>* files_out = nullptr)
{
    std::string text;
    if (!detail::read_text_file(path, text)) throw std::runtime_error("raykit: cannot read shader " + path);
    return resolve_shader_includes(inject_shader_defines(text, defines), path, detail::dir_of(path), include_dirs,
                                   files_out);
}

}  // namespace raykit
