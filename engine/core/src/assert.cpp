#include "lantern/core/assert.hpp"

#include <cstdio>
#include <cstdlib>

namespace lantern::detail {

void assert_fail(const char* expr, const char* msg, const char* file, int line) {
    std::fprintf(stderr, "%s:%d: Lantern assertion failed: %s\n  %s\n", file, line, expr, msg);
    std::fflush(stderr);
    std::abort();
}

} // namespace lantern::detail
