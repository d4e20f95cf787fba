// GI textures as the C++ side sees them: a format, a size and the texel values as floats,
// already quantised exactly as the GPU stores them (so references and readbacks compare
// texel by texel).
//
// Storage formats (DESIGN.md's texture contract): r8 and rg8 are UNORM (value = round(v *
// 255) / 255 after clamping to [0, 1]); rgba16f is IEEE half with round-to-nearest-even
// (what GLSL packHalf2x16 does), clamped to +-65504 so values beyond the half range stay
// finite instead of becoming Inf, and NaN stored as 0 so it cannot propagate.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace lantern::gi {

enum class TexFormat : std::uint8_t { r8, rg8, rgba16f };

constexpr int channel_count(TexFormat f) { return f == TexFormat::r8 ? 1 : f == TexFormat::rg8 ? 2 : 4; }
constexpr int bytes_per_texel(TexFormat f) { return f == TexFormat::r8 ? 1 : f == TexFormat::rg8 ? 2 : 8; }

inline constexpr float max_half = 65504.0f;

std::uint16_t float_to_half(float v); // RNE, clamped to +-65504, NaN -> 0
float half_to_float(std::uint16_t h);
inline float quantize_half(float v) { return half_to_float(float_to_half(v)); }

std::uint8_t float_to_unorm8(float v); // clamp to [0, 1], round half up: floor(v * 255 + 0.5)
inline float unorm8_to_float(std::uint8_t v) { return float(v) / 255.0f; }
inline float quantize_unorm8(float v) { return unorm8_to_float(float_to_unorm8(v)); }

struct Texture {
    std::string name;
    TexFormat format = TexFormat::rgba16f;
    int width = 0;
    int height = 0;
    std::vector<float> texels; // width * height * channel_count, row-major, row 0 at min z

    Texture() = default;
    Texture(std::string texture_name, TexFormat fmt, int w, int h)
        : name(std::move(texture_name)), format(fmt), width(w), height(h),
          texels(std::size_t(w) * std::size_t(h) * std::size_t(channel_count(fmt)), 0.0f) {}

    int channels() const { return channel_count(format); }
    float* at(int x, int y) { return &texels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels())]; }
    const float* at(int x, int y) const {
        return &texels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels())];
    }
    // Stores `values` (channels() of them) at (x, y), quantised to the format.
    void store(int x, int y, const float* values);
};

// Writes the texture as a little-endian float PFM (RGB for colour and two-channel textures,
// with B = 0 for rg8; greyscale for r8), rows bottom to top as the format specifies, so the
// first stored row is texture row 0. Atomic (temporary file + rename).
bool write_pfm(const Texture& texture, const std::string& path, std::string* error);

} // namespace lantern::gi
