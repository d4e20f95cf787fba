// PNG output (stb_image_write), written atomically like every Lantern output file.
#pragma once

#include "lantern/core/result.hpp"

#include <cstdint>
#include <span>
#include <string>

namespace lantern {

// Encodes width x height pixels of `channels` (1..4) 8-bit values, rows top to bottom as
// given, and writes them to `path` with write_file_atomic.
Result<void> write_png(const std::string& path, int width, int height, int channels,
                       std::span<const std::uint8_t> pixels);

} // namespace lantern
