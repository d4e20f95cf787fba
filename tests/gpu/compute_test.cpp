// Compute pipelines on the device, compared exactly with C++ references.
#include "gpu/gpu_test_support.hpp"
#include "gpu/test_shader_types.hpp"

#include "lantern/gpu/device.hpp"
#include "lantern_test_shaders.hpp"

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <random>
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

// gi_exact.glsl (shaders/include/lantern): gi_div and gi_sqrt equal IEEE 754 division and
// square root bit for bit on whatever driver runs them, so the GI passes' cell decisions
// match the C++ reference there too. Vulkan lets a driver's own division err by 2.5 ULP
// (NVIDIA's does; lavapipe's is exact): the test prints how many of the driver's own
// results were not correctly rounded.
TEST_F(Compute, ExactDivisionAndSquareRootAreCorrectlyRounded) {
    std::vector<glm::vec2> pairs;
    std::mt19937 rng(20261126u);
    std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
    std::uniform_int_distribution<int> exponent(-14, 14), coin(0, 1);
    auto any = [&] { return (coin(rng) ? -1.0f : 1.0f) * std::ldexp(mantissa(rng), exponent(rng)); };
    for (int i = 0; i < 30000; ++i) pairs.emplace_back(any(), any());
    // The GI passes' own kinds: texel centres at odd resolutions, unit directions, distances.
    for (int x = 0; x < 2048; ++x)
        for (float tpu : {3.0f, 5.0f, 6.0f, 7.0f}) pairs.emplace_back(float(x) + 0.5f, tpu);
    std::uniform_real_distribution<float> coordinate(-40.0f, 40.0f);
    for (int i = 0; i < 10000; ++i) {
        const float dx = coordinate(rng), dz = coordinate(rng);
        const float length = std::sqrt(dx * dx + dz * dz);
        pairs.emplace_back(dx, length);
        pairs.emplace_back(dx * dx + dz * dz, 1.0f - dz / 64.0f);
    }
    for (int x = 1; x < 200; ++x) pairs.emplace_back(float(x * x) * 0.0625f + 0.25f, float(x) * 0.25f);
    const auto count = std::uint32_t(pairs.size());

    gpu::Buffer in = device().create_buffer(
        {count * sizeof(glm::vec2), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::device_local, "pairs"});
    gpu::Buffer out = device().create_buffer(
        {count * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryKind::device_local, "results"});
    device().upload(in, bytes_of(pairs));

    // One run: EXACT_ROUNDING `mode` (1: Dekker's residuals, any driver; 2: fma residuals,
    // which the GI renderer chooses only where its probe finds fma fused), the helpers
    // started `ulp_error` ULP off (0: as the GI passes call them; more: as an inexact
    // driver's division would start them, lavapipe's being exact).
    auto run = [&](gpu::ComputePipeline& pipeline, std::uint32_t mode, std::uint32_t ulp_error) {
        SCOPED_TRACE(testing::Message() << "mode " << mode << ", " << ulp_error << " ULP off");
        gpu::CommandList cmd = device().begin("exact");
        cmd.bind(pipeline);
        cmd.push_descriptors(gpu::DescriptorWrites().storage_buffer(0, in).storage_buffer(1, out));
        cmd.push_constants(lantern::test::FillPush{.count = count, .multiplier = ulp_error});
        cmd.dispatch(groups_for(count, test_group_size));
        device().wait(device().submit(std::move(cmd)));
        const auto results = read_back_as<glm::vec4>(device(), out);
        ASSERT_EQ(results.size(), pairs.size());
        int driver_div = 0, driver_sqrt = 0, exact_div = 0, exact_sqrt = 0;
        for (std::size_t i = 0; i < pairs.size(); ++i) {
            const float q = pairs[i].x / pairs[i].y, s = std::sqrt(std::abs(pairs[i].x));
            const glm::vec4 r = results[i];
            driver_div += std::bit_cast<std::uint32_t>(r.x) != std::bit_cast<std::uint32_t>(q);
            driver_sqrt += std::bit_cast<std::uint32_t>(r.z) != std::bit_cast<std::uint32_t>(s);
            if (std::bit_cast<std::uint32_t>(r.y) != std::bit_cast<std::uint32_t>(q) && exact_div++ < 5)
                ADD_FAILURE() << "gi_div(" << pairs[i].x << ", " << pairs[i].y << ") = " << r.y << ", IEEE " << q;
            if (std::bit_cast<std::uint32_t>(r.w) != std::bit_cast<std::uint32_t>(s) && exact_sqrt++ < 5)
                ADD_FAILURE() << "gi_sqrt(" << std::abs(pairs[i].x) << ") = " << r.w << ", IEEE " << s;
        }
        std::printf("%u pairs on %s, residuals by %s, started %u ULP off: the driver's division was not correctly "
                    "rounded %d times, its square root %d times; gi_div %d times, gi_sqrt %d times\n",
                    count, device().name().c_str(), mode == 1 ? "Dekker" : "fma", ulp_error, driver_div,
                    driver_sqrt, exact_div, exact_sqrt);
        EXPECT_EQ(exact_div, 0);
        EXPECT_EQ(exact_sqrt, 0);
        // The GI passes skip the helpers on CPU drivers (spec_exact_rounding 0): theirs must be exact.
        if (device().type() == gpu::DeviceType::cpu) {
            EXPECT_EQ(driver_div, 0);
            EXPECT_EQ(driver_sqrt, 0);
        }
    };
    for (std::uint32_t mode : {1u, 2u}) {
        if (mode == 2 && device().type() == gpu::DeviceType::cpu) continue; // lavapipe's fma rounds twice
        gpu::ComputePipeline pipeline = device().create_compute_pipeline(
            {.spirv = spirv("test_exact.comp"),
             .bindings = {gpu::BindingType::storage_buffer, gpu::BindingType::storage_buffer},
             .specialization = {{10, mode}},
             .push_constant_size = sizeof(lantern::test::FillPush),
             .name = "test_exact"});
        ASSERT_TRUE(pipeline);
        for (std::uint32_t ulp_error = 0; ulp_error <= 3; ++ulp_error) run(pipeline, mode, ulp_error);
    }
}
