// gpu::reflect_spirv on the real shaders Lantern builds (no device needed): the bindings and
// push-constant blocks it reads, the pipeline contract it enforces (set 0, dense bindings),
// and malformed words (every truncation, random corruption) ending in an error, never a
// crash.
#include "lantern/gpu/pipeline.hpp"
#include "lantern/gpu/reflect.hpp"

#include "lantern_gi_shaders.hpp"
#include "lantern_test_shaders.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace {

using lantern::gpu::BindingType;
using lantern::gpu::reflect_spirv;
using B = BindingType;
using lantern::gpu::PushMember;
using lantern::gpu::ScalarKind;

std::vector<std::uint32_t> words_of(std::span<const std::uint32_t> s) { return {s.begin(), s.end()}; }

TEST(Reflect, GiShadersDeclareTheBindingsTheirRecordersPush) {
    // What renderer.cpp's hand-written table used to say, now read from the shaders.
    const std::vector<std::pair<const char*, std::vector<BindingType>>> expected = {
        {"gi_conduction.comp", {B::uniform_texel_buffer, B::uniform_buffer, B::storage_buffer}},
        {"gi_emission.comp", {B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_light_bins.comp", {B::uniform_buffer, B::storage_buffer, B::uniform_buffer, B::storage_buffer}},
        {"gi_heat.comp", {B::uniform_texel_buffer, B::uniform_texel_buffer, B::storage_buffer}},
        {"gi_direct.comp",
         {B::uniform_texel_buffer, B::uniform_buffer, B::uniform_buffer, B::storage_buffer, B::storage_buffer,
          B::storage_buffer, B::storage_buffer, B::storage_buffer, B::storage_buffer, B::storage_buffer,
          B::storage_buffer, B::storage_buffer, B::storage_buffer, B::storage_buffer, B::storage_buffer,
          B::storage_buffer, B::storage_buffer, // 16: the dirty light bins' list
          // 17-26: the realtime suns' own textures (SUNS)
          B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer,
          B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer, B::uniform_texel_buffer,
          B::uniform_texel_buffer, B::uniform_texel_buffer}},
    };
    for (const auto& [shader, bindings] : expected) {
        auto layout = reflect_spirv(lantern_gi_shaders_spirv(shader));
        ASSERT_TRUE(layout) << shader << ": " << layout.error().message;
        auto dense = layout->dense_bindings();
        ASSERT_TRUE(dense) << dense.error().message;
        EXPECT_EQ(*dense, bindings) << shader;
        EXPECT_EQ(layout->push_constant_size, 112u) << shader << ": GiPush";
        // Four shared vec4/ivec4 fields, the pass's eight 4-byte parameters, grid_phase.
        const auto& m = layout->push_constant_members;
        ASSERT_EQ(m.size(), 13u) << shader;
        for (std::uint32_t i = 0; i < 4; ++i) EXPECT_EQ(m[i], (PushMember{16 * i, 16, ScalarKind::other})) << shader;
        for (std::uint32_t i = 0; i < 8; ++i) {
            EXPECT_EQ(m[4 + i].offset, 64 + 4 * i) << shader;
            EXPECT_NE(m[4 + i].kind, ScalarKind::other) << shader;
        }
        EXPECT_EQ(m[12], (PushMember{96, 16, ScalarKind::other})) << shader;
    }
    // Named parameters: gi_emission's EmissionParams is a float, then seven ints.
    auto emission = reflect_spirv(lantern_gi_shaders_spirv("gi_emission.comp"));
    ASSERT_TRUE(emission);
    EXPECT_EQ(emission->push_constant_members[4].kind, ScalarKind::f32);
    EXPECT_EQ(emission->push_constant_members[5].kind, ScalarKind::i32);
    // Every GI shader reads as a valid pipeline layout.
    for (std::string_view name : lantern_gi_shaders_names()) {
        auto layout = reflect_spirv(lantern_gi_shaders_spirv(name));
        ASSERT_TRUE(layout) << name << ": " << layout.error().message;
        EXPECT_TRUE(layout->dense_bindings()) << name;
        EXPECT_LE(layout->bindings.size(), lantern::gpu::max_pipeline_bindings) << name;
    }
}

TEST(Reflect, TestShaderPushBlock) {
    auto layout = reflect_spirv(lantern_test_shaders_spirv("test_fill.comp"));
    ASSERT_TRUE(layout) << layout.error().message;
    EXPECT_EQ(layout->bindings.size(), 1u);
    EXPECT_EQ(layout->bindings.at(0), B::storage_buffer);
    EXPECT_GT(layout->push_constant_size, 0u);
    EXPECT_EQ(layout->push_constant_size % 4, 0u);
}

// The index of the first OpDecorate(target, decoration) instruction, or 0.
std::size_t find_decoration(const std::vector<std::uint32_t>& w, std::uint32_t decoration) {
    for (std::size_t i = 5; i < w.size();) {
        const std::uint32_t count = w[i] >> 16, opcode = w[i] & 0xffffu;
        if (count == 0) break;
        if (opcode == 71 && count >= 3 && w[i + 2] == decoration) return i;
        i += count;
    }
    return 0;
}

TEST(Reflect, ASecondDescriptorSetIsAnError) {
    auto w = words_of(lantern_gi_shaders_spirv("gi_emission.comp"));
    const std::size_t at = find_decoration(w, 34); // DescriptorSet
    ASSERT_NE(at, 0u);
    w[at + 3] = 1;
    auto layout = reflect_spirv(w);
    ASSERT_FALSE(layout);
    EXPECT_NE(layout.error().message.find("descriptor set 1"), std::string::npos) << layout.error().message;
}

TEST(Reflect, APushBlockOffsetThatWouldWrapIsAnError) {
    // Every member Offset (OpMemberDecorate ... Offset) moved near 2^32: in 32 bits the
    // block's end would wrap around to a few bytes, with members far outside it.
    auto w = words_of(lantern_gi_shaders_spirv("gi_emission.comp"));
    int moved = 0;
    for (std::size_t i = 5; i < w.size();) {
        const std::uint32_t count = w[i] >> 16, opcode = w[i] & 0xffffu;
        if (count == 0) break;
        if (opcode == 72 && count >= 5 && w[i + 3] == 35) { // OpMemberDecorate, Offset
            w[i + 4] += 0xFFFFFF00u;
            ++moved;
        }
        i += count;
    }
    ASSERT_GT(moved, 0);
    auto layout = reflect_spirv(w);
    ASSERT_FALSE(layout);
    EXPECT_NE(layout.error().message.find("over 65536 bytes"), std::string::npos) << layout.error().message;
}

TEST(Reflect, AGapInTheBindingsIsAnError) {
    auto w = words_of(lantern_gi_shaders_spirv("gi_conduction.comp"));
    // Move binding 0 to binding 5: bindings 1, 2 and 5 remain, 0 is missing.
    for (std::size_t i = 5; i < w.size();) {
        const std::uint32_t count = w[i] >> 16, opcode = w[i] & 0xffffu;
        if (opcode == 71 && count >= 4 && w[i + 2] == 33 && w[i + 3] == 0) w[i + 3] = 5;
        i += count;
    }
    auto layout = reflect_spirv(w);
    ASSERT_TRUE(layout) << layout.error().message;
    auto dense = layout->dense_bindings();
    ASSERT_FALSE(dense);
    EXPECT_NE(dense.error().message.find("binding 0 is missing"), std::string::npos) << dense.error().message;
}

TEST(Reflect, MalformedWordsAreErrorsNeverCrashes) {
    const auto whole = words_of(lantern_gi_shaders_spirv("gi_lit.comp"));
    for (std::size_t n = 0; n < whole.size(); ++n) {
        auto layout = reflect_spirv(std::span(whole).first(n)); // every truncation
        (void)layout;
    }
    EXPECT_FALSE(reflect_spirv({}));
    std::mt19937 rng(7);
    for (int round = 0; round < 2000; ++round) {
        auto w = whole;
        for (int k = 0; k < 4; ++k) w[5 + rng() % (w.size() - 5)] = rng();
        auto layout = reflect_spirv(w); // an error or a layout, never a crash or a hang
        (void)layout;
    }
}

TEST(Reflect, MergedStagesMustAgree) {
    using lantern::gpu::ShaderLayout;
    ShaderLayout vs, fs;
    vs.bindings = {{0, B::uniform_buffer}};
    fs.bindings = {{0, B::uniform_buffer}, {1, B::combined_image_sampler}};
    fs.push_constant_size = 16;
    auto merged = lantern::gpu::merge_layouts(vs, fs);
    ASSERT_TRUE(merged);
    EXPECT_EQ(merged->bindings.size(), 2u);
    EXPECT_EQ(merged->push_constant_size, 16u);
    fs.bindings[0] = B::storage_buffer;
    EXPECT_FALSE(lantern::gpu::merge_layouts(vs, fs));
}

} // namespace
