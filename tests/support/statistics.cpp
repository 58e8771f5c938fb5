// statistics.cpp — chi-square p-values and sample means (statistics.h).
// Q(a, x) by its series (x < a + 1) or Lentz's continued fraction (otherwise), as in any
// numerical-analysis text; double precision is ample for p-values down to 1e-12.
#include "support/statistics.h"

#include <cmath>
#include <stdexcept>

namespace fen { namespace test {

double gammaQ(double a, double x)
{
    if (x <= 0.0)
        return 1.0;
    const double lg = std::lgamma(a);
    if (x < a + 1.0) {
        double sum = 1.0 / a, term = sum, ap = a;
        for (int n = 0; n < 10000; ++n) {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * 1e-15)
                break;
        }
        return 1.0 - sum * std::exp(-x + a * std::log(x) - lg);
    }
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::fabs(d) < tiny)
            d = tiny;
        c = b + an / c;
        if (std::fabs(c) < tiny)
            c = tiny;
        d = 1.0 / d;
        const double del = d * c;
        h *= del;
        if (std::fabs(del - 1.0) < 1e-15)
            break;
    }
    return std::exp(-x + a * std::log(x) - lg) * h;
}

double chiSquarePValue(const std::vector<double>& observed, const std::vector<double>& expected)
{
    if (observed.size() != expected.size())
        throw std::invalid_argument("chi-square: size mismatch");
    double chi2 = 0.0, accO = 0.0, accE = 0.0;
    int bins = 0;
    for (std::size_t i = 0; i < observed.size(); ++i) {
        accO += observed[i];
        accE += expected[i];
        if (accE >= 5.0 || i + 1 == observed.size()) {
            if (accE > 0.0) {
                chi2 += (accO - accE) * (accO - accE) / accE;
                ++bins;
            } else if (accO > 0.0) {
                return 0.0;  // counts where nothing was expected
            }
            accO = accE = 0.0;
        }
    }
    if (bins < 2)
        throw std::invalid_argument("chi-square: fewer than two bins");
    return gammaQ(0.5 * (bins - 1), 0.5 * chi2);
}

MeanSe meanAndStdErr(const std::vector<double>& v)
{
    MeanSe r;
    if (v.empty())
        return r;
    double s = 0.0;
    for (double x : v)
        s += x;
    r.mean = s / static_cast<double>(v.size());
    double ss = 0.0;
    for (double x : v)
        ss += (x - r.mean) * (x - r.mean);
    if (v.size() > 1)
        r.se = std::sqrt(ss / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
    return r;
}

} }  // namespace fen::test
