// File helpers with the error contract of lantern::Result.
//
// write_file_atomic never leaves a half-written file: it writes a temporary file in the
// same folder, flushes it to disk, then renames it over the target, so a crash or kill at
// any moment leaves either the old contents or the new ones. Safe for untrusted paths in
// the sense that failures come back as messages; it does not sanitise the path.
#pragma once

#include "lantern/core/result.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace lantern {

Result<std::string> read_text_file(const std::string& path);
Result<std::vector<std::uint8_t>> read_binary_file(const std::string& path);

Result<void> write_file_atomic(const std::string& path, std::span<const std::byte> bytes);
Result<void> write_file_atomic(const std::string& path, const std::string& text);

// Creates the folder and its parents if missing.
Result<void> ensure_directory(const std::string& path);

} // namespace lantern
