// error.h — the one exception type for everything a user can get wrong (input files, options,
// devices), and `cat` to build its message.
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

}  // namespace fen
