// Source scans shared by the dialect lint (test_shader_source.cpp) and the ODR coverage check
// (test_odr.cpp): what of a shared .glsl the C++ build sees, which files C++ compiles, and the
// option macros the files declare.
#pragma once

#include <dirent.h>

#include <cctype>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "raykit/shader_source.hpp"

namespace rktest {

// Blanks the parts of a shared file that only GLSL sees (`#ifndef __cplusplus` blocks and the
// `#else` of `#ifdef __cplusplus`), keeping line structure.
inline std::string cpp_view(const std::string& code)
{
    std::istringstream in(code);
    std::string line, out;
    std::vector<std::pair<int, bool>> stack;  // kind (0 other, 1 GLSL only, 2 C++ only), active
    while (std::getline(in, line)) {
        size_t i = line.find_first_not_of(" \t");
        const std::string t = i == std::string::npos ? std::string() : line.substr(i);
        if (t.rfind("#if", 0) == 0) {
            const int kind = t.rfind("#ifndef __cplusplus", 0) == 0 ? 1 : (t.rfind("#ifdef __cplusplus", 0) == 0 ? 2 : 0);
            stack.push_back({kind, kind != 1});
            out += "\n";
            continue;
        }
        if (t.rfind("#else", 0) == 0 && !stack.empty()) {
            if (stack.back().first != 0) stack.back().second = !stack.back().second;
            out += "\n";
            continue;
        }
        if (t.rfind("#endif", 0) == 0 && !stack.empty()) {
            stack.pop_back();
            out += "\n";
            continue;
        }
        bool active = true;
        for (const auto& s : stack) active = active && s.second;
        out += (active ? line : std::string()) + "\n";
    }
    return out;
}

/// The text of every file in `dir` whose name ends with `ext`, by name (empty when unreadable).
inline std::map<std::string, std::string> read_dir(const std::string& dir, const std::string& ext)
{
    std::map<std::string, std::string> files;
    if (DIR* d = opendir(dir.c_str())) {
        while (dirent* e = readdir(d)) {
            const std::string n = e->d_name;
            if (n.size() > ext.size() && n.compare(n.size() - ext.size(), ext.size(), ext) == 0) {
                raykit::detail::read_text_file(dir + "/" + n, files[n]);
            }
        }
        closedir(d);
    }
    return files;
}

/// The .glsl files C++ compiles: included by a header (`#include "raykit/x.glsl"`), or by such a file.
inline std::set<std::string> cpp_compiled(const std::map<std::string, std::string>& headers,
                                          const std::map<std::string, std::string>& glsl)
{
    std::set<std::string> cpp;
    const std::regex hpp_include(R"(#include "raykit/(\w+\.glsl)\")"), glsl_include(R"(#include "(\w+\.glsl)\")");
    for (const auto& h : headers) {
        for (std::sregex_iterator it(h.second.begin(), h.second.end(), hpp_include), end; it != end; ++it) cpp.insert((*it)[1]);
    }
    for (bool grew = true; grew;) {
        grew = false;
        for (const std::string& f : std::set<std::string>(cpp)) {
            const auto g = glsl.find(f);
            if (g == glsl.end()) continue;
            for (std::sregex_iterator it(g->second.begin(), g->second.end(), glsl_include), end; it != end; ++it) {
                grew = cpp.insert((*it)[1]).second || grew;
            }
        }
    }
    return cpp;
}

/// The option macros of the shared files: `#ifndef RK_X` directly followed by `#define RK_X`
/// (include guards, RK_*_GLSL, excluded), with the file that declares each.
inline std::map<std::string, std::string> option_macros(const std::map<std::string, std::string>& glsl)
{
    std::map<std::string, std::string> macros;
    const std::regex option(R"(#ifndef (RK_[A-Z0-9_]+)\n#define \1\b)");
    for (const auto& kv : glsl) {
        for (std::sregex_iterator it(kv.second.begin(), kv.second.end(), option), end; it != end; ++it) {
            const std::string m = (*it)[1];
            if (m.size() < 5 || m.compare(m.size() - 5, 5, "_GLSL") != 0) macros[m] = kv.first;
        }
    }
    return macros;
}

/// `code` without its comments (// and /* */) and, with `strings`, the contents of its string and
/// character literals (kept as "" and ''); line breaks stay, so line numbers do.
inline std::string strip_comments(const std::string& code, bool strings)
{
    std::string out;
    out.reserve(code.size());
    for (size_t i = 0; i < code.size();) {
        const char c = code[i];
        if (c == '/' && i + 1 < code.size() && code[i + 1] == '/') {
            while (i < code.size() && code[i] != '\n') ++i;
        } else if (c == '/' && i + 1 < code.size() && code[i + 1] == '*') {
            for (i += 2; i < code.size() && !(code[i] == '*' && i + 1 < code.size() && code[i + 1] == '/'); ++i) {
                if (code[i] == '\n') out += '\n';
            }
            i += 2;
        } else if (strings && (c == '"' || c == '\'')) {
            out += c;
            for (++i; i < code.size() && code[i] != c && code[i] != '\n'; ++i) {
                if (code[i] == '\\') ++i;
            }
            if (i < code.size() && code[i] == c) out += c, ++i;
        } else {
            out += c;
            ++i;
        }
    }
    return out;
}

/// Whether `word` occurs in `text` as a whole identifier.
inline bool mentions(const std::string& text, const std::string& word)
{
    auto ident = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (size_t p = text.find(word); p != std::string::npos; p = text.find(word, p + 1)) {
        const size_t q = p + word.size();
        if ((p == 0 || !ident(text[p - 1])) && (q >= text.size() || !ident(text[q]))) return true;
    }
    return false;
}
}  // namespace rktest
