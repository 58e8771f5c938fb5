// state_io.cpp — tagged binary fields (state_io.h).
#include "io/state_io.h"

#include <cmath>

#include <cstring>

#include "util/error.h"

namespace fen {

namespace {

std::uint64_t bitsOf(double v)
{
    std::uint64_t b;
    std::memcpy(&b, &v, 8);
    return b;
}

double doubleOf(std::uint64_t b)
{
    double v;
    std::memcpy(&v, &b, 8);
    return v;
}

}  // namespace

void StateWriter::raw(std::uint64_t v)
{
    for (int i = 0; i < 8; ++i)
        bytes_.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
}

void StateWriter::key(const char* k)
{
    const std::size_t n = std::strlen(k);
    raw(n);
    bytes_.append(k, n);
}

void StateWriter::u64(const char* k, std::uint64_t v)
{
    key(k);
    raw(v);
}

void StateWriter::f64(const char* k, double v)
{
    key(k);
    raw(bitsOf(v));
}

void StateWriter::str(const char* k, const std::string& v)
{
    key(k);
    raw(v.size());
    bytes_ += v;
}

void StateWriter::u64s(const char* k, const std::vector<std::uint64_t>& v)
{
    key(k);
    raw(v.size());
    for (std::uint64_t x : v)
        raw(x);
}

void StateWriter::f64s(const char* k, const std::vector<double>& v)
{
    key(k);
    raw(v.size());
    for (double x : v)
        raw(bitsOf(x));
}

StateReader::StateReader(const std::string& bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

void StateReader::fail(const char* k, const std::string& why) const
{
    throw Error(cat(what_, ": ", k, ": ", why));
}

std::uint64_t StateReader::raw(const char* k)
{
    if (bytes_.size() - at_ < 8)
        fail(k, "the file ends early (truncated)");
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i)
        v |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes_[at_ + i])) << (8 * i);
    at_ += 8;
    return v;
}

void StateReader::key(const char* k)
{
    const std::size_t n = std::strlen(k);
    const std::uint64_t len = raw(k);
    if (len != n || bytes_.size() - at_ < n || bytes_.compare(at_, n, k) != 0)
        fail(k, "not where the file has it (not a checkpoint of this version)");
    at_ += n;
}

std::size_t StateReader::count(const char* k, std::size_t max)
{
    const std::uint64_t n = raw(k);
    if (n > max)
        fail(k, cat(n, " values, more than the ", max, " it can hold"));
    if (n > (bytes_.size() - at_) / 8)
        fail(k, "the file ends early (truncated)");
    return static_cast<std::size_t>(n);
}

std::uint64_t StateReader::u64(const char* k)
{
    key(k);
    return raw(k);
}

std::uint64_t StateReader::u64(const char* k, std::uint64_t max)
{
    const std::uint64_t v = u64(k);
    if (v > max)
        fail(k, cat(v, " is beyond ", max));
    return v;
}

// Every number a render keeps is finite: a NaN or infinity in a checkpoint is damage (or an edit
// whose checksum was recomputed), refused here rather than rendered.
double StateReader::finite(const char* k, double v) const
{
    if (!std::isfinite(v))
        fail(k, "a value that is not a finite number");
    return v;
}

double StateReader::f64(const char* k)
{
    key(k);
    return finite(k, doubleOf(raw(k)));
}

std::string StateReader::str(const char* k, std::size_t maxBytes)
{
    key(k);
    const std::uint64_t n = raw(k);
    if (n > maxBytes || n > bytes_.size() - at_)
        fail(k, "a string longer than the file allows");
    std::string s = bytes_.substr(at_, static_cast<std::size_t>(n));
    at_ += static_cast<std::size_t>(n);
    return s;
}

std::vector<std::uint64_t> StateReader::u64s(const char* k, std::size_t maxCount)
{
    key(k);
    std::vector<std::uint64_t> v(count(k, maxCount));
    for (auto& x : v)
        x = raw(k);
    return v;
}

std::vector<double> StateReader::f64s(const char* k, std::size_t maxCount)
{
    key(k);
    std::vector<double> v(count(k, maxCount));
    for (auto& x : v)
        x = finite(k, doubleOf(raw(k)));
    return v;
}

std::vector<double> StateReader::f64s(const char* k, std::size_t n, bool exact)
{
    std::vector<double> v = f64s(k, n);
    if (exact && v.size() != n)
        fail(k, cat(v.size(), " values where ", n, " belong"));
    return v;
}

void StateReader::end()
{
    if (at_ != bytes_.size())
        fail("end", cat(bytes_.size() - at_, " bytes after the last field"));
}

}  // namespace fen
