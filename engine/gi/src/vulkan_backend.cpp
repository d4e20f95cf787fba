// Backend on the Vulkan renderer: one submission per frame that has work, at most two in
// flight, timestamps read back from earlier frames without stalling.
#include "lantern/profile/profiler.hpp"
#include "lantern/gi/backend.hpp"

#include "lantern/gi/vulkan/renderer.hpp"

namespace lantern::gi {
namespace {

using vk::Tex;

constexpr std::uint64_t frames_in_flight = 2;

class VulkanBackend final : public Backend {
  public:
    explicit VulkanBackend(vk::Renderer& r) : renderer_(r) {}

    std::string name() const override { return renderer_.device().name(); }

    Result<void> execute(std::uint64_t frame, const FrameInputs& in, const PassPlan& plan, PassSet run,
                         const WallUpdate& walls) override {
        gpu::Device& device = renderer_.device();
        // Throttle: wait for the submission two frames back before recording a third.
        if (device.last_submitted_serial() >= frames_in_flight) {
            LANTERN_PROFILE_SCOPE("gi.wait");
            device.wait(device.last_submitted_serial() - (frames_in_flight - 1));
        }
        {
            LANTERN_PROFILE_SCOPE("gi.prepare");
            if (auto ok = renderer_.prepare(in, plan); !ok) return ok;
        }
        const bool walls_changed = walls.whole || !walls.ranges.empty();
        if (run.bits == 0 && !walls_changed) return {}; // an unchanged frame: no GPU work
        gpu::CommandList cmd = device.begin("gi frame");
        // On a raster device, earlier frames' fragment shaders read these textures: their
        // reads finish before this frame's copies and passes overwrite them.
        if (device.capabilities().graphics)
            cmd.memory_barrier(VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0,
                               VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0);
        renderer_.begin_frame(cmd, frame);
        if (walls.whole || !uploaded_walls_)
            renderer_.upload_walls(cmd, in.walls);
        else
            renderer_.update_walls(cmd, in.walls, walls.ranges);
        uploaded_walls_ = true;
        if (run.has(Pass::direct) || run.has(Pass::directional)) renderer_.upload_lights(cmd, in);
        {
            LANTERN_PROFILE_SCOPE("gi.record");
            renderer_.record_plan(cmd, in, plan, run);
        }
        LANTERN_PROFILE_SCOPE("gi.submit");
        device.submit(std::move(cmd));
        return {};
    }

    std::vector<FrameTimes> completed_times() override {
        std::vector<FrameTimes> out;
        for (const vk::FrameTimings& f : renderer_.completed_timings()) {
            FrameTimes t{f.frame, {}};
            for (const vk::PassTiming& p : f.passes)
                if (!p.part) // the profiler's lanes show whole passes
                    t.passes.push_back({p.pass, p.gpu_ms, p.region.cpu_begin_ns, p.region.cpu_end_ns});
            out.push_back(std::move(t));
        }
        return out;
    }

    std::optional<Texture> read(const std::string& name) override {
        const std::optional<Tex> t = texture_by_name(name);
        if (!t || texture_row(*t).internal || !renderer_.has(*t)) return std::nullopt;
        return renderer_.read_back(*t);
    }

    std::optional<Image> read_lit() override {
        if (!renderer_.has(Tex::lit)) return std::nullopt;
        const glm::ivec2 size = renderer_.size(Tex::lit);
        return Image{size.x, size.y, renderer_.read_back_lit_rgb()};
    }

    std::vector<std::string> texture_names() const override {
        std::vector<std::string> out;
        for (Tex t : contract_textures([&](Tex held) { return renderer_.has(held); })) out.emplace_back(tex_name(t));
        return out;
    }

    void wait_idle() override { renderer_.device().wait_idle(); }

  private:
    vk::Renderer& renderer_;
    bool uploaded_walls_ = false;
};

} // namespace

std::unique_ptr<Backend> make_vulkan_backend(vk::Renderer& renderer) {
    return std::make_unique<VulkanBackend>(renderer);
}

} // namespace lantern::gi
