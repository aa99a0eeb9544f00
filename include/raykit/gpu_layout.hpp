// raykit — gpu_layout.hpp: writing raykit's shared structs into GLSL uniform (std140) and storage
// (std430) blocks. C++ only, GLM only, no exceptions.
//
// The C++ build of a shared struct is a plain struct of glm types, and glm's layout is not GLSL's:
// a vec3 is 12 bytes aligned to 4 in C++ but aligned to 16 in both block layouts, and std140 also
// rounds structs up to 16 (rk_im_grid: origin at byte 12 in C++, 16 in a block). So never memcpy
// one into a block; gpu_pack() writes each field at its block offset, from a field list that the
// struct's header declares next to it:
//
//   template <class V> void rk_gpu_fields(V& v, const rk_im_grid& s) { v("room_size", s.room_size); ... }
//
// tests/test_gpu_layout.cpp compiles each struct inside a std140 and a std430 block with glslang
// and checks every member's offset, the member set and the block size against its reflection, so a
// field list that drifts from the GLSL struct fails there. Supported members: float, int32_t,
// uint32_t, bool (a 4-byte uint in a block), glm vec2/3/4, ivec2/3/4, uvec2/3/4, mat4 (column-major,
// as GLSL's default), and nested structs with their own rk_gpu_fields. Arrays and other matrices:
// not needed by any raykit struct yet.
//
// Cost: one pass over the fields (no allocation) per gpu_pack; the offsets are the same each call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>

namespace raykit {

/// A GLSL block layout: `layout(std140) uniform` or `layout(std430) buffer` (also Vulkan's scalar-
/// free default for storage buffers).
enum class GpuLayout { std140, std430 };

/// One member of a struct laid out in a block: its dotted name ("grid.origin") and byte offset.
struct GpuMember {
    std::string name;
    size_t offset;
};

namespace detail {

template <class T>
struct gpu_leaf {
    static constexpr bool value = false;
};
#define RK_GPU_LEAF(T, N, A)                          \
    template <>                                       \
    struct gpu_leaf<T> {                              \
        static constexpr bool value = true;           \
        static constexpr size_t size = N;             \
        static constexpr size_t align = A;            \
    };
RK_GPU_LEAF(float, 4, 4)
RK_GPU_LEAF(int32_t, 4, 4)
RK_GPU_LEAF(uint32_t, 4, 4)
RK_GPU_LEAF(bool, 4, 4)
RK_GPU_LEAF(glm::vec2, 8, 8)
RK_GPU_LEAF(glm::ivec2, 8, 8)
RK_GPU_LEAF(glm::uvec2, 8, 8)
RK_GPU_LEAF(glm::vec3, 12, 16)
RK_GPU_LEAF(glm::ivec3, 12, 16)
RK_GPU_LEAF(glm::uvec3, 12, 16)
RK_GPU_LEAF(glm::vec4, 16, 16)
RK_GPU_LEAF(glm::ivec4, 16, 16)
RK_GPU_LEAF(glm::uvec4, 16, 16)
RK_GPU_LEAF(glm::mat4, 64, 16)
#undef RK_GPU_LEAF

inline size_t gpu_round_up(size_t x, size_t a) { return (x + a - 1) / a * a; }

template <class T>
void gpu_write_leaf(uint8_t* dst, const T& v)
{
    if constexpr (std::is_same<T, bool>::value) {
        const uint32_t u = v ? 1u : 0u;
        std::memcpy(dst, &u, 4);
    } else if constexpr (std::is_arithmetic<T>::value) {
        std::memcpy(dst, &v, 4);
    } else if constexpr (std::is_same<T, glm::mat4>::value) {
        for (int c = 0; c < 4; ++c) std::memcpy(dst + 16 * c, &v[c][0], 16);  // column-major, vec4 columns
    } else {
        for (int i = 0; i < T::length(); ++i) std::memcpy(dst + 4 * i, &v[i], 4);
    }
}

/// Base alignment of a struct in a block: its largest member's (std140: at least 16).
struct GpuAlignVisitor {
    explicit GpuAlignVisitor(GpuLayout l) : layout(l) {}
    GpuLayout layout;
    size_t align = 4;
    template <class T>
    void operator()(const char*, const T& v);
};

template <class T>
size_t gpu_struct_align(GpuLayout layout)
{
    GpuAlignVisitor a(layout);
    rk_gpu_fields(a, T{});
    return layout == GpuLayout::std140 ? gpu_round_up(a.align, 16) : a.align;
}

template <class T>
void GpuAlignVisitor::operator()(const char*, const T&)
{
    size_t m;
    if constexpr (gpu_leaf<T>::value) {
        m = gpu_leaf<T>::align;
    } else {
        m = gpu_struct_align<T>(layout);
    }
    align = m > align ? m : align;
}

/// Lays the fields out in order (GLSL's rules), writing them to `dst` and/or naming them.
struct GpuPackVisitor {
    explicit GpuPackVisitor(GpuLayout l) : layout(l) {}
    GpuLayout layout;
    uint8_t* dst = nullptr;                   // null: offsets only
    std::vector<GpuMember>* members = nullptr;  // null: no names
    std::string prefix;
    size_t offset = 0;

    template <class T>
    void operator()(const char* name, const T& v)
    {
        if constexpr (gpu_leaf<T>::value) {
            offset = gpu_round_up(offset, gpu_leaf<T>::align);
            if (dst) gpu_write_leaf(dst + offset, v);
            if (members) members->push_back({prefix + name, offset});
            offset += gpu_leaf<T>::size;
        } else {
            const size_t a = gpu_struct_align<T>(layout);
            offset = gpu_round_up(offset, a);
            const size_t saved = prefix.size();
            if (members) prefix += std::string(name) + ".";
            rk_gpu_fields(*this, v);
            if (members) prefix.resize(saved);
            offset = gpu_round_up(offset, a);  // the member after a struct starts at its alignment
        }
    }
};

}  // namespace detail

/// gpu_size: bytes of T in a block of this layout (what `T v;` alone occupies; the block's size
/// when it is the only member), padding included.
template <class T>
size_t gpu_size(GpuLayout layout)
{
    detail::GpuPackVisitor v(layout);
    rk_gpu_fields(v, T{});
    return detail::gpu_round_up(v.offset, detail::gpu_struct_align<T>(layout));
}

/// gpu_members: every leaf member of T with its dotted name and byte offset in a block of this
/// layout, in declaration order (for checks and debugging).
template <class T>
std::vector<GpuMember> gpu_members(GpuLayout layout)
{
    std::vector<GpuMember> out;
    detail::GpuPackVisitor v(layout);
    v.members = &out;
    rk_gpu_fields(v, T{});
    return out;
}

/// gpu_pack: writes `value` into `dst` (gpu_size<T>(layout) bytes) as a block of this layout reads
/// it; padding bytes are zeroed.
template <class T>
void gpu_pack(const T& value, GpuLayout layout, void* dst)
{
    std::memset(dst, 0, gpu_size<T>(layout));
    detail::GpuPackVisitor v(layout);
    v.dst = static_cast<uint8_t*>(dst);
    rk_gpu_fields(v, value);
}

/// gpu_pack into a new byte vector.
template <class T>
std::vector<uint8_t> gpu_pack(const T& value, GpuLayout layout)
{
    std::vector<uint8_t> bytes(gpu_size<T>(layout));
    gpu_pack(value, layout, bytes.data());
    return bytes;
}

}  // namespace raykit
