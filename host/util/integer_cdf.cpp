// integer_cdf.cpp — integer CDFs and their integer alias tables (integer_cdf.h).
#include "util/integer_cdf.h"

#include <algorithm>

namespace fen {

namespace {

constexpr double kUnits = 4294967296.0;  // 2^32

}  // namespace

IntegerCdf makeIntegerCdf(const std::vector<double>& weight, bool alias)
{
    IntegerCdf c;
    double total = 0.0;
    for (double w : weight)
        total += std::max(0.0, w);
    std::vector<std::uint64_t> n(weight.size(), 0);
    std::uint64_t sum = 0;
    std::size_t largest = 0;
    for (std::size_t e = 0; e < weight.size(); ++e) {
        if (weight[e] > 0.0)
            n[e] = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(weight[e] / total * kUnits));
        sum += n[e];
        if (n[e] > n[largest])
            largest = e;
    }
    // The rounding remainder (a few units, either sign) goes to the largest entry.
    n[largest] = n[largest] + (std::uint64_t{1} << 32) - sum;
    c.cdf.assign(weight.size() + 1, 0);
    for (std::size_t e = 0; e < weight.size(); ++e)
        c.cdf[e + 1] = c.cdf[e] + n[e];
    if (!alias)
        return c;
    // Vose's alias method in integers: 2^bits >= n columns of C = 2^(32 - bits) units each hold
    // 2^32 units in all, as many as the entries. A column short of C takes the rest from an entry
    // with more; what is moved is whole units, so the counts stay exact.
    std::uint32_t bits = 1;
    while ((std::size_t{1} << bits) < weight.size())
        ++bits;
    c.aliasShift = 32 - bits;
    const std::size_t columns = std::size_t{1} << bits;
    const std::uint64_t C = std::uint64_t{1} << c.aliasShift;
    std::vector<std::uint64_t> left(columns, 0);
    std::copy(n.begin(), n.end(), left.begin());
    std::vector<std::uint32_t> small, large;
    for (std::size_t j = columns; j-- > 0;)
        (left[j] < C ? small : large).push_back(static_cast<std::uint32_t>(j));
    c.alias.assign(2 * columns, 0);
    while (!small.empty() && !large.empty()) {
        const std::uint32_t s = small.back(), l = large.back();
        small.pop_back();
        c.alias[2 * s] = static_cast<std::uint32_t>(left[s]);
        c.alias[2 * s + 1] = l;
        left[l] -= C - left[s];
        if (left[l] < C) {
            large.pop_back();
            small.push_back(l);
        }
    }
    // The units left equal C times the columns left, so small is empty and each of these holds
    // exactly C.
    for (std::uint32_t j : large) {
        c.alias[2 * j] = static_cast<std::uint32_t>(C);  // C <= 2^31
        c.alias[2 * j + 1] = j;
    }
    return c;
}

std::uint32_t IntegerCdf::pick(std::uint32_t r) const
{
    const std::uint32_t j = r >> aliasShift;
    const std::uint32_t offset = r & ((std::uint32_t{1} << aliasShift) - 1u);
    return offset < alias[2 * j] ? j : alias[2 * j + 1];
}

}  // namespace fen
