// cl_fixture.h — the OpenCL device the kernel tests run on.
//
// One device per test process, chosen like the CLI does (FEN_CL_DEVICE, else the default:
// first GPU, else first CPU -- PoCL in CI). With no device the kernel tests skip, except when
// FEN_REQUIRE_DEVICE=1 (set by CTest for every test), where a missing device is a failure: CI
// must never pass by skipping.
#pragma once

#include <gtest/gtest.h>

#include "cl/context.h"

namespace fen { namespace test {

// The process-wide device context, or nullptr (with the reason in *why).
ocl::Context* clContext(std::string* why);
bool deviceRequired();

} }  // namespace fen::test

#define FEN_CL_CONTEXT_OR_SKIP(ctx)                                              \
    std::string fen_why_;                                                        \
    ::fen::ocl::Context* ctx = ::fen::test::clContext(&fen_why_);                \
    if (!ctx) {                                                                  \
        if (::fen::test::deviceRequired())                                       \
            FAIL() << "no OpenCL device (FEN_REQUIRE_DEVICE=1): " << fen_why_;   \
        GTEST_SKIP() << "no OpenCL device: " << fen_why_;                        \
    }
