// probes_test.cpp — what the device compiler sees equals what the host compiler sees:
// struct sizes/offsets (FEN_SHARED_LAYOUT) and the Philox random stream, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cctype>
#include <cstddef>
#include <sstream>
#include <vector>

#include "cl/launch.h"
#include "shared/fen_layout.h"
#include "shared/fen_rng.h"
#include "support/cl_fixture.h"
#include "cl/device.h"
#include "util/error.h"

namespace fen {
namespace {

using namespace fen::dev;

// Runs test_probes.cl's `kernel`(in_0, ..., in_k, out, n) over n items, in_j[i] the inputs of item i,
// and returns out, which holds per_item floats for each item.
std::vector<float> runProbe(ocl::Context& ctx, const char* kernel, const std::vector<const std::vector<float>*>& in,
                            std::size_t per_item)
{
    const auto n = static_cast<std::uint32_t>(in.front()->size());
    cl::Kernel k(ctx.program("test_probes.cl"), kernel);
    std::vector<cl::Buffer> inputs;
    for (const std::vector<float>* v : in) {
        inputs.push_back(ctx.buffer(CL_MEM_READ_ONLY, n * 4, "probe input", v->data()));
        k.setArg(static_cast<cl_uint>(inputs.size() - 1), inputs.back());
    }
    cl::Buffer out = ctx.buffer(CL_MEM_WRITE_ONLY, n * per_item * 4, "probe results");
    k.setArg(static_cast<cl_uint>(in.size()), out);
    k.setArg(static_cast<cl_uint>(in.size() + 1), n);
    ocl::launch(ctx, k, kernel, n);
    std::vector<float> device(n * per_item);
    ctx.queue().enqueueReadBuffer(out, CL_TRUE, 0, device.size() * 4, device.data());
    return device;
}

// n pairs of positive floats over twenty orders of magnitude (2^-32 .. 2^32), from the stream (k0, k1).
void spreadOperands(std::uint32_t n, std::uint32_t k0, std::uint32_t k1, std::vector<float>& a, std::vector<float>& b)
{
    a.resize(n);
    b.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        const RngBlock r = fen_philox4x32_10({i, 0, 0, 0}, k0, k1);
        a[i] = std::ldexp(1.0f + fen_u32_to_unit(r.x), static_cast<int>(r.y % 64) - 32);
        b[i] = std::ldexp(1.0f + fen_u32_to_unit(r.z), static_cast<int>(r.w % 64) - 32);
    }
}

TEST(Probes, SharedStructLayoutMatchesHost)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    std::vector<std::uint32_t> host;
    std::vector<std::string> names;
#define FEN_HOST_PROBE(T, m)                               \
    host.push_back(static_cast<std::uint32_t>(sizeof(T))); \
    host.push_back(static_cast<std::uint32_t>(offsetof(T, m))); \
    names.push_back(#T "." #m);
    FEN_SHARED_LAYOUT(FEN_HOST_PROBE)
#undef FEN_HOST_PROBE

    cl::Program prog = ctx->program("test_probes.cl");
    cl::Kernel k(prog, "layout_probe");
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, host.size() * 4, "layout");
    cl::Buffer scratch = ctx->buffer(CL_MEM_READ_WRITE, 4096, "scratch");
    ocl::setKernelArgs(k, out, scratch);
    ocl::launch(*ctx, k, "layout_probe", 1, 1);
    std::vector<std::uint32_t> device(host.size());
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, device.size() * 4, device.data());
    for (std::size_t i = 0; i < names.size(); ++i) {
        EXPECT_EQ(device[2 * i], host[2 * i]) << "sizeof " << names[i];
        EXPECT_EQ(device[2 * i + 1], host[2 * i + 1]) << "offsetof " << names[i];
    }
}

TEST(Probes, PhiloxStreamMatchesHostBitForBit)
{
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const std::uint32_t n = 10000, c1 = 7, c2 = 0xFFFFFFFFu, c3 = 3, k0 = 0xDEADBEEFu, k1 = 42;
    cl::Program prog = ctx->program("test_probes.cl");
    cl::Kernel k(prog, "rng_probe");
    cl::Buffer out = ctx->buffer(CL_MEM_WRITE_ONLY, n * 16, "rng");
    ocl::setKernelArgs(k, out, n, c1, c2, c3, k0, k1);
    ocl::launch(*ctx, k, "rng_probe", n);
    std::vector<std::uint32_t> device(4 * n);
    ctx->queue().enqueueReadBuffer(out, CL_TRUE, 0, device.size() * 4, device.data());
    std::size_t mismatches = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const RngBlock r = fen_philox4x32_10({i, c1, c2, c3}, k0, k1);
        mismatches += r.x != device[4 * i] || r.y != device[4 * i + 1] ||
                      r.z != device[4 * i + 2] || r.w != device[4 * i + 3];
    }
    EXPECT_EQ(mismatches, 0u);
}

TEST(Probes, DivisionAndSqrtRoundAsOnTheHost)
{
    // OpenCL allows float / and sqrt to be 2.5 and 3 ulp off; NVIDIA's driver uses that, and its
    // triangle hits then differed from the CPU reference in the last bits. Context::program asks
    // for IEEE rounding wherever the device offers it; then every quotient and root must be the
    // host's, bit for bit, across twenty orders of magnitude.
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    if (!ctx->info().correctlyRoundedDivSqrt)
        GTEST_SKIP() << ctx->info().label() << " cannot round float division as IEEE 754 does";
    const std::uint32_t n = 1u << 16;
    std::vector<float> a, b;
    spreadOperands(n, 11, 12, a, b);
    const std::vector<float> device = runProbe(*ctx, "divsqrt_probe", {&a, &b}, 2);
    std::size_t quotients = 0, roots = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        quotients += device[2 * i] != a[i] / b[i];
        roots += device[2 * i + 1] != std::sqrt(a[i]);
    }
    EXPECT_EQ(quotients, 0u);
    EXPECT_EQ(roots, 0u);
}

TEST(Probes, ProductsAndSumsRoundSeparately)
{
    // OpenCL lets a compiler fuse a product and a sum into one fused multiply-add, rounded once.
    // A fused and an unfused edge test can send a ray through a shared edge to different
    // neighbours, so every program starts with FP_CONTRACT OFF (resolveKernelSource): this checks
    // that the device honours it, each product and each sum rounding on its own as on the host.
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const std::uint32_t n = 1u << 16;
    std::vector<float> x, y, c(n);
    spreadOperands(n, 13, 14, x, y);
    for (std::uint32_t i = 0; i < n; ++i) {
        volatile float p = x[i] * y[i];  // volatile: the host's compiler may not fuse either
        c[i] = -p;
    }
    const std::vector<float> device = runProbe(*ctx, "contract_probe", {&x, &y, &c}, 2);
    std::size_t inStatement = 0, acrossStatements = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        inStatement += device[2 * i] != 0.0f;
        acrossStatements += device[2 * i + 1] != 0.0f;
    }
    EXPECT_EQ(inStatement, 0u) << "x * y + c fused in one statement";
    EXPECT_EQ(acrossStatements, 0u) << "p = x * y; p + c fused across statements";
}

TEST(Probes, CpuKernelsFlushDenormals)
{
    // Kernels are built with -cl-denorms-are-zero (host/cl/context.cpp): on x86 a float3's spare
    // lane often holds bits that read as a denormal, and arithmetic on it took microcode assists
    // that cost a uniform render of scenes/room.gltf 30 % of its time (docs/results/denormals.md).
    // If the option stopped reaching the CPU's flush modes, renders would slow down with no other
    // symptom; this says so.
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    if (!ctx->info().isCpu())
        GTEST_SKIP() << ctx->info().label() << " is not a CPU: denormals cost no assists there";
    const float tiny = std::ldexp(1.0f, -140);  // a denormal operand
    const float small = std::ldexp(1.0f, -70);  // normal, but its square is a denormal
    const std::vector<float> a = {tiny, small, 3.0f, -tiny};
    const std::vector<float> b = {1.0f, small, 0.5f, 1.0f};
    ASSERT_GT(tiny * 1.0f, 0.0f) << "the host itself flushes denormals";
    const std::vector<float> device = runProbe(*ctx, "denormal_probe", {&a, &b}, 1);
    EXPECT_EQ(device[0], 0.0f) << "a denormal operand was not treated as zero";
    EXPECT_EQ(device[1], 0.0f) << "a denormal result was not flushed to zero";
    EXPECT_EQ(device[2], 1.5f);
    EXPECT_EQ(device[3], 0.0f);
}

TEST(Probes, DeviceIsFoundByItsPlatformVersion)
{
    // --device matches "platform / device (platform version)": PoCL's platform is named "Portable
    // Computing Language", and `--device pocl` finds it only through its version string
    // ("OpenCL 3.0 PoCL 3.1 ..."); NVIDIA's is found by "cuda" the same way.
    FEN_CL_CONTEXT_OR_SKIP(ctx);
    const ocl::DeviceInfo& d = ctx->info();
    std::istringstream words(d.platformVersion);
    std::string opencl, version, implementation;
    words >> opencl >> version >> implementation;  // "OpenCL" "3.0" "<implementation>"
    if (implementation.empty())
        GTEST_SKIP() << "platform version '" << d.platformVersion << "' names no implementation";
    for (char& c : implementation)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const ocl::DeviceInfo found = ocl::selectDevice(implementation);
    EXPECT_NE(found.matchText().find(d.platformVersion), std::string::npos) << implementation;
    EXPECT_THROW(ocl::selectDevice("no such implementation"), Error);
}

TEST(Probes, PhiloxKnownAnswer)
{
    // Known-answer vectors of Random123 (kat_vectors, philox4x32_10).
    const RngBlock zero = fen_philox4x32_10({0, 0, 0, 0}, 0, 0);
    EXPECT_EQ(zero.x, 0x6627e8d5u);
    EXPECT_EQ(zero.y, 0xe169c58du);
    EXPECT_EQ(zero.z, 0xbc57ac4cu);
    EXPECT_EQ(zero.w, 0x9b00dbd8u);
    const RngBlock ones = fen_philox4x32_10({0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu},
                                            0xffffffffu, 0xffffffffu);
    EXPECT_EQ(ones.x, 0x408f276du);
    EXPECT_EQ(ones.y, 0x41c83b0eu);
    EXPECT_EQ(ones.z, 0xa20bc7c6u);
    EXPECT_EQ(ones.w, 0x6d5451fdu);
}

TEST(Probes, UnitFloatNeverReachesOne)
{
    EXPECT_EQ(fen_u32_to_unit(0u), 0.0f);
    EXPECT_LT(fen_u32_to_unit(0xFFFFFFFFu), 1.0f);
}

}  // namespace
}  // namespace fen
