#include "render/render_test_support.hpp"

#include "platform/xvfb_support.hpp"

namespace lantern::test {

namespace {

struct SharedDevice {
    std::unique_ptr<gpu::Device> device;
    std::string error;
};

SharedDevice& shared() {
    // Destroyed at exit, after every test: tests hold no resources past TearDown.
    static SharedDevice instance = [] {
        SharedDevice s;
        auto created = gpu::Device::create(
            {.validation = true, .application_name = "lantern render tests", .graphics = true});
        if (created)
            s.device = std::move(created).value();
        else
            s.error = created.error().message;
        return s;
    }();
    return instance;
}

} // namespace

std::string describe_validation(const gpu::Device& device) {
    std::string out = std::to_string(device.validation_message_count()) + " validation messages:";
    for (const std::string& m : device.validation_messages()) out += "\n  " + m;
    return out;
}

void RenderTest::SetUp() {
    SharedDevice& s = shared();
    if (!s.device) LANTERN_SKIP_NO_GPU(s.error);
    device_ = s.device.get();
    device_->clear_validation_messages();
}

void RenderTest::TearDown() {
    if (!device_) return;
    device_->wait_idle();
    EXPECT_EQ(device_->validation_message_count(), 0u) << describe_validation(*device_);
}

void WindowedTest::open_or_skip(platform::Extent size, bool vsync) {
    if (auto display = xvfb_display(); !display) LANTERN_SKIP_NO_GPU(display.error().message);
    if (auto missing = missing_x_tools(); !missing.empty())
        LANTERN_SKIP_NO_GPU("missing X tools: " << missing << " (run scripts/setup.sh)");
    auto window = platform::Window::create(
        {.title = "lantern render test", .width = size.width, .height = size.height});
    if (!window) {
        ADD_FAILURE() << window.error().message;
        return;
    }
    window_.emplace(std::move(window).value());
    gpu::DeviceOptions options{.validation = true, .application_name = "lantern windowed tests"};
    if (auto presentable = render::add_presentation(options, *window_); !presentable)
        LANTERN_SKIP_NO_GPU(presentable.error().message);
    auto device = gpu::Device::create(options);
    if (!device) LANTERN_SKIP_NO_GPU(device.error().message);
    device_ = std::move(device).value();
    auto surface = window_->create_surface(*device_);
    if (!surface) {
        ADD_FAILURE() << surface.error().message;
        return;
    }
    auto swapchain = render::Swapchain::create(*device_, std::move(surface).value(),
                                               window_->framebuffer_size(), {.vsync = vsync});
    if (!swapchain) {
        ADD_FAILURE() << swapchain.error().message;
        return;
    }
    swapchain_.emplace(std::move(swapchain).value());
}

bool WindowedTest::open(platform::Extent size, bool vsync) {
    open_or_skip(size, vsync);
    return swapchain_.has_value() && !IsSkipped();
}

void WindowedTest::TearDown() {
    if (!device_) return;
    device_->wait_idle();
    EXPECT_EQ(device_->validation_message_count(), 0u) << describe_validation(*device_);
    swapchain_.reset();
    EXPECT_EQ(device_->validation_message_count(), 0u) << describe_validation(*device_);
}

std::uint32_t rgb_at(const render::Rgba8Image& image, std::uint32_t x, std::uint32_t y) {
    const std::uint32_t rgba = image.at(x, y);
    return ((rgba & 0xff) << 16) | (rgba & 0xff00) | ((rgba >> 16) & 0xff);
}

} // namespace lantern::test
