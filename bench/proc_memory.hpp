// Memory figures of the Linux /proc files for the benchmarks: a "Key: <n> kB" line of
// /proc/self/status or /proc/meminfo, and the available memory the benches size their largest
// rows against. 0 where the file or key does not exist (other systems).
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace rkbench_mem {

/// The value in kB of the line "key: <n> kB" of `path`; 0 when absent.
inline std::uint64_t proc_kb(const char* path, const char* key)
{
#if defined(__linux__)
    std::FILE* f = std::fopen(path, "r");
    if (!f) return 0;
    char line[256];
    const std::size_t n = std::strlen(key);
    std::uint64_t kb = 0;
    while (std::fgets(line, sizeof line, f)) {
        if (std::strncmp(line, key, n) == 0 && line[n] == ':') {
            kb = std::strtoull(line + n + 1, nullptr, 10);
            break;
        }
    }
    std::fclose(f);
    return kb;
#else
    (void)path;
    (void)key;
    return 0;
#endif
}

/// MemAvailable in bytes (0 when unknown).
inline std::uint64_t mem_available_bytes() { return proc_kb("/proc/meminfo", "MemAvailable") * 1024u; }

}  // namespace rkbench_mem
