#include "lantern/core/text.hpp"

#include <cstdio>

namespace lantern {

std::size_t utf8_char(std::string_view text, std::uint32_t* code_point) {
    if (text.empty()) return 0;
    const auto b0 = static_cast<unsigned char>(text[0]);
    std::size_t n = 0;
    std::uint32_t cp = 0, min = 0;
    if (b0 < 0x80) {
        n = 1, cp = b0;
    } else if ((b0 & 0xE0) == 0xC0) {
        n = 2, cp = b0 & 0x1F, min = 0x80;
    } else if ((b0 & 0xF0) == 0xE0) {
        n = 3, cp = b0 & 0x0F, min = 0x800;
    } else if ((b0 & 0xF8) == 0xF0) {
        n = 4, cp = b0 & 0x07, min = 0x10000;
    } else {
        return 0;
    }
    if (text.size() < n) return 0;
    for (std::size_t i = 1; i < n; ++i) {
        const auto b = static_cast<unsigned char>(text[i]);
        if ((b & 0xC0) != 0x80) return 0;
        cp = (cp << 6) | (b & 0x3F);
    }
    if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
    if (code_point) *code_point = cp;
    return n;
}

std::string printable(std::string_view text, std::size_t max_bytes) {
    std::string out;
    std::size_t i = 0;
    while (i < text.size()) {
        std::uint32_t cp = 0;
        std::size_t n = utf8_char(text.substr(i), &cp);
        if (i + (n ? n : 1) > max_bytes) return out + "...";
        if (n == 0) {
            char buffer[8];
            std::snprintf(buffer, sizeof(buffer), "\\x%02X", static_cast<unsigned char>(text[i]));
            out += buffer;
            i += 1;
        } else if (cp == '\t') {
            out += "\\t", i += 1;
        } else if (cp == '\n') {
            out += "\\n", i += 1;
        } else if (cp == '\r') {
            out += "\\r", i += 1;
        } else if (cp < 0x20 || cp == 0x7F || (cp >= 0x80 && cp < 0xA0)) {
            char buffer[16];
            if (cp < 0x80) std::snprintf(buffer, sizeof(buffer), "\\x%02X", unsigned(cp));
            else std::snprintf(buffer, sizeof(buffer), "\\u%04X", unsigned(cp)); // C1 controls
            out += buffer;
            i += n;
        } else {
            out.append(text.substr(i, n));
            i += n;
        }
    }
    return out;
}

} // namespace lantern
