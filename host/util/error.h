// error.h — the one exception type for everything a user can get wrong (input files, options,
// devices), `cat` to build its message and `printable` for the parts of it that come from a file.
//
// Errors are thrown where they are found, with the file / node / key they point at, and caught
// once, in main() (host/main.cpp), which prints "fenestra: error: <message>" and exits non-zero.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace fen {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

template <class... Args>
std::string cat(const Args&... args)
{
    std::ostringstream s;
    (s << ... << args);
    return s.str();
}

// Text from an input file (a name, a URI, a parser's message) made fit for a one-line message:
// control characters escaped, at most `max` bytes kept. Errors are one line whatever a file holds.
inline std::string printable(const std::string& text, std::size_t max = 200)
{
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (std::size_t i = 0; i < text.size() && i < max; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (c < 0x20 || c == 0x7f) {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        } else {
            out += static_cast<char>(c);
        }
    }
    if (text.size() > max)
        out += "...";
    return out;
}

}  // namespace fen
