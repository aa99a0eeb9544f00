// raykit — shader_source.hpp: load GLSL that #includes raykit, for drivers that cannot.
//
// glslang/glslc resolve `#include "raykit/fresnel.glsl"` offline (GL_GOOGLE_include_directive, see
// raykit_compile_shaders() in CMake). An OpenGL driver compiling GLSL at run time does not, so this
// header inlines the includes on the CPU and injects feature macros after #version. C++17, no GL,
// no exceptions (errors through raykit::Status, status.hpp).
//
// What the resolver guarantees (tests/test_shader_source.cpp; tests/gpu/parity_shader_source.cpp
// compiles broken shaders on the driver and checks the file and line it reports):
//  - driver messages name the right file and line: every inlined file starts with `#line 1 F`, the
//    including file resumes with `#line L F` after it, injected defines are followed by `#line`,
//    and a `#line` is re-emitted after the #else/#elif/#endif of any block that inlined a file;
//    `files[F]` names source string F, and shader_log_with_files() rewrites a log with the names;
//  - includes are processed only in active #if blocks (conditions are evaluated with the macros
//    defined so far: injected, predefined by #version, #define/#undef above), so an include in an
//    inactive block is neither read nor required. Integer expressions, defined, object-like macros
//    and the version's GL_ES / GL_core_profile / __VERSION__ are decided as glslang does; __LINE__,
//    __FILE__, function-like macros and GL_* extension names count as undecidable (see below).
//    Not modelled: a block comment that starts inside a directive and ends on a later line
//    (glslang joins what follows it to the directive); paths use '/' (give Windows paths so);
//  - `#line` follows the version's rule: the next line is N from GLSL 3.30 / ES 3.00 on, N + 1
//    before (and without #version), as drivers read it;
//  - each include-guarded file is inlined once: a file whose text is one `#ifndef G / #define G ...
//    #endif` block is skipped when G is already defined (the result the preprocessor would give);
//  - `#version` is found only as a directive (not in comments), `#extension
//    GL_GOOGLE_include_directive` lines are dropped, and comments are blanked (lines and columns
//    kept): the sample interior material resolves to 61 KB (386 KB when every include was inlined);
//  - a loader callback can supply files (Android assets, Emscripten's virtual file system, packs).
// A condition raykit cannot evaluate (a GL_* extension macro, a function-like macro) counts as
// "maybe": its includes are inlined, and line numbers stay right whichever branch the driver takes.
#pragma once

#include <cstdio>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "raykit/shader_define.hpp"
#include "raykit/status.hpp"

namespace raykit {

/// The line-number stride of ShaderSourceOptions::unique_line_numbers (files up to 99,999 lines).
constexpr long long RK_SHADER_LINE_STRIDE = 100000;

/// Supplies the text of the file at `path` (a candidate built from an include directory and the
/// include's name); returns false when there is no such file. The default reads the filesystem.
using ShaderLoader = std::function<bool(const std::string& path, std::string& text)>;

/// How to resolve a shader: where includes are searched (after the including file's folder), the
/// feature macros to inject after #version, and optionally where files come from.
struct ShaderSourceOptions {
    std::vector<std::string> include_dirs;
    std::vector<ShaderDefine> defines;
    ShaderLoader loader;  ///< empty: read files with std::FILE
    /// Number the lines of source string F from F * RK_SHADER_LINE_STRIDE + 1, so the line alone
    /// names the file. Some drivers report string 0 for some errors whatever `#line` said (Mesa
    /// 22.3 does for undeclared identifiers: tests/gpu/parity_shader_source.cpp); with this set,
    /// shader_log_with_files() recovers the file and line from the line number. Raw logs then show
    /// large line numbers, so pass them through shader_log_with_files().
    bool unique_line_numbers = false;
};

/// A resolved shader: the text to hand the driver, and the name of each source-string number
/// (`#line L F`): files[0] is the shader itself, then each inlined file in order.
struct ShaderSource {
    std::string text;
    std::vector<std::string> files;
};

namespace detail {

inline bool read_text_file(const std::string& path, std::string& out)
{
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) return false;
    out.clear();
    char buf[65536];
    size_t n = 0;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
    const bool ok = std::ferror(f) == 0;
    std::fclose(f);
    return ok;
}

inline std::string dir_of(const std::string& path)
{
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

/// Removes "./" segments and "x/.." pairs, so one file reached two ways has one name.
inline std::string normalize_path(const std::string& path)
{
    const bool absolute = !path.empty() && path[0] == '/';
    std::vector<std::string> parts;
    size_t i = 0;
    while (i <= path.size()) {
        size_t j = path.find('/', i);
        if (j == std::string::npos) j = path.size();
        const std::string seg = path.substr(i, j - i);
        if (seg == "..") {
            if (!parts.empty() && parts.back() != "..") {
                parts.pop_back();
            } else if (!absolute) {
                parts.push_back(seg);
            }
        } else if (!seg.empty() && seg != ".") {
            parts.push_back(seg);
        }
        i = j + 1;
    }
    std::string out = absolute ? "/" : "";
    for (size_t k = 0; k < parts.size(); ++k) out += (k ? "/" : "") + parts[k];
    return out.empty() ? std::string(".") : out;
}

inline std::string rtrim(const std::string& s)
{
    const size_t e = s.find_last_not_of(" \t\r\f\v");
    return e == std::string::npos ? std::string() : s.substr(0, e + 1);
}

inline bool is_ident_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
inline bool is_ident_char(char c) { return is_ident_start(c) || (c >= '0' && c <= '9'); }
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

/// Splits text into physical lines (ended by "\n", "\r\n" or a lone "\r", as drivers count them) and,
/// for each, the code with comments blanked (comment state carried across lines; a `//` comment
/// ending in a backslash continues on the next line, as the preprocessor splices it).
inline void split_code_lines(const std::string& text, std::vector<std::string>& raw, std::vector<std::string>& code)
{
    bool in_block = false, line_comment_continues = false;
    size_t i = 0;
    while (i < text.size()) {
        size_t e = text.find_first_of("\r\n", i);
        if (e == std::string::npos) e = text.size();
        std::string line = text.substr(i, e - i);
        const size_t next = e < text.size() && text[e] == '\r' && e + 1 < text.size() && text[e + 1] == '\n' ? e + 2 : e + 1;
        std::string c(line.size(), ' ');
        if (line_comment_continues) {
            const size_t p = line.find_last_not_of(" \t");
            line_comment_continues = p != std::string::npos && line[p] == '\\';
            raw.push_back(line);
            code.push_back(c);
            i = next;
            continue;
        }
        bool in_quote = false;
        for (size_t k = 0; k < line.size(); ++k) {
            if (in_block) {
                if (line[k] == '*' && k + 1 < line.size() && line[k + 1] == '/') {
                    in_block = false;
                    ++k;
                }
                continue;
            }
            if (!in_quote && line[k] == '/' && k + 1 < line.size() && line[k + 1] == '/') {
                const size_t p = line.find_last_not_of(" \t");
                line_comment_continues = p != std::string::npos && p > k + 1 && line[p] == '\\';
                break;
            }
            if (!in_quote && line[k] == '/' && k + 1 < line.size() && line[k + 1] == '*') {
                in_block = true;
                ++k;
                continue;
            }
            if (line[k] == '"') in_quote = !in_quote;
            c[k] = line[k];
        }
        raw.push_back(line);
        code.push_back(c);
        i = next;
    }
}

/// A directive line: `# keyword rest`; false for any other line.
inline bool parse_directive(const std::string& code, std::string& keyword, std::string& rest)
{
    size_t i = 0;
    while (i < code.size() && is_space(code[i])) ++i;
    if (i >= code.size() || code[i] != '#') return false;
    ++i;
    while (i < code.size() && is_space(code[i])) ++i;
    const size_t k0 = i;
    while (i < code.size() && is_ident_char(code[i])) ++i;
    keyword = code.substr(k0, i - k0);
    rest = code.substr(i);
    return true;
}

inline std::string first_ident(const std::string& s, size_t* end = nullptr)
{
    size_t i = 0;
    while (i < s.size() && is_space(s[i])) ++i;
    const size_t b = i;
    if (i < s.size() && is_ident_start(s[i])) {
        while (i < s.size() && is_ident_char(s[i])) ++i;
    }
    if (end) *end = i;
    return s.substr(b, i - b);
}

/// The state of one macro as far as the resolver can tell.
struct PpMacro {
    std::string value;
    bool function_like = false;
    bool uncertain = false;  ///< defined or undefined in a block the resolver could not decide
};

/// Tri-state value of a preprocessor expression: known (v) or unknown.
struct PpValue {
    long long v = 0;
    bool known = true;
};

/// Evaluates a #if expression (integer arithmetic, defined, macros expanded) over `macros`.
class PpExpr {
public:
    PpExpr(const std::map<std::string, PpMacro>& macros, const std::set<std::string>& absent)
        : macros_(macros), absent_(absent)
    {
    }

    PpValue eval(const std::string& text)
    {
        toks_.clear();
        pos_ = 0;
        bad_ = false;
        std::vector<std::string> active;
        tokenize(text, 0, active);
        if (bad_) return unknown();
        PpValue v = binary(1);
        if (bad_ || pos_ != toks_.size()) return unknown();
        return v;
    }

private:
    struct Tok {
        int kind;  // 0 number, 1 identifier, 2 punctuator, 3 unknown value (an undecidable macro)
        std::string s;
        long long v;
    };
    static PpValue unknown()
    {
        PpValue u;
        u.known = false;
        return u;
    }

    void tokenize(const std::string& text, int depth, std::vector<std::string>& active)
    {
        if (depth > 64) {
            bad_ = true;
            return;
        }
        size_t i = 0;
        bool after_defined = false;
        while (i < text.size() && !bad_) {
            const char c = text[i];
            if (is_space(c)) {
                ++i;
                continue;
            }
            if (c >= '0' && c <= '9') {
                size_t j = i;
                long long v = 0;
                int base = 10;
                if (c == '0' && i + 1 < text.size() && (text[i + 1] == 'x' || text[i + 1] == 'X')) {
                    base = 16;
                    j += 2;
                } else if (c == '0') {
                    base = 8;
                }
                bool any = base != 16;
                for (; j < text.size(); ++j) {
                    const char d = text[j];
                    int dv = -1;
                    if (d >= '0' && d <= '9') dv = d - '0';
                    if (base == 16 && d >= 'a' && d <= 'f') dv = d - 'a' + 10;
                    if (base == 16 && d >= 'A' && d <= 'F') dv = d - 'A' + 10;
                    if (dv < 0 || dv >= base) break;
                    any = true;
                    v = (v * base + dv) & 0xffffffffll;  // GLSL's preprocessor integers are 32-bit
                }
                if (j < text.size() && (text[j] == 'u' || text[j] == 'U')) ++j;
                if (!any || (j < text.size() && (is_ident_char(text[j]) || text[j] == '.'))) {
                    bad_ = true;  // a float literal or a malformed number: leave it to the driver
                    return;
                }
                toks_.push_back({0, "", v >= 0x80000000ll ? v - 0x100000000ll : v});
                i = j;
                continue;
            }
            if (is_ident_start(c)) {
                size_t j = i;
                while (j < text.size() && is_ident_char(text[j])) ++j;
                const std::string id = text.substr(i, j - i);
                i = j;
                if (id == "defined") {
                    toks_.push_back({1, id, 0});
                    after_defined = true;
                    continue;
                }
                if (after_defined) {  // the operand of defined is not expanded
                    toks_.push_back({1, id, 0});
                    after_defined = false;
                    continue;
                }
                bool in_use = false;
                for (const std::string& a : active) in_use = in_use || a == id;
                const auto it = macros_.find(id);
                if (it != macros_.end() && !in_use) {
                    if (it->second.function_like || it->second.uncertain) {
                        toks_.push_back({3, id, 0});
                        continue;
                    }
                    active.push_back(id);
                    tokenize(it->second.value, depth + 1, active);
                    active.pop_back();
                    continue;
                }
                toks_.push_back({1, id, 0});
                continue;
            }
            static const char* const two[] = {"||", "&&", "==", "!=", "<=", ">=", "<<", ">>"};
            bool matched = false;
            for (const char* t : two) {
                if (text.compare(i, 2, t) == 0) {
                    toks_.push_back({2, t, 0});
                    i += 2;
                    matched = true;
                    break;
                }
            }
            if (matched) continue;
            if (std::string("()+-*/%<>&|^!~").find(c) == std::string::npos) {
                bad_ = true;
                return;
            }
            if (!(after_defined && c == '(')) after_defined = false;
            toks_.push_back({2, std::string(1, c), 0});
            ++i;
        }
    }

    bool peek(const char* p) const { return pos_ < toks_.size() && toks_[pos_].kind == 2 && toks_[pos_].s == p; }

    static int precedence(const std::string& op)
    {
        if (op == "||") return 1;
        if (op == "&&") return 2;
        if (op == "|") return 3;
        if (op == "^") return 4;
        if (op == "&") return 5;
        if (op == "==" || op == "!=") return 6;
        if (op == "<" || op == ">" || op == "<=" || op == ">=") return 7;
        if (op == "<<" || op == ">>") return 8;
        if (op == "+" || op == "-") return 9;
        if (op == "*" || op == "/" || op == "%") return 10;
        return 0;
    }

    PpValue binary(int min_prec)
    {
        PpValue lhs = unary();
        while (!bad_ && pos_ < toks_.size() && toks_[pos_].kind == 2) {
            const std::string op = toks_[pos_].s;
            const int p = precedence(op);
            if (p == 0 || p < min_prec) break;
            ++pos_;
            const PpValue rhs = binary(p + 1);
            lhs = apply(op, lhs, rhs);
        }
        return lhs;
    }

    static PpValue apply(const std::string& op, PpValue a, PpValue b)
    {
        if (op == "&&") {
            if ((a.known && a.v == 0) || (b.known && b.v == 0)) return {0, true};
            if (a.known && b.known) return {1, true};
            return unknown();
        }
        if (op == "||") {
            if ((a.known && a.v != 0) || (b.known && b.v != 0)) return {1, true};
            if (a.known && b.known) return {0, true};
            return unknown();
        }
        if (!a.known || !b.known) return unknown();
        const long long x = a.v, y = b.v;
        long long r = 0;
        if (op == "|") r = x | y;
        else if (op == "^") r = x ^ y;
        else if (op == "&") r = x & y;
        else if (op == "==") r = x == y;
        else if (op == "!=") r = x != y;
        else if (op == "<") r = x < y;
        else if (op == ">") r = x > y;
        else if (op == "<=") r = x <= y;
        else if (op == ">=") r = x >= y;
        else if (op == "<<") r = (y < 0 || y > 31) ? 0 : static_cast<long long>(static_cast<unsigned long long>(x) << y);
        else if (op == ">>") r = (y < 0 || y > 31) ? 0 : x >> y;
        else if (op == "+") r = x + y;
        else if (op == "-") r = x - y;
        else if (op == "*") r = x * y;
        else if (op == "/" || op == "%") {
            if (y == 0) return unknown();  // the driver reports the division by zero
            r = op == "/" ? x / y : x % y;
        }
        r &= 0xffffffffll;
        return {r >= 0x80000000ll ? r - 0x100000000ll : r, true};
    }

    PpValue unary()
    {
        if (pos_ >= toks_.size()) {
            bad_ = true;
            return unknown();
        }
        const Tok t = toks_[pos_++];
        if (t.kind == 0) return {t.v, true};
        if (t.kind == 3) return unknown();
        if (t.kind == 1) {
            if (t.s == "defined") {
                const bool paren = peek("(");
                if (paren) ++pos_;
                if (pos_ >= toks_.size() || (toks_[pos_].kind != 1 && toks_[pos_].kind != 3)) {
                    bad_ = true;
                    return unknown();
                }
                const std::string name = toks_[pos_++].s;
                if (paren) {
                    if (!peek(")")) {
                        bad_ = true;
                        return unknown();
                    }
                    ++pos_;
                }
                const auto it = macros_.find(name);
                if (it != macros_.end()) return it->second.uncertain ? unknown() : PpValue{1, true};
                if (name == "__LINE__" || name == "__FILE__") return {1, true};
                if (absent_.count(name)) return {0, true};
                // Extension macros (GL_ARB_...) depend on the driver.
                if (name.compare(0, 3, "GL_") == 0) return unknown();
                return {0, true};
            }
            // __LINE__ and __FILE__ have values the resolver does not track: undecidable.
            if (t.s == "__LINE__" || t.s == "__FILE__") return unknown();
            if (absent_.count(t.s)) return {0, true};
            // An identifier left after expansion: 0 in C; an extension name the driver may define.
            if (t.s.compare(0, 3, "GL_") == 0) return unknown();
            return {0, true};
        }
        if (t.s == "(") {
            const PpValue v = binary(1);
            if (!peek(")")) {
                bad_ = true;
                return unknown();
            }
            ++pos_;
            return v;
        }
        const PpValue v = unary();
        if (!v.known) return v;
        if (t.s == "-") return apply("-", {0, true}, v);
        if (t.s == "+") return v;
        if (t.s == "!") return {v.v == 0 ? 1 : 0, true};
        if (t.s == "~") return apply("^", v, {-1, true});
        bad_ = true;
        return unknown();
    }

    const std::map<std::string, PpMacro>& macros_;
    const std::set<std::string>& absent_;  // names known not to be defined (GL_ES under #version 450)
    std::vector<Tok> toks_;
    size_t pos_ = 0;
    bool bad_ = false;
};

/// Whether a file's text is one include-guard block: `#ifndef G` and `#define G` first, the matching
/// `#endif` last (comments and blank lines aside). Returns G, or "" when it is not.
inline std::string include_guard(const std::vector<std::string>& code)
{
    std::string guard;
    int stage = 0;  // 0: expect #ifndef, 1: expect #define, 2: inside, 3: after the #endif
    int depth = 0;
    for (const std::string& c : code) {
        bool blank = true;
        for (char ch : c) blank = blank && is_space(ch);
        if (blank) continue;
        if (stage == 3) return "";
        std::string kw, rest;
        const bool dir = parse_directive(c, kw, rest);
        if (stage == 0) {
            if (!dir || kw != "ifndef") return "";
            guard = first_ident(rest);
            if (guard.empty()) return "";
            stage = 1;
            depth = 1;
            continue;
        }
        if (stage == 1) {
            if (!dir || kw != "define" || first_ident(rest) != guard) return "";
            stage = 2;
            continue;
        }
        if (!dir) continue;
        if (kw == "if" || kw == "ifdef" || kw == "ifndef") ++depth;
        if ((kw == "else" || kw == "elif") && depth == 1) return "";  // an alternative: not a guard
        if (kw == "endif" && --depth == 0) stage = 3;
    }
    return stage == 3 ? guard : "";
}

/// Whether a define can be injected: its name an identifier, its value one line. "" when it can,
/// else the reason.
inline std::string define_error(const ShaderDefine& d)
{
    bool ok = !d.name.empty() && is_ident_start(d.name[0]);
    for (char ch : d.name) ok = ok && is_ident_char(ch);
    if (!ok) return "raykit: invalid shader macro name '" + d.name + "' (names are identifiers)";
    if (d.value.find('\n') != std::string::npos) return "raykit: shader macro '" + d.name + "' has a newline in its value";
    return "";
}

/// The `#define name value` lines of `defines`, in order.
inline std::string define_block(const std::vector<ShaderDefine>& defines)
{
    std::string block;
    for (const ShaderDefine& d : defines) block += "#define " + d.name + " " + d.value + "\n";
    return block;
}

/// The line index of the `#version` directive when it is the first directive and nothing but
/// blank lines or comments precedes it (where defines go); `code.size()` when there is none.
inline size_t version_line(const std::vector<std::string>& code)
{
    for (size_t i = 0; i < code.size(); ++i) {
        std::string kw, rest;
        if (parse_directive(code[i], kw, rest)) return kw == "version" ? i : code.size();
        if (code[i].find_first_not_of(" \t\r\f\v") != std::string::npos) break;
    }
    return code.size();
}

/// The number and profile of a `#version` directive's text (after the keyword); numbers above
/// 100000 (not GLSL versions) stop the parse, the driver reports them.
inline void parse_version(const std::string& rest, long long& version, std::string& profile)
{
    size_t i = 0;
    while (i < rest.size() && is_space(rest[i])) ++i;
    version = 0;
    while (i < rest.size() && rest[i] >= '0' && rest[i] <= '9' && version <= 100000) version = version * 10 + (rest[i++] - '0');
    profile = first_ident(rest.substr(i));
}

/// 1 where `#line N` makes the next line N + 1 (GLSL before 3.30, ES 1.00, no #version: 1.10),
/// 0 where it makes it N (GLSL 3.30 and later, ES 3.00 and later).
inline long long glsl_line_offset(long long version, const std::string& profile)
{
    if (profile == "es") return version >= 300 ? 0 : 1;
    return version >= 330 ? 0 : 1;
}

class ShaderResolver {
public:
    ShaderResolver(const ShaderSourceOptions& opt, ShaderSource& out, Status& st) : opt_(opt), out_(out), st_(st) {}

    bool run(const std::string& source, const std::string& name, const std::string& dir)
    {
        out_ = ShaderSource{};
        macros_["__VERSION__"] = PpMacro{"110", false, false};  // until a #version says otherwise
        for (const ShaderDefine& d : opt_.defines) {
            const std::string why = define_error(d);
            if (!why.empty()) return st_.fail(Error::invalid_argument, why);
            macros_[d.name] = PpMacro{d.value, false, false};
        }
        return file(source, name, dir, 0);
    }

private:
    struct Cond {
        bool parent_active;  // the enclosing region is active or maybe
        bool parent_sure;    // ... and surely so
        int state;           // this branch: 1 taken, 0 not, -1 unknown
        bool any_true;       // some earlier branch was taken for sure
        bool any_unknown;    // some earlier branch was unknown
        bool else_seen;
    };

    static bool active(const std::vector<Cond>& cs) { return cs.empty() || (cs.back().parent_active && cs.back().state != 0); }
    // Surely active: in this file, and the include that brought the file in was surely active.
    bool sure(const std::vector<Cond>& cs) const
    {
        return outer_sure_ && (cs.empty() || (cs.back().parent_sure && cs.back().state == 1));
    }

    bool load(const std::string& path, std::string& text) const
    {
        return opt_.loader ? opt_.loader(path, text) : read_text_file(path, text);
    }

    void define(const std::string& rest, bool certain)
    {
        size_t e = 0;
        const std::string name = first_ident(rest, &e);
        if (name.empty()) return;  // the driver reports it
        PpMacro m;
        m.function_like = e < rest.size() && rest[e] == '(';
        size_t b = e;
        while (b < rest.size() && is_space(rest[b])) ++b;
        m.value = rest.substr(b);
        m.uncertain = !certain;
        macros_[name] = m;
    }

    void predefine_version(const std::string& rest)
    {
        long long v = 0;
        std::string profile;
        parse_version(rest, v, profile);
        macros_["__VERSION__"] = PpMacro{std::to_string(v), false, false};
        line_offset_ = glsl_line_offset(v, profile);
        for (const char* m : {"GL_ES", "GL_core_profile", "GL_compatibility_profile"}) known_absent_.insert(m);
        if (profile == "es" || v == 100) macros_["GL_ES"] = PpMacro{"1", false, false};
        if (profile == "compatibility") macros_["GL_compatibility_profile"] = PpMacro{"1", false, false};
        if (profile != "es" && profile != "compatibility" && v >= 150) macros_["GL_core_profile"] = PpMacro{"1", false, false};
    }

    bool file(const std::string& text, const std::string& name, const std::string& dir, int depth)
    {
        if (depth > 32) {
            return st_.fail(Error::syntax, "raykit: #include nesting deeper than 32 at " + name +
                                               " (an include without a guard including itself?)");
        }
        const int index = static_cast<int>(out_.files.size());
        out_.files.push_back(name);
        std::vector<std::string> raw, code;
        split_code_lines(text, raw, code);
        std::vector<Cond> cs;
        long long line = 0;          // the number the driver gives the current line
        bool dirty = false;          // an inline happened whose #line the driver may have skipped
        bool injected = index != 0;  // defines go after the main file's #version
        const long long base = opt_.unique_line_numbers ? static_cast<long long>(index) * RK_SHADER_LINE_STRIDE : 0;
        auto sync = [&](long long next) {
            out_.text += "#line " + std::to_string(base + next - line_offset_) + " " + std::to_string(index) + "\n";
        };
        if (index == 0 && !opt_.defines.empty()) {
            // Inject at the top unless a #version directive comes first (then right after it).
            if (version_line(code) == code.size()) {
                emit_defines();
                sync(1);
                injected = true;
            }
        }
        for (size_t li = 0; li < raw.size(); ++li) {
            ++line;
            std::string kw, rest;
            if (!parse_directive(code[li], kw, rest)) {
                out_.text += rtrim(code[li]) + "\n";  // comments blanked: same lines and columns
                continue;
            }
            // A directive continued on the next lines (backslash-newline): parse it joined.
            size_t last = li;
            auto continued = [](const std::string& c) {
                const size_t p = c.find_last_not_of(" \t");
                return p != std::string::npos && c[p] == '\\';
            };
            while (continued(code[last]) && last + 1 < raw.size()) {
                const size_t bs = rest.find_last_of('\\');
                if (bs != std::string::npos) rest = rest.substr(0, bs);
                rest += " " + code[++last];
            }
            const bool act = active(cs), surely = sure(cs);
            const std::string where = name + ":" + std::to_string(line);
            // A directive replaced by the resolver consumes its continuation lines too.
            const long long spanned = static_cast<long long>(last - li);
            if (kw == "include" && act) {
                const bool outer = outer_sure_;
                outer_sure_ = surely;
                const bool ok = include(rest, where, dir, depth, surely);
                outer_sure_ = outer;
                if (!ok) return false;
                line += spanned;
                li = last;
                sync(line + 1);
                dirty = dirty || !surely;
                continue;
            }
            if (kw == "include" || (kw == "extension" && rest.find("GL_GOOGLE_include_directive") != std::string::npos)) {
                for (size_t k = li; k <= last; ++k) out_.text += "\n";  // the driver would reject it; keep the line count
                line += spanned;
                li = last;
                continue;
            }
            for (size_t k = li; k <= last; ++k) out_.text += rtrim(code[k]) + "\n";
            line += static_cast<long long>(last - li);
            li = last;
            if (kw == "version" && index == 0 && act) {
                predefine_version(rest);
                if (!injected) {
                    emit_defines();
                    sync(line + 1);
                    injected = true;
                }
            } else if (kw == "line" && act) {
                size_t i = 0;
                while (i < rest.size() && is_space(rest[i])) ++i;
                long long v = 0;
                bool any = false;
                while (i < rest.size() && rest[i] >= '0' && rest[i] <= '9') {
                    v = v * 10 + (rest[i++] - '0');
                    any = true;
                    if (v > (1ll << 40)) break;
                }
                if (any) line = v - 1 + line_offset_;
            } else if (kw == "define" && act) {
                define(rest, surely);
            } else if (kw == "undef" && act) {
                const std::string n = first_ident(rest);
                if (surely) {
                    macros_.erase(n);
                } else if (macros_.count(n)) {
                    macros_[n].uncertain = true;
                }
            } else if (kw == "if" || kw == "ifdef" || kw == "ifndef") {
                Cond c{act, surely, 0, false, false, false};
                if (act) {
                    int s = 0;
                    if (kw == "if") {
                        const PpValue v = PpExpr(macros_, known_absent_).eval(rest);
                        s = !v.known ? -1 : (v.v != 0 ? 1 : 0);
                    } else {
                        const PpValue d = PpExpr(macros_, known_absent_).eval("defined(" + first_ident(rest) + ")");
                        s = !d.known ? -1 : ((d.v != 0) == (kw == "ifdef") ? 1 : 0);
                    }
                    c.state = s;
                }
                c.any_true = c.state == 1;
                c.any_unknown = c.state == -1;
                cs.push_back(c);
            } else if (kw == "elif" || kw == "else") {
                if (cs.empty() || cs.back().else_seen) {
                    return st_.fail(Error::syntax, where + ": #" + kw + " without a matching #if");
                }
                Cond& c = cs.back();
                c.else_seen = kw == "else";
                if (!c.parent_active || c.any_true) {
                    c.state = 0;
                } else if (kw == "else") {
                    c.state = c.any_unknown ? -1 : 1;
                } else {
                    const PpValue v = PpExpr(macros_, known_absent_).eval(rest);
                    const int s = !v.known ? -1 : (v.v != 0 ? 1 : 0);
                    c.state = (s == 1 && c.any_unknown) ? -1 : s;
                }
                c.any_true = c.any_true || c.state == 1;
                c.any_unknown = c.any_unknown || c.state == -1;
            } else if (kw == "endif") {
                if (cs.empty()) return st_.fail(Error::syntax, where + ": #endif without a matching #if");
                cs.pop_back();
            }
            if (dirty && (kw == "elif" || kw == "else" || kw == "endif")) {
                sync(line + 1);
                if (sure(cs)) dirty = false;
            }
        }
        if (!cs.empty()) return st_.fail(Error::syntax, name + ": #if without #endif at the end of the file");
        return true;
    }

    void emit_defines() { out_.text += define_block(opt_.defines); }

    bool include(const std::string& rest, const std::string& where, const std::string& dir, int depth, bool surely)
    {
        size_t i = 0;
        while (i < rest.size() && is_space(rest[i])) ++i;
        const char open = i < rest.size() ? rest[i] : '\0';
        const char close = open == '"' ? '"' : (open == '<' ? '>' : '\0');
        const size_t end = close ? rest.find(close, i + 1) : std::string::npos;
        if (end == std::string::npos || end == i + 1) {
            return st_.fail(Error::syntax, where + ": malformed #include (expected \"name\" or <name>)");
        }
        const std::string inc = rest.substr(i + 1, end - i - 1);
        std::vector<std::string> candidates{normalize_path(dir.empty() ? inc : dir + "/" + inc)};
        for (const std::string& d : opt_.include_dirs) candidates.push_back(normalize_path(d + "/" + inc));
        std::string path, body;
        for (const std::string& c : candidates) {
            const auto g = guards_.find(c);
            if (g != guards_.end()) {  // read before: skip it if its guard is surely defined
                const auto m = macros_.find(g->second);
                if (m != macros_.end() && !m->second.uncertain) {
                    out_.text += "\n";  // one line for the #include line; the caller's #line follows
                    return true;
                }
            }
            if (load(c, body)) {
                path = c;
                break;
            }
        }
        if (path.empty()) {
            return st_.fail(Error::not_found,
                            where + ": cannot find #include \"" + inc + "\" (searched the including file's folder and " +
                                std::to_string(opt_.include_dirs.size()) + " include dirs" +
                                (surely ? ")" : "; in a block whose #if raykit cannot evaluate)"));
        }
        {
            std::vector<std::string> raw, code;
            split_code_lines(body, raw, code);
            const std::string g = include_guard(code);
            if (!g.empty()) guards_[path] = g;
        }
        const long long first = opt_.unique_line_numbers ? static_cast<long long>(out_.files.size()) * RK_SHADER_LINE_STRIDE : 0;
        out_.text += "#line " + std::to_string(first + 1 - line_offset_) + " " + std::to_string(out_.files.size()) + "\n";
        return file(body, path, dir_of(path), depth + 1);
    }

    const ShaderSourceOptions& opt_;
    ShaderSource& out_;
    Status& st_;
    std::map<std::string, PpMacro> macros_;
    std::map<std::string, std::string> guards_;  // file -> its include-guard macro
    bool outer_sure_ = true;                      // the file being read was included surely
    // GLSL before 3.30 (and ES 1.00, and no #version: 1.10) reads `#line N` as "the next line is
    // N + 1"; 3.30+ and ES 3.00+ as "the next line is N". Emitted numbers subtract this.
    long long line_offset_ = 1;
    std::set<std::string> known_absent_;          // built-in macros the #version rules out
};

}  // namespace detail

/// resolve_shader: `source` (named `source_name`, its includes searched first in `source_dir`)
/// with its includes inlined and opt.defines injected after #version (see the header comment).
/// False, with `st` naming file:line, for a missing include (Error::not_found), nesting deeper than
/// 32 or an unbalanced #if (Error::syntax), or a define whose name is not an identifier
/// (Error::invalid_argument). Cost: linear in the output, which holds each guarded file once.
inline bool resolve_shader(const std::string& source, const std::string& source_name, const std::string& source_dir,
                           const ShaderSourceOptions& opt, ShaderSource& out, Status& st)
{
    st = Status{};
    detail::ShaderResolver r(opt, out, st);
    if (!r.run(source, source_name, source_dir)) {
        out = ShaderSource{};
        return false;
    }
    return true;
}

/// load_shader: reads `path` (through opt.loader when set) and resolves it (resolve_shader); a file
/// that cannot be read is Error::io.
inline bool load_shader(const std::string& path, const ShaderSourceOptions& opt, ShaderSource& out, Status& st)
{
    std::string text;
    if (!(opt.loader ? opt.loader(path, text) : detail::read_text_file(path, text))) {
        out = ShaderSource{};
        return st.fail(Error::io, "raykit: cannot read shader " + path);
    }
    return resolve_shader(text, path, detail::dir_of(path), opt, out, st);
}

/// shader_log_with_files: a driver's compile log with source-string numbers replaced by file names,
/// for the message prefixes of Mesa ("F:L(C): error"), NVIDIA ("F(L) : error") and glslang/ANGLE
/// ("ERROR: F:L: ..."), where F indexes `files` (ShaderSource::files). A line number of
/// RK_SHADER_LINE_STRIDE or more (ShaderSourceOptions::unique_line_numbers) names the file itself
/// and is turned back into the file's own line, whatever F the driver printed. Other text is
/// unchanged.
inline std::string shader_log_with_files(const std::string& log, const std::vector<std::string>& files)
{
    std::string out;
    size_t i = 0;
    while (i < log.size()) {
        size_t e = log.find('\n', i);
        if (e == std::string::npos) e = log.size();
        std::string line = log.substr(i, e - i);
        size_t p = 0;
        for (const char* prefix : {"ERROR: ", "WARNING: "}) {
            const size_t n = std::char_traits<char>::length(prefix);
            if (line.compare(0, n, prefix) == 0) p = n;
        }
        size_t q = p;
        unsigned long long f = 0;
        while (q < line.size() && line[q] >= '0' && line[q] <= '9' && q - p < 9) f = f * 10 + static_cast<unsigned>(line[q++] - '0');
        if (q > p && q + 1 < line.size() && (line[q] == ':' || line[q] == '(') && line[q + 1] >= '0' && line[q + 1] <= '9') {
            size_t r = q + 1;
            unsigned long long l = 0;
            while (r < line.size() && line[r] >= '0' && line[r] <= '9' && r - q < 16) l = l * 10 + static_cast<unsigned>(line[r++] - '0');
            const unsigned long long stride = static_cast<unsigned long long>(RK_SHADER_LINE_STRIDE);
            if (l >= stride && l / stride < files.size()) {
                line = line.substr(0, p) + files[l / stride] + line[q] + std::to_string(l % stride) + line.substr(r);
            } else if (f < files.size()) {
                line = line.substr(0, p) + files[f] + line.substr(q);
            }
        }
        out += line;
        if (e < log.size()) out += '\n';
        i = e + 1;
    }
    return out;
}

/// resolve_shader_includes: resolve_shader without defines, returning the text ("" on failure, with
/// *st describing it) and the source-string names in *files_out.
inline std::string resolve_shader_includes(const std::string& source, const std::string& source_name,
                                           const std::string& source_dir, const std::vector<std::string>& include_dirs,
                                           std::vector<std::string>* files_out = nullptr, Status* st = nullptr)
{
    ShaderSourceOptions opt;
    opt.include_dirs = include_dirs;
    ShaderSource out;
    Status s;
    resolve_shader(source, source_name, source_dir, opt, out, s);
    if (files_out) *files_out = out.files;
    if (st) *st = s;
    return out.text;
}

/// inject_shader_defines: inserts `#define name value` lines right after the `#version` directive
/// (or at the top when there is none), followed by `#line` so driver line numbers stay those of the
/// file; everything else, includes too, is left alone (resolve_shader honours the `#line`). A name
/// that is not an identifier, or a value with a newline: "" and *st describes it.
inline std::string inject_shader_defines(const std::string& source, const std::vector<ShaderDefine>& defines,
                                         Status* st = nullptr)
{
    detail::reset(st);
    if (defines.empty()) return source;
    for (const ShaderDefine& d : defines) {
        const std::string why = detail::define_error(d);
        if (!why.empty()) {
            detail::report(st, why);
            return "";
        }
    }
    const std::string block = detail::define_block(defines);
    std::vector<std::string> raw, code;
    detail::split_code_lines(source, raw, code);
    const size_t version = detail::version_line(code);
    long long offset = 1;  // no #version: GLSL 1.10, where `#line N` makes the next line N + 1
    if (version < code.size()) {
        std::string kw, rest, profile;
        detail::parse_directive(code[version], kw, rest);
        long long v = 0;
        detail::parse_version(rest, v, profile);
        offset = detail::glsl_line_offset(v, profile);
    }
    if (version == raw.size()) return block + "#line " + std::to_string(1 - offset) + " 0\n" + source;
    std::string out;
    for (size_t i = 0; i < raw.size(); ++i) {
        out += raw[i] + "\n";
        if (i == version) out += block + "#line " + std::to_string(static_cast<long long>(i) + 2 - offset) + " 0\n";
    }
    return out;
}

/// load_shader_file: load_shader with these include dirs and defines, returning the text ("" on
/// failure, with *st describing it) and the source-string names in *files_out.
inline std::string load_shader_file(const std::string& path, const std::vector<std::string>& include_dirs,
                                    const std::vector<ShaderDefine>& defines = {},
                                    std::vector<std::string>* files_out = nullptr, Status* st = nullptr)
{
    ShaderSourceOptions opt;
    opt.include_dirs = include_dirs;
    opt.defines = defines;
    ShaderSource out;
    Status s;
    load_shader(path, opt, out, s);
    if (files_out) *files_out = out.files;
    if (st) *st = s;
    return out.text;
}

}  // namespace raykit
