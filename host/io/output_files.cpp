// output_files.cpp — checked, all-or-nothing output writing (output_files.h).
#include "io/output_files.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <stb/stb_image_write.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/error.h"

namespace fen {

namespace {

namespace fs = std::filesystem;

// The process's umask (reading it means setting it; set back at once, before any file is made).
mode_t processUmask()
{
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return mask;
}

std::string errnoText(int e) { return std::strerror(e); }

// A new file next to `path` (same folder: the rename stays within one file system), created
// exclusively; returns its descriptor and name.
int createTemporary(const std::string& path, std::string* name)
{
    const fs::path p(path);
    std::string pattern = (p.parent_path().empty() ? fs::path(".") : p.parent_path()) / ("." + p.filename().string() + ".XXXXXX");
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    const int fd = mkstemp(buf.data());
    if (fd < 0)
        throw Error(cat(path, ": cannot create a file there: ", errnoText(errno)));
    *name = buf.data();
    return fd;
}

void writeAll(int fd, const std::string& path, const std::string& bytes)
{
    const char* fail = std::getenv("FEN_FAIL_WRITE");
    if (fail && *fail && path.find(fail) != std::string::npos)
        throw Error(cat(path, ": cannot write: ", errnoText(ENOSPC), " (FEN_FAIL_WRITE)"));
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            throw Error(cat(path, ": cannot write: ", errnoText(errno)));
        }
        done += static_cast<std::size_t>(n);
    }
    if (::fsync(fd) != 0)
        throw Error(cat(path, ": cannot write: ", errnoText(errno)));
}

}  // namespace

void OutputFiles::add(const std::string& path, std::string bytes) { files_.emplace_back(path, std::move(bytes)); }

void OutputFiles::commit()
{
    std::vector<std::string> temporaries;
    try {
        for (const auto& [path, bytes] : files_) {
            std::string tmp;
            const int fd = createTemporary(path, &tmp);
            temporaries.push_back(tmp);
            try {
                writeAll(fd, path, bytes);
            } catch (...) {
                ::close(fd);
                throw;
            }
            if (::close(fd) != 0)
                throw Error(cat(path, ": cannot write: ", errnoText(errno)));
            // mkstemp makes the file private; outputs are ordinary files, with the permissions the
            // user's umask gives a new file (as open(2) with 0666 would).
            ::chmod(tmp.c_str(), 0666 & ~processUmask());
        }
        for (std::size_t i = 0; i < files_.size(); ++i)
            if (std::rename(temporaries[i].c_str(), files_[i].first.c_str()) != 0)
                throw Error(cat(files_[i].first, ": cannot write: ", errnoText(errno)));
    } catch (...) {
        for (const auto& t : temporaries)
            ::unlink(t.c_str());
        throw;
    }
}

void checkOutputPath(const std::string& path, const std::string& what)
{
    std::error_code ec;
    const fs::path p(path);
    const fs::path dir = p.parent_path();
    if (!dir.empty())
        fs::create_directories(dir, ec);
    if (ec)
        throw Error(cat(what, " ", path, ": cannot create folder ", dir.string(), ": ", ec.message()));
    if (fs::is_directory(p, ec))
        throw Error(cat(what, " ", path, ": is a folder, not a file"));
    std::string tmp;
    const int fd = createTemporary(path, &tmp);
    ::close(fd);
    ::unlink(tmp.c_str());
}

std::string encodePng(int width, int height, int channels, const std::vector<unsigned char>& pixels)
{
    std::string out;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
    };
    if (!stbi_write_png_to_func(append, &out, width, height, channels, pixels.data(), width * channels))
        throw Error("cannot encode PNG");
    return out;
}

}  // namespace fen
