// PassTimer: per-frame GPU timings of named passes, each frame returned once, in order,
// without blocking on frames still running.
#include "lantern/render/pass_timer.hpp"

#include "lantern/gpu/device.hpp"
#include "lantern/render/quad_batch.hpp"
#include "lantern/render/render_target.hpp"
#include "render/render_test_support.hpp"

#include <gtest/gtest.h>

#include <cstring>

namespace lantern::render {
namespace {

using PassTimerTest = test::RenderTest;

TEST_F(PassTimerTest, EachFrameIsReportedOnceWithItsPasses) {
    auto timer = PassTimer::create(device(), 4);
    if (!timer) LANTERN_SKIP_NO_GPU(timer.error().message);
    RenderTarget target = RenderTarget::create(
        device(), {64, 32, VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_D32_SFLOAT, "timed"});
    QuadBatch batch = QuadBatch::create(device(), {target.color_format(), target.depth_format()});
    batch.add({{0, 0}, {64, 32}, 0.5f, {1, 0, 0, 1}});
    gpu::Image copy = device().create_image(
        {64, 32, VK_FORMAT_R8G8B8A8_UNORM, VK_IMAGE_USAGE_SAMPLED_BIT, "copy"});

    std::vector<FrameTimings> seen;
    for (std::uint64_t frame = 10; frame < 17; ++frame) {
        gpu::CommandList cmd = device().begin("timed frame");
        timer->begin_frame(cmd, frame);
        batch.upload(cmd);
        const std::uint32_t scene = timer->begin(cmd, "scene");
        target.begin(cmd);
        batch.draw(cmd, target.extent());
        target.end(cmd);
        timer->end(cmd, scene);
        const std::uint32_t blit = timer->begin(cmd, "blit");
        cmd.transition(copy, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        cmd.blit(target.color(), {{0, 0}, {64, 32}}, copy, {{0, 0}, {64, 32}}, VK_FILTER_NEAREST);
        cmd.transition(copy, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
        timer->end(cmd, blit);
        device().submit(std::move(cmd));
        for (FrameTimings& t : timer->take_completed()) seen.push_back(std::move(t));
    }
    device().wait_idle();
    for (FrameTimings& t : timer->take_completed()) seen.push_back(std::move(t));
    EXPECT_TRUE(timer->take_completed().empty()); // nothing twice

    ASSERT_EQ(seen.size(), 7u);
    for (std::size_t i = 0; i < seen.size(); ++i) {
        EXPECT_EQ(seen[i].frame, 10 + i);
        ASSERT_EQ(seen[i].passes.size(), 2u);
        EXPECT_STREQ(seen[i].passes[0].name, "scene");
        EXPECT_STREQ(seen[i].passes[1].name, "blit");
        EXPECT_GE(seen[i].passes[0].duration_ns, 0);
        EXPECT_GE(seen[i].passes[1].cpu_begin_ns, seen[i].passes[0].cpu_end_ns - 1); // in order
    }
}

} // namespace
} // namespace lantern::render
