// statistics.h — the statistical yardsticks of the tests (fixed seeds; tolerances from the
// estimator's own standard error, stated in sigmas at each use).
#pragma once

#include <vector>

namespace fen { namespace test {

// Pearson's chi-square test of observed counts against expected counts (same total). Bins with
// expected < 5 are pooled with their neighbours first, as the test requires. Returns the p-value.
double chiSquarePValue(const std::vector<double>& observed, const std::vector<double>& expected);

// Regularised upper incomplete gamma function Q(a, x).
double gammaQ(double a, double x);

// Mean and standard error of the mean of samples.
struct MeanSe {
    double mean = 0.0, se = 0.0;
};
MeanSe meanAndStdErr(const std::vector<double>& v);

} }  // namespace fen::test
