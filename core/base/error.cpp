#include "core/base/error.hpp"
#include "core/base/quote_value.hpp"

#include <cstdio>

namespace weft {

namespace {

// Length of the valid UTF-8 sequence starting at s[i], or 0 (RFC 3629:
// no lead byte above 0xF4, no overlong form, no surrogate, nothing past U+10FFFF).
std::size_t utf8Length(std::string_view s, std::size_t i) {
    const auto b = static_cast<unsigned char>(s[i]);
    const std::size_t n = b >= 0xC2 && b <= 0xDF ? 2 : b >= 0xE0 && b <= 0xEF ? 3 : b >= 0xF0 && b <= 0xF4 ? 4 : 0;
    if (n == 0 || i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
    const auto second = static_cast<unsigned char>(s[i + 1]);
    if ((b == 0xE0 && second < 0xA0) || (b == 0xED && second > 0x9F) || (b == 0xF0 && second < 0x90) || (b == 0xF4 && second > 0x8F))
        return 0;
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
