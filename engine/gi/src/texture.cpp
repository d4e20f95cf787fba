#include "lantern/gi/texture.hpp"

#include "lantern/core/file.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace lantern::gi {

std::uint16_t float_to_half(float v) {
    if (std::isnan(v)) return 0;
    if (v > max_half) v = max_half;
    if (v < -max_half) v = -max_half;
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(v);
    const std::uint32_t sign = (bits >> 16) & 0x8000u;
    const std::uint32_t abs_bits = bits & 0x7FFFFFFFu;
    if (abs_bits < 0x38800000u) {
        // Half subnormal or zero: value = m * 2^-24. Round the float to a multiple of 2^-24
        // with ties to even, using the exact float arithmetic of the scaled value.
        float scaled = std::bit_cast<float>(abs_bits) * 16777216.0f; // * 2^24, exact
        float rounded = std::nearbyint(scaled);                     // default mode: ties to even
        return static_cast<std::uint16_t>(sign | std::uint32_t(rounded));
    }
    // Normal: rebias the exponent, round the 23-bit mantissa to 10 bits, ties to even.
    std::uint32_t h = ((abs_bits - 0x38000000u) >> 13);
    const std::uint32_t rest = abs_bits & 0x1FFFu;
    if (rest > 0x1000u || (rest == 0x1000u && (h & 1u))) ++h; // may carry into the exponent: correct
    return static_cast<std::uint16_t>(sign | h);
}

float half_to_float(std::uint16_t h) {
    const std::uint32_t sign = std::uint32_t(h & 0x8000u) << 16;
    const std::uint32_t exponent = (h >> 10) & 0x1Fu;
    const std::uint32_t mantissa = h & 0x3FFu;
    if (exponent == 0) {
        float v = float(mantissa) / 16777216.0f; // m * 2^-24
        return sign ? -v : v;
    }
    if (exponent == 31) return std::bit_cast<float>(sign | 0x7F800000u | (mantissa << 13));
    return std::bit_cast<float>(sign | ((exponent + 112u) << 23) | (mantissa << 13));
}

std::uint8_t float_to_unorm8(float v) {
    if (!(v > 0.0f)) return 0; // also NaN
    if (v >= 1.0f) return 255;
    return static_cast<std::uint8_t>(std::floor(v * 255.0f + 0.5f));
}

void Texture::store(int x, int y, const float* values) {
    float* dst = at(x, y);
    for (int c = 0; c < channels(); ++c)
        dst[c] = format == TexFormat::rgba16f ? quantize_half(values[c]) : quantize_unorm8(values[c]);
}

bool write_pfm(const Texture& t, const std::string& path, std::string* error) {
    const bool grey = t.format == TexFormat::r8;
    const int out_channels = grey ? 1 : 3;
    std::string header = std::string(grey ? "Pf" : "PF") + "\n" + std::to_string(t.width) + " " +
                         std::to_string(t.height) + "\n-1.0\n";
    std::string bytes = header;
    bytes.reserve(header.size() + std::size_t(t.width) * std::size_t(t.height) * std::size_t(out_channels) * 4);
    // PFM rows run bottom to top; the first stored row is the image's bottom row, which we
    // define to be texture row 0 (the window's minimum z).
    for (int y = 0; y < t.height; ++y) {
        for (int x = 0; x < t.width; ++x) {
            const float* src = t.at(x, y);
            for (int c = 0; c < out_channels; ++c) {
                float v = c < t.channels() ? src[c] : 0.0f;
                char le[4];
                std::memcpy(le, &v, 4); // x86-64 and ARM64 are little-endian
                bytes.append(le, 4);
            }
        }
    }
    auto r = write_file_atomic(path, bytes);
    if (!r) {
        if (error) *error = r.error().message;
        return false;
    }
    return true;
}

} // namespace lantern::gi
