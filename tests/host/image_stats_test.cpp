// image_stats_test.cpp — the ROI figures a render reports (render/image_stats.h) against values
// computed by hand: mean, RMS, the noise estimate and the share of it the noisiest 1 % hold.
#include <gtest/gtest.h>

#include <cmath>

#include "render/image_stats.h"

namespace fen {
namespace {

Image greyImage(int w, int h, float value)
{
    Image img(w, h);
    img.rgb.assign(img.rgb.size(), value);
    return img;
}

TEST(ImageStats, EvenNoiseSpreadsOverThePixels)
{
    const Image img = greyImage(20, 10, 2.0f);
    const std::vector<double> se(200, 0.5);
    const RoiStats s = roiStats(img, se, nullptr, parseRoi("", 20, 10));
    EXPECT_NEAR(s.meanLuminance_cd_m2, 2.0, 1e-6);
    EXPECT_NEAR(s.rmsLuminance_cd_m2, 0.0, 1e-6);
    EXPECT_NEAR(s.noiseStdErr_cd_m2, 0.5, 1e-12);
    EXPECT_NEAR(s.noiseTop1Share, 2.0 / 200.0, 1e-12);  // the top 1 %: 2 of 200 equal pixels
}

TEST(ImageStats, AFireflyHoldsTheNoise)
{
    const Image img = greyImage(20, 10, 2.0f);
    std::vector<double> se(200, 0.1);
    se[37] = 10.0;  // one pixel: 100 times the others' standard error
    const RoiStats s = roiStats(img, se, nullptr, parseRoi("", 20, 10));
    const double total = 199 * 0.01 + 100.0;
    EXPECT_NEAR(s.noiseStdErr_cd_m2, std::sqrt(total / 200.0), 1e-12);
    EXPECT_NEAR(s.noiseTop1Share, (100.0 + 0.01) / total, 1e-12);
    // Outside the ROI it does not count.
    const RoiStats r = roiStats(img, se, nullptr, parseRoi("0,5,20,10", 20, 10));
    EXPECT_NEAR(r.noiseTop1Share, 1.0 / 100.0, 1e-12);
    // Without batches there is no noise, and no share of it.
    EXPECT_EQ(roiStats(img, {}, nullptr, parseRoi("", 20, 10)).noiseTop1Share, 0.0);
}

}  // namespace
}  // namespace fen
