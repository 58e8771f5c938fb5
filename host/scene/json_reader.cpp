// json_reader.cpp — strict JSON access with error paths (json_reader.h).
#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/error.h"

namespace fen {

const nlohmann::json& member(const nlohmann::json& obj, const std::string& key)
{
    static const nlohmann::json null;
    if (!obj.is_object())
        return null;
    const auto it = obj.find(key);
    return it == obj.end() ? null : *it;
}

const nlohmann::json& element(const nlohmann::json& array, std::size_t i)
{
    static const nlohmann::json null;
    return array.is_array() && i < array.size() ? array[i] : null;
}

std::string describe(const nlohmann::json& v)
{
    if (v.is_array())
        return cat("an array of ", v.size());
    if (v.is_object())
        return cat("an object of ", v.size(), " keys");
    return printable(v.dump(), 60);
}

JsonReader::JsonReader(nlohmann::json object, std::string path)
    : object_(std::move(object)), path_(std::move(path))
{
    if (!object_.is_object())
        throw Error(cat(path_, ": must be a JSON object"));
}

bool JsonReader::has(const std::string& key) const { return object_.contains(key); }

const nlohmann::json& JsonReader::get(const std::string& key) const
{
    if (!object_.contains(key))
        throw Error(cat(keyPath(key), ": missing"));
    used_.push_back(key);
    return object_.at(key);
}

const nlohmann::json& JsonReader::raw(const std::string& key) const { return get(key); }

double JsonReader::number(const std::string& key) const
{
    const auto& v = get(key);
    if (!v.is_number())
        throw Error(cat(keyPath(key), ": must be a number, not ", describe(v)));
    const double d = v.get<double>();
    if (!std::isfinite(d))
        throw Error(cat(keyPath(key), ": must be finite"));
    return d;
}

double JsonReader::number(const std::string& key, double fallback) const
{
    return has(key) ? number(key) : fallback;
}

std::int64_t JsonReader::integer(const std::string& key) const
{
    const auto& v = get(key);
    if (v.is_number_unsigned() && v.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<std::int64_t>::max()))
        return static_cast<std::int64_t>(v.get<std::uint64_t>());
    if (v.is_number_integer() && !v.is_number_unsigned())
        return v.get<std::int64_t>();
    // 12.0 is 12; beyond 2^53 a double no longer says which integer it is.
    if (v.is_number_float() && v.get<double>() == std::floor(v.get<double>()) &&
        std::fabs(v.get<double>()) <= 9007199254740992.0)
        return static_cast<std::int64_t>(v.get<double>());
    throw Error(cat(keyPath(key), ": must be an integer, not ", describe(v)));
}

std::string JsonReader::string(const std::string& key) const
{
    const auto& v = get(key);
    if (!v.is_string())
        throw Error(cat(keyPath(key), ": must be a string, not ", describe(v)));
    return v.get<std::string>();
}

std::vector<double> JsonReader::numbers(const std::string& key) const
{
    const auto& v = get(key);
    if (!v.is_array())
        throw Error(cat(keyPath(key), ": must be an array of numbers"));
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
            throw Error(cat(keyPath(key), "[", i, "]: must be a finite number, not ", describe(v[i])));
        out.push_back(v[i].get<double>());
    }
    return out;
}

std::vector<std::vector<double>> JsonReader::numberRows(const std::string& key) const
{
    const auto& v = get(key);
    if (!v.is_array())
        throw Error(cat(keyPath(key), ": must be an array of rows"));
    std::vector<std::vector<double>> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
        if (!v[i].is_array())
            throw Error(cat(keyPath(key), "[", i, "]: must be an array of numbers"));
        std::vector<double> row;
        for (std::size_t j = 0; j < v[i].size(); ++j) {
            const auto& x = v[i][j];
            if (!x.is_number() || !std::isfinite(x.get<double>()))
                throw Error(cat(keyPath(key), "[", i, "][", j, "]: must be a finite number, not ", describe(x)));
            row.push_back(x.get<double>());
        }
        out.push_back(std::move(row));
    }
    return out;
}

void JsonReader::rejectUnknownKeys() const
{
    for (auto it = object_.begin(); it != object_.end(); ++it)
        if (std::find(used_.begin(), used_.end(), it.key()) == used_.end())
            throw Error(cat(keyPath(printable(it.key(), 60)), ": unknown key"));
}

}  // namespace fen
