// output_files.cpp — checked, all-or-nothing output writing (output_files.h).
#include "io/output_files.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <fcntl.h>
#include <stb/stb_image_write.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/error.h"

namespace fen {

namespace {

namespace fs = std::filesystem;

// An OpenEXR output stream into memory: the file is written (and checked) by us, not by the
// library's destructor, which cannot report a failure.
class MemoryStream : public Imf::OStream {
public:
    MemoryStream() : Imf::OStream("memory") {}
    void write(const char c[], int n) override
    {
        if (pos_ + n > data_.size())
            data_.resize(pos_ + n);
        std::memcpy(&data_[pos_], c, n);
        pos_ += n;
    }
    uint64_t tellp() override { return pos_; }
    void seekp(uint64_t pos) override { pos_ = pos; }
    std::string take() { return std::move(data_); }

private:
    std::string data_;
    std::size_t pos_ = 0;
};

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
            // mkstemp makes the file private; outputs are ordinary files.
            ::chmod(tmp.c_str(), 0644);
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

std::string encodeExr(const Image& image)
{
    try {
        Imf::Header header(image.width, image.height);
        for (const char* c : {"R", "G", "B"})
            header.channels().insert(c, Imf::Channel(Imf::FLOAT));
        Imf::FrameBuffer fb;
        const std::size_t xs = 3 * sizeof(float), ys = xs * static_cast<std::size_t>(image.width);
        char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgb.data()));
        fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
        fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
        fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
        MemoryStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(fb);
            file.writePixels(image.height);
        }
        return stream.take();
    } catch (const std::exception& e) {
        throw Error(cat("cannot encode EXR: ", e.what()));
    }
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
