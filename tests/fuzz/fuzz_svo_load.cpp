// Fuzz test of svo_load (raykit/svo_file.hpp), built with AddressSanitizer + UBSan.
//
// Standalone (default): `fuzz_svo_load SECONDS [SEED] [--write-seeds DIR]` runs a deterministic
// mutation loop (xorshift seeded by SEED) for SECONDS of wall time over seed files it builds itself
// (small valid trees packed by tests/svo_test_pack.hpp and saved with svo_save). Mutations: bit
// flips, bytes set to 0 / 0xFF / random, truncation, extension, insertion, deletion, header fields
// and payload words set to boundary values; most mutants get their CRCs recomputed so that they
// reach the count checks and svo_validate instead of stopping at the checksum. Every load must
// either fail with a non-ok code and a message, or succeed, and then svo_validate passes, saving
// gives back the exact input bytes, and svo_for_each_voxel plus rk_svo_lookup on random cells stay
// in bounds (ASan aborts otherwise) and return attributes below attr_count. Exit 0 when every
// iteration held; prints iterations, successes and failures per error code. --write-seeds writes
// the seed files (a corpus for libFuzzer) and exits.
//
// libFuzzer: with -DRAYKIT_FUZZ_LIBFUZZER=ON and clang, target fuzz_svo_load_libfuzzer builds the
// same checks as LLVMFuzzerTestOneInput, with these mutations as LLVMFuzzerCustomMutator
// (RAYKIT_LIBFUZZER defined). Corpus: `fuzz_svo_load 0 --write-seeds DIR`, then
// `fuzz_svo_load_libfuzzer DIR -max_total_time=60`.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "raykit/svo_file.hpp"
#include "svo_test_pack.hpp"

using namespace raykit;

namespace {

using Bytes = std::vector<uint8_t>;

struct Rng {
    uint64_t s;
    uint64_t next()
    {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        return s;
    }
    uint64_t below(uint64_t n) { return n ? next() % n : 0; }
};

[[noreturn]] void die(const char* what, const uint8_t* data, size_t size)
{
    std::fprintf(stderr, "fuzz_svo_load: INVARIANT BROKEN: %s (input of %zu bytes written to fuzz_svo_load_failure.bin)\n", what, size);
    if (std::FILE* f = std::fopen("fuzz_svo_load_failure.bin", "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    std::abort();
}

/// One input: load it and check what a successful load promises. Returns the load's code.
SvoError check_one(const uint8_t* data, size_t size, uint64_t salt)
{
    SvoTree t;
    SvoStatus st;
    const bool ok = svo_load(data, size, t, st);
    if (ok != st.ok()) die("return value and status disagree", data, size);
    if (!ok) {
        if (st.message.empty()) die("failure without a message", data, size);
        return st.code;
    }
    SvoStatus vs;
    if (!svo_validate(t, vs)) die("a loaded tree fails svo_validate", data, size);
    Bytes again;
    if (!svo_save(t, again, vs) || again.size() != size || std::memcmp(again.data(), data, size) != 0)
        die("saving a loaded tree does not give back its bytes", data, size);
    uint64_t n = 0;
    svo_for_each_voxel(t, [&](glm::uvec3 c, uint64_t a) {
        const uint32_t side = 1u << t.depth;
        if (c.x >= side || c.y >= side || c.z >= side || a >= t.attr_count) die("svo_for_each_voxel out of range", data, size);
        ++n;
    });
    if (n != t.voxel_count) die("svo_for_each_voxel count != voxel_count", data, size);
    const std::vector<uint32_t> g = t.gpu_words();
    Rng r{salt | 1u};
    const uint32_t side = 1u << t.depth;
    for (int i = 0; i < 64; ++i) {
        const uvec3 cell(uint32_t(r.below(side + 1)), uint32_t(r.below(side)), uint32_t(r.below(side)));
        const uint32_t lvl = uint32_t(r.below(t.depth + 2));
        const rk_svo_hit h = rk_svo_lookup(g.data(), t.desc_words, t.gpu_brick_base_word(), t.depth, cell, lvl);
        if (h.found && h.attr >= t.attr_count) die("rk_svo_lookup attribute index out of range", data, size);
    }
    return SvoError::ok;
}

void fix_crcs(Bytes& f)
{
    if (f.size() < 16) return;
    const uint32_t hs = detail::svo_file::get_u32(&f[12]);
    if (hs < 16 || hs > f.size()) return;
    detail::svo_file::put_u32(&f[hs - 8], svo_crc32(f.data() + hs, f.size() - hs));
    detail::svo_file::put_u32(&f[hs - 4], svo_crc32(f.data(), hs - 4));
}

#ifndef RAYKIT_LIBFUZZER
std::vector<Bytes> make_seeds()
{
    struct Spec {
        uint32_t depth;
        size_t voxels;
        uint32_t pointer_bits, attributes, materials;
    };
    const Spec specs[] = {{1, 3, 23, 7, 2}, {2, 20, 23, 1, 1}, {3, 40, 4, 7, 3}, {4, 120, 4, 6, 2}, {5, 60, 4, 4, 5},
                          {3, 0, 23, 7, 1}, {1, 0, 23, 0, 1}, {6, 30, 4, 0, 1}, {4, 4096, 23, 2, 1}};
    std::vector<Bytes> seeds;
    for (const Spec& s : specs) {
        svotest::PackOptions o;
        o.pointer_bits = s.pointer_bits;
        o.attributes = s.attributes;
        o.materials = s.materials;
        const SvoTree t = svotest::pack_cells(s.depth, svotest::random_cells(s.depth, s.voxels, s.depth * 7 + s.voxels), o);
        Bytes b;
        SvoStatus st;
        if (!svo_save(t, b, st)) {
            std::fprintf(stderr, "fuzz_svo_load: seed tree does not save: %s\n", st.message.c_str());
            std::exit(2);
        }
        seeds.push_back(b);
    }
    return seeds;
}

#endif

uint64_t interesting(Rng& r, uint64_t v)
{
    switch (r.below(12)) {
        case 0: return 0;
        case 1: return 1;
        case 2: return v + 1;
        case 3: return v - 1;
        case 4: return 0xFFFFFFFFull;
        case 5: return 0x80000000ull;
        case 6: return 1ull << 32;
        case 7: return ~0ull;
        case 8: return 1ull << 62;
        case 9: return v + (1ull << 31);
        case 10: return v ^ (1ull << r.below(64));
        default: return r.next();
    }
}

void mutate(Rng& r, Bytes& f)
{
    using detail::svo_file::get_u32;
    using detail::svo_file::get_u64;
    using detail::svo_file::put_u32;
    using detail::svo_file::put_u64;
    const int rounds = 1 + int(r.below(3));
    bool fix = r.below(4) != 0;
    for (int k = 0; k < rounds; ++k) {
        const size_t n = f.size();
        switch (r.below(9)) {
            case 0:  // bit flip
                if (n) f[r.below(n)] ^= uint8_t(1u << r.below(8));
                break;
            case 1: {  // byte set
                if (!n) break;
                const uint64_t c = r.below(3);
                f[r.below(n)] = c == 0 ? 0 : c == 1 ? 0xFF : uint8_t(r.next());
                break;
            }
            case 2:  // truncate
                f.resize(r.below(n + 1));
                break;
            case 3: {  // extend
                const size_t add = 1 + r.below(64);
                for (size_t i = 0; i < add; ++i) f.push_back(uint8_t(r.next()));
                break;
            }
            case 4: {  // insert
                const size_t at = r.below(n + 1), add = 1 + r.below(8);
                f.insert(f.begin() + long(at), add, uint8_t(r.next()));
                break;
            }
            case 5: {  // delete
                if (!n) break;
                const size_t at = r.below(n), len = 1 + r.below(n - at < 16 ? n - at : 16);
                f.erase(f.begin() + long(at), f.begin() + long(at + len));
                break;
            }
            case 6: {  // a header field (u32 in 16..63, u64 from 64 to the CRCs), CRCs fixed
                if (n < 208) break;
                uint32_t hs = get_u32(&f[12]);
                if (hs < 208 || hs > 360 || hs > n) hs = 208;
                if (r.below(2)) {
                    const size_t off = 16 + 4 * size_t(r.below(12));
                    put_u32(&f[off], uint32_t(interesting(r, get_u32(&f[off]))));
                } else {
                    const size_t off = 64 + 8 * size_t(r.below((hs - 72) / 8));
                    put_u64(&f[off], interesting(r, get_u64(&f[off])));
                }
                fix = true;
                break;
            }
            default: {  // a payload word (geometry most of the time), CRCs fixed
                if (n < 216) break;
                const uint64_t hs = get_u32(&f[12]);
                if (hs < 208 || hs + 4 > n) break;
                const uint32_t dw = get_u32(&f[48]);
                const uint64_t span = r.below(3) ? uint64_t(dw) + 4u : (n - hs) / 4;
                const uint64_t maxw = (n - hs) / 4;
                const size_t off = hs + 4 * size_t(r.below(span < maxw ? span : maxw));
                const uint32_t v = get_u32(&f[off]);
                uint32_t nv;
                switch (r.below(5)) {
                    case 0: nv = v ^ (1u << r.below(32)); break;                        // any bit
                    case 1: nv = v ^ (1u << r.below(9)); break;                         // mask / far bit
                    case 2: nv = (v & 0x1FFu) | uint32_t(r.below(64) << 9); break;      // small pointer
                    case 3: nv = v + (r.below(2) ? 1u : 0xFFFFFFFFu); break;           // off by one
                    default: nv = uint32_t(interesting(r, v)); break;
                }
                put_u32(&f[off], nv);
                fix = true;
                break;
            }
        }
    }
    if (fix) fix_crcs(f);
}


}  // namespace

#ifdef RAYKIT_LIBFUZZER
extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size);

// libFuzzer's own mutations half the time, these structure-aware ones (which mostly recompute the
// CRCs, so that mutants reach the count checks and svo_validate) the other half.
extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t max_size, unsigned int seed)
{
    Rng r{(uint64_t(seed) << 1) | 1u};
    if (r.below(2)) {
        size = LLVMFuzzerMutate(data, size, max_size);
        if (r.below(2)) {
            Bytes f(data, data + size);
            fix_crcs(f);
            std::memcpy(data, f.data(), size);
        }
        return size;
    }
    Bytes f(data, data + size);
    mutate(r, f);
    if (f.size() > max_size) f.resize(max_size);
    std::memcpy(data, f.data(), f.size());
    return f.size();
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    check_one(data, size, size);
    return 0;
}
#else
int main(int argc, char** argv)
{
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s SECONDS [SEED] [--write-seeds DIR]\n", argv[0]);
        return 2;
    }
    const std::vector<Bytes> seeds = make_seeds();
    for (int i = 1; i + 1 < argc; ++i)
        if (std::string(argv[i]) == "--write-seeds") {
            for (size_t s = 0; s < seeds.size(); ++s) {
                const std::string p = std::string(argv[i + 1]) + "/seed" + std::to_string(s) + ".rksvo";
                std::FILE* f = std::fopen(p.c_str(), "wb");
                if (!f || std::fwrite(seeds[s].data(), 1, seeds[s].size(), f) != seeds[s].size()) return 1;
                std::fclose(f);
            }
            std::printf("wrote %zu seeds to %s\n", seeds.size(), argv[i + 1]);
            return 0;
        }
    const double seconds = std::atof(argv[1]);
    const uint64_t seed = argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 20240611u;
    Rng r{seed * 0x9E3779B97F4A7C15ull + 1};
    long counts[16] = {};
    long iters = 0;
    // The seeds themselves load.
    for (const Bytes& s : seeds)
        if (check_one(s.data(), s.size(), 1) != SvoError::ok) die("a seed file does not load", s.data(), s.size());
    const auto t0 = std::chrono::steady_clock::now();
    for (;;) {
        if ((iters & 63) == 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >= seconds) break;
        Bytes f = seeds[r.below(seeds.size())];
        mutate(r, f);
        ++counts[int(check_one(f.data(), f.size(), r.next()))];
        ++iters;
    }
    std::printf("fuzz_svo_load: seed %llu, %.1f s, %ld iterations, %ld loaded\n", static_cast<unsigned long long>(seed), seconds, iters,
                counts[0]);
    for (int c = 1; c < 16; ++c)
        if (counts[c]) std::printf("  %-20s %ld\n", svo_error_name(SvoError(c)), counts[c]);
    return 0;
}
#endif
