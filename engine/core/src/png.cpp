#include "lantern/core/png.hpp"

#include "lantern/core/file.hpp"

#include <vector>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace lantern {

Result<void> write_png(const std::string& path, int width, int height, int channels,
                       std::span<const std::uint8_t> pixels) {
    if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
        pixels.size() < std::size_t(width) * std::size_t(height) * std::size_t(channels))
        return make_error(path + ": invalid image for PNG output", 1);
    std::vector<std::byte> encoded;
    auto sink = [](void* context, void* data, int size) {
        auto* out = static_cast<std::vector<std::byte>*>(context);
        auto* bytes = static_cast<const std::byte*>(data);
        out->insert(out->end(), bytes, bytes + size);
    };
    if (!stbi_write_png_to_func(sink, &encoded, width, height, channels, pixels.data(), width * channels))
        return make_error(path + ": PNG encoding failed", 1);
    return write_file_atomic(path, encoded);
}

} // namespace lantern
