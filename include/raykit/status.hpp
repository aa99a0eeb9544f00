// raykit — status.hpp: how raykit's C++ reports errors without exceptions (engines build with
// -fno-exceptions -fno-rtti). C++ only; no GLM.
//
// Two conventions, one type:
//  - an operation that can fail in correct use (a file, a memory budget, a shader include) takes a
//    `Status& st`, returns false (or an empty result) and says why in `st`;
//  - a helper whose only failure is a precondition the caller broke (a size out of range) returns
//    an empty or neutral result documented with the function, and describes the violation in an
//    optional `Status* st` (nullptr: not reported). It never aborts and never reads out of bounds.
// Allocation failure is left to the C++ runtime (std::bad_alloc, or termination without exceptions).
#pragma once

#include <string>
#include <utility>

namespace raykit {

/// Why an operation failed. `ok` means it did not.
enum class Error {
    ok = 0,
    invalid_argument,   ///< an option or argument outside its documented range
    empty_mesh,         ///< no triangle survived validation (all degenerate, NaN, out of range)
    budget_exceeded,    ///< the estimated or measured memory exceeds the caller's budget
    cancelled,          ///< the progress callback asked to stop
    too_large,          ///< the result exceeds a format's limits (2^32 words, 2^32 attributes)
    io,                 ///< a file could not be opened, read or written
    bad_magic,          ///< not a raykit octree file
    unsupported_version,
    truncated,          ///< the file ends before what its header announces
    corrupt,            ///< a count, offset, pointer or mask is inconsistent
    checksum_mismatch,  ///< the payload does not match its checksum
    not_found,          ///< a shader include that no include directory or loader provides
    syntax,             ///< a malformed shader directive (#include, #version, #if nesting)
};

/// error_name: the enumerator's name ("ok", "checksum_mismatch", ...), for logs and tests.
inline const char* error_name(Error e)
{
    switch (e) {
        case Error::ok: return "ok";
        case Error::invalid_argument: return "invalid_argument";
        case Error::empty_mesh: return "empty_mesh";
        case Error::budget_exceeded: return "budget_exceeded";
        case Error::cancelled: return "cancelled";
        case Error::too_large: return "too_large";
        case Error::io: return "io";
        case Error::bad_magic: return "bad_magic";
        case Error::unsupported_version: return "unsupported_version";
        case Error::truncated: return "truncated";
        case Error::corrupt: return "corrupt";
        case Error::checksum_mismatch: return "checksum_mismatch";
        case Error::not_found: return "not_found";
        case Error::syntax: return "syntax";
    }
    return "?";
}

/// Outcome of an operation: `code` and a human-readable message naming what was wrong.
struct Status {
    Error code = Error::ok;
    std::string message;
    bool ok() const { return code == Error::ok; }
    explicit operator bool() const { return ok(); }
    /// Records an error and returns false, so a function can `return st.fail(...)`.
    bool fail(Error c, std::string m)
    {
        code = c;
        message = std::move(m);
        return false;
    }
};

namespace detail {
/// Reports a broken precondition into an optional Status (see the header comment); returns false.
inline bool report(Status* st, std::string message)
{
    if (st) st->fail(Error::invalid_argument, std::move(message));
    return false;
}
/// Clears an optional Status on entry, so it describes the last call.
inline void reset(Status* st)
{
    if (st) *st = Status{};
}
}  // namespace detail

}  // namespace raykit
