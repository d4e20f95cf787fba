// ImGuiOverlay: ImGui context and backends, the overlay render pass, imageless framebuffers.
#include "lantern/render/imgui_overlay.hpp"

#include "lantern/core/clock.hpp"
#include "lantern/gpu/device.hpp"
#include "lantern/gpu/vk_check.hpp"

#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <array>
#include <utility>

namespace lantern::render {

namespace {

// ImGui's backends are global: one overlay at a time.
bool overlay_exists = false;

// ImGui 1.86 keeps ImageCount vertex/index buffer pairs and uses them round robin.
constexpr std::uint32_t imgui_buffer_sets = 3;

void check_vk(VkResult result) {
    VK_CHECK(result);
}

VkRenderPass create_render_pass(VkDevice device, VkFormat format, VkImageLayout final_layout) {
    VkAttachmentDescription attachment{};
    attachment.format = format;
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD; // drawn over the finished image
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    attachment.finalLayout = final_layout;
    const VkAttachmentReference color{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &color;

    const bool present = final_layout == VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    std::array<VkSubpassDependency, 2> dependencies{};
    // Earlier colour writes (the upscale's transition ends at COLOR_ATTACHMENT_OUTPUT) first.
    dependencies[0] = {VK_SUBPASS_EXTERNAL,
                       0,
                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                       VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                       VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                       0};
    // Then whatever reads the result: presentation (ordered by its semaphore) or anything.
    dependencies[1] = {
        0,
        VK_SUBPASS_EXTERNAL,
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
        present ? VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT : VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
        present ? VkAccessFlags{0}
                : VkAccessFlags{VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT},
        0};

    VkRenderPassCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    info.attachmentCount = 1;
    info.pAttachments = &attachment;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = static_cast<std::uint32_t>(dependencies.size());
    info.pDependencies = dependencies.data();
    VkRenderPass render_pass = VK_NULL_HANDLE;
    VK_CHECK(vkCreateRenderPass(device, &info, nullptr, &render_pass));
    return render_pass;
}

// The font texture's descriptor set is the only one ImGui 1.86 allocates.
VkDescriptorPool create_descriptor_pool(VkDevice device) {
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
    VkDescriptorPoolCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    info.maxSets = 1;
    info.poolSizeCount = 1;
    info.pPoolSizes = &size;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorPool(device, &info, nullptr, &pool));
    return pool;
}

// An imageless framebuffer: any image of this size, usage and format can be its attachment.
VkFramebuffer create_framebuffer(VkDevice device, VkRenderPass render_pass, VkFormat format,
                                 VkExtent2D extent, VkImageUsageFlags usage) {
    VkFramebufferAttachmentImageInfo image{};
    image.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_ATTACHMENT_IMAGE_INFO;
    image.usage = usage;
    image.width = extent.width;
    image.height = extent.height;
    image.layerCount = 1;
    image.viewFormatCount = 1;
    image.pViewFormats = &format;
    VkFramebufferAttachmentsCreateInfo attachments{};
    attachments.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_ATTACHMENTS_CREATE_INFO;
    attachments.attachmentImageInfoCount = 1;
    attachments.pAttachmentImageInfos = &image;
    VkFramebufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    info.pNext = &attachments;
    info.flags = VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT;
    info.renderPass = render_pass;
    info.attachmentCount = 1;
    info.width = extent.width;
    info.height = extent.height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VK_CHECK(vkCreateFramebuffer(device, &info, nullptr, &framebuffer));
    return framebuffer;
}

} // namespace

struct ImGuiOverlay::State {
    gpu::Device* device = nullptr;
    ImGuiOverlayDesc desc;
    VkRenderPass render_pass = VK_NULL_HANDLE;
    VkDescriptorPool descriptor_pool = VK_NULL_HANDLE;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    VkExtent2D framebuffer_extent{};
    VkImageUsageFlags framebuffer_usage = 0;
    bool context = false, glfw_backend = false, vulkan_backend = false;
    bool frame_open = false;
    // Device::last_submitted_serial() at the last two record() calls (see record()).
    std::array<std::uint64_t, 2> submitted_at_record{};
    std::uint64_t records = 0;
    std::int64_t last_frame_ns = 0;

    State() = default;
    State(const State&) = delete;
    State& operator=(const State&) = delete;
    ~State();

    Result<void> init_backends();
    void upload_fonts();
    void ensure_framebuffer(const gpu::Image& target);
};

ImGuiOverlay::State::~State() {
    if (!device) return;
    device->wait_idle();
    if (vulkan_backend) ImGui_ImplVulkan_Shutdown();
    if (glfw_backend) ImGui_ImplGlfw_Shutdown();
    if (context) ImGui::DestroyContext();
    vkDestroyFramebuffer(device->vk_device(), framebuffer, nullptr);
    vkDestroyRenderPass(device->vk_device(), render_pass, nullptr);
    vkDestroyDescriptorPool(device->vk_device(), descriptor_pool, nullptr);
    overlay_exists = false;
}

Result<void> ImGuiOverlay::State::init_backends() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    context = true;
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini next to whatever the working directory is
    io.LogFilename = nullptr;
    ImGui::StyleColorsDark();
    if (desc.window) {
        if (!ImGui_ImplGlfw_InitForVulkan(desc.window->glfw_handle(), true))
            return make_error("render::ImGuiOverlay: ImGui's GLFW backend failed to initialise");
        glfw_backend = true;
    }
    const VkDevice vk_device = device->vk_device();
    render_pass = create_render_pass(vk_device, desc.format, desc.final_layout);
    descriptor_pool = create_descriptor_pool(vk_device);
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = device->vk_instance();
    info.PhysicalDevice = device->vk_physical_device();
    info.Device = vk_device;
    info.QueueFamily = device->queue_family();
    info.Queue = device->vk_queue();
    info.DescriptorPool = descriptor_pool;
    info.MinImageCount = 2;
    info.ImageCount = imgui_buffer_sets;
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = &check_vk;
    if (!ImGui_ImplVulkan_Init(&info, render_pass))
        return make_error("render::ImGuiOverlay: ImGui's Vulkan backend failed to initialise");
    vulkan_backend = true;
    return {};
}

// Blocking, once: the font atlas goes through a staging buffer ImGui frees afterwards.
void ImGuiOverlay::State::upload_fonts() {
    gpu::CommandList cmd = device->begin("imgui fonts");
    ImGui_ImplVulkan_CreateFontsTexture(cmd.vk());
    device->wait(device->submit(std::move(cmd)));
    ImGui_ImplVulkan_DestroyFontUploadObjects();
}

void ImGuiOverlay::State::ensure_framebuffer(const gpu::Image& target) {
    const VkExtent2D extent = target.extent();
    if (framebuffer && extent.width == framebuffer_extent.width &&
        extent.height == framebuffer_extent.height && target.usage() == framebuffer_usage)
        return;
    device->destroy_deferred(framebuffer); // frames in flight may still use it
    framebuffer =
        create_framebuffer(device->vk_device(), render_pass, desc.format, extent, target.usage());
    framebuffer_extent = extent;
    framebuffer_usage = target.usage();
}

// --- ImGuiOverlay ------------------------------------------------------------------------------

Result<ImGuiOverlay> ImGuiOverlay::create(gpu::Device& device, const ImGuiOverlayDesc& desc) {
    LANTERN_ASSERT(desc.format != VK_FORMAT_UNDEFINED,
                   "render::ImGuiOverlay needs the targets' format");
    LANTERN_ASSERT(device.capabilities().graphics,
                   "render::ImGuiOverlay needs DeviceOptions::graphics");
    if (overlay_exists)
        return make_error("render::ImGuiOverlay: only one overlay can exist at a time");
    overlay_exists = true;
    auto state = std::make_unique<State>();
    state->device = &device;
    state->desc = desc;
    if (auto ok = state->init_backends(); !ok) return ok.error(); // ~State undoes what was done
    state->upload_fonts();
    state->last_frame_ns = now_ns();
    return ImGuiOverlay(std::move(state));
}

ImGuiOverlay::ImGuiOverlay(std::unique_ptr<State> state) : state_(std::move(state)) {}
ImGuiOverlay::ImGuiOverlay(ImGuiOverlay&& other) noexcept = default;
ImGuiOverlay& ImGuiOverlay::operator=(ImGuiOverlay&& other) noexcept = default;
ImGuiOverlay::~ImGuiOverlay() = default;

void ImGuiOverlay::new_frame(platform::Extent display_size) {
    State& s = *state_;
    LANTERN_ASSERT(!s.frame_open, "render::ImGuiOverlay::new_frame twice without record");
    ImGui_ImplVulkan_NewFrame();
    if (s.glfw_backend) {
        ImGui_ImplGlfw_NewFrame(); // display size, time step and input from the window
    } else {
        LANTERN_ASSERT(!display_size.empty(),
                       "render::ImGuiOverlay::new_frame headless needs a display size");
        ImGuiIO& io = ImGui::GetIO();
        io.DisplaySize = ImVec2(float(display_size.width), float(display_size.height));
        const std::int64_t now = now_ns();
        io.DeltaTime = std::max(1e-6f, float(now - s.last_frame_ns) * 1e-9f);
        s.last_frame_ns = now;
    }
    ImGui::NewFrame();
    s.frame_open = true;
}

void ImGuiOverlay::record(gpu::CommandList& cmd, const gpu::Image& target) {
    State& s = *state_;
    LANTERN_ASSERT(s.frame_open, "render::ImGuiOverlay::record without new_frame");
    LANTERN_ASSERT(target.format() == s.desc.format,
                   "render::ImGuiOverlay::record: target format differs");
    ImGui::Render();
    s.frame_open = false;
    // This record reuses the ImGui buffers of the record three calls ago, whose list was
    // submitted before the record two calls ago: wait for everything submitted by then
    // (already complete when a Swapchain paces the frames).
    std::uint64_t& submitted = s.submitted_at_record[s.records % 2];
    if (submitted != 0) s.device->wait(submitted);
    submitted = s.device->last_submitted_serial();
    ++s.records;

    s.ensure_framebuffer(target);
    const VkImageView view = target.view();
    VkRenderPassAttachmentBeginInfo attachments{};
    attachments.sType = VK_STRUCTURE_TYPE_RENDER_PASS_ATTACHMENT_BEGIN_INFO;
    attachments.attachmentCount = 1;
    attachments.pAttachments = &view;
    VkRenderPassBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    begin.pNext = &attachments;
    begin.renderPass = s.render_pass;
    begin.framebuffer = s.framebuffer;
    begin.renderArea = {{0, 0}, target.extent()};
    vkCmdBeginRenderPass(cmd.vk(), &begin, VK_SUBPASS_CONTENTS_INLINE);
    ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd.vk());
    vkCmdEndRenderPass(cmd.vk());
}

bool ImGuiOverlay::wants_mouse() const {
    return ImGui::GetIO().WantCaptureMouse;
}
bool ImGuiOverlay::wants_keyboard() const {
    return ImGui::GetIO().WantCaptureKeyboard;
}

} // namespace lantern::render
