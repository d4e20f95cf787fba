// C++ mirrors of the test shaders' push-constant blocks (tests/gpu/shaders/test_common.glsl).
#pragma once

#include <cstdint>

namespace lantern::test {

inline constexpr std::uint32_t test_group_size = 64; // TEST_GROUP_SIZE

struct alignas(16) FillPush {
    std::uint32_t count = 0;
    std::uint32_t multiplier = 0;
    std::uint32_t offset = 0;
    std::uint32_t pad = 0;
};
static_assert(sizeof(FillPush) == 16, "FillPush must match test_common.glsl");

struct alignas(16) HalfPush {
    std::uint32_t count = 0;
    float scale = 1.0f;
    std::uint32_t pad0 = 0;
    std::uint32_t pad1 = 0;
};
static_assert(sizeof(HalfPush) == 16, "HalfPush must match test_common.glsl");

} // namespace lantern::test
