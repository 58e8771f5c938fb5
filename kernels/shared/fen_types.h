/* fen_types.h — the scalar and vector types that host C++ and OpenCL C share.
 *
 * Compiled by both g++ (host) and the OpenCL C 1.2 compiler (PoCL, NVIDIA). Every struct that
 * crosses the host/device boundary is built only from these types, so its layout is the same
 * on both sides (DESIGN.md §4; README "Kernels and OpenCL"):
 *   - fen_float4 is the 16-byte padded vector; there is deliberately no 3-vector type here,
 *     because OpenCL's float3 is 16 bytes and glm::vec3 is 12.
 *   - no bool, size_t, long, enum or pointer members; 64-bit values are fen_u64.
 * Sizes and offsets are asserted with FEN_ASSERT_SIZE / FEN_ASSERT_OFFSET on both sides, and a
 * layout kernel compares them on every device at test time (tests/kernels/probes_test.cpp).
 */
#ifndef FEN_TYPES_H
#define FEN_TYPES_H

#ifdef __OPENCL_VERSION__

typedef uint   fen_u32;
typedef int    fen_i32;
typedef ulong  fen_u64;
typedef float  fen_f32;
typedef float4 fen_float4;

#define FEN_NS_BEGIN
#define FEN_NS_END
#define FEN_GLOBAL global
/* PoCL (clang) accepts C11 _Static_assert in OpenCL C 1.2; other front ends rely on the
   layout test kernel instead. */
#if defined(__clang__)
#define FEN_ASSERT_SIZE(T, n) _Static_assert(sizeof(T) == (n), #T " has the wrong size")
#define FEN_ASSERT_OFFSET(T, m, n) \
    _Static_assert(__builtin_offsetof(T, m) == (n), #T "." #m " has the wrong offset")
#else
#define FEN_ASSERT_SIZE(T, n)
#define FEN_ASSERT_OFFSET(T, m, n)
#endif

#else /* host C++ */

#include <cstddef>
#include <cstdint>
#include <cstring>

#define FEN_NS_BEGIN namespace fen { namespace dev {
#define FEN_NS_END } }
#define FEN_GLOBAL

FEN_NS_BEGIN
typedef std::uint32_t fen_u32;
typedef std::int32_t  fen_i32;
typedef std::uint64_t fen_u64;
typedef float         fen_f32;
/* The host twin of OpenCL's float4: 16 bytes, 16-byte aligned. */
struct alignas(16) fen_float4 {
    float x, y, z, w;
};
static_assert(sizeof(fen_float4) == 16, "fen_float4 must be 16 bytes");
/* The host twin of OpenCL's as_float: an id stored in a float lane that the device reads back
   with as_uint. */
inline fen_f32 fen_as_float(fen_u32 u)
{
    fen_f32 f;
    std::memcpy(&f, &u, sizeof f);
    return f;
}
/* ... and of as_uint: a float's bits, stored in a uint buffer. */
inline fen_u32 fen_as_uint(fen_f32 f)
{
    fen_u32 u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}
FEN_NS_END

#define FEN_ASSERT_SIZE(T, n) static_assert(sizeof(T) == (n), #T " has the wrong size")
#define FEN_ASSERT_OFFSET(T, m, n) static_assert(offsetof(T, m) == (n), #T "." #m " has the wrong offset")

#endif

#endif /* FEN_TYPES_H */
