// cl_fixture.cpp — lazily opened, process-wide test device (cl_fixture.h).
#include "support/cl_fixture.h"

#include <cstdlib>
#include <memory>

#include "cl/cl_error.h"
#include "util/error.h"

namespace fen { namespace test {

bool deviceRequired()
{
    const char* v = std::getenv("FEN_REQUIRE_DEVICE");
    return v && std::string(v) == "1";
}

ocl::Context* clContext(std::string* why)
{
    static std::unique_ptr<ocl::Context> ctx;
    static std::string error;
    static bool tried = false;
    if (!tried) {
        tried = true;
        try {
            ctx = std::make_unique<ocl::Context>(ocl::selectDevice(""));
        } catch (const Error& e) {
            error = e.what();
        } catch (const cl::Error& e) {
            error = ocl::describe(e);
        }
    }
    if (!ctx && why)
        *why = error;
    return ctx.get();
}

} }  // namespace fen::test
