// json_reader.cpp — strict JSON access with error paths (json_reader.h).
#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>

#include <tiny_gltf.h>

#include "util/error.h"

namespace fen {

nlohmann::json toJson(const tinygltf::Value& v)
{
    if (v.IsBool())
        return v.Get<bool>();
    if (v.IsInt())
        return v.Get<int>();
    if (v.IsReal())
        return v.Get<double>();
    if (v.IsString())
        return v.Get<std::string>();
    if (v.IsArray()) {
        nlohmann::json a = nlohmann::json::array();
        for (std::size_t i = 0; i < v.ArrayLen(); ++i)
            a.push_back(toJson(v.Get(static_cast<int>(i))));
        return a;
    }
    if (v.IsObject()) {
        nlohmann::json o = nlohmann::json::object();
        for (const auto& k : v.Keys())
            o[k] = toJson(v.Get(k));
        return o;
    }
    return nullptr;
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
        throw Error(cat(keyPath(key), ": must be a number, not ", v.dump()));
    const double d = v.get<double>();
    if (!std::isfinite(d))
        throw Error(cat(keyPath(key), ": must be finite"));
    return d;
}

double JsonReader::number(const std::string& key, double fallback) const
{
    return has(key) ? number(key) : fallback;
}

int JsonReader::integer(const std::string& key) const
{
    const double d = number(key);
    if (d != std::floor(d) || std::fabs(d) > 1e9)
        throw Error(cat(keyPath(key), ": must be an integer, not ", object_.at(key).dump()));
    return static_cast<int>(d);
}

std::string JsonReader::string(const std::string& key) const
{
    const auto& v = get(key);
    if (!v.is_string())
        throw Error(cat(keyPath(key), ": must be a string, not ", v.dump()));
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
            throw Error(cat(keyPath(key), "[", i, "]: must be a finite number, not ", v[i].dump()));
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
                throw Error(cat(keyPath(key), "[", i, "][", j, "]: must be a finite number, not ", x.dump()));
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
            throw Error(cat(keyPath(it.key()), ": unknown key"));
}

}  // namespace fen
