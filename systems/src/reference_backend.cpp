// GiBackend on the C++ reference: the rows of the pass table run on the CPU
// (gi::execute_reference), every texture kept between frames as the GPU backend keeps it.
#include "lantern/gi/pass_table.hpp"
#include "lantern/systems/gi_backend.hpp"

#include <utility>

namespace lantern::systems {
namespace {

using gi::Pass;

class ReferenceBackend final : public GiBackend {
  public:
    explicit ReferenceBackend(jobs::JobSystem* jobs) : options_{jobs} {}

    std::string name() const override { return "C++ reference"; }

    Result<void> execute(std::uint64_t frame, const gi::FrameInputs& in, const gi::PassPlan& plan, gi::PassSet run,
                         const WallUpdate&) override {
        FrameTimes times{frame, {}};
        gi::release_unwritten(in, plan, store_); // as the GPU backend releases them
        gi::execute_reference(in, plan, run, options_, store_, [](void* user, gi::Pass pass, std::int64_t start, std::int64_t end) {
            static_cast<FrameTimes*>(user)->passes.push_back({pass, double(end - start) * 1e-6, start, end});
        }, &times);
        if (!times.passes.empty()) done_.push_back(std::move(times));
        return {};
    }

    std::vector<FrameTimes> completed_times() override { return std::exchange(done_, {}); }

    std::optional<gi::Texture> read(const std::string& name) override {
        const std::optional<gi::Tex> t = gi::texture_by_name(name);
        if (!t || gi::texture_row(*t).internal) return std::nullopt;
        const gi::Texture* found = store_.find(*t);
        return found ? std::optional<gi::Texture>(*found) : std::nullopt;
    }
    std::optional<gi::Image> read_lit() override { return store_.lit; }
    std::vector<std::string> texture_names() const override {
        std::vector<std::string> out;
        for (int t = 0; t < gi::registered_texture_count(); ++t) {
            const gi::TextureRow& row = gi::texture_row(gi::Tex(t));
            if (!row.internal && store_.find(row.id)) out.emplace_back(row.name);
        }
        return out;
    }
    void wait_idle() override {}

  private:
    gi::RefOptions options_;
    gi::ReferenceStore store_;
    std::vector<FrameTimes> done_;
};

} // namespace

std::unique_ptr<GiBackend> make_reference_backend(jobs::JobSystem* jobs) {
    return std::make_unique<ReferenceBackend>(jobs);
}

} // namespace lantern::systems
