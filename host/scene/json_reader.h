// json_reader.h — strict reading of the JSON objects fenestra defines inside glTF `extras`
// (DESIGN.md §6): every key must be known, every value of the right type, and every error names
// the file and the key's path ("room.gltf: scenes[0].extras.sky.luminance: must be >= 0").
// The objects come from the file's JSON as written (not tinygltf's copy of extras, which drops
// empty objects and arrays and squeezes integers into 32 bits).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fen {

// obj[key] when obj is an object holding key, else null: lookups into a document that may have
// any shape.
const nlohmann::json& member(const nlohmann::json& obj, const std::string& key);
// array[i] when it exists, else null.
const nlohmann::json& element(const nlohmann::json& array, std::size_t i);
// A JSON value for a one-line message: scalars as written (strings made printable), arrays and
// objects by kind and size (they may be large).
std::string describe(const nlohmann::json& v);

class JsonReader {
public:
    // `path` is the object's location for messages, e.g. "room.gltf: scenes[0].extras.sky".
    JsonReader(nlohmann::json object, std::string path);

    bool has(const std::string& key) const;
    double number(const std::string& key) const;                 // required
    double number(const std::string& key, double fallback) const;  // optional
    // Required, integral; read wide (a 64-bit value is not squeezed into 32 bits), the caller
    // checks its range.
    std::int64_t integer(const std::string& key) const;
    std::string string(const std::string& key) const;            // required
    std::vector<double> numbers(const std::string& key) const;   // required array of numbers
    std::vector<std::vector<double>> numberRows(const std::string& key) const;
    const nlohmann::json& raw(const std::string& key) const;     // required, any type
    std::string keyPath(const std::string& key) const { return path_ + "." + key; }
    const std::string& path() const { return path_; }

    // Throws naming the first key that was never read.
    void rejectUnknownKeys() const;

private:
    const nlohmann::json& get(const std::string& key) const;
    nlohmann::json object_;  // owned: readers are often built from temporaries
    std::string path_;
    mutable std::vector<std::string> used_;
};

}  // namespace fen
