// Minimal leveled logging to stderr. Thread-safe: each call writes one whole line.
// LANTERN_LOG_LEVEL=debug|info|warn|error in the environment sets the threshold
// (default info). Use for progress and diagnostics, never for results a tool outputs.
#pragma once

#include <cstdarg>

namespace lantern::log {

enum class Level { debug = 0, info = 1, warn = 2, error = 3 };

void set_level(Level level);
Level level();

void write(Level level, const char* fmt, ...) __attribute__((format(printf, 2, 3)));

#define LANTERN_LOG_DEBUG(...) ::lantern::log::write(::lantern::log::Level::debug, __VA_ARGS__)
#define LANTERN_LOG_INFO(...) ::lantern::log::write(::lantern::log::Level::info, __VA_ARGS__)
#define LANTERN_LOG_WARN(...) ::lantern::log::write(::lantern::log::Level::warn, __VA_ARGS__)
#define LANTERN_LOG_ERROR(...) ::lantern::log::write(::lantern::log::Level::error, __VA_ARGS__)

} // namespace lantern::log
