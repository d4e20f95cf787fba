// Backend on the C++ reference: the rows of the pass table run on the CPU
// (execute_reference), every texture kept between frames as the GPU backend keeps it.
#include "lantern/gi/backend.hpp"

#include "lantern/gi/pass_table.hpp"

#include <utility>

namespace lantern::gi {
namespace {


class ReferenceBackend final : public Backend {
  public:
    explicit ReferenceBackend(jobs::JobSystem* jobs) : options_{jobs} {}

    std::string name() const override { return "C++ reference"; }

    Result<void> execute(std::uint64_t frame, const FrameInputs& in, const PassPlan& plan, PassSet run,
                         const WallUpdate&) override {
        if (auto ok = check_texture_budget(in, plan, TextureStorage::reference); !ok) return ok;
        FrameTimes times{frame, {}};
        release_unwritten(in, plan, store_); // as the GPU backend releases them
        execute_reference(in, plan, run, options_, store_, [](void* user, Pass pass, std::int64_t start, std::int64_t end) {
            static_cast<FrameTimes*>(user)->passes.push_back({pass, double(end - start) * 1e-6, start, end});
        }, &times);
        if (!times.passes.empty()) done_.push_back(std::move(times));
        return {};
    }

    std::vector<FrameTimes> completed_times() override { return std::exchange(done_, {}); }

    std::optional<Texture> read(const std::string& name) override {
        const std::optional<Tex> t = texture_by_name(name);
        if (!t || texture_row(*t).internal) return std::nullopt;
        const Texture* found = store_.find(*t);
        return found ? std::optional<Texture>(*found) : std::nullopt;
    }
    std::optional<Image> read_lit() override { return store_.lit; }
    std::vector<std::string> texture_names() const override {
        std::vector<std::string> out;
        for (Tex t : contract_textures([&](Tex held) { return store_.find(held) != nullptr; })) out.emplace_back(tex_name(t));
        return out;
    }
    void wait_idle() override {}

  private:
    RefOptions options_;
    ReferenceStore store_;
    std::vector<FrameTimes> done_;
};

} // namespace

std::unique_ptr<Backend> make_reference_backend(jobs::JobSystem* jobs) {
    return std::make_unique<ReferenceBackend>(jobs);
}

} // namespace lantern::gi
