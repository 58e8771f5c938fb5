// kernel_source_test.cpp — the include resolver: nesting, once-only, #line mapping, errors that
// name the including file, and that every embedded kernel resolves.
#include <gtest/gtest.h>

#include <map>

#include "cl/kernel_source.h"
#include "util/error.h"

namespace fen {
namespace {

ocl::KernelFileReader mapReader(std::map<std::string, std::string> files)
{
    return [files](const std::string& path, std::string* out) {
        const auto it = files.find(path);
        if (it == files.end())
            return false;
        *out = it->second;
        return true;
    };
}

TEST(KernelSource, NestedIncludesOnceWithLineMarkers)
{
    const auto reader = mapReader({{"main.cl", "#include \"lib/a.h\"\nkernel void k() {}\n#include \"lib/b.h\"\n"},
                                   {"lib/a.h", "#include \"lib/b.h\"\nint a;\n"},
                                   {"lib/b.h", "int b;\n"}});
    const std::string out = ocl::resolveKernelSource("main.cl", reader);
    // Every program starts by turning contraction off (kernel_source.cpp says why).
    EXPECT_EQ(out,
              "#pragma OPENCL FP_CONTRACT OFF\n"
              "#line 1 \"kernels/main.cl\"\n"
              "#line 1 \"kernels/lib/a.h\"\n"
              "#line 1 \"kernels/lib/b.h\"\n"
              "int b;\n"
              "#line 2 \"kernels/lib/a.h\"\n"
              "int a;\n"
              "#line 2 \"kernels/main.cl\"\n"
              "kernel void k() {}\n"
              "\n");
}

TEST(KernelSource, MissingIncludeNamesTheIncluder)
{
    const auto reader = mapReader({{"main.cl", "int x;\n  #  include \"lib/nope.h\"\n"}});
    try {
        ocl::resolveKernelSource("main.cl", reader);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "kernels/main.cl:2: cannot find included file \"lib/nope.h\"");
    }
    EXPECT_THROW(ocl::resolveKernelSource("absent.cl", reader), Error);
}

TEST(KernelSource, CyclesAreBrokenBySingleInclusion)
{
    const auto reader = mapReader({{"a.h", "#include \"b.h\"\nA\n"}, {"b.h", "#include \"a.h\"\nB\n"}});
    const std::string out = ocl::resolveKernelSource("a.h", reader);
    EXPECT_NE(out.find("A"), std::string::npos);
    EXPECT_NE(out.find("B"), std::string::npos);
}

TEST(KernelSource, SystemIncludesAreLeftToTheCompiler)
{
    const auto reader = mapReader({{"a.cl", "#ifndef __OPENCL_VERSION__\n#include <cstdint>\n#endif\n"}});
    EXPECT_NE(ocl::resolveKernelSource("a.cl", reader).find("#include <cstdint>"), std::string::npos);
}

TEST(KernelSource, EveryEmbeddedKernelResolves)
{
    const auto reader = ocl::defaultKernelReader();
    int programs = 0;
    for (const auto& [name, text] : ocl::embeddedKernelFiles()) {
        if (name.size() < 3 || name.substr(name.size() - 3) != ".cl")
            continue;
        ++programs;
        EXPECT_NO_THROW(ocl::resolveKernelSource(name, reader)) << name;
    }
    EXPECT_GE(programs, 2);
}

}  // namespace
}  // namespace fen
