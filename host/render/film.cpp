// film.cpp — pixel accumulators and batch statistics (film.h).
#include "render/film.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "io/state_io.h"
#include "render/pooled_variance.h"
#include "util/error.h"
#include "util/fixed_point.h"

namespace fen {

Film::Film(ocl::Context& ctx, int width, int height, double referenceLuminance_cd_m2)
    : ctx_(ctx), width_(width), height_(height),
      fixedScale_(static_cast<float>(std::ldexp(1.0, kPixelFixedPointBits) / referenceLuminance_cd_m2)),
      accum_(ctx.buffer(CL_MEM_READ_WRITE, pixels() * kWordsPerPixel * 8, "pixel accumulators")),
      camera_(ctx.buffer(CL_MEM_READ_WRITE, pixels() * 16, "camera-pass image")),
      cameraSamples_(ctx.buffer(CL_MEM_READ_ONLY, pixels() * 4, "camera-pass samples per pixel"))
{
    // Zero until the camera pass writes it: a camera that sees nothing (no image) never does.
    ctx.queue().enqueueFillBuffer(camera_, cl_float(0), 0, pixels() * 16);
    ctx.queue().enqueueFillBuffer(cameraSamples_, cl_uint(1), 0, pixels() * 4);
}

void Film::setCameraSamples(const std::vector<std::uint32_t>& perPixel)
{
    if (perPixel.size() != pixels())
        throw std::logic_error("Film::setCameraSamples: one count per pixel");
    ctx_.queue().enqueueWriteBuffer(cameraSamples_, CL_TRUE, 0, perPixel.size() * 4, perPixel.data());
}

void Film::clear()
{
    ctx_.queue().enqueueFillBuffer(accum_, cl_ulong(0), 0, pixels() * kWordsPerPixel * 8);
}

std::vector<double> Film::read(std::uint64_t paths, std::vector<float>* camera)
{
    const std::size_t px = pixels();
    std::vector<std::uint64_t> acc(px * kWordsPerPixel);
    std::vector<float> local;
    std::vector<float>& cam = camera ? *camera : local;
    cam.resize(px * 4);
    auto& q = ctx_.queue();
    q.enqueueReadBuffer(accum_, CL_FALSE, 0, acc.size() * 8, acc.data());
    q.enqueueReadBuffer(camera_, CL_TRUE, 0, cam.size() * 4, cam.data());
    std::vector<double> img(px * 3);
    const double toValue = 1.0 / (static_cast<double>(fixedScale_) * static_cast<double>(paths));
    for (std::size_t p = 0; p < px; ++p)
        for (int c = 0; c < 3; ++c)
            img[3 * p + c] = fixed128(acc.data() + kWordsPerPixel * p + 2 * c) * toValue + (camera ? 0.0 : cam[4 * p + c]);
    return img;
}

void Film::writeCamera(const std::vector<float>& camera)
{
    if (camera.size() != pixels() * 4)
        throw Error(cat("internal error: a camera image of ", camera.size(), " floats for ", pixels(), " pixels"));
    ctx_.queue().enqueueWriteBuffer(camera_, CL_TRUE, 0, camera.size() * 4, camera.data());
}

std::vector<float> Film::readCamera()
{
    std::vector<float> cam(pixels() * 4);
    ctx_.queue().enqueueReadBuffer(camera_, CL_TRUE, 0, cam.size() * 4, cam.data());
    return cam;
}

BatchStatistics::BatchStatistics(int width, int height, std::vector<Roi> rois)
    : width_(width), height_(height), rois_(std::move(rois)),
      sum_(static_cast<std::size_t>(width) * height * 3, 0.0),
      sumY2_(static_cast<std::size_t>(width) * height, 0.0),
      camSum_(sum_.size(), 0.0), camN_(sumY2_.size(), 0.0), camM2_(sumY2_.size(), 0.0),
      camY1_(sumY2_.size(), 0.0), camY2_(sumY2_.size(), 0.0), roiMeans_(rois_.size())
{
}

void BatchStatistics::addCamera(const std::vector<float>& camera, const std::vector<std::uint32_t>& counts)
{
    const std::size_t px = camN_.size();
    if (camera.size() != 4 * px || counts.size() != px)
        throw std::logic_error("BatchStatistics::addCamera: one value per pixel");
    for (std::size_t p = 0; p < px; ++p) {
        const double n = counts[p];
        for (int c = 0; c < 3; ++c)
            camSum_[3 * p + c] += n * camera[4 * p + c];
        const double m = luminance(camera[4 * p], camera[4 * p + 1], camera[4 * p + 2]);
        camN_[p] += n;
        camM2_[p] += std::max(0.0, static_cast<double>(camera[4 * p + 3]));
        camY1_[p] += n * m;
        camY2_[p] += n * m * m;
    }
}

double BatchStatistics::cameraSampleVar(std::size_t p) const
{
    return pooledSampleVariance(camN_[p], camY1_[p], camY2_[p], camM2_[p]);
}

std::pair<double, double> BatchStatistics::roiCamera(std::size_t k) const
{
    const Roi& roi = rois_.at(k);
    double mean = 0.0, var = 0.0;
    for (int y = roi.y0; y < roi.y1; ++y)
        for (int x = roi.x0; x < roi.x1; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * width_ + x;
            if (camN_[p] > 0.0) {
                mean += camY1_[p] / camN_[p];
                var += cameraSampleVar(p) / camN_[p];
            }
        }
    const double n = static_cast<double>(roi.pixels());
    return {mean / n, var / (n * n)};
}

void BatchStatistics::add(const std::vector<double>& img, double w)
{
    const std::size_t px = sumY2_.size();
    for (std::size_t p = 0; p < px; ++p) {
        for (int c = 0; c < 3; ++c)
            sum_[3 * p + c] += w * img[3 * p + c];
        const double y = luminance(img[3 * p], img[3 * p + 1], img[3 * p + 2]);
        sumY2_[p] += w * y * y;
    }
    for (std::size_t k = 0; k < rois_.size(); ++k) {
        const Roi& roi = rois_[k];
        double m = 0.0;
        for (int y = roi.y0; y < roi.y1; ++y)
            for (int x = roi.x0; x < roi.x1; ++x) {
                const std::size_t p = static_cast<std::size_t>(y) * width_ + x;
                m += luminance(img[3 * p], img[3 * p + 1], img[3 * p + 2]);
            }
        roiMeans_[k].push_back(m / static_cast<double>(roi.pixels()));
    }
    weights_.push_back(w);
    weight_ += w;
    ++batches_;
}

Image BatchStatistics::mean() const
{
    Image image(width_, height_);
    const double W = weight_;
    for (std::size_t i = 0; i < sum_.size(); ++i) {
        const double n = camN_[i / 3];
        image.rgb[i] = static_cast<float>(sum_[i] / W + (n > 0.0 ? camSum_[i] / n : 0.0));
    }
    return image;
}

std::vector<double> BatchStatistics::stdErrLuminance() const
{
    const std::size_t px = sumY2_.size();
    std::vector<double> se(px, 0.0);
    if (batches_ < 2)
        return se;  // one batch: no spread to measure (an interrupted render); reported as unknown
    const double W = weight_, B = batches_;
    for (std::size_t p = 0; p < px; ++p) {
        const double meanY = luminance(sum_[3 * p], sum_[3 * p + 1], sum_[3 * p + 2]) / W;
        const double var = std::max(0.0, (sumY2_[p] - W * meanY * meanY) / (B - 1.0));
        se[p] = std::sqrt(var / W + (camN_[p] > 0.0 ? cameraSampleVar(p) / camN_[p] : 0.0));
    }
    return se;
}

void BatchStatistics::save(StateWriter& w) const
{
    w.u64("film.batches", static_cast<std::uint64_t>(batches_));
    w.f64("film.weight", weight_);
    w.f64s("film.weights", weights_);
    w.f64s("film.sum", sum_);
    w.f64s("film.sum_y2", sumY2_);
    w.f64s("film.camera_sum", camSum_);
    w.f64s("film.camera_n", camN_);
    w.f64s("film.camera_m2", camM2_);
    w.f64s("film.camera_y1", camY1_);
    w.f64s("film.camera_y2", camY2_);
    w.u64("film.rois", rois_.size());
    for (const auto& m : roiMeans_)
        w.f64s("film.roi_means", m);
}

void BatchStatistics::load(StateReader& r)
{
    const std::size_t batches = r.u64("film.batches", 1u << 20);
    weight_ = r.f64("film.weight");
    weights_ = r.f64s("film.weights", batches, true);
    sum_ = r.f64s("film.sum", sum_.size(), true);
    sumY2_ = r.f64s("film.sum_y2", sumY2_.size(), true);
    camSum_ = r.f64s("film.camera_sum", camSum_.size(), true);
    camN_ = r.f64s("film.camera_n", camN_.size(), true);
    camM2_ = r.f64s("film.camera_m2", camM2_.size(), true);
    camY1_ = r.f64s("film.camera_y1", camY1_.size(), true);
    camY2_ = r.f64s("film.camera_y2", camY2_.size(), true);
    if (r.u64("film.rois") != rois_.size())
        r.fail("film.rois", "made with other regions (--roi)");
    for (auto& m : roiMeans_)
        m = r.f64s("film.roi_means", batches, true);
    batches_ = static_cast<int>(batches);
    // Light is never negative, and batches weigh something (a checksum recomputed after an edit
    // must not make a render of negative light).
    const auto nonNegative = [&](const std::vector<double>& v, const char* key) {
        for (const double x : v)
            if (x < 0.0)
                r.fail(key, "a negative value: light is never negative");
    };
    nonNegative(sum_, "film.sum");
    nonNegative(sumY2_, "film.sum_y2");
    nonNegative(camSum_, "film.camera_sum");
    nonNegative(camN_, "film.camera_n");
    nonNegative(camM2_, "film.camera_m2");
    nonNegative(camY1_, "film.camera_y1");
    nonNegative(camY2_, "film.camera_y2");
    for (const auto& m : roiMeans_)
        nonNegative(m, "film.roi_means");
    if (!(weight_ > 0.0) && batches > 0)
        r.fail("film.weight", "not positive");
    for (const double w : weights_)
        if (!(w > 0.0))
            r.fail("film.weights", "a batch of no weight");
}

}  // namespace fen
