#include "lantern/core/log.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace lantern::log {
namespace {

Level level_from_env() {
    const char* env = std::getenv("LANTERN_LOG_LEVEL");
    if (!env) return Level::info;
    if (std::strcmp(env, "debug") == 0) return Level::debug;
    if (std::strcmp(env, "warn") == 0) return Level::warn;
    if (std::strcmp(env, "error") == 0) return Level::error;
    return Level::info;
}

std::atomic<Level>& threshold() {
    static std::atomic<Level> value{level_from_env()};
    return value;
}

const char* prefix(Level level) {
    switch (level) {
    case Level::debug: return "lantern [debug] ";
    case Level::info: return "lantern: ";
    case Level::warn: return "lantern [warning] ";
    case Level::error: return "lantern [error] ";
    }
    return "";
}

} // namespace

void set_level(Level level) { threshold().store(level, std::memory_order_relaxed); }
Level level() { return threshold().load(std::memory_order_relaxed); }

void write(Level lvl, const char* fmt, ...) {
    if (lvl < level()) return;
    // Format into one buffer so concurrent lines never interleave mid-line.
    char buffer[2048];
    int used = std::snprintf(buffer, sizeof(buffer), "%s", prefix(lvl));
    va_list args;
    va_start(args, fmt);
    int n = std::vsnprintf(buffer + used, sizeof(buffer) - used - 1, fmt, args);
    va_end(args);
    size_t len = used + (n < 0 ? 0 : static_cast<size_t>(n));
    if (len > sizeof(buffer) - 2) len = sizeof(buffer) - 2;
    buffer[len++] = '\n';
    std::fwrite(buffer, 1, len, stderr);
}

} // namespace lantern::log
