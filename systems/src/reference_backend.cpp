// GiBackend on the C++ reference: the same passes, run on the CPU, keeping every texture
// between frames like the GPU backend does.
#include "lantern/core/clock.hpp"
#include "lantern/gi/reference_indirect.hpp"
#include "lantern/gi/shading.hpp"
#include "lantern/systems/gi_backend.hpp"

#include <map>

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
        const bool suns = !in.directional_lights.empty();
        auto timed = [&](Pass p, auto&& fn) {
            if (!plan.run.has(p) || !run.has(p)) return;
            const std::int64_t start = now_ns();
            fn();
            const std::int64_t end = now_ns();
            times.passes.push_back({p, double(end - start) * 1e-6, start, end});
        };
        drop_unplanned(plan, suns);
        timed(Pass::conduction, [&] { put(gi::reference_conduction(in, options_)); });
        timed(Pass::ao, [&] { put(gi::reference_ao(in, options_)); });
        timed(Pass::direct, [&] {
            gi::DirectTextures d = gi::reference_direct(in, options_);
            if (suns)
                point_ = std::move(d);
            else
                put_direct(std::move(d));
        });
        timed(Pass::directional, [&] {
            gi::DirectTextures d = point_; // the directional pass never works in place
            gi::reference_directional(in, d, options_);
            put_direct(std::move(d));
        });
        timed(Pass::emission, [&] { put(gi::reference_emission(in, at("direct"), options_)); });
        timed(Pass::heat, [&] { put(gi::reference_heat(in, at("emission"), at("shadow"), options_)); });
        timed(Pass::blur, [&] { put(gi::reference_blur(in, at("indirect"), options_)); });
        timed(Pass::wall_indirect, [&] {
            for (gi::Texture& t : gi::reference_wall_indirect(in, at("indirect"), options_)) put(std::move(t));
        });
        timed(Pass::lit, [&] { lit_ = gi::reference_lit_image(shading_inputs(in), options_); });
        if (!times.passes.empty()) done_.push_back(std::move(times));
        return {};
    }

    std::vector<FrameTimes> completed_times() override { return std::exchange(done_, {}); }

    std::optional<gi::Texture> read(const std::string& name) override {
        auto it = textures_.find(name);
        if (it == textures_.end()) return std::nullopt;
        return it->second;
    }
    std::optional<gi::Image> read_lit() override { return lit_; }
    std::vector<std::string> texture_names() const override {
        std::vector<std::string> out;
        for (const auto& [name, t] : textures_) out.push_back(name);
        return out;
    }
    void wait_idle() override {}

  private:
    void put(gi::Texture t) {
        std::string name = t.name;
        textures_[name] = std::move(t);
    }
    void put_direct(gi::DirectTextures d) {
        put(std::move(d.direct));
        put(std::move(d.shadow));
        for (gi::Texture& t : d.wall_direct) put(std::move(t));
    }
    const gi::Texture& at(const char* name) const { return textures_.at(name); }
    const gi::Texture* find(const std::string& name) const {
        auto it = textures_.find(name);
        return it == textures_.end() ? nullptr : &it->second;
    }
    // Textures of passes the plan no longer has are released, as the GPU backend does.
    void drop_unplanned(const gi::PassPlan& plan, bool suns) {
        auto drop = [&](const std::string& name) { textures_.erase(name); };
        if (!plan.run.has(Pass::ao)) drop("ao");
        if (!plan.run.has(Pass::emission)) drop("emission");
        if (!plan.run.has(Pass::heat)) drop("indirect");
        if (!plan.run.has(Pass::wall_indirect))
            for (const char* f : gi::face_suffix) drop(std::string("wall_indirect_") + f);
        if (!plan.run.has(Pass::lit)) lit_.reset();
        if (!suns) point_ = {};
    }
    gi::ShadingInputs shading_inputs(const gi::FrameInputs& in) const {
        gi::ShadingInputs s;
        s.frame = &in;
        s.direct = find("direct");
        s.indirect = find("indirect");
        s.ao = find("ao");
        s.shadow = find("shadow");
        for (int f = 0; f < 4; ++f) {
            s.wall_direct[std::size_t(f)] = find(std::string("wall_direct_") + gi::face_suffix[f]);
            s.wall_indirect[std::size_t(f)] = find(std::string("wall_indirect_") + gi::face_suffix[f]);
        }
        return s;
    }

    gi::RefOptions options_;
    std::map<std::string, gi::Texture> textures_;
    gi::DirectTextures point_;
    std::optional<gi::Image> lit_;
    std::vector<FrameTimes> done_;
};

} // namespace

std::unique_ptr<GiBackend> make_reference_backend(jobs::JobSystem* jobs) {
    return std::make_unique<ReferenceBackend>(jobs);
}

} // namespace lantern::systems
