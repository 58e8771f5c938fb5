// image_stats.cpp — ROI statistics (image_stats.h).
#include "render/image_stats.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "util/error.h"

namespace fen {

Roi parseRoi(const std::string& spec, int width, int height, const std::string& option)
{
    Roi r{0, 0, width, height};
    if (spec.empty())
        return r;
    std::vector<int> v;
    std::stringstream in(spec);
    std::string item;
    while (std::getline(in, item, ',')) {
        try {
            std::size_t used = 0;
            v.push_back(std::stoi(item, &used));
            if (used != item.size())
                throw std::invalid_argument(item);
        } catch (const std::exception&) {
            throw Error(cat(option, " '", printable(spec, 80), "': '", printable(item, 40), "' is not an integer"));
        }
    }
    if (v.size() != 4)
        throw Error(cat(option, " '", printable(spec, 80), "': expected x0,y0,x1,y1"));
    r = Roi{v[0], v[1], v[2], v[3]};
    if (r.x0 < 0 || r.y0 < 0 || r.x1 > width || r.y1 > height || r.x0 >= r.x1 || r.y0 >= r.y1)
        throw Error(cat(option, " '", printable(spec, 80), "': must satisfy 0 <= x0 < x1 <= ", width,
                        " and 0 <= y0 < y1 <= ", height));
    return r;
}

RoiStats roiStats(const Image& image, const std::vector<double>& stdErr, const Image* reference,
                  const Roi& roi)
{
    RoiStats s;
    s.pixels = roi.pixels();
    double sum = 0.0, se = 0.0, sq = 0.0, rel = 0.0;
    std::vector<double> variances;
    if (!stdErr.empty())
        variances.reserve(s.pixels);
    for (int y = roi.y0; y < roi.y1; ++y)
        for (int x = roi.x0; x < roi.x1; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * image.width + x;
            sum += image.luminance(p);
            if (!stdErr.empty()) {
                se += stdErr[p] * stdErr[p];
                variances.push_back(stdErr[p] * stdErr[p]);
            }
            if (reference) {
                const double d = image.luminance(p) - reference->luminance(p);
                const double r = reference->luminance(p);
                sq += d * d;
                rel += d * d / (r * r + 0.01);
            }
        }
    const double n = static_cast<double>(s.pixels);
    s.meanLuminance_cd_m2 = sum / n;
    double var = 0.0;
    for (int y = roi.y0; y < roi.y1; ++y)
        for (int x = roi.x0; x < roi.x1; ++x) {
            const double d = image.luminance(static_cast<std::size_t>(y) * image.width + x) -
                             s.meanLuminance_cd_m2;
            var += d * d;
        }
    s.rmsLuminance_cd_m2 = std::sqrt(var / n);
    s.noiseStdErr_cd_m2 = std::sqrt(se / n);
    if (se > 0.0) {
        const std::size_t top = std::max<std::size_t>(1, variances.size() / 100);
        std::nth_element(variances.begin(), variances.begin() + (top - 1), variances.end(), std::greater<double>());
        double topSum = 0.0;
        for (std::size_t i = 0; i < top; ++i)
            topSum += variances[i];
        s.noiseTop1Share = topSum / se;
    }
    if (reference) {
        s.rmse_cd_m2 = std::sqrt(sq / n);
        s.relMse = rel / n;
    }
    return s;
}

}  // namespace fen
