#include "core/base/error.hpp"
#include "core/base/quote_value.hpp"

#include <cstdio>

namespace weft {

namespace {

// Length of the valid UTF-8 sequence starting at s[i], or 0.
std::size_t utf8Length(std::string_view s, std::size_t i) {
    const auto b = static_cast<unsigned char>(s[i]);
    const std::size_t n = b >= 0xF0 && b <= 0xF4 ? 4 : b >= 0xE0 ? 3 : b >= 0xC2 && b < 0xE0 ? 2 : 0;
    if (n == 0 || i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
    return n;
}

}  // namespace

std::string printableLine(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        const auto b = static_cast<unsigned char>(text[i]);
        if (b >= 0x20 && b < 0x7F) {
            out += char(b), ++i;
        } else if (b == '\n' || b == '\t' || b == '\r') {
            out += ' ', ++i;
        } else if (const std::size_t n = b >= 0x80 ? utf8Length(text, i) : 0) {
            out.append(text.substr(i, n)), i += n;
        } else {
            char hex[5];
            std::snprintf(hex, sizeof hex, "\\x%02X", b);
            out += hex, ++i;
        }
    }
    return out;
}

std::string quoteValue(std::string_view value) {
    constexpr std::size_t kShown = 60;
    if (value.size() <= kShown) return "'" + std::string(value) + "'";
    return "'" + std::string(value.substr(0, kShown)) + "...' (" + std::to_string(value.size()) + " characters)";
}

}  // namespace weft
