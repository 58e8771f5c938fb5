// path_checks.cpp — checks on the names a user gives (path_checks.h).
#include "io/path_checks.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <sys/stat.h>

#include "util/error.h"

namespace fen {

namespace fs = std::filesystem;

std::string resolvedPath(const std::string& path)
{
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::absolute(fs::path(path), ec), ec);
    if (ec)
        return fs::absolute(fs::path(path)).lexically_normal().string();
    return p.string();
}

bool sameFile(const std::string& a, const std::string& b)
{
    struct stat sa {}, sb {};
    if (::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0)
        return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
    return resolvedPath(a) == resolvedPath(b);
}

void refuseOverwritingInputs(const std::string& output, const std::string& option,
                             const std::vector<std::pair<std::string, std::string>>& inputs)
{
    for (const auto& [what, input] : inputs)
        if (!input.empty() && sameFile(output, input))
            throw Error(cat(option, " ", printable(output), ": is ", what, " (", printable(input),
                            "); it would be overwritten: write elsewhere"));
}

void requireRegularFile(const std::string& path, const std::string& option)
{
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(cat(printable(path), ": cannot open ", option, ": ", std::strerror(errno)));
    if (!S_ISREG(st.st_mode))
        throw Error(cat(printable(path), ": ", option, " must be a regular file, not ",
                        S_ISDIR(st.st_mode) ? "a folder" : S_ISFIFO(st.st_mode) ? "a FIFO" : "a device or socket"));
}

}  // namespace fen
