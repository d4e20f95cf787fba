// Graphics pipelines with push descriptors of every kind a lit pass reads (the GI texture as
// a uniform texel buffer, a uniform buffer, a combined image sampler), a full-screen draw,
// compared texel for texel; and the raster contracts (asserts).
#include "lantern/gpu/device.hpp"
#include "lantern/render/render_target.hpp"

#include "gpu/gpu_test_support.hpp"
#include "render/render_test_support.hpp"

#include "lantern_render_shaders.hpp"
#include "lantern_render_test_shaders.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace lantern::render {
namespace {

// Mirrors `Params` of test_bindings.frag.glsl (std140).
struct alignas(16) Params {
    float scale[4];
    std::int32_t size[4]; // gi width, first texture column
};
static_assert(sizeof(Params) == 32, "Params mirrors the shader's std140 block");

constexpr std::uint32_t gi_width = 8, height = 8, target_width = 16;

gpu::GraphicsPipeline bindings_pipeline(gpu::Device& device) {
    return device.create_graphics_pipeline(
        {.vertex_spirv = lantern_render_shaders_spirv("render_fullscreen.vert"),
         .fragment_spirv = lantern_render_test_shaders_spirv("test_bindings.frag"),
         .bindings = {gpu::BindingType::uniform_texel_buffer, gpu::BindingType::uniform_buffer,
                      gpu::BindingType::combined_image_sampler},
         .color_format = VK_FORMAT_R8G8B8A8_UNORM,
         .name = "test_bindings"});
}

using GraphicsPipelineTest = test::RenderTest;

TEST_F(GraphicsPipelineTest, FragmentShaderReadsTexelBufferUniformsAndTexture) {
    gpu::Device& dev = device();
    // The "GI texture": RGBA16F, multiples of 4/255 so that the scaled values stay exact.
    std::vector<std::uint16_t> gi(gi_width * height * 4);
    for (std::uint32_t i = 0; i < gi_width * height; ++i) {
        gi[i * 4 + 0] = test::float_to_half(float(4 * (i % 64)) / 255.0f);
        gi[i * 4 + 1] = test::float_to_half(float(4 * ((i * 3) % 64)) / 255.0f);
        gi[i * 4 + 2] = test::float_to_half(float(4 * ((i * 7) % 64)) / 255.0f);
        gi[i * 4 + 3] = test::float_to_half(1.0f);
    }
    gpu::Buffer gi_buffer =
        dev.create_buffer({gi.size() * 2, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT,
                           gpu::MemoryKind::device_local, "gi"});
    dev.upload(gi_buffer, test::bytes_of(gi));
    gpu::BufferView gi_view = dev.create_buffer_view(gi_buffer, VK_FORMAT_R16G16B16A16_SFLOAT);

    const Params params{{1.0f, 0.5f, 0.25f, 1.0f}, {gi_width, gi_width, 0, 0}};
    gpu::Buffer params_buffer = dev.create_buffer(
        {sizeof(Params), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, gpu::MemoryKind::upload, "params"});
    dev.upload(params_buffer, std::as_bytes(std::span(&params, 1)));

    std::vector<std::uint32_t> texels(16);
    for (std::uint32_t i = 0; i < 16; ++i)
        texels[i] = 0xff000000u | (i * 15) | ((200 - i * 9) << 8) | (i * 3 << 16);
    gpu::Image texture =
        dev.create_image({4, 4, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "sprite"});
    dev.upload(texture, std::as_bytes(std::span(texels)), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    gpu::Sampler sampler = dev.create_sampler();

    gpu::GraphicsPipeline pipeline = bindings_pipeline(dev);
    RenderTarget target = RenderTarget::create(
        dev, {target_width, height, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_UNDEFINED, "bindings"});
    gpu::CommandList cmd = dev.begin("bindings");
    target.begin(cmd);
    cmd.bind(pipeline);
    cmd.push_descriptors(gpu::DescriptorWrites()
                             .uniform_texel_buffer(0, gi_view)
                             .uniform_buffer(1, params_buffer)
                             .combined_image_sampler(2, texture, sampler));
    cmd.draw(3);
    target.end(cmd);
    dev.submit(std::move(cmd));
    const Rgba8Image image = target.read_back();

    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < target_width; ++x) {
            std::uint32_t want = 0;
            if (x < gi_width) {
                const std::uint32_t i = y * gi_width + x;
                for (int c = 0; c < 4; ++c) {
                    const float v = test::half_to_float(gi[i * 4 + c]) * params.scale[c];
                    want |= std::uint32_t(std::lround(v * 255.0f)) << (8 * c);
                }
            } else {
                want = texels[(y / 2) * 4 + (x - gi_width) / 2];
            }
            EXPECT_EQ(image.at(x, y), want) << "pixel (" << x << ", " << y << ")";
        }
    }
}

TEST_F(GraphicsPipelineTest, IndexedMeshWithViewportAndScissor) {
    struct Vertex {
        float position[2];
        std::uint32_t color; // RGBA8 UNORM
    };
    static_assert(sizeof(Vertex) == 12);
    // Two rectangles of two triangles each, sharing vertices through 16-bit indices.
    const std::vector<Vertex> vertices = {
        {{2, 2}, 0xff0000ffu},  {{10, 2}, 0xff0000ffu}, {{10, 6}, 0xff0000ffu},
        {{2, 6}, 0xff0000ffu},  {{12, 1}, 0xffff0000u}, {{16, 1}, 0xffff0000u},
        {{16, 8}, 0xffff0000u}, {{12, 8}, 0xffff0000u}, {{2, 6}, 0xff00ff00u},
        {{10, 6}, 0xff00ff00u}, {{10, 8}, 0xff00ff00u}, {{2, 8}, 0xff00ff00u}};
    // Counter-clockwise as seen on the y-down target faces the viewer; the third rectangle
    // winds the other way and is culled.
    const std::vector<std::uint16_t> indices = {0, 3, 2, 2, 1, 0,  4,  7,  6,
                                                6, 5, 4, 8, 9, 10, 10, 11, 8};
    gpu::Buffer vertex_buffer =
        device().create_buffer({vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                                gpu::MemoryKind::device_local, "mesh"});
    device().upload(vertex_buffer, test::bytes_of(vertices));
    gpu::Buffer index_buffer =
        device().create_buffer({indices.size() * 2, VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                                gpu::MemoryKind::device_local, "mesh indices"});
    device().upload(index_buffer, test::bytes_of(indices));

    gpu::GraphicsPipeline pipeline = device().create_graphics_pipeline(
        {.vertex_spirv = lantern_render_test_shaders_spirv("test_mesh.vert"),
         .fragment_spirv = lantern_render_test_shaders_spirv("test_mesh.frag"),
         .vertex = {.stride = sizeof(Vertex),
                    .attributes = {{0, VK_FORMAT_R32G32_SFLOAT, 0},
                                   {1, VK_FORMAT_R8G8B8A8_UNORM, 8}}},
         .push_constant_size = 8,
         .cull = VK_CULL_MODE_BACK_BIT,
         .color_format = VK_FORMAT_R8G8B8A8_UNORM,
         .name = "mesh"});
    RenderTarget target = RenderTarget::create(
        device(), {target_width, height, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_UNDEFINED, "mesh"});
    gpu::CommandList cmd = device().begin("mesh");
    target.begin(cmd);
    cmd.bind(pipeline);
    const float inverse_size[2] = {1.0f / target_width, 1.0f / height};
    cmd.push_constants(inverse_size, sizeof(inverse_size));
    cmd.bind_vertex_buffer(vertex_buffer);
    cmd.bind_index_buffer(index_buffer, VK_INDEX_TYPE_UINT16);
    cmd.set_scissor({{0, 0}, {target_width, 4}}); // only the top half for the first rectangle
    cmd.draw_indexed(6);
    cmd.set_scissor({{0, 0}, {target_width, height}});
    cmd.set_viewport(-4.0f, 0.0f, float(target_width), float(height)); // the second, shifted 4 left
    cmd.draw_indexed(6, 1, 6);
    cmd.set_viewport(0.0f, 0.0f, float(target_width), float(height));
    cmd.draw_indexed(6, 1, 12); // back-facing: nothing
    target.end(cmd);
    device().submit(std::move(cmd));
    const Rgba8Image image = target.read_back();
    for (std::uint32_t y = 0; y < height; ++y) {
        for (std::uint32_t x = 0; x < target_width; ++x) {
            std::uint32_t want = 0xff000000u;
            if (x >= 2 && x < 10 && y >= 2 && y < 4) want = 0xff0000ffu; // scissored at y = 4
            if (x >= 8 && x < 12 && y >= 1 && y < 8) want = 0xffff0000u; // 12..16 moved by -4
            EXPECT_EQ(image.at(x, y), want) << "pixel (" << x << ", " << y << ")";
        }
    }
}

TEST_F(GraphicsPipelineTest, PipelineKeepsItsFormatsAndBindings) {
    gpu::GraphicsPipeline pipeline = bindings_pipeline(device());
    EXPECT_TRUE(pipeline);
    EXPECT_EQ(pipeline.color_format(), VK_FORMAT_R8G8B8A8_UNORM);
    EXPECT_EQ(pipeline.depth_format(), VK_FORMAT_UNDEFINED);
    ASSERT_EQ(pipeline.bindings().size(), 3u);
    EXPECT_EQ(pipeline.bindings()[2], gpu::BindingType::combined_image_sampler);
    gpu::GraphicsPipeline moved = std::move(pipeline);
    EXPECT_TRUE(moved);
    EXPECT_FALSE(pipeline);
    const std::size_t pending = device().pending_deletions();
    moved.reset();
    EXPECT_EQ(device().pending_deletions(), pending + 1);
    device().collect();
    EXPECT_EQ(device().pending_deletions(), pending);
}

TEST_F(GraphicsPipelineTest, DrawOutsideARenderingScopeAsserts) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            gpu::GraphicsPipeline pipeline = bindings_pipeline(device());
            gpu::CommandList cmd = device().begin("no scope");
            cmd.bind(pipeline);
            cmd.draw(3);
        },
        "rendering scope");
}

TEST(GraphicsPipelineContracts, RasterNeedsAGraphicsDevice) {
    std::string why;
    gpu::Device* compute_only = test::shared_gpu_device(&why); // DeviceOptions::graphics off
    if (!compute_only) LANTERN_SKIP_NO_GPU(why);
    EXPECT_FALSE(compute_only->capabilities().graphics);
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_DEATH(
        {
            gpu::Image image =
                compute_only->create_image({4, 4, VK_FORMAT_R8G8B8A8_UNORM,
                                            VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "attachment"});
            gpu::CommandList cmd = compute_only->begin("raster");
            cmd.begin_rendering({&image});
        },
        "DeviceOptions::graphics");
}

} // namespace
} // namespace lantern::render
