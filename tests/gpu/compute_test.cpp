// Compute pipelines on the device, compared exactly with C++ references.
#include "gpu/gpu_test_support.hpp"
#include "gpu/test_shader_types.hpp"

#include "lantern/gpu/device.hpp"
#include "lantern_test_shaders.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace gpu = lantern::gpu;
using lantern::test::bytes_of;
using lantern::test::float_to_half;
using lantern::test::half_to_float;
using lantern::test::read_back_as;
using lantern::test::test_group_size;

namespace {

class Compute : public lantern::test::GpuTest {
  protected:
    std::span<const std::uint32_t> spirv(std::string_view name) {
        auto words = lantern_test_shaders_spirv(name);
        EXPECT_FALSE(words.empty()) << name;
        return words;
    }
};

std::uint32_t groups_for(std::uint32_t count, std::uint32_t group_size) {
    return (count + group_size - 1) / group_size;
}

} // namespace

TEST_F(Compute, FillShaderWritesIndexTimesMultiplierPlusOffset) {
    constexpr std::uint32_t capacity = 1024, count = 1000; // not a multiple of the group size
    gpu::ComputePipeline pipeline = device().create_compute_pipeline(
        {.spirv = spirv("test_fill.comp"),
         .bindings = {gpu::BindingType::storage_buffer},
         .push_constant_size = sizeof(lantern::test::FillPush),
         .name = "test_fill"});
    ASSERT_TRUE(pipeline);
    gpu::Buffer data = device().create_buffer(
        {capacity * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::device_local, "fill data"});

    gpu::CommandList cmd = device().begin("fill");
    cmd.fill_buffer(data, 0xdeadbeefu); // the tail past `count` must keep this
    cmd.barrier_transfer_to_compute();
    cmd.begin_label("test_fill");
    cmd.bind(pipeline);
    cmd.push_descriptors(gpu::DescriptorWrites().storage_buffer(0, data));
    cmd.push_constants(lantern::test::FillPush{.count = count, .multiplier = 3, .offset = 17});
    cmd.dispatch(groups_for(count, test_group_size));
    cmd.end_label();
    device().wait(device().submit(std::move(cmd)));

    std::vector<std::uint32_t> expected(capacity, 0xdeadbeefu);
    for (std::uint32_t i = 0; i < count; ++i) expected[i] = i * 3 + 17;
    EXPECT_EQ(read_back_as<std::uint32_t>(device(), data), expected);
}

TEST_F(Compute, SpecializationConstantsChangeBehaviourAndGroupSize) {
    struct Variant {
        std::uint32_t mode, value, group_size;
    };
    const Variant variants[] = {{0, 7, 32}, {1, 3, 64}};
    constexpr std::uint32_t count = 256;
    for (const Variant& v : variants) {
        SCOPED_TRACE(v.mode);
        gpu::ComputePipeline pipeline = device().create_compute_pipeline(
            {.spirv = spirv("test_spec.comp"),
             .bindings = {gpu::BindingType::storage_buffer},
             .specialization = {{0, v.mode}, {1, v.value}, {2, v.group_size}},
             .name = "test_spec"});
        gpu::Buffer data = device().create_buffer(
            {count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::readback, "spec data"});
        gpu::CommandList cmd = device().begin("spec");
        cmd.bind(pipeline);
        cmd.push_descriptors(gpu::DescriptorWrites().storage_buffer(0, data));
        cmd.dispatch(count / v.group_size); // exact only if the group size took effect
        cmd.barrier_to_host();
        device().wait(device().submit(std::move(cmd)));

        std::vector<std::uint32_t> expected(count);
        for (std::uint32_t i = 0; i < count; ++i) expected[i] = v.mode == 0 ? i + v.value : i * v.value;
        EXPECT_EQ(read_back_as<std::uint32_t>(device(), data), expected);
    }
}

// The GI backend's texel layout: RGBA16F read through a uniform texel buffer, written as
// packHalf2x16 pairs into a uvec2 SSBO.
TEST_F(Compute, HalfTexelBufferToPackedHalfPairs) {
    constexpr std::uint32_t count = 300;
    constexpr float scale = 2.0f; // exact in half precision while nothing overflows
    std::vector<std::uint16_t> texels(count * 4);
    for (std::uint32_t i = 0; i < texels.size(); ++i) {
        // Normal halves of both signs and a spread of exponents; no NaN, no subnormals.
        const float value = (static_cast<float>(i % 97) - 48.0f) * (1.0f + static_cast<float>(i % 7) / 8.0f) /
                            static_cast<float>(1u << (i % 11));
        texels[i] = float_to_half(value == 0.0f ? 0.5f : value);
    }

    gpu::Buffer source = device().create_buffer(
        {texels.size() * 2, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, gpu::MemoryKind::device_local, "rgba16f"});
    gpu::BufferView view = device().create_buffer_view(source, VK_FORMAT_R16G16B16A16_SFLOAT, 0, VK_WHOLE_SIZE,
                                                       "rgba16f view");
    gpu::Buffer packed = device().create_buffer(
        {count * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::device_local, "packed"});
    gpu::ComputePipeline pipeline = device().create_compute_pipeline(
        {.spirv = spirv("test_half.comp"),
         .bindings = {gpu::BindingType::uniform_texel_buffer, gpu::BindingType::storage_buffer},
         .push_constant_size = sizeof(lantern::test::HalfPush),
         .name = "test_half"});

    device().upload(source, bytes_of(texels));
    gpu::CommandList cmd = device().begin("half");
    cmd.bind(pipeline);
    cmd.push_descriptors(gpu::DescriptorWrites().uniform_texel_buffer(0, view).storage_buffer(1, packed));
    cmd.push_constants(lantern::test::HalfPush{.count = count, .scale = scale});
    cmd.dispatch(groups_for(count, test_group_size));
    device().wait(device().submit(std::move(cmd)));

    std::vector<std::uint32_t> expected(count * 2);
    for (std::uint32_t i = 0; i < count * 4; i += 2) {
        const std::uint32_t lo = float_to_half(half_to_float(texels[i]) * scale);
        const std::uint32_t hi = float_to_half(half_to_float(texels[i + 1]) * scale);
        expected[i / 2] = lo | (hi << 16);
    }
    EXPECT_EQ(read_back_as<std::uint32_t>(device(), packed), expected);
}
