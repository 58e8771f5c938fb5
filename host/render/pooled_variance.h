// pooled_variance.h — the variance of one sample from batches of samples, each batch known only by
// its count n_b, its mean m_b and its squared deviations about that mean (what the camera pass
// returns per pixel: kernels/camera_pass.cl). The squares about the overall mean are the
// within-batch ones plus the between-batch sum n_b (m_b - m)^2 = sum n_b m_b^2 - (sum n_b m_b)^2 / N,
// over N - 1 (the usual unbiased estimate). Used by the camera pass's pilot
// (render/camera_sampler.h) and the film's camera part (render/film.h).
#pragma once

#include <algorithm>

namespace fen {

// n = sum n_b, sumNM = sum n_b m_b, sumNM2 = sum n_b m_b^2, within = the batches' squared
// deviations; 0 below two samples.
inline double pooledSampleVariance(double n, double sumNM, double sumNM2, double within)
{
    if (n < 2.0)
        return 0.0;
    const double between = std::max(0.0, sumNM2 - sumNM * sumNM / n);
    return (within + between) / (n - 1.0);
}

}  // namespace fen
