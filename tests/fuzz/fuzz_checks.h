// fuzz_checks.h — what every fuzz target asks of a message: one line of text, whatever the input
// held. A control character (a newline, an escape) is a finding: the target traps.
#pragma once

#include <string>

namespace fen::fuzz {

inline void requireOneLine(const std::string& message)
{
    for (const char c : message)
        if (static_cast<unsigned char>(c) < 0x20)
            __builtin_trap();
}

}  // namespace fen::fuzz
