// parse_number.h — a command-line or file word read as one finite number, the whole word or
// nothing: the options that take numbers in text of their own (`--adaptive-aim-share`, the sun's
// and the annual study's pairs) share it, so "0.5x", "nan" and "" are refused alike. The caller
// words the error, naming its option.
#pragma once

#include <cmath>
#include <exception>
#include <optional>
#include <string>

namespace fen {

// The number the whole of `text` spells (leading blanks allowed, as std::stod does), if finite.
inline std::optional<double> parseWholeNumber(const std::string& text)
{
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(text, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    if (used == 0 || used != text.size() || !std::isfinite(v))
        return std::nullopt;
    return v;
}

}  // namespace fen
