// Presentation in real GLFW windows under Xvfb on lavapipe swapchains, checked by capturing
// the window with xwd: the upscaled pixel-art frame, resizes, stale sizes (out of date /
// suboptimal), zero-size framebuffers, vsync on and off, the ImGui overlay clicked through
// real X input, pass timings. Validation is on; any message fails the test.
#include "lantern/render/render.hpp"

#include "lantern/gpu/device.hpp"
#include "platform/xvfb_support.hpp"
#include "render/render_test_support.hpp"

#include <gtest/gtest.h>
#include <imgui.h>

#include <chrono>
#include <thread>

namespace lantern::render {
namespace {

using namespace std::chrono_literals;

class PresentTest : public test::WindowedTest {
  protected:
    // The internal target (encoding matching the swapchain) and a test pattern in it.
    void make_scene() {
        const bool srgb = swapchain().format() == VK_FORMAT_B8G8R8A8_SRGB ||
                          swapchain().format() == VK_FORMAT_R8G8B8A8_SRGB;
        target_ = RenderTarget::create(
            device(), {.color_format = srgb ? VK_FORMAT_R8G8B8A8_SRGB : VK_FORMAT_R8G8B8A8_UNORM});
        batch_ = QuadBatch::create(device(), {target_.color_format(), target_.depth_format()});
        batch_.add({{0, 0}, {1, 1}, 0.5f, {1, 1, 1, 1}});         // top-left pixel
        batch_.add({{479, 269}, {480, 270}, 0.5f, {1, 0, 0, 1}}); // bottom-right pixel
        batch_.add({{10, 10}, {200, 100}, 0.5f, {0, 1, 0, 1}});
        batch_.add({{150, 50}, {400, 250}, 0.25f, {0, 0, 1, 1}});
        for (int i = 0; i < 20;
             ++i) { // a checker strip: every source pixel distinct from its neighbours
            const float x = 20.0f + float(i);
            batch_.add({{x, 200},
                        {x + 1, 201},
                        0.1f,
                        (i % 2) ? glm::vec4(1, 1, 0, 1) : glm::vec4(1, 0, 1, 1)});
        }
    }

    // One frame: the scene, upscaled into the swapchain image, the overlay on top when given.
    // False when acquire had nothing to present to.
    bool present_frame(platform::Extent framebuffer, ImGuiOverlay* overlay = nullptr,
                       PassTimer* timer = nullptr, std::uint64_t frame_number = 0) {
        auto frame = swapchain().acquire(framebuffer);
        if (!frame) return false;
        gpu::CommandList cmd = device().begin("frame");
        if (timer) timer->begin_frame(cmd, frame_number);
        batch_.upload(cmd);
        const std::uint32_t scene = timer ? timer->begin(cmd, "scene") : 0;
        target_.begin(cmd);
        batch_.draw(cmd, target_.extent());
        target_.end(cmd);
        if (timer) timer->end(cmd, scene);
        const std::uint32_t upscale = timer ? timer->begin(cmd, "upscale") : 0;
        const VkExtent2D size = frame->image().extent();
        rect_ = fit_integer_scale({480, 270}, {size.width, size.height});
        record_upscale(cmd, target_.color(), frame->image(), rect_,
                       overlay ? VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL
                               : VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
        if (timer) timer->end(cmd, upscale);
        if (overlay) overlay->record(cmd, frame->image());
        swapchain().present(std::move(*frame), std::move(cmd));
        return true;
    }

    // The window as it should look: bars black, the target scaled by rect_.
    std::uint32_t expected_pixel(const Rgba8Image& source, std::uint32_t x, std::uint32_t y) const {
        const std::int64_t lx = std::int64_t(x) - rect_.x, ly = std::int64_t(y) - rect_.y;
        if (lx < 0 || ly < 0 || lx >= rect_.width || ly >= rect_.height) return 0;
        return test::rgb_at(source, std::uint32_t(lx) / rect_.scale,
                            std::uint32_t(ly) / rect_.scale);
    }

    // Captures the window until it shows the expected frame (presentation is asynchronous)
    // or `timeout` passes; reports the first mismatches.
    void expect_window_shows_target(std::chrono::milliseconds timeout = 60000ms) {
        device().wait_idle();
        const Rgba8Image source = target_.read_back();
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        std::string report;
        do {
            auto capture = test::capture_window(test::x11_window(window()));
            ASSERT_TRUE(capture) << capture.error().message;
            report = compare(*capture, source);
            if (report.empty()) return;
            std::this_thread::sleep_for(20ms);
        } while (std::chrono::steady_clock::now() < deadline);
        ADD_FAILURE() << report;
    }

    std::string compare(const test::RgbImage& capture, const Rgba8Image& source) const {
        const platform::Extent size = window_->framebuffer_size();
        if (capture.width != size.width || capture.height != size.height)
            return "capture is " + std::to_string(capture.width) + "x" +
                   std::to_string(capture.height);
        std::string report;
        int mismatches = 0;
        for (std::uint32_t y = 0; y < capture.height; ++y) {
            for (std::uint32_t x = 0; x < capture.width; ++x) {
                const std::uint32_t want = expected_pixel(source, x, y), got = capture.at(x, y);
                if (got != want && ++mismatches <= 5) {
                    char line[96];
                    std::snprintf(line, sizeof line, "\n  (%u, %u): %06x != %06x", x, y, got, want);
                    report += line;
                }
            }
        }
        return mismatches ? std::to_string(mismatches) + " pixels differ:" + report : "";
    }

    void TearDown() override {
        batch_ = {};
        target_ = {};
        WindowedTest::TearDown();
    }

    RenderTarget target_;
    QuadBatch batch_;
    PresentRect rect_;
};

TEST_F(PresentTest, UpscaledFrameAppearsInTheWindow) {
    if (!open({1000, 600})) return;
    make_scene();
    ASSERT_TRUE(present_frame(window().framebuffer_size()));
    EXPECT_EQ(rect_, (PresentRect{20, 30, 960, 540, 2}));
    EXPECT_EQ(swapchain().generation(), 1u);
    EXPECT_EQ(swapchain().extent().width, 1000u);
    EXPECT_EQ(swapchain().present_mode(), VK_PRESENT_MODE_FIFO_KHR);
    expect_window_shows_target();
}

TEST_F(PresentTest, ResizeRecreatesTheSwapchain) {
    if (!open({640, 360})) return;
    make_scene();
    ASSERT_TRUE(present_frame(window().framebuffer_size()));
    window().set_size({1000, 560});
    ASSERT_TRUE(test::poll_until(window(), [&] {
        return window().framebuffer_size() == platform::Extent{1000, 560};
    }));
    ASSERT_TRUE(present_frame(window().framebuffer_size()));
    EXPECT_EQ(swapchain().generation(), 2u);
    EXPECT_EQ(swapchain().extent().width, 1000u);
    EXPECT_EQ(swapchain().extent().height, 560u);
    EXPECT_EQ(rect_, (PresentRect{20, 10, 960, 540, 2}));
    expect_window_shows_target();
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(present_frame(window().framebuffer_size()));
    EXPECT_EQ(swapchain().generation(), 2u); // no recreation without a change
}

TEST_F(PresentTest, StaleSizeIsCaughtThroughOutOfDateOrSuboptimal) {
    if (!open({640, 360})) return;
    make_scene();
    const platform::Extent stale = window().framebuffer_size();
    ASSERT_TRUE(present_frame(stale));
    window().set_size({800, 450});
    ASSERT_TRUE(test::poll_until(window(), [&] {
        return window().framebuffer_size() == platform::Extent{800, 450};
    }));
    // The caller keeps passing the old size: only the driver's OUT_OF_DATE / SUBOPTIMAL
    // results can tell the swapchain, which then takes the surface's new extent.
    for (int i = 0; i < 6 && swapchain().extent().width != 800; ++i)
        ASSERT_TRUE(present_frame(stale));
    EXPECT_EQ(swapchain().extent().width, 800u);
    EXPECT_EQ(swapchain().extent().height, 450u);
    EXPECT_GE(swapchain().generation(), 2u);
    ASSERT_TRUE(present_frame(stale));
    expect_window_shows_target();
}

TEST_F(PresentTest, ZeroSizeFramebufferSkipsTheFrame) {
    if (!open({640, 360})) return;
    make_scene();
    ASSERT_TRUE(present_frame(window().framebuffer_size()));
    // A minimised window reports a 0x0 framebuffer: nothing is acquired or recreated.
    for (int i = 0; i < 3; ++i) EXPECT_FALSE(present_frame({0, 0}));
    EXPECT_FALSE(present_frame({640, 0}));
    EXPECT_EQ(swapchain().generation(), 1u);
    ASSERT_TRUE(present_frame(window().framebuffer_size())); // restored
    EXPECT_EQ(swapchain().generation(), 1u);
    expect_window_shows_target();
}

TEST_F(PresentTest, SwapchainCreatedWhileMinimisedStartsAtTheFirstAcquire) {
    if (!open({640, 360})) return;
    make_scene();
    // Replace the fixture's swapchain by one made for a 0x0 framebuffer.
    swapchain_.reset();
    auto surface = window().create_surface(device());
    ASSERT_TRUE(surface) << surface.error().message;
    auto created = Swapchain::create(device(), std::move(surface).value(), {0, 0});
    ASSERT_TRUE(created) << created.error().message;
    swapchain_.emplace(std::move(created).value());
    EXPECT_EQ(swapchain().generation(), 0u);
    EXPECT_EQ(swapchain().extent().width, 0u);
    EXPECT_NE(swapchain().format(), VK_FORMAT_UNDEFINED); // known before any image exists
    ASSERT_TRUE(present_frame(window().framebuffer_size()));
    EXPECT_EQ(swapchain().generation(), 1u);
    expect_window_shows_target();
}

TEST_F(PresentTest, VsyncOffAndOnBothPresent) {
    if (!open({640, 360}, false)) return;
    make_scene();
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(present_frame(window().framebuffer_size()));
    const VkPresentModeKHR unsynced = swapchain().present_mode();
    EXPECT_TRUE(unsynced == VK_PRESENT_MODE_MAILBOX_KHR ||
                unsynced == VK_PRESENT_MODE_IMMEDIATE_KHR)
        << "present mode " << unsynced << " (lavapipe's X11 surfaces offer both)";
    expect_window_shows_target();

    swapchain().set_vsync(true);
    EXPECT_TRUE(swapchain().vsync());
    for (int i = 0; i < 4; ++i) ASSERT_TRUE(present_frame(window().framebuffer_size()));
    EXPECT_EQ(swapchain().present_mode(), VK_PRESENT_MODE_FIFO_KHR);
    EXPECT_EQ(swapchain().generation(), 2u);
    expect_window_shows_target();

    swapchain().set_vsync(false);
    ASSERT_TRUE(present_frame(window().framebuffer_size()));
    EXPECT_EQ(swapchain().present_mode(), unsynced);
    EXPECT_EQ(swapchain().generation(), 3u);
}

TEST_F(PresentTest, ImGuiOverlayIsDrawnAndClickedThroughX) {
    if (!open({640, 360})) return;
    make_scene();
    auto overlay =
        ImGuiOverlay::create(device(), {.format = swapchain().format(), .window = &window()});
    ASSERT_TRUE(overlay) << overlay.error().message;
    int clicks = 0;
    auto frame = [&] {
        window().poll();
        overlay->new_frame();
        ImGui::SetNextWindowPos(ImVec2(300, 200));
        ImGui::SetNextWindowSize(ImVec2(200, 100));
        ImGui::Begin("HUD", nullptr, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoMove);
        if (ImGui::Button("Click me", ImVec2(120, 40))) ++clicks;
        ImGui::End();
        ASSERT_TRUE(present_frame(window().framebuffer_size(), &*overlay));
    };
    for (int i = 0; i < 3; ++i) frame();
    device().wait_idle();
    // The scene shows around the overlay, the overlay covers its window.
    const std::uint64_t id = test::x11_window(window());
    auto capture = test::capture_window(id);
    ASSERT_TRUE(capture) << capture.error().message;
    const Rgba8Image source = target_.read_back();
    EXPECT_EQ(capture->at(50, 50), expected_pixel(source, 50, 50));
    EXPECT_NE(capture->at(310, 290), expected_pixel(source, 310, 290))
        << "the ImGui window is drawn";

    // A real click on the button (at window pixels ~ (300 + 8 + 60, 200 + 27 + 20)).
    ASSERT_TRUE(test::x_mouse_move(id, 368, 247));
    for (int i = 0; i < 2; ++i) frame(); // ImGui sees the hover first
    ASSERT_TRUE(test::x_button(1, true));
    for (int i = 0; i < 2; ++i) frame();
    ASSERT_TRUE(test::x_button(1, false));
    for (int i = 0; i < 20 && clicks == 0; ++i) frame();
    EXPECT_EQ(clicks, 1);
    EXPECT_TRUE(overlay->wants_mouse()); // the pointer is over the ImGui window
    // The game's InputState saw the click too: ImGui chains the Window's callbacks.
    EXPECT_EQ(window().input().mouse_position(), glm::vec2(368.0f, 247.0f));
}

TEST_F(PresentTest, FrameLoopRecordsPassTimings) {
    if (!open({640, 360})) return;
    make_scene();
    auto timer = PassTimer::create(device());
    if (!timer) LANTERN_SKIP_NO_GPU(timer.error().message);
    std::vector<FrameTimings> timings;
    for (std::uint64_t f = 0; f < 6; ++f) {
        ASSERT_TRUE(present_frame(window().framebuffer_size(), nullptr, &*timer, f));
        for (FrameTimings& t : timer->take_completed()) timings.push_back(std::move(t));
    }
    device().wait_idle();
    for (FrameTimings& t : timer->take_completed()) timings.push_back(std::move(t));
    ASSERT_EQ(timings.size(), 6u);
    for (std::uint64_t f = 0; f < 6; ++f) {
        EXPECT_EQ(timings[f].frame, f);
        ASSERT_EQ(timings[f].passes.size(), 2u);
        EXPECT_STREQ(timings[f].passes[1].name, "upscale");
        EXPECT_GE(timings[f].passes[1].duration_ns, 0);
    }
}

TEST_F(PresentTest, DeviceWithoutSwapchainSupportIsAnError) {
    if (!open({320, 180})) return;
    gpu::DeviceOptions options{.validation = true, .graphics = true};
    options.instance_extensions = *window().vulkan_instance_extensions(); // no VK_KHR_swapchain
    auto plain = gpu::Device::create(options);
    ASSERT_TRUE(plain) << plain.error().message;
    auto surface = window().create_surface(**plain);
    ASSERT_TRUE(surface) << surface.error().message;
    auto swapchain =
        Swapchain::create(**plain, std::move(surface).value(), window().framebuffer_size());
    ASSERT_FALSE(swapchain);
    EXPECT_NE(swapchain.error().message.find("VK_KHR_swapchain"), std::string::npos)
        << swapchain.error().message;
    EXPECT_EQ((*plain)->validation_message_count(), 0u) << test::describe_validation(**plain);
}

} // namespace
} // namespace lantern::render
