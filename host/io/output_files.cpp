// output_files.cpp — checked, all-or-nothing output writing (output_files.h).
#include "io/output_files.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <csignal>
#include <fstream>

#include <fcntl.h>
#include <sys/file.h>
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

// Beside `path`: ".NAME" + suffix.
std::string besides(const std::string& path, const std::string& suffix)
{
    const fs::path p(path);
    return ((p.parent_path().empty() ? fs::path(".") : p.parent_path()) / ("." + p.filename().string() + suffix)).string();
}

// `bytes` in a new temporary file beside `path` (every write, the flush and fsync checked), with the
// permissions the user's umask gives a new file (mkstemp makes it private; outputs are ordinary
// files, as open(2) with 0666 would make them). Returns its name; on failure nothing is left.
std::string writeTemporary(const std::string& path, const std::string& bytes)
{
    std::string tmp;
    const int fd = createTemporary(path, &tmp);
    try {
        writeAll(fd, path, bytes);
    } catch (...) {
        ::close(fd);
        ::unlink(tmp.c_str());
        throw;
    }
    if (::close(fd) != 0) {
        const int e = errno;
        ::unlink(tmp.c_str());
        throw Error(cat(path, ": cannot write: ", errnoText(e)));
    }
    ::chmod(tmp.c_str(), 0666 & ~processUmask());
    return tmp;
}

// Writes `bytes` to `path` through a temporary and a rename (the journal itself).
void writeAtomically(const std::string& path, const std::string& bytes)
{
    const std::string tmp = writeTemporary(path, bytes);
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        ::unlink(tmp.c_str());
        throw Error(cat(path, ": cannot write: ", errnoText(errno)));
    }
}

// A journal left by a commit that did not finish: rename what is still a temporary into place.
// Returns the number of files it moved.
int finishCommit(const std::string& journal)
{
    std::ifstream in(journal);
    if (!in)
        return 0;
    std::string line;
    int moved = 0;
    while (std::getline(in, line)) {
        const std::size_t tab = line.find('\t');
        if (tab == std::string::npos)
            continue;
        const std::string tmp = line.substr(0, tab), final = line.substr(tab + 1);
        if (::access(tmp.c_str(), F_OK) == 0 && std::rename(tmp.c_str(), final.c_str()) == 0)
            ++moved;
    }
    ::unlink(journal.c_str());
    return moved;
}

void killAfterRenamesForTests(int renames)
{
    const char* n = std::getenv("FEN_KILL_AFTER_RENAMES");
    if (n && *n && std::atoi(n) == renames)
        ::raise(SIGKILL);
}

void OutputFiles::commit()
{
    std::vector<std::string> temporaries;
    try {
        for (const auto& [path, bytes] : files_)
            temporaries.push_back(writeTemporary(path, bytes));
    } catch (...) {
        for (const auto& t : temporaries)
            ::unlink(t.c_str());
        throw;
    }
    // From here the set is on disk: the journal makes the renames all-or-nothing across a kill.
    const std::string journal = besides(files_.front().first, ".commit");
    if (files_.size() > 1) {
        std::string list;
        for (std::size_t i = 0; i < files_.size(); ++i)
            list += temporaries[i] + "\t" + files_[i].first + "\n";
        try {
            writeAtomically(journal, list);
        } catch (...) {
            for (const auto& t : temporaries)
                ::unlink(t.c_str());
            throw;
        }
    }
    for (std::size_t i = 0; i < files_.size(); ++i) {
        if (std::rename(temporaries[i].c_str(), files_[i].first.c_str()) != 0) {
            const int e = errno;
            // Some may be in place already: finish the set if the journal can, else leave it whole.
            if (files_.size() > 1)
                finishCommit(journal);
            for (std::size_t k = i; k < files_.size(); ++k)
                ::unlink(temporaries[k].c_str());
            throw Error(cat(files_[i].first, ": cannot write: ", errnoText(e)));
        }
        killAfterRenamesForTests(static_cast<int>(i + 1));
    }
    if (files_.size() > 1)
        ::unlink(journal.c_str());
}

OutputSetLock::OutputSetLock(const std::vector<std::string>& files)
{
    lockPath_ = besides(files.front(), ".lock");
    // Lock, then make sure the name still leads to the file locked: a render that just finished
    // may have removed it in between (then take the new one).
    for (int attempt = 0; attempt < 8; ++attempt) {
        fd_ = ::open(lockPath_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666 & ~processUmask());
        if (fd_ < 0)
            throw Error(cat(files.front(), ": cannot create its lock ", lockPath_, ": ", errnoText(errno)));
        if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
            const int e = errno;
            ::close(fd_);
            fd_ = -1;
            if (e == EWOULDBLOCK)
                throw Error(cat(files.front(), ": another render is writing these outputs now (it holds ", lockPath_,
                                "); give this one another --out"));
            throw Error(cat(files.front(), ": cannot lock ", lockPath_, ": ", errnoText(e)));
        }
        struct stat held {}, named {};
        if (::fstat(fd_, &held) == 0 && ::stat(lockPath_.c_str(), &named) == 0 && held.st_ino == named.st_ino &&
            held.st_dev == named.st_dev)
            break;
        ::close(fd_);
        fd_ = -1;
    }
    if (fd_ < 0)
        throw Error(cat(files.front(), ": cannot lock ", lockPath_, ": it keeps changing"));
    // Holding the lock, what a killed render left is ours to finish or remove.
    const int moved = finishCommit(besides(files.front(), ".commit"));
    int orphans = 0;
    for (const std::string& f : files) {
        const fs::path p(f);
        const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
        const std::string prefix = "." + p.filename().string() + ".";
        std::error_code ec;
        for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
            const std::string name = it->path().filename().string();
            // mkstemp's six characters after ".NAME." (the data) or ".NAME.commit." (a journal)
            const bool data = name.size() == prefix.size() + 6 && name.compare(0, prefix.size(), prefix) == 0;
            const bool journal = name.size() == prefix.size() + 13 && name.compare(0, prefix.size() + 7, prefix + "commit.") == 0;
            if (data || journal)
                orphans += ::unlink(it->path().c_str()) == 0;
        }
    }
    if (moved > 0)
        recovered_ = cat("finished writing the ", moved, " outputs of a render killed while it wrote them");
    if (orphans > 0)
        recovered_ += cat(recovered_.empty() ? "" : "; ", "removed ", orphans,
                          " temporary files a killed render left beside the outputs");
}

OutputSetLock::~OutputSetLock()
{
    if (fd_ >= 0) {
        ::unlink(lockPath_.c_str());
        ::close(fd_);
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
