// error_of.h — the message of the fen::Error a call throws, for tests of one-line errors.
#pragma once

#include <functional>
#include <string>

#include "util/error.h"

namespace fen { namespace test {

// What f throws as fen::Error, or "(no error)" when it throws nothing.
inline std::string errorOf(const std::function<void()>& f)
{
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

} }  // namespace fen::test
