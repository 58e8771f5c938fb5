// state_io.h — a render's state as bytes and back: the payload of a checkpoint
// (render/checkpoint.h).
//
// Values are written as tagged fields (a key, then little-endian 64-bit integers or IEEE doubles,
// or a count and that many), so that reading back is exact -- a resumed render is bit-identical
// -- and a reader that meets anything other than what it expects (another key, a count beyond
// its limit, the end of the bytes) throws fen::Error naming the file and the key, never reads
// past the end. Whoever saves a piece of state also loads it: both halves sit side by side in
// the class that owns the state.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fen {

class StateWriter {
public:
    void u64(const char* key, std::uint64_t v);
    void f64(const char* key, double v);
    void str(const char* key, const std::string& v);
    void u64s(const char* key, const std::vector<std::uint64_t>& v);
    void f64s(const char* key, const std::vector<double>& v);
    // The fields another writer wrote, as if written here (a snapshot taken earlier).
    void append(const std::string& fields) { bytes_ += fields; }
    const std::string& bytes() const { return bytes_; }

private:
    void key(const char* k);
    void raw(std::uint64_t v);
    std::string bytes_;
};

class StateReader {
public:
    // `what` names the source in errors (the checkpoint's path).
    StateReader(const std::string& bytes, std::string what);
    std::uint64_t u64(const char* key);
    // u64(key), required to be at most `max`.
    std::uint64_t u64(const char* key, std::uint64_t max);
    double f64(const char* key);
    std::string str(const char* key, std::size_t maxBytes);
    std::vector<std::uint64_t> u64s(const char* key, std::size_t maxCount);
    std::vector<double> f64s(const char* key, std::size_t maxCount);
    // The same, required to hold exactly `count` values.
    std::vector<double> f64s(const char* key, std::size_t count, bool exact);
    // Throws unless every byte was read.
    void end();
    // An error about `key` in this source.
    [[noreturn]] void fail(const char* key, const std::string& why) const;
    // `v`, or fail() when it is NaN or infinite.
    double finite(const char* key, double v) const;

private:
    void key(const char* k);
    std::uint64_t raw(const char* k);
    std::size_t count(const char* k, std::size_t max);
    const std::string& bytes_;
    std::string what_;
    std::size_t at_ = 0;
};

}  // namespace fen
