// exr_io.cpp — OpenEXR encoding and reading through the Imf C++ API (exr_io.h).
#include "io/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImathBox.h>
#include <cstring>
#include <exception>

#include "util/error.h"

namespace fen {

namespace {

// An OpenEXR output stream into memory: the file is written, checked and renamed into place by
// io/output_files.h, not by the library's destructor, which cannot report a failure.
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

}  // namespace

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

Image readExr(const std::string& path)
{
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
        Image img(w, h);
        const Imf::ChannelList& ch = file.header().channels();
        const bool rgb = ch.findChannel("R") && ch.findChannel("G") && ch.findChannel("B");
        const bool y = ch.findChannel("Y") != nullptr;
        if (!rgb && !y)
            throw Error(cat(path, ": EXR has neither R, G, B nor Y channels"));
        const std::size_t xs = 3 * sizeof(float), ys = xs * static_cast<std::size_t>(w);
        // Slices are addressed from the data window's origin.
        char* base = reinterpret_cast<char*>(img.rgb.data()) -
                     (static_cast<std::ptrdiff_t>(dw.min.x) * static_cast<std::ptrdiff_t>(xs) +
                      static_cast<std::ptrdiff_t>(dw.min.y) * static_cast<std::ptrdiff_t>(ys));
        Imf::FrameBuffer fb;
        if (rgb) {
            fb.insert("R", Imf::Slice(Imf::FLOAT, base, xs, ys));
            fb.insert("G", Imf::Slice(Imf::FLOAT, base + sizeof(float), xs, ys));
            fb.insert("B", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), xs, ys));
        } else {
            fb.insert("Y", Imf::Slice(Imf::FLOAT, base, xs, ys));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        if (!rgb)
            for (std::size_t i = 0; i < img.pixels(); ++i)
                img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = img.rgb[3 * i];
        return img;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        std::string msg = e.what();
        for (auto& c : msg)
            if (c == '\n')
                c = ' ';
        throw Error(cat(path, ": cannot read EXR: ", msg));
    }
}

}  // namespace fen
