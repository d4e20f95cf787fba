// Shared by the GPU layer's test shaders (shaders/test_*.comp.glsl); included through
// lantern_add_shader_library's INCLUDE_DIRS. Mirrored in tests/gpu/test_shader_types.hpp.
#ifndef LANTERN_TEST_COMMON_GLSL
#define LANTERN_TEST_COMMON_GLSL

#define TEST_GROUP_SIZE 64

// FillPush in C++.
struct FillPush {
    uint count;
    uint multiplier;
    uint offset;
    uint pad;
};

// HalfPush in C++.
struct HalfPush {
    uint count;
    float scale;
    uint pad0;
    uint pad1;
};

#endif
