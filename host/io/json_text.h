// json_text.h — a JSON document made safe to write (util/utf8.h): every string and key that is not
// valid UTF-8 (a file or region name with Latin-1 bytes) gets its stray bytes as \xNN, so that
// writing a render's JSON or a checkpoint's header can never fail after the work is done.
#pragma once

#include <nlohmann/json.hpp>

#include "util/utf8.h"

namespace fen {

inline void makeUtf8(nlohmann::json& j)
{
    if (j.is_string()) {
        const std::string& s = j.get_ref<const std::string&>();
        if (!isValidUtf8(s))
            j = utf8OrEscaped(s);
    } else if (j.is_array()) {
        for (auto& e : j)
            makeUtf8(e);
    } else if (j.is_object()) {
        nlohmann::json fixed = nlohmann::json::object();
        for (auto it = j.begin(); it != j.end(); ++it) {
            nlohmann::json v = it.value();
            makeUtf8(v);
            fixed[isValidUtf8(it.key()) ? it.key() : utf8OrEscaped(it.key())] = std::move(v);
        }
        j = std::move(fixed);
    }
}

// j.dump(indent) of the safe document.
inline std::string dumpUtf8(nlohmann::json j, int indent = -1)
{
    makeUtf8(j);
    return j.dump(indent);
}

}  // namespace fen
